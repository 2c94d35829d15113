#include "common.glsl"
#include "shadow.glsl"
#include "tone.glsl"
// Spray, drawn over the composited image: a soft white disc, lit diffusely as a
// small sphere (sun and sky), fading towards its rim; hidden behind the scene and
// behind the water's smoothed surface. Premultiplied alpha.
flat in vec3 v_center;
flat in float v_radius_px;
flat in float v_size;
layout(binding = 1) uniform sampler2D t_scene_depth;
layout(binding = 2) uniform sampler2D t_fluid_depth;
layout(location = 0) out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float d = -v_center.z;
  if (d > eye_distance(texelFetch(t_scene_depth, p, 0).r)) discard;
  float water = texelFetch(t_fluid_depth, p, 0).r;
  if (is_fluid(water) && d > water) discard;
  // Offset from the centre with y up, in units of a disc half a pixel wider than
  // the drop, so that the smallest drops still cover a pixel centre.
  vec2 q = (gl_PointCoord * 2.0 - 1.0) * vec2(1.0, -1.0) * (0.5 * v_size / (v_radius_px + 0.5));
  float r2 = dot(q, q);
  if (r2 >= 1.0) discard;
  vec3 n_view = vec3(q, sqrt(1.0 - r2));
  mat3 to_world = mat3(u_inv_view);
  vec3 n = to_world * n_view;
  vec3 world = (u_inv_view * vec4(v_center, 1.0)).xyz;
  vec3 to_sun = -u_light_dir.xyz;
  vec3 sun = u_light_color.rgb * u_light_dir.w * sunlight(world, n);
  // Spray scatters light in all directions: the sun's side brighter, the far side
  // still lit through the drop.
  vec3 lit = u_light_color.w * (0.7 + 0.3 * n.z) + sun * (0.3 + 0.7 * max(dot(n, to_sun), 0.0));
  vec3 color = encode_srgb(tone(vec3(0.9) * lit));
  float alpha = u_spray.w * (1.0 - r2) * (1.0 - r2);
  o_color = vec4(color * alpha, alpha);
}

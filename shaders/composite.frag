#include "common.glsl"
#include "sky.glsl"
#include "shadow.glsl"
#include "tone.glsl"
// The water over the scene: Fresnel (Schlick) mix of the reflected sky and of the
// scene refracted through the water, attenuated by Beer-Lambert absorption along
// the thickness, plus the light scattered inside and the sun's specular glint.
// Drawn only over the fluid mask; composite_scene.frag draws the rest. Tone mapping
// and sRGB encoding are in tone.glsl, shared by both.
layout(binding = 0) uniform sampler2D t_scene_color;
layout(binding = 1) uniform sampler2D t_scene_depth;
layout(binding = 2) uniform sampler2D t_fluid_depth;
layout(binding = 3) uniform sampler2D t_thickness;
layout(binding = 7) uniform sampler2D t_normals;
layout(location = 0) out vec4 o_color;

// Reflectance of water at normal incidence: ((1.33 - 1) / (1.33 + 1))^2.
const float kF0 = 0.02;

void main() {
  vec2 frag = gl_FragCoord.xy;
  ivec2 p = ivec2(frag);
  vec3 scene = texelFetch(t_scene_color, p, 0).rgb;
  float scene_d = eye_distance(texelFetch(t_scene_depth, p, 0).r);
  float d = texelFetch(t_fluid_depth, p, 0).r;
  vec2 thickness_foam = texelFetch(t_thickness, p, 0).rg;
  float thickness = thickness_foam.x;
  vec3 n = texelFetch(t_normals, p, 0).xyz;
  int mode = int(u_camera_position.w + 0.5);
  bool water = is_fluid(d) && d < scene_d && dot(n, n) > 0.5;

  if (mode == 1) {  // depth: near is bright
    o_color = vec4(vec3(water ? 1.0 - (d - u_camera.x) / (u_camera.y - u_camera.x) : 0.0), 1.0);
    return;
  }
  if (mode == 2) {  // thickness: 1 - exp(-thickness / 0.1 m)
    o_color = vec4(vec3(1.0 - exp(-thickness / 0.1)), 1.0);
    return;
  }
  if (mode == 3) {  // normals: view space, mapped to [0, 1]
    o_color = vec4(water ? n * 0.5 + 0.5 : vec3(0.0), 1.0);
    return;
  }

  vec3 color = scene;
  if (water) {
    vec3 pos = view_position(frag, d);
    vec3 v = normalize(-pos);
    float cos_v = max(dot(n, v), 0.0);
    float fresnel = kF0 + (1.0 - kF0) * pow(1.0 - cos_v, 5.0);

    mat3 to_world = mat3(u_inv_view);
    vec3 world_pos = (u_inv_view * vec4(pos, 1.0)).xyz;
    vec3 world_n = to_world * n;
    vec3 reflected = sky(to_world * reflect(-v, n));

    // Refraction: the scene seen through the water, displaced along the normal by
    // an amount that grows with the thickness (in metres at the surface's depth).
    vec2 shift = n.xy * u_fluid_color.w * sqrt(max(thickness, 0.0)) * 0.1 * u_camera.z / d;
    vec2 uv = (frag + shift) * u_viewport.zw;
    float behind = eye_distance(texture(t_scene_depth, uv).r);
    vec3 background = behind > d ? texture(t_scene_color, uv).rgb : scene;
    vec3 transmit = exp(-u_absorption.rgb * thickness);

    // Light scattered back by the water body: more of it where the water is deep.
    vec3 to_sun = -u_light_dir.xyz;
    vec3 sun_light = u_light_color.rgb * u_light_dir.w * sunlight(world_pos, world_n);
    vec3 lit = u_light_color.w + sun_light * (0.3 + 0.7 * max(dot(world_n, to_sun), 0.0));
    float depth_amount = 1.0 - exp(-dot(u_absorption.rgb, vec3(1.0 / 3.0)) * thickness);
    vec3 body = u_fluid_color.rgb * lit * depth_amount;

    vec3 refracted = background * transmit + body;
    vec3 h = normalize(v + mat3(u_view) * to_sun);
    float glint = pow(max(dot(n, h), 0.0), 600.0) * 6.0 + pow(max(dot(n, h), 0.0), 60.0) * 0.25;
    vec3 specular = u_absorption.w * glint * sun_light;
    color = mix(refracted, reflected, fresnel) + specular;
    // Foam on edges and thin sheets: white and diffuse (lit like a rough surface),
    // over the water in proportion to the foam on the ray.
    float foam = u_spray.x * (1.0 - exp(-thickness_foam.y / max(u_spray.y, 1e-9)));
    vec3 foam_lit = vec3(0.9) * (u_light_color.w * (0.6 + 0.4 * world_n.z) +
                                 sun_light * (0.35 + 0.65 * max(dot(world_n, to_sun), 0.0)));
    color = mix(color, foam_lit, foam);
  }
  o_color = vec4(encode_srgb(tone(color)), 1.0);
}

#include "common.glsl"
#include "shadow.glsl"
// Lambert shading under the sun and the sky, with shadows; the ground plane gets a
// filtered checkerboard and fades into the horizon's haze far away.
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
uniform int u_is_ground;
layout(location = 0) out vec4 o_color;

// Fraction of "dark" squares of a checkerboard of period 2 over the pixel footprint
// (box-filtered, so distant squares blend to grey instead of flickering).
float checker(vec2 p) {
  vec2 w = max(fwidth(p), vec2(1e-5));
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) - abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_camera_position.xyz - v_world);
  if (dot(n, to_eye) < 0.0) n = -n;  // open meshes are seen from both sides
  vec3 albedo = v_color;
  if (u_is_ground == 1) albedo *= mix(1.0, 0.82, checker(v_world.xy / u_ground_color.w));
  vec3 to_sun = -u_light_dir.xyz;
  vec3 sun = u_light_color.rgb * u_light_dir.w * max(dot(n, to_sun), 0.0) * sunlight(v_world, n);
  // Sky light: full from above, a quarter from below (light bounced off the ground).
  float sky_amount = mix(0.25, 1.0, 0.5 + 0.5 * n.z);
  vec3 ambient = u_light_color.w * sky_amount * mix(u_horizon_color.rgb, vec3(1.0), 0.5);
  vec3 c = albedo * (sun + ambient);
  if (u_is_ground == 1) {
    float fog = 1.0 - exp(-length(v_world - u_camera_position.xyz) / u_horizon_color.w);
    c = mix(c, u_horizon_color.rgb, fog * fog);
  }
  o_color = vec4(c, 1.0);
}

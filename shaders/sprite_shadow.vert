#include "common.glsl"
// A particle seen from the sun (orthographic): a square of the sphere's radius.
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };
out vec2 v_offset;        // position in the square, in radii
flat out vec3 v_center;   // light view space

void main() {
  int i = gl_VertexID / 6;
  int corner = gl_VertexID % 6;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  vec3 c = (u_light_view * vec4(world, 1.0)).xyz;
  const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 k = corners[corner];
  v_offset = k;
  v_center = c;
  gl_Position = u_light_proj * vec4(c + vec3(k * u_camera.w, 0.0), 1.0);
}

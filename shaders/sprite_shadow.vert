#include "common.glsl"
// A particle seen from the sun (orthographic): a point sprite of the sphere's
// diameter in shadow-map texels.
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };
flat out vec3 v_center;   // light view space

void main() {
  int i = gl_VertexID;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  v_center = (u_light_view * vec4(world, 1.0)).xyz;
  gl_Position = u_light_proj * vec4(v_center, 1.0);
  gl_PointSize = u_misc.z;
}

#include "common.glsl"
// A particle seen from the sun (orthographic): a point sprite of the sphere's
// diameter in shadow-map texels. Only every u_stride-th particle is drawn, with its
// radius grown to carry the volume of the ones left out (renderer.cpp).
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };
flat out vec3 v_center;   // light view space

uniform int u_stride;

void main() {
  int i = gl_VertexID * u_stride;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  v_center = (u_light_view * vec4(world, 1.0)).xyz;
  gl_Position = u_light_proj * vec4(v_center, 1.0);
  gl_PointSize = u_misc.z;
}

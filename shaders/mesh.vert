#include "common.glsl"
// Solids and the ground: world-space triangles with a normal and a colour per vertex.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_color = a_color;
  gl_Position = u_proj * u_view * vec4(a_position, 1.0);
}

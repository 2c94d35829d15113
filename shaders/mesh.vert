#include "common.glsl"
// Solids and the ground: world-space triangles with a normal and a colour per vertex,
// and for solids the run's solid row that colours them by the wall pressure.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;
layout(location = 3) in int a_solid;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
flat out int v_solid;
void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_color = a_color;
  v_solid = a_solid;
  gl_Position = u_proj * u_view * vec4(a_position, 1.0);
}

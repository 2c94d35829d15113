#include "common.glsl"
// A spray particle (render/particle_classes.h) as a small point sprite of radius
// u_spray.z; they follow the water and foam in the particle buffer, from u_first.
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };
uniform int u_first;

flat out vec3 v_center;   // view space
flat out float v_radius_px;
flat out float v_size;     // gl_PointSize

void main() {
  int i = u_first + gl_VertexID;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  vec3 c = (u_view * vec4(world, 1.0)).xyz;
  v_center = c;
  gl_Position = u_proj * vec4(c, 1.0);
  if (-c.z < u_camera.x) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    gl_PointSize = 1.0;
    v_radius_px = 0.0;
    v_size = 1.0;
    return;
  }
  v_radius_px = u_spray.z * u_camera.z / -c.z;
  // At least 2 pixels across, so that a far drop stays a dot instead of flickering
  // between pixel centres.
  v_size = clamp(2.0 * v_radius_px + 1.0, 2.0, u_misc.y);
  gl_PointSize = v_size;
}

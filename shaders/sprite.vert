#include "common.glsl"
// A particle as a camera-facing square that covers its sphere's silhouette, made
// from gl_VertexID (six vertices per particle) and the positions in a storage buffer.
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };

flat out vec3 v_center;   // sphere centre, view space
out vec3 v_point;         // point on the square, view space

void main() {
  int i = gl_VertexID / 6;
  int corner = gl_VertexID % 6;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  vec3 c = (u_view * vec4(world, 1.0)).xyz;
  float r = u_camera.w;
  float dist = length(c);
  v_center = c;
  // The camera inside a sphere, or a sphere behind the near plane: nothing to draw.
  if (dist <= r * 1.001 || -c.z < u_camera.x) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    v_point = c;
    return;
  }
  // The tangent cone from the eye meets the plane through the centre, facing the
  // eye, in a circle of radius r * dist / sqrt(dist^2 - r^2).
  vec3 w = c / dist;
  vec3 helper = abs(w.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(helper, w));
  vec3 v = cross(w, u);
  float s = r * dist / sqrt(dist * dist - r * r);
  const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 k = corners[corner];
  vec3 q = c + s * (k.x * u + k.y * v);
  v_point = q;
  gl_Position = u_proj * vec4(q, 1.0);
}

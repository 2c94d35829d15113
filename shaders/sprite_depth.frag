#include "common.glsl"
// Fluid depth: the front of the sphere seen along the pixel's ray; hidden where a
// solid stands in front.
flat in vec3 v_center;
in vec3 v_point;
layout(binding = 0) uniform sampler2D t_scene_depth;
layout(location = 0) out float o_depth;

void main() {
  vec3 d = normalize(v_point);
  float r = u_camera.w;
  float b = dot(d, v_center);
  float disc = b * b - (dot(v_center, v_center) - r * r);
  if (disc < 0.0) discard;
  float t = b - sqrt(disc);
  vec3 hit = t * d;
  float z = window_depth(hit);
  if (z > texelFetch(t_scene_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
  gl_FragDepth = z;
  o_depth = -hit.z;
}

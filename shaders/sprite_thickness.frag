#include "common.glsl"
// Fluid thickness: the sphere's chord along the pixel's ray, cut where a solid stands,
// added up over all particles (additive blending).
flat in vec3 v_center;
in vec3 v_point;
layout(binding = 0) uniform sampler2D t_scene_depth;
layout(location = 0) out float o_thickness;

void main() {
  vec3 d = normalize(v_point);
  float r = u_camera.w;
  float b = dot(d, v_center);
  float disc = b * b - (dot(v_center, v_center) - r * r);
  if (disc < 0.0) discard;
  float h = sqrt(disc);
  float t_front = b - h, t_back = b + h;
  // Ray parameter of the scene surface behind this pixel.
  float scene = eye_distance(texelFetch(t_scene_depth, ivec2(gl_FragCoord.xy), 0).r);
  float t_scene = scene / max(-d.z, 1e-6);
  t_back = min(t_back, t_scene);
  if (t_back <= t_front) discard;
  o_thickness = (t_back - t_front) * u_ground.w;
}

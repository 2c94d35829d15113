#include "common.glsl"
// One pass for two layers of the fluid, per pixel of a particle's sprite:
//  0. eye distance of the sphere's front along the pixel's ray (blended with MIN:
//     the nearest sphere wins), unless a solid stands in front;
//  1. the sphere's chord along the ray, cut where a solid stands (blended with ADD:
//     the thickness of all the water on the ray), and in its second channel the
//     chords of the foam particles;
// and, through the depth buffer, the fluid mask (sprite.vert), so that later passes
// skip the other pixels.
flat in vec3 v_center;
flat in float v_foam;
layout(binding = 0) uniform sampler2D t_scene_depth;
layout(location = 0) out float o_depth;
layout(location = 1) out vec2 o_thickness;

void main() {
  vec3 d = normalize(view_position(gl_FragCoord.xy, 1.0));
  float r = u_camera.w;
  float b = dot(d, v_center);
  float disc = b * b - (dot(v_center, v_center) - r * r);
  if (disc < 0.0) discard;
  float h = sqrt(disc);
  float t_front = b - h, t_back = b + h;
  // Ray parameter of the scene surface behind this pixel.
  float scene = eye_distance(texelFetch(t_scene_depth, ivec2(gl_FragCoord.xy), 0).r);
  float t_scene = scene / max(-d.z, 1e-6);
  o_depth = t_front < t_scene ? -t_front * d.z : kNoFluid;
  float chord = max(min(t_back, t_scene) - t_front, 0.0) * u_ground.w;
  o_thickness = vec2(chord, chord * v_foam);
}

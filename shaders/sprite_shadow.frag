#include "common.glsl"
// Water seen from the sun: thickness along the light ray (added up) and the depth of
// the nearest water surface (blended with MIN), so that only what lies behind the
// water is shaded by it.
flat in vec3 v_center;
layout(location = 0) out float o_thickness;
layout(location = 1) out float o_front;

void main() {
  vec2 offset = gl_PointCoord * 2.0 - 1.0;
  float q = dot(offset, offset);
  if (q > 1.0) discard;
  float radius = u_misc.w;
  float half_chord = radius * sqrt(1.0 - q);
  o_thickness = 2.0 * half_chord * u_ground.w;
  vec4 clip = u_light_proj * vec4(v_center.xy + offset * radius, v_center.z + half_chord, 1.0);
  o_front = clip.z / clip.w * 0.5 + 0.5;
}

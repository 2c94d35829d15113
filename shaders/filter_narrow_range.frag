#include "common.glsl"
// One 1-D pass (along u_direction) of the narrow-range filter of Truong and Yuksel
// (2018) over the fluid's eye distance. A Gaussian whose screen radius follows the
// world-space radius u_filter.x, that only averages depths within a narrow range of
// the centre's:
//  - a sample nearer the eye than the range belongs to another layer in front: it is
//    left out, and so is its mirror sample on the other side, which keeps the
//    average of a sloped plane on the plane;
//  - a sample farther than the range (or no fluid at all) is clamped to the centre's
//    depth plus u_filter.w, so that the surface bends down smoothly at silhouettes
//    instead of flattening or bleeding into the background;
//  - a sample inside the range widens the range around itself, so that a steep but
//    continuous surface is followed outwards.
layout(binding = 0) uniform sampler2D t_depth;
uniform ivec2 u_direction;
layout(location = 0) out float o_depth;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(t_depth, 0) - 1;
  float d0 = texelFetch(t_depth, p, 0).r;
  if (!is_fluid(d0)) {
    o_depth = kNoFluid;
    return;
  }
  float radius_px = u_filter.x * u_camera.z / d0;
  int n = int(min(ceil(radius_px), u_filter.y));
  if (n < 1) {
    o_depth = d0;
    return;
  }
  float sigma = float(n) / 3.0;
  float two_sigma2 = 2.0 * sigma * sigma;
  float threshold = u_filter.z;
  float clamped = d0 + u_filter.w;
  // Range [near, far] of each side, widened as the walk goes outwards.
  vec2 near = vec2(d0 - threshold);
  vec2 far = vec2(d0 + threshold);
  float sum = d0, weight_sum = 1.0;
  for (int k = 1; k <= n; ++k) {
    float w = exp(-float(k * k) / two_sigma2);
    vec2 s = vec2(texelFetch(t_depth, clamp(p + k * u_direction, ivec2(0), last), 0).r,
                  texelFetch(t_depth, clamp(p - k * u_direction, ivec2(0), last), 0).r);
    vec2 weight = vec2(w);
    for (int side = 0; side < 2; ++side) {
      float v = s[side];  // no fluid reads as kNoFluid: infinitely far
      if (v < near[side]) {
        weight = vec2(0.0);
      } else if (v > far[side]) {
        v = clamped;
      } else {
        near[side] = min(near[side], v - threshold);
        far[side] = max(far[side], v + threshold);
      }
      s[side] = v;
    }
    sum += dot(s, weight);
    weight_sum += weight.x + weight.y;
  }
  o_depth = sum / weight_sum;
}

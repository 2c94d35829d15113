#include "common.glsl"
// The last pass of the narrow-range filter (Truong and Yuksel 2018): a small 2-D
// window after the two 1-D passes of filter_narrow_range.frag, which smooth well but
// leave streaks along silhouettes (each 1-D pass sees a silhouette from one side
// only). The same rules over point pairs mirrored about the centre: a sample nearer
// than the range leaves out itself and its mirror; a farther one, or no fluid, is
// clamped to the centre's depth plus u_filter.w.
layout(binding = 0) uniform sampler2D t_depth;
layout(location = 0) out float o_depth;

// Half side of the window (pixels): 7 x 7 samples.
const int kRadius = 3;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(t_depth, 0) - 1;
  float d0 = texelFetch(t_depth, p, 0).r;
  if (!is_fluid(d0)) {
    o_depth = kNoFluid;
    return;
  }
  float near = d0 - u_filter.z, far = d0 + u_filter.z;
  float clamped = d0 + u_filter.w;
  // sigma = kRadius / 2 pixels
  const float two_sigma2 = 2.0 * (0.5 * kRadius) * (0.5 * kRadius);
  float sum = d0, weight_sum = 1.0;
  // Half of the window (the other half are the mirrors): rows above the centre, and
  // the right half of the centre row.
  for (int j = 0; j <= kRadius; ++j)
    for (int i = -kRadius; i <= kRadius; ++i) {
      if (j == 0 && i <= 0) continue;
      ivec2 o = ivec2(i, j);
      float w = exp(-float(i * i + j * j) / two_sigma2);
      vec2 s = vec2(texelFetch(t_depth, clamp(p + o, ivec2(0), last), 0).r,
                    texelFetch(t_depth, clamp(p - o, ivec2(0), last), 0).r);
      if (s.x < near || s.y < near) continue;
      s = mix(s, vec2(clamped), greaterThan(s, vec2(far)));
      sum += w * (s.x + s.y);
      weight_sum += 2.0 * w;
    }
  o_depth = sum / weight_sum;
}

#include "common.glsl"
// One 1-D pass (along u_direction) of a bilateral filter over the fluid's eye
// distance: a Gaussian in screen space (radius from the world-space radius
// u_filter.x) times a Gaussian in depth of width u_filter.z; pixels without fluid
// are left out. The classic choice (van der Laan et al. 2009), kept to compare.
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
  float sigma = max(float(n), 1.0) / 3.0;
  float two_sigma2 = 2.0 * sigma * sigma;
  float two_range2 = 2.0 * u_filter.z * u_filter.z;
  float sum = d0, weight_sum = 1.0;
  for (int k = -n; k <= n; ++k) {
    if (k == 0) continue;
    float s = texelFetch(t_depth, clamp(p + k * u_direction, ivec2(0), last), 0).r;
    if (!is_fluid(s)) continue;
    float w = exp(-float(k * k) / two_sigma2) * exp(-(s - d0) * (s - d0) / two_range2);
    sum += s * w;
    weight_sum += w;
  }
  o_depth = sum / weight_sum;
}

#include "common.glsl"
// One 1-D pass (along u_direction) of a Gaussian over the thickness, about a particle
// diameter wide on screen: the sum of sphere chords is bumpy at the particle scale,
// and absorption would show every bump. Both channels: the water's and the foam's.
layout(binding = 0) uniform sampler2D t_thickness;
layout(binding = 1) uniform sampler2D t_depth;
uniform ivec2 u_direction;
layout(location = 0) out vec2 o_thickness;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(t_thickness, 0) - 1;
  vec2 t0 = texelFetch(t_thickness, p, 0).rg;
  float d = texelFetch(t_depth, p, 0).r;
  if (!is_fluid(d)) {
    o_thickness = t0;
    return;
  }
  // Two particle radii on screen at this depth, capped like the depth filter.
  float radius_px = 2.0 * u_camera.w * u_camera.z / d;
  int n = int(min(ceil(radius_px), u_filter.y));
  float sigma = max(float(n), 1.0) / 2.0;
  vec2 sum = t0;
  float weight_sum = 1.0;
  for (int k = 1; k <= n; ++k) {
    float w = exp(-float(k * k) / (2.0 * sigma * sigma));
    sum += w * (texelFetch(t_thickness, clamp(p + k * u_direction, ivec2(0), last), 0).rg +
                texelFetch(t_thickness, clamp(p - k * u_direction, ivec2(0), last), 0).rg);
    weight_sum += 2.0 * w;
  }
  o_thickness = sum / weight_sum;
}

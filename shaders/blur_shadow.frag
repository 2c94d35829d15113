// One 1-D pass (along u_direction) of a small Gaussian over the water's thickness
// as seen from the sun: the particles drawn into it are few and large, and a water
// shadow is soft anyway.
layout(binding = 0) uniform sampler2D t_source;
uniform ivec2 u_direction;
layout(location = 0) out float o_thickness;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(t_source, 0) - 1;
  // Weights of a Gaussian with sigma = 1.5 texels at offsets 0, 1, 2, 3.
  const float w[4] = float[4](0.266, 0.213, 0.110, 0.036);
  float sum = w[0] * texelFetch(t_source, p, 0).r;
  for (int k = 1; k < 4; ++k)
    sum += w[k] * (texelFetch(t_source, clamp(p + k * u_direction, ivec2(0), last), 0).r +
                   texelFetch(t_source, clamp(p - k * u_direction, ivec2(0), last), 0).r);
  o_thickness = sum;
}

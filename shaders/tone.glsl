// Linear colour to the 8-bit image.

// Identity below the knee, a soft shoulder above it, so bright glints saturate
// without changing the colours of the sky and the solids.
vec3 tone(vec3 c) {
  const float knee = 0.8;
  vec3 over = max(c - knee, 0.0);
  return min(c, vec3(knee)) + (1.0 - knee) * (1.0 - exp(-over / (1.0 - knee)));
}

vec3 encode_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

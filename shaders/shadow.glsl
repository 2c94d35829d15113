// Sunlight reaching a world point: the solids' shadow map (4 bilinear-filtered
// comparisons, so a 3 x 3 texel footprint) times
// the transmittance of the water between the point and the sun (Beer-Lambert).
layout(binding = 4) uniform sampler2DShadow t_shadow_depth;
layout(binding = 5) uniform sampler2D t_shadow_thickness;
layout(binding = 6) uniform sampler2D t_shadow_front;

vec3 sunlight(vec3 world, vec3 normal) {
  if (u_sky_color.w < 0.5) return vec3(1.0);
  // Offset along the normal by a texel or two against self-shadowing (acne).
  vec3 p = world + normal * (1.5 * u_ground.z);
  vec4 clip = u_light_proj * u_light_view * vec4(p, 1.0);
  vec3 s = clip.xyz / clip.w * 0.5 + 0.5;
  if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return vec3(1.0);
  vec2 texel = 1.0 / vec2(textureSize(t_shadow_depth, 0));
  float lit = 0.25 * (texture(t_shadow_depth, vec3(s.xy + vec2(-0.5, -0.5) * texel, s.z)) +
                      texture(t_shadow_depth, vec3(s.xy + vec2(0.5, -0.5) * texel, s.z)) +
                      texture(t_shadow_depth, vec3(s.xy + vec2(-0.5, 0.5) * texel, s.z)) +
                      texture(t_shadow_depth, vec3(s.xy + vec2(0.5, 0.5) * texel, s.z)));
  vec3 water = vec3(1.0);
  // Only water in front of the point shades it; the front is as bumpy as the
  // spheres drawn into it, so a water surface does not shade itself.
  float front = texture(t_shadow_front, s.xy).r + u_shadow.x;
  if (s.z > front) water = exp(-u_absorption.rgb * texture(t_shadow_thickness, s.xy).r);
  return lit * water;
}

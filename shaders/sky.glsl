// The sky: a gradient from the horizon to the zenith with the sun's disc and glow,
// and below the horizon the ground's tone fading into haze. Drawn as the background
// and reflected by the water.
vec3 sky(vec3 dir) {
  dir = normalize(dir);
  vec3 to_sun = -u_light_dir.xyz;
  vec3 sun = u_light_color.rgb * u_light_dir.w;
  float mu = max(dot(dir, to_sun), 0.0);
  vec3 c;
  if (dir.z >= 0.0) {
    c = mix(u_horizon_color.rgb, u_sky_color.rgb, pow(dir.z, 0.55));
    // Glow around the sun and its disc (about half a degree across).
    c += sun * (0.06 * pow(mu, 8.0) + 0.25 * pow(mu, 120.0));
    c += sun * 4.0 * smoothstep(0.99996, 0.99999, mu);
  } else {
    vec3 ground = u_ground_color.rgb * (u_light_color.w + 0.3 * u_light_dir.w * max(to_sun.z, 0.0));
    c = mix(u_horizon_color.rgb, ground, smoothstep(0.0, 0.25, -dir.z));
  }
  return c;
}

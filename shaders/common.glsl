// Uniforms shared by every pass of bw-render (libcore/render/renderer.cpp fills the
// matching C++ struct FrameUniforms; std140, so only vec4 and mat4 members).
layout(std140, binding = 0) uniform Frame {
  mat4 u_view;             // world -> view
  mat4 u_proj;             // view -> clip
  mat4 u_inv_view;         // view -> world
  mat4 u_light_view;       // world -> light view (orthographic sun)
  mat4 u_light_proj;       // light view -> light clip
  vec4 u_viewport;         // width, height, 1/width, 1/height
  vec4 u_camera;           // near, far, focal length in pixels, particle radius
  vec4 u_light_dir;        // direction the sunlight travels (world, unit), intensity
  vec4 u_light_color;      // rgb, ambient
  vec4 u_sky_color;        // rgb at the zenith, shadows on (1) or off (0)
  vec4 u_horizon_color;    // rgb at the horizon, fog distance (m)
  vec4 u_ground_color;     // rgb, checker tile (m)
  vec4 u_ground;           // height, enabled, shadow texel (m), thickness scale
  vec4 u_fluid_color;      // rgb, refraction strength
  vec4 u_absorption;       // rgb (1/m), specular strength
  vec4 u_camera_position;  // world xyz, view mode (0 shaded, 1 depth, 2 thickness, 3 normals)
  vec4 u_filter;           // world radius (m), max radius (pixels), range threshold (m), clamp (m)
  vec4 u_misc;             // guard band (pixels), largest point size, water shadow point size, its radius (m)
  vec4 u_shadow;           // water front bias (light depth units), unused x 3
  vec4 u_spray;            // foam strength, foam depth that saturates (m), spray radius (m), spray opacity
};

// Eye distance stored where a pixel shows no fluid (cleared to it; depth is blended
// with MIN, so any water in front replaces it).
const float kNoFluid = 1e30;
bool is_fluid(float d) { return d < 1e29; }

// Eye distance along the view axis of a window-space depth of the scene (perspective).
float eye_distance(float window_depth) {
  float n = u_camera.x, f = u_camera.y;
  float z_ndc = 2.0 * window_depth - 1.0;
  return 2.0 * n * f / (f + n - z_ndc * (f - n));
}

// View-space position of pixel `p` (window coordinates) at eye distance `d`.
vec3 view_position(vec2 p, float d) {
  vec2 ndc = p * u_viewport.zw * 2.0 - 1.0;
  return vec3(ndc.x / u_proj[0][0] * d, ndc.y / u_proj[1][1] * d, -d);
}

// Window-space depth of a view-space point.
float window_depth(vec3 view_point) {
  vec4 clip = u_proj * vec4(view_point, 1.0);
  return clip.z / clip.w * 0.5 + 0.5;
}

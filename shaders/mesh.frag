#include "common.glsl"
#include "shadow.glsl"
// Lambert shading under the sun and the sky, with shadows; the ground plane gets a
// filtered checkerboard and fades into the horizon's haze far away.
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
flat in int v_solid;
uniform int u_is_ground;
layout(location = 0) out vec4 o_color;

// Solids coloured by the wall pressure (libcore/render/wall_paint.h, whose
// PaintTable::value computes the same on the host): the particles that can colour a
// pixel, bucketed by a hash of their cell of edge u_paint_reach, and the colour map.
uniform int u_paint;              // 1: colour the solids by the wall pressure
uniform float u_paint_reach;      // R (m)
uniform uint u_paint_mask;        // buckets - 1
uniform vec2 u_paint_range;       // the values at the map's two ends (Pa)
uniform int u_paint_colors;       // entries of the colour map
layout(std430, binding = 3) readonly buffer PaintPoints { vec4 paint_points[]; };  // x, y, z, p
layout(std430, binding = 4) readonly buffer PaintCells { ivec4 paint_cells[]; };   // cell x, y, z, solid
layout(std430, binding = 5) readonly buffer PaintStart { uint paint_start[]; };
layout(std430, binding = 6) readonly buffer PaintColors { vec4 paint_colors[]; };  // linear RGB

uint paint_bucket(ivec3 c) {
  return ((uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u)) & u_paint_mask;
}

// p(x) = sum w_j p_j / sum w_j over the solid's particles within R, w = (1 - r^2/R^2)^3.
float wall_pressure(vec3 x, int solid) {
  ivec3 c = ivec3(floor(x / u_paint_reach));
  float r2 = u_paint_reach * u_paint_reach;
  float sum = 0.0, weight = 0.0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 cell = c + ivec3(dx, dy, dz);
        uint b = paint_bucket(cell);
        for (uint j = paint_start[b]; j < paint_start[b + 1u]; ++j) {
          if (paint_cells[j] != ivec4(cell, solid)) continue;
          vec3 d = paint_points[j].xyz - x;
          float d2 = dot(d, d);
          if (d2 >= r2) continue;
          float s = 1.0 - d2 / r2;
          float w = s * s * s;
          sum += w * paint_points[j].w;
          weight += w;
        }
      }
  return weight > 0.0 ? sum / weight : 0.0;
}

vec3 paint_color(float value) {
  float t = clamp((value - u_paint_range.x) / (u_paint_range.y - u_paint_range.x), 0.0, 1.0);
  float at = t * float(u_paint_colors - 1);
  int i = min(int(at), u_paint_colors - 2);
  return mix(paint_colors[i].rgb, paint_colors[i + 1].rgb, at - float(i));
}

// Fraction of "dark" squares of a checkerboard of period 2 over the pixel footprint
// (box-filtered, so distant squares blend to grey instead of flickering).
float checker(vec2 p) {
  vec2 w = max(fwidth(p), vec2(1e-5));
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) - abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_camera_position.xyz - v_world);
  if (dot(n, to_eye) < 0.0) n = -n;  // open meshes are seen from both sides
  if (u_paint == 1 && u_is_ground == 0) {
    // The map's colour where a face looks at the camera (the colour bar's), darker as
    // it turns away; no sun and no shadow, which would change what the colour says.
    o_color = vec4(paint_color(wall_pressure(v_world, v_solid)) * mix(0.55, 1.0, dot(n, to_eye)), 1.0);
    return;
  }
  vec3 albedo = v_color;
  if (u_is_ground == 1) albedo *= mix(1.0, 0.82, checker(v_world.xy / u_ground_color.w));
  vec3 to_sun = -u_light_dir.xyz;
  vec3 sun = u_light_color.rgb * u_light_dir.w * max(dot(n, to_sun), 0.0) * sunlight(v_world, n);
  // Sky light: full from above, a quarter from below (light bounced off the ground).
  float sky_amount = mix(0.25, 1.0, 0.5 + 0.5 * n.z);
  vec3 ambient = u_light_color.w * sky_amount * mix(u_horizon_color.rgb, vec3(1.0), 0.5);
  vec3 c = albedo * (sun + ambient);
  if (u_is_ground == 1) {
    float fog = 1.0 - exp(-length(v_world - u_camera_position.xyz) / u_horizon_color.w);
    c = mix(c, u_horizon_color.rgb, fog * fog);
  }
  o_color = vec4(c, 1.0);
}

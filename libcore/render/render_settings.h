// What bw-render draws with: camera, light and the look of water, solids and ground.
//
// The scene file (TOML) may hold the tables [camera], [light] and [render]; this is
// the only code that reads them (the simulator's scene parser ignores them, and this
// parser ignores every other table). Unknown keys inside the three tables are errors
// naming the key's path. docs/rendering.md documents every key.
//
// Units: metres, degrees for angles, colours as linear RGB in [0, 1], absorption in
// 1/m. Scenes are z-up.
#pragma once

#include <optional>
#include <string>

#include "common/geometry.h"
#include "render/camera_path.h"

namespace bw::render {

struct Light {
  // Direction in which the sun's light travels (from the sun into the scene).
  Vec3d direction = Vec3d(-0.55, 0.45, -0.75);
  Vec3d color = Vec3d(1.0, 0.95, 0.88);
  double intensity = 1.7;    // sun radiance scale
  double ambient = 0.4;      // sky light on surfaces facing up
  bool shadows = true;       // solids and water cast shadows on the ground and solids
};

enum class Filter { kNarrowRange, kBilateral, kNone };

// "narrow-range", "bilateral", "none"; std::nullopt for anything else.
std::optional<Filter> parse_filter(const std::string& name);
const char* filter_name(Filter filter);

// What the image shows: the shaded picture or one of the intermediate layers of the
// fluid (for inspecting the smoothing).
enum class View { kShaded, kDepth, kThickness, kNormals };
std::optional<View> parse_view(const std::string& name);

// What colours the solids: their own colours, or the pressure on their faces (the
// frames' wall_pressure field; render/wall_paint.h). "shaded", "wall_pressure".
enum class SolidColoring { kShaded, kWallPressure };
std::optional<SolidColoring> parse_solid_coloring(const std::string& name);
const char* solid_coloring_name(SolidColoring coloring);

// A value range [min, max] (Pa for a pressure).
struct ValueRange {
  double min = 0, max = 0;
};

struct RenderSettings {
  int width = 1280;
  int height = 720;

  // The camera, fixed or moving over time; empty means "frame the scene" (see
  // fit_camera in camera.h).
  std::optional<CameraPath> camera;
  // [camera] track: the name of a body (a dynamic or breakable solid, or a fragment,
  // "plate.12") whose centre of mass the camera looks at in each frame; empty: the
  // camera's own target.
  std::string camera_track;
  Light light;

  // Particles are drawn as spheres of this radius (m). 0: particle_radius_factor
  // times the particle spacing estimated from the first frame of the sequence.
  double particle_radius = 0;
  double particle_radius_factor = 0.8;

  // Water: Beer-Lambert absorption per metre of thickness (red, green, blue), and the
  // colour of the light scattered back inside the water.
  Vec3d fluid_color = Vec3d(0.02, 0.14, 0.2);
  Vec3d absorption = Vec3d(4.0, 1.3, 0.8);
  double refraction = 0.35;        // screen-space offset of refracted rays (x thickness^0.5)
  double specular = 1.0;           // sun glint strength

  // Depth smoothing (method.md 7.3).
  Filter filter = Filter::kNarrowRange;
  double filter_radius = 6.0;      // world-space kernel radius in particle radii
  int filter_max_pixels = 24;      // cap on the kernel radius on screen

  // Spray and foam (render/particle_classes.h): a particle with at most
  // spray_neighbours others within two spacings is spray, drawn as a soft white
  // sprite of spray_size spacings' radius at spray_opacity, and left out of the
  // water's surface; one with at most foam_neighbours is water tinted white by foam
  // (0: no tint, 1: white where a particle's depth of foam is on the ray).
  bool spray = true;
  int spray_neighbours = 3;
  int foam_neighbours = 8;
  double spray_size = 0.5;
  double spray_opacity = 0.85;
  double foam = 0.3;

  // Sky (background and what water reflects): colour at the zenith and the horizon.
  Vec3d sky_color = Vec3d(0.06, 0.18, 0.48);
  Vec3d horizon_color = Vec3d(0.5, 0.64, 0.8);

  // Ground plane z = ground_height (empty: just below the lowest particle or solid of
  // the first frame), a checkerboard of ground_tile metres.
  bool ground = true;
  std::optional<double> ground_height;
  double ground_tile = 0.25;
  Vec3d ground_color = Vec3d(0.32, 0.3, 0.27);

  Vec3d solid_color = Vec3d(0.45, 0.44, 0.42);    // static solids
  Vec3d body_color = Vec3d(0.5, 0.22, 0.13);     // dynamic solids and fragments

  View view = View::kShaded;

  // The solids coloured by the pressure on their faces, on a colour scale over
  // pressure_range (empty: from the frames, wall_paint.h's wall_pressure_range), with
  // a colour bar when `legend`. Without the water (water = false) nothing hides them.
  SolidColoring solids = SolidColoring::kShaded;
  std::optional<ValueRange> pressure_range;
  bool legend = true;
  bool water = true;

  // Throws InputError "<where>: <key>: <problem>" for a value out of range.
  void validate(const std::string& where = "settings") const;
};

// Reads [camera], [light] and [render] of a scene file over the defaults. Other tables
// are ignored. Throws InputError naming the file and the key path ("scene.toml:
// render.width: ...") for a missing file, a TOML syntax error, an unknown key inside
// the three tables or a value of the wrong type or out of range.
RenderSettings load_render_settings(const std::string& scene_path);

// The same from TOML text; `name` is used in messages.
RenderSettings parse_render_settings(const std::string& toml_text, const std::string& name);

}  // namespace bw::render

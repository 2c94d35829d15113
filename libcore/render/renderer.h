// Screen-space fluid rendering (method.md section 7; van der Laan et al. 2009):
//   0. shadow maps from the sun: the solids' depth, and the water's thickness and
//      nearest surface (a strided subset of the particles carrying the same volume,
//      blurred), so that water casts tinted, partial shadows;
//   1. scene: ground plane and solid meshes, lit and shadowed, then the sky;
//   2. fluid depth and thickness (and the foam particles' share of it) in one pass
//      of point sprites: per pixel the ray meets the particle's sphere; the nearest
//      front wins (MIN blending) and the chords add up (ADD blending), cut where a solid stands; the pass also marks
//      a fluid mask so that the passes below only run on fluid pixels;
//   3. depth smoothing: the narrow-range filter (Truong and Yuksel 2018), a
//      bilateral filter, or none; the thickness is blurred over a particle diameter;
//      view-space normals from depth differences;
//   4. composite: Fresnel reflection of the sky, refraction through the thickness
//      with Beer-Lambert absorption, light scattered in the water, a specular glint,
//      over the scene, whitened where foam is on the ray; tone shoulder and sRGB
//      encoding;
//   5. spray: particles with few neighbours (render/particle_classes.h), left out
//      of passes 0 to 4, drawn over the image as small, soft, diffusely lit white
//      sprites, hidden behind the solids and the smoothed water surface.
// Every layer has a guard band around the image; the image is read back with
// glReadPixels. The same input gives the same bytes on the same driver.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_context.h"
#include "render/image.h"
#include "render/render_settings.h"
#include "render/solids.h"
#include "render/wall_paint.h"

namespace bw::render {

struct RenderInput {
  // Fluid particle positions, `count` entries each (world, metres).
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  std::size_t count = 0;
  const TriangleSoup* solids = nullptr;   // may be null
  // With settings.solids = wall_pressure: the frame's table and the colour scale.
  const PaintTable* paint = nullptr;
  ColorScale paint_scale;
  Camera camera;
  double particle_radius = 0.01;          // sphere radius (m), > 0
  // Thickness is scaled by (particle volume) / (sphere volume) so that a block of
  // water measures its real depth: pass the particle spacing (m); 0 means no scaling.
  double particle_spacing = 0;
  double ground_height = 0;               // used when settings.ground
};

// The fluid's intermediate layers of the last render, rows from the top, for tests
// and inspection: eye distance along the view axis (0 where there is no fluid)
// before and after smoothing, thickness (m), and view-space normals (3 per pixel,
// zero where there is no fluid).
struct FluidLayers {
  int width = 0, height = 0;
  std::vector<float> depth, smoothed_depth, thickness, normals;
};

class Renderer {
 public:
  // Compiles the shaders and allocates the framebuffers for settings.width x
  // settings.height. Needs a current context. Throws RunError with the compiler's
  // log when a shader does not build.
  Renderer(GlContext& context, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  Image render(const RenderInput& input);
  FluidLayers read_fluid_layers() const;

  // With profiling on, every pass waits for the device (glFinish) and its wall time
  // is kept: names and milliseconds of the last render, in order. Off by default,
  // since waiting costs time on a GPU.
  void set_profiling(bool on);
  std::vector<std::pair<std::string, double>> pass_times() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::render

// Rendering benchmark: ms per frame at 1280 x 720 for a synthetic splash (a pool, a
// falling ball and a wall) of 30 k, 120 k and 500 k particles, on whatever EGL
// device the machine offers (llvmpipe without a GPU). Prints figures, asserts
// nothing. Optional arguments: particle counts to run instead of the default ones.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "common/terminal.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/particle_spacing.h"
#include "render/renderer.h"
#include "render/solids.h"
#include "synthetic.h"
#include "test_support.h"

namespace br = bw::render;

int main(int argc, char** argv) {
  std::vector<std::size_t> counts = {30000, 120000, 500000};
  if (argc > 1) {
    counts.clear();
    for (int i = 1; i < argc; ++i) counts.push_back(std::strtoull(argv[i], nullptr, 10));
  }
  // Frames rendered per count after one warm-up frame.
  constexpr int kRepeats = 3;
  bw::test::TempDir dir;
  br::test::write_wall_run(dir.path());
  const br::SolidScene solids = br::SolidScene::load({dir.file("run.h5"), ""}, {});
  const br::TriangleSoup soup = solids.place({});

  auto context = br::GlContext::create();
  std::printf("renderer: %s (%s), %s\n", context->renderer().c_str(), context->display().c_str(),
              context->version().c_str());
  br::RenderSettings settings;  // 1280 x 720, narrow-range filter, shadows
  br::Renderer renderer(*context, settings);

  for (std::size_t count : counts) {
    const bw::FrameData f = br::test::splash_frame(count);
    const double spacing = br::estimate_particle_spacing(f.x.data(), f.y.data(), f.z.data(), f.fluid_count());
    br::RenderInput in;
    in.x = f.x.data(), in.y = f.y.data(), in.z = f.z.data(), in.count = f.fluid_count();
    in.solids = &soup;
    in.camera.position = bw::Vec3d(-1.7, -3.1, 1.9);
    in.camera.target = bw::Vec3d(0, -0.1, 0.45);
    in.particle_radius = 0.8 * spacing;
    in.particle_spacing = spacing;
    in.ground_height = 0;
    renderer.render(in);  // warm-up: first use of every pass
    bw::Stopwatch clock;
    std::vector<std::uint8_t> png;
    double png_seconds = 0;
    for (int k = 0; k < kRepeats; ++k) {
      const br::Image image = renderer.render(in);
      bw::Stopwatch png_clock;
      png = br::encode_png(image);
      png_seconds += png_clock.seconds();
    }
    const double ms = 1000 * clock.seconds() / kRepeats;
    renderer.set_profiling(true);
    renderer.render(in);
    renderer.set_profiling(false);
    std::printf("%7zu particles (spacing %.4f m): %7.1f ms per frame (of which PNG %5.1f ms)  [", f.fluid_count(),
                spacing, ms, 1000 * png_seconds / kRepeats);
    for (const auto& [name, t] : renderer.pass_times()) std::printf(" %s %.0f;", name.c_str(), t);
    std::printf(" ]\n");
    std::fflush(stdout);
  }
  return 0;
}

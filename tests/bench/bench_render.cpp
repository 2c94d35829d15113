// Rendering benchmark: ms per frame (drawing, reading back and PNG encoding) at 1280
// x 720 for a synthetic splash (a pool in a tank, a falling ball and a wall) of 30 k, 120 k and 500 k particles, on whatever EGL
// device the machine offers (llvmpipe without a GPU). Prints figures, asserts
// nothing. Optional arguments: particle counts to run instead of the default ones.
//
//   build/tests/bench/bench-render
//   build/tests/bench/bench-render 1000000 --csv render.csv --device 0
#include <cstdio>
#include <ctime>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/tool.h"
#include "common/atomic_file.h"
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
  CLI::App app{"Rendering benchmark: ms per frame at 1280 x 720 for a synthetic splash; prints figures, asserts "
               "nothing.",
               "bench-render"};
  bw::cli::setup(app,
                 "  bench-render\n"
                 "  bench-render 1000000 --csv render.csv\n"
                 "  bench-render 30000 120000 --device 1\n");
  std::vector<std::size_t> counts = {30000, 120000, 500000};
  int device = -1;
  std::string csv;
  app.add_option("counts", counts, "Particle counts to render (default 30000 120000 500000)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  app.add_option("--device", device, "EGL device index (default: the first that offers OpenGL 4.5, as bw-render)")
      ->check(bw::cli::kNonNegative);
  app.add_option("--csv", csv, "Also write one CSV row per count to this file");
  return bw::cli::run(app, argc, argv, [&]() -> int {
    // Frames rendered per count after one warm-up frame; the fastest is reported (the
    // machine is shared: the others measure the neighbours), the median beside it.
    constexpr int kRepeats = 5;
    bw::test::TempDir dir;
    br::test::write_wall_run(dir.path(), bw::Vec3d::Zero(), true);
    const br::SolidScene solids = br::SolidScene::load({dir.file("run.h5"), ""}, {});
    const br::TriangleSoup soup = solids.place({});

    auto context = br::GlContext::create(device);
    std::printf("renderer: %s (%s), %s\n", context->renderer().c_str(), context->display().c_str(),
                context->version().c_str());
    br::RenderSettings settings;  // 1280 x 720, narrow-range filter, shadows
    br::Renderer renderer(*context, settings);

    std::string rows = "renderer,particles,ms_best,ms_median,draw_ms_best,png_ms_best,cpu_ms\n";
    std::string renderer_name = context->renderer();
    std::replace(renderer_name.begin(), renderer_name.end(), ',', ';');
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
      std::vector<double> ms, png_ms, draw_ms;
      const std::clock_t cpu_start = std::clock();
      for (int k = 0; k < kRepeats; ++k) {
        bw::Stopwatch clock;
        const br::Image image = renderer.render(in);
        const double render_s = clock.seconds();
        const std::vector<std::uint8_t> png = br::encode_png(image);
        ms.push_back(1000 * clock.seconds());
        png_ms.push_back(1000 * (clock.seconds() - render_s));
        draw_ms.push_back(1000 * render_s);
      }
      // Processor time of all the process's threads (the driver's too): what a frame
      // costs whatever else the machine runs.
      const double cpu_ms = 1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / kRepeats;
      std::sort(ms.begin(), ms.end());
      std::sort(png_ms.begin(), png_ms.end());
      std::sort(draw_ms.begin(), draw_ms.end());
      rows += fmt::format("{},{},{:.2f},{:.2f},{:.2f},{:.2f},{:.1f}\n", renderer_name, f.fluid_count(), ms.front(),
                          ms[ms.size() / 2], draw_ms.front(), png_ms.front(), cpu_ms);
      renderer.set_profiling(true);
      renderer.render(in);
      renderer.set_profiling(false);
      std::printf("%7zu particles (spacing %.4f m): %6.1f ms per frame (median %.1f; CPU %.0f ms; drawing and "
                  "reading back %.1f ms, PNG %.1f ms)  [",
                  f.fluid_count(), spacing, ms.front(), ms[ms.size() / 2], cpu_ms, draw_ms.front(), png_ms.front());
      for (const auto& [name, t] : renderer.pass_times()) std::printf(" %s %.0f;", name.c_str(), t);
      std::printf(" ]\n");
      std::fflush(stdout);
    }
    if (!csv.empty()) bw::write_file_atomically(csv, rows.data(), rows.size());
    return bw::kExitOk;
  });
}

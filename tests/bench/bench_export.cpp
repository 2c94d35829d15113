// Export benchmark: one frame of water to VDB (level set, smoothing, the .vdb file)
// and, beside it, to a mesh, for a synthetic splash (tests/render/synthetic.h) of
// 100 k particles with bw-export's defaults (radius = spacing, voxel = radius / 2,
// one smoothing pass), on every core OpenVDB's TBB finds. Prints figures, asserts
// nothing. Optional arguments: particle counts to run instead.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <thread>
#include <algorithm>
#include <vector>

#include "common/terminal.h"
#include "export/water.h"
#include "synthetic.h"
#include "test_support.h"

namespace ex = bw::exporter;

int main(int argc, char** argv) {
  std::vector<std::size_t> counts = {100000};
  if (argc > 1) {
    counts.clear();
    for (int i = 1; i < argc; ++i) counts.push_back(std::strtoull(argv[i], nullptr, 10));
  }
  // Repeats after a warm-up; the fastest is reported (the machine is shared), the
  // median beside it.
  constexpr int kRepeats = 3;
  bw::test::TempDir dir;
  std::printf("cores: %u\n", std::thread::hardware_concurrency());
  for (std::size_t count : counts) {
    const bw::FrameData f = bw::render::test::splash_frame(count);
    // The splash's spacing (synthetic.cpp): its volume over its particle count.
    const double volume = 2.0 * 1.2 * 0.25 + 4.0 / 3.0 * 3.14159265358979 * 0.027;
    ex::WaterOptions options;
    options.spacing = std::cbrt(volume / static_cast<double>(count));
    options.resolve("bench");
    const std::string path = dir.file("water.vdb");
    auto once = [&] {
      ex::WaterSurface s = ex::WaterSurface::build(f.x.data(), f.y.data(), f.z.data(), f.fluid_count(), options);
      s.write_vdb(path, false);
      return s;
    };
    once();  // warm-up: OpenVDB's registries, TBB's threads
    std::vector<double> total, build;
    std::size_t voxels = 0;
    const std::clock_t cpu_start = std::clock();
    for (int k = 0; k < kRepeats; ++k) {
      bw::Stopwatch clock;
      const ex::WaterSurface s = once();
      total.push_back(clock.seconds());
      build.push_back(s.stats().seconds);
      voxels = s.stats().active_voxels;
    }
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / kRepeats;
    const ex::WaterSurface s = ex::WaterSurface::build(f.x.data(), f.y.data(), f.z.data(), f.fluid_count(), options);
    bw::Stopwatch mesh_clock;
    const bw::TriMesh mesh = s.mesh();
    const double mesh_s = mesh_clock.seconds();
    std::sort(total.begin(), total.end());
    std::sort(build.begin(), build.end());
    std::printf(
        "%7zu particles (spacing %.4f m, voxel %.4f m): VDB %.2f s per frame (median %.2f; level set %.2f s; CPU "
        "%.2f s), %zu voxels, %.1f MB; mesh %.2f s, %zu triangles\n",
        f.fluid_count(), options.spacing, options.voxel, total.front(), total[total.size() / 2], build.front(), cpu,
        voxels, static_cast<double>(std::filesystem::file_size(path)) / 1e6, mesh_s, mesh.triangles.size());
    std::fflush(stdout);
  }
  return 0;
}

#include "rigid_fixtures.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "compute/device.h"
#include "io/particles_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "scene/scene.h"

namespace bw::test {

void write_box(const std::string& path, const Vec3d& size, double spacing, bool volume) {
  SampledSolid solid = sample::sample_mesh(mesh::box(Vec3d::Zero(), size), {spacing, volume, "box", 1.0});
  write_particles(solid, path, "rigid test");
}

void write_open_tank(const std::string& path, const Vec3d& inner, double wall, double spacing) {
  SampledSolid solid = sample::sample_mesh(mesh::open_box(Vec3d::Zero(), inner, wall), {spacing, false, "tank", 1.0});
  write_particles(solid, path, "rigid test");
}

void write_pool(const std::string& dir, double spacing, double density, double end, double lift) {
  write_open_tank(dir + "/tank.h5", {kPoolTank, kPoolTank, 0.2}, 0.03, spacing);
  write_box(dir + "/box.h5", {kPoolWidth, kPoolWidth, kPoolHeight}, spacing);
  const double corner = 0.5 * (kPoolTank - kPoolWidth);
  std::ofstream(dir + "/pool.toml") << fmt::format(R"(
spacing = {}
[time]
end = {}
[domain]
min = [-0.04, -0.04, -0.04]
max = [0.28, 0.28, 0.24]
[fluid]
mu = 0.05
[[fluid.block]]
min = [0, 0, 0]
max = [{}, {}, {}]
[[solid]]
particles = "tank.h5"
[[solid]]
particles = "box.h5"
dynamic = true
density = {}
translation = [{}, {}, {}]
)",
                                                   spacing, end, kPoolTank, kPoolTank, kPoolDepth, density, corner,
                                                   corner, kPoolDepth + lift);
}

double pool_level(sim::Solver& solver, double spacing) {
  const FrameData d = solver.frame(FrameFields{}, 0);
  const int n = static_cast<int>(std::lround(kPoolTank / spacing));
  std::vector<double> top(static_cast<std::size_t>(n * n), -1.0);
  for (std::size_t i = 0; i < d.fluid_count(); ++i) {
    const int cx = std::clamp(static_cast<int>(d.x[i] / spacing), 0, n - 1);
    const int cy = std::clamp(static_cast<int>(d.y[i] / spacing), 0, n - 1);
    double& t = top[static_cast<std::size_t>(cy * n + cx)];
    t = std::max(t, double(d.z[i]));
  }
  double sum = 0;
  int count = 0;
  for (int cy = 0; cy < n; ++cy)
    for (int cx = 0; cx < n; ++cx) {
      const double t = top[static_cast<std::size_t>(cy * n + cx)];
      if (std::min({cx, cy, n - 1 - cx, n - 1 - cy}) < 3 && t >= 0) sum += t, ++count;
    }
  return sum / count + 0.5 * spacing;
}

sim::Setup prepare_file(const std::string& scene_path) {
  const scene::Scene scene = scene::load_scene(scene_path);
  return sim::prepare(scene, scene.time.end);
}

compute::Context& shared_context() {
  static compute::Context context(compute::choose_device("auto"));
  return context;
}

}  // namespace bw::test

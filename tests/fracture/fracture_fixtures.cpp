#include "fracture_fixtures.h"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "compute/device.h"
#include "io/particles_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "scene/scene.h"
#include "test_support.h"

namespace bw::test {

void write_fracture_solids(const std::string& folder, bool wall_voxels) {
  SampledSolid floor = sample::sample_mesh(mesh::box(Vec3d(-0.02, -0.02, -0.06), Vec3d(0.5, 0.34, 0.0)),
                                           {kWallSpacing, false, "floor", 1.0});
  write_particles(floor, folder + "/floor.h5", "fracture test");
  SampledSolid wall = sample::sample_mesh(mesh::box(Vec3d::Zero(), Vec3d(0.06, 0.3, 0.3)),
                                          {kWallSpacing, wall_voxels, "wall", 1.0});
  write_particles(wall, folder + "/wall.h5", "fracture test");
}

std::string fracture_scene(double speed, double frc, double end, const std::string& extra, double gap) {
  const double x1 = 0.3 - gap;
  return fmt::format(R"(spacing = 0.02
[time]
end = {}
frame_rate = 100
[domain]
min = [-0.02, -0.02, -0.06]
max = [0.5, 0.34, 0.4]
[[fluid.block]]
min = [{}, 0.08, 0.08]
max = [{}, 0.22, 0.2]
velocity = [{}, 0, 0]
[[solid]]
particles = "floor.h5"
[[solid]]
name = "wall"
particles = "wall.h5"
translation = [0.3, 0.02, 0]
breakable = true
frc = {}
{}
)",
                     end, x1 - 0.12, x1, speed, frc, extra);
}

Vec3d impact_point() { return Vec3d(0.3, 0.15, 0.14); }

sim::Setup prepare_text(const std::string& folder, const std::string& text) {
  const std::string path = folder + "/scene.toml";
  std::ofstream(path) << text;
  const scene::Scene scene = scene::load_scene(path);
  return sim::prepare(scene, scene.time.end);
}

compute::Context& shared_context() {
  static compute::Context context(compute::choose_device("auto"));
  return context;
}

FractureOutcome run_fracture_scene(const std::string& text, double end) {
  TempDir dir;
  write_fracture_solids(dir.file(""));
  sim::Solver solver(prepare_text(dir.file(""), text), shared_context());
  FractureOutcome out;
  while (solver.time() < end) {
    solver.step(end);
    std::int64_t active = 0;
    for (int b = 0; b < solver.body_count(); ++b) active += solver.body_info(b).active ? 1 : 0;
    out.most_active = std::max(out.most_active, active);
    if (out.first < 0 && !solver.fracture_events().empty()) out.first = solver.time();
  }
  out.events = solver.fracture_events();
  for (int b = 0; b < solver.body_count(); ++b) {
    out.infos.push_back(solver.body_info(b));
    out.masses.push_back(solver.body(b).mass());
  }
  out.states = solver.body_states();
  return out;
}

std::size_t fragments(const FractureOutcome& o) {
  std::size_t n = 0;
  for (const sim::BodyInfo& i : o.infos) n += i.active && i.parent >= 0 ? 1 : 0;
  return n;
}

}  // namespace bw::test

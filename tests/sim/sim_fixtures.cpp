#include "sim_fixtures.h"

#include "compute/device.h"
#include "io/particles_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "scene/scene.h"

namespace bw::test {

Vec3d tank_size(const Eigen::Vector3i& n, double spacing) { return (n.cast<double>().array() + 0.5).matrix() * spacing; }

void write_tank(const std::string& path, const Eigen::Vector3i& n, double spacing) {
  TriMesh box = mesh::box(Vec3d::Zero(), tank_size(n, spacing));
  SampledSolid solid = sample::sample_mesh(std::move(box), {spacing, false, "tank", 1.0});
  write_particles(solid, path, "sim test");
}

void write_thick_tank(const std::string& path, const Eigen::Vector3i& n, double spacing, double thickness) {
  TriMesh tank = mesh::sealed_box(Vec3d::Zero(), n.cast<double>() * spacing, thickness);
  SampledSolid solid = sample::sample_mesh(std::move(tank), {spacing, false, "thick tank", 1.0});
  write_particles(solid, path, "sim test");
}

void write_block(const std::string& path, const Vec3d& lo, const Vec3d& hi, double spacing, bool volume) {
  SampledSolid solid = sample::sample_mesh(mesh::box(lo, hi), {spacing, volume, "block", 1.0});
  write_particles(solid, path, "sim test");
}

sim::RunSummary run_scene(const std::string& scene_path, const std::string& output, bool quiet) {
  const scene::Scene scene = scene::load_scene(scene_path);
  sim::RunOptions options;
  options.output = output;
  options.progress = !quiet;
  sim::Simulation simulation(scene, compute::choose_device("auto"), options);
  return simulation.run();
}

}  // namespace bw::test

#include "rigid_fixtures.h"

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

sim::Setup prepare_file(const std::string& scene_path) {
  const scene::Scene scene = scene::load_scene(scene_path);
  return sim::prepare(scene, scene.time.end);
}

compute::Context& shared_context() {
  static compute::Context context(compute::choose_device("auto"));
  return context;
}

}  // namespace bw::test

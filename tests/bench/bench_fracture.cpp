// Fracture benchmark: one fracture event in the solver (docs/performance.md) for a
// solid of 100 k voxels (a breakable slab of 100 x 100 x 10 voxels at 1 cm standing
// on a floor) and 100 seeds: the seed choice among the particles over their binding
// energy, then Solver::break_body, the path the energy criterion takes (the nearest
// seed of every voxel on the device, the cells' components, the fragments' particles
// and mass, their binding energies, the new bodies and the event), and the extra cost
// of the next step (the new particles' upload, their boundary sort and Psi_b). Prints
// figures, asserts nothing.
//   bench-fracture [SEEDS [DEVICE]]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include <fmt/format.h>

#include "common/terminal.h"
#include "compute/context.h"
#include "compute/device.h"
#include "fracture/fracture.h"
#include "io/particles_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "scene/scene.h"
#include "sim/setup.h"
#include "sim/solver.h"
#include "test_support.h"

namespace {

// Mean wall time of `count` steps (s).
double time_steps(bw::sim::Solver& solver, int count) {
  bw::Stopwatch clock;
  for (int k = 0; k < count; ++k) solver.step(solver.time() + 1.0);
  return clock.seconds() / count;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bw;
  const std::size_t nseeds = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100;
  const std::string device = argc > 2 ? argv[2] : "auto";
  constexpr double s = 0.01;
  test::TempDir dir;
  write_particles(sample::sample_mesh(mesh::box(Vec3d::Zero(), Vec3d(1, 1, 0.1)), {s, true, "slab", 1.0}),
                  dir.file("slab.h5"), "bench-fracture");
  write_particles(sample::sample_mesh(mesh::box(Vec3d(-0.05, -0.05, -0.05), Vec3d(1.05, 1.05, 0)), {s, false, "floor", 1.0}),
                  dir.file("floor.h5"), "bench-fracture");
  std::ofstream(dir.file("scene.toml")) << R"(spacing = 0.01
[time]
end = 1
[domain]
min = [-0.1, -0.1, -0.1]
max = [1.1, 1.1, 0.3]
[fracture]
max_chunks = 1000
[[solid]]
particles = "floor.h5"
[[solid]]
particles = "slab.h5"
breakable = true
)";
  const scene::Scene scene = scene::load_scene(dir.file("scene.toml"));
  const sim::Setup setup = sim::prepare(scene, scene.time.end);
  compute::Context context(compute::choose_device(device));
  const fracture::Piece piece = sim::breakable_piece(setup.bodies.at(0));

  // Every particle of the top face over its binding energy, the strongest near one
  // corner (an impact there).
  std::mt19937 rng(7);
  std::vector<fracture::Candidate> candidates;
  std::int32_t highest = piece.particle_cells.front()[2];
  for (const CellIndex& c : piece.particle_cells) highest = std::max(highest, c[2]);
  for (std::size_t p = 0; p < piece.particles.size(); ++p)
    if (piece.particle_cells[p][2] == highest)
      candidates.push_back({static_cast<std::int32_t>(p), 1.0 + 10.0 / (1.0 + piece.particles[p].head<2>().norm() * 10) +
                                                               std::uniform_real_distribution<double>(0, 0.1)(rng)});

  // The same event on a fresh solver, `kRuns` times; the first also pays what a device
  // compiles at its first launches.
  constexpr int kRuns = 6;
  struct Run {
    double seeds, partition, fragments, bonds, bodies, breaking, first_step, step, event;
  };
  std::vector<Run> runs;
  int fragments = 0;
  std::size_t particles = 0, seed_count = 0;
  std::int64_t host_decided = 0;
  for (int r = 0; r < kRuns; ++r) {
    sim::Solver solver(setup, context);
    time_steps(solver, 2);
    Stopwatch clock;
    const std::vector<std::int32_t> chosen = fracture::select_seeds(candidates, piece.particles, 2 * s, nseeds);
    const std::vector<std::int32_t> voxel_of = fracture::particle_voxels(piece);
    std::vector<Vec3d> seeds;
    for (std::size_t k = 0; k < chosen.size(); ++k)  // off the voxel lattice, as the solver's seeds are
      seeds.push_back(piece.centers[static_cast<std::size_t>(voxel_of[static_cast<std::size_t>(chosen[k])])] +
                      s * Vec3d(0.02 + 0.003 * double(k % 7), 0.03 + 0.002 * double(k % 11), 0.04 + 0.001 * double(k % 13)));
    Run run{};
    run.seeds = clock.seconds();
    clock.restart();
    fragments = solver.break_body(0, seeds);
    run.breaking = clock.seconds();
    clock.restart();
    solver.step(solver.time() + 1.0);
    run.first_step = clock.seconds();
    run.step = time_steps(solver, 3);
    const sim::Solver::FractureTimes t = solver.fracture_times();
    run.partition = t.partition, run.fragments = t.fragments, run.bonds = t.bonds, run.bodies = t.bodies;
    run.event = run.seeds + run.breaking + std::max(0.0, run.first_step - run.step);
    runs.push_back(run);
    particles = 0;
    for (int b = 0; b < solver.body_count(); ++b)
      if (solver.body_info(b).active) particles += solver.body_info(b).particles;
    seed_count = seeds.size();
    host_decided = solver.fracture_host_decided_voxels();
  }
  std::printf("fracture: %zu voxels, %zu particles, %zu seeds, device %s; %d runs (the first apart, then the "
              "median and range of the others)\n",
              piece.size(), piece.particles.size(), seed_count, context.device().name.c_str(), kRuns);
  test::figure("fragments", fragments);
  test::figure("fragment particles", static_cast<double>(particles));
  test::figure("voxels decided on the host", static_cast<double>(host_decided));
  auto report = [&](const std::string& name, double Run::*part) {
    std::vector<double> v;
    for (std::size_t r = 1; r < runs.size(); ++r) v.push_back(runs[r].*part);
    std::sort(v.begin(), v.end());
    std::printf("  %-58s first %7.2f ms, median %7.2f ms (%.2f to %.2f)\n", name.c_str(), 1e3 * (runs[0].*part),
                1e3 * v[v.size() / 2], 1e3 * v.front(), 1e3 * v.back());
  };
  report("seed choice (host)", &Run::seeds);
  report("partition: nearest seed of every voxel (device)", &Run::partition);
  report("fragments: components, voxels, particles, mass (host)", &Run::fragments);
  report("binding energies (host)", &Run::bonds);
  report("new bodies, event, slots", &Run::bodies);
  report("break_body in all", &Run::breaking);
  report("first step after (new particles uploaded, sorted, Psi_b)", &Run::first_step);
  report("a step after", &Run::step);
  report("event: seed choice + break_body + the first step's extra", &Run::event);
  return 0;
}

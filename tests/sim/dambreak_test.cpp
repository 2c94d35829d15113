// Dam break in a closed tank (Martin & Moyce's set-up: a column a wide and 2a high
// against one wall): no particle leaves the tank, and the total energy (kinetic,
// potential and the elastic energy of compression) never grows.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/run_file.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

constexpr double kSpacing = 0.01;

TEST(DamBreak, StaysInTheTankAndLosesEnergy) {
  test::TempDir dir;
  const Eigen::Vector3i n(40, 6, 30);  // tank 4a long, a = 0.1 m
  test::write_tank(dir.file("tank.h5"), n, kSpacing);
  std::ofstream(dir.file("dambreak.toml")) << R"(
spacing = 0.01
[time]
end = 1.2
frame_rate = 30
[domain]
min = [-0.05, -0.05, -0.05]
max = [0.46, 0.12, 0.36]
[fluid]
mu = 0.02
[[fluid.block]]
min = [0.01, 0.01, 0.01]
max = [0.11, 0.06, 0.21]
[[solid]]
particles = "tank.h5"
)";
  const sim::RunSummary summary = test::run_scene(dir.file("dambreak.toml"), dir.file("out"));
  const RunRecord run = read_run(dir.file("out/run.h5"));
  ASSERT_EQ(run.status, "complete");
  ASSERT_EQ(static_cast<int>(run.frames.size()), 37);
  EXPECT_EQ(summary.removed, 0);

  // Every particle of every frame lies between the walls' particle layers.
  const Vec3d lo = Vec3d::Constant(0.5 * kSpacing);
  const Vec3d hi = (n.cast<double>().array() + 0.5).matrix() * kSpacing;
  double front = 0;
  for (std::size_t f = 0; f < run.frames.size(); ++f) {
    const FrameData d = read_frame(frame_file_name(dir.file("out/frames"), static_cast<int>(f)));
    ASSERT_EQ(d.fluid_count(), 1000u) << "frame " << f;
    for (std::size_t i = 0; i < d.fluid_count(); ++i) {
      const Vec3d q(d.x[i], d.y[i], d.z[i]);
      ASSERT_TRUE((q.array() > lo.array()).all() && (q.array() < hi.array()).all())
          << "frame " << f << ": particle at " << q.transpose() << " left the tank";
    }
    if (f == 6) front = *std::max_element(d.x.begin(), d.x.end());
  }

  // Energy: never grows from frame to frame (viscosity and wall friction dissipate;
  // symplectic Euler's small oscillation is bounded by the tolerance).
  const double e0 = run.frames.front().kinetic_energy + run.frames.front().potential_energy +
                    run.frames.front().elastic_energy;
  double largest_rise = 0, previous = e0;
  for (const FrameStats& s : run.frames) {
    const double e = s.kinetic_energy + s.potential_energy + s.elastic_energy;
    largest_rise = std::max(largest_rise, e - previous);
    previous = e;
  }
  const double released = e0 - run.frames.back().potential_energy;  // what the fall made available
  test::figure("initial energy (kinetic + potential + elastic)", e0, "J");
  test::figure("final energy", previous, "J");
  test::figure("largest rise between frames / energy the fall released", largest_rise / released);
  // Front distance from the back wall in column widths, against Martin & Moyce's
  // measurements (Z = 3.4 at T = t sqrt(2 g / a) = 2.8), for later validation.
  test::figure("surge front Z at T = 2.8 (Martin & Moyce: about 3.4)", (front + 0.5 * kSpacing - 0.01) / 0.1);
  test::figure("worst density error", summary.worst_density_error);
  test::figure("particle-steps per second", summary.particle_steps / summary.wall_seconds);
  EXPECT_LE(largest_rise, 1e-3 * released);
  EXPECT_LT(previous, e0);
  EXPECT_LT(summary.worst_density_error, 0.1);
}

}  // namespace
}  // namespace bw

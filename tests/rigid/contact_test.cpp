// Contacts between rigid bodies and static solids, without fluid (docs/scene.md,
// "Physics"): a box dropped on a floor bounces with about its restitution and comes
// to rest on it without passing through, a stack of three boxes stands, Coulomb
// friction stops a sliding box after the distance v^2 / (2 mu g), a floor moved as told
// lifts the box on it.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "rigid_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

constexpr double kSpacing = 0.01;
constexpr double kBox = 0.1;  // edge of the boxes (m)

// An open tank 0.3 x 0.3 x 0.4 (floor face at z = 0) and a box file, in `dir`.
void write_solids(const test::TempDir& dir) {
  test::write_open_tank(dir.file("tank.h5"), {0.3, 0.3, 0.4}, 0.03, kSpacing);
  test::write_box(dir.file("box.h5"), {kBox, kBox, kBox}, kSpacing);
}

std::string dry_scene(const std::string& bodies, double end, const std::string& tank_extra = "") {
  return "spacing = 0.01\n[time]\nend = " + std::to_string(end) +
         "\n[domain]\nmin = [-0.04, -0.04, -0.04]\nmax = [0.34, 0.34, 0.42]\n"
         "[[solid]]\nparticles = \"tank.h5\"\n" +
         tank_extra + bodies;
}

std::string box(const Vec3d& corner, double density, const std::string& extra = "") {
  return fmt::format("[[solid]]\nparticles = \"box.h5\"\ndynamic = true\ndensity = {}\ntranslation = [{}, {}, {}]\n{}",
                     density, corner.x(), corner.y(), corner.z(), extra);
}

TEST(Contact, DroppedBoxBouncesAndComesToRestOnTheFloor) {
  test::TempDir dir;
  write_solids(dir);
  // Dropped from 5 cm: it lands at 0.99 m/s.
  std::ofstream(dir.file("drop.toml")) << dry_scene(box({0.1, 0.1, 0.05}, 500), 1.0);
  sim::Solver solver(test::prepare_file(dir.file("drop.toml")), test::shared_context());
  const double rest = 0.5 * kBox;  // centre height with the bottom face on the floor face
  double deepest = 0, v_in = 0, v_out = 0, jitter = 0, drift = 0;
  bool bounced = false;
  double previous_vz = 0;
  while (solver.time() < 1.0) {
    solver.step(1.0);
    const rigid::BodyState& st = solver.body(0).state();
    deepest = std::max(deepest, rest - st.position.z());
    const double vz = st.linear_velocity.z();
    if (!bounced && previous_vz < 0 && vz >= 0) bounced = true;  // the first bounce turned it
    if (!bounced) v_in = std::min(v_in, vz);
    if (bounced && v_out == 0 && vz < previous_vz) v_out = previous_vz;  // left the floor: gravity only
    previous_vz = vz;
    if (solver.time() > 0.8) {
      jitter = std::max(jitter, st.linear_velocity.norm() + st.angular_velocity.norm() * 0.5 * std::sqrt(3) * kBox);
      drift = std::max(drift, std::hypot(st.position.x() - 0.15, st.position.y() - 0.15));
    }
  }
  const rigid::BodyState& st = solver.body(0).state();
  const double restitution = -v_out / v_in;
  test::figure("impact speed", -v_in, "m/s");
  test::figure("restitution of the first bounce (scene: 0.3)", restitution);
  test::figure("deepest penetration", deepest / kSpacing, "spacings");
  test::figure("penetration at rest", (rest - st.position.z()) / kSpacing, "spacings");
  test::figure("jitter over the last 0.2 s (fastest point of the box)", jitter, "m/s");
  test::figure("lateral drift", drift, "m");
  EXPECT_NEAR(-v_in, std::sqrt(2 * 9.81 * 0.05), 0.02);
  EXPECT_NEAR(restitution, 0.3, 0.05);
  EXPECT_LT(deepest, 0.3 * kSpacing) << "the floor is one layer of particles";
  EXPECT_LT(std::abs(rest - st.position.z()), 0.01 * kSpacing) << "at rest, g / omega^2 deep";
  EXPECT_LT(jitter, 1e-3);
  EXPECT_LT(drift, 1e-4);
  EXPECT_LT(Eigen::AngleAxisd(st.orientation).angle(), 1e-4) << "it lands flat and stays so";
}

TEST(Contact, StackOfThreeBoxesStands) {
  test::TempDir dir;
  write_solids(dir);
  // Each box on the one below, particle layers one contact distance apart, the upper
  // ones shifted 1 and 2 cm along x (their centres of mass still over their support).
  std::ofstream(dir.file("stack.toml")) << dry_scene(
      box({0.1, 0.1, 0.0}, 500) + box({0.11, 0.1, kBox}, 500) + box({0.12, 0.1, 2 * kBox}, 500), 1.5);
  sim::Solver solver(test::prepare_file(dir.file("stack.toml")), test::shared_context());
  double deepest = 0, jitter = 0, tilt = 0, sink = 0;
  while (solver.time() < 1.5) {
    solver.step(1.5);
    for (int b = 0; b < 3; ++b) {
      const rigid::BodyState& st = solver.body(b).state();
      const double rest = (b + 0.5) * kBox;
      deepest = std::max(deepest, rest - st.position.z());
      if (solver.time() > 1.3) {
        jitter = std::max(jitter, st.linear_velocity.norm() + st.angular_velocity.norm() * kBox);
        tilt = std::max(tilt, Eigen::AngleAxisd(st.orientation).angle());
        sink = std::max(sink, rest - st.position.z());
      }
    }
  }
  for (int b = 0; b < 3; ++b) {
    const Vec3d p = solver.body(b).state().position;
    EXPECT_NEAR(p.x(), 0.15 + 0.01 * b, 1e-3) << "box " << b;
    EXPECT_NEAR(p.y(), 0.15, 1e-3) << "box " << b;
    EXPECT_NEAR(p.z(), (b + 0.5) * kBox, 0.05 * kSpacing) << "box " << b;
  }
  test::figure("stack: deepest penetration of a box (sum of the contacts below it)", deepest / kSpacing,
               "spacings");
  test::figure("stack: largest tilt over the last 0.2 s", tilt, "rad");
  test::figure("stack: jitter over the last 0.2 s", jitter, "m/s");
  test::figure("stack: sinking of the top box at rest", sink / kSpacing, "spacings");
  EXPECT_LT(deepest, 0.3 * kSpacing);
  EXPECT_LT(tilt, 1e-3);
  EXPECT_LT(jitter, 1e-3);
}

TEST(Contact, CoulombFrictionStopsASlidingBox) {
  test::TempDir dir;
  write_solids(dir);
  // A box sliding at 0.5 m/s on the floor, friction 0.4 on both solids (the pair's
  // coefficient is their geometric mean): it stops after v^2 / (2 mu g) = 3.19 cm.
  const double v0 = 0.5, mu = 0.4, g = 9.81;
  std::ofstream(dir.file("slide.toml"))
      << dry_scene(box({0.05, 0.1, 0.0}, 500, fmt::format("velocity = [{}, 0, 0]\nfriction = {}\n", v0, mu)), 0.4,
                   fmt::format("friction = {}\n", mu));
  sim::Solver solver(test::prepare_file(dir.file("slide.toml")), test::shared_context());
  const double x0 = solver.body(0).state().position.x();
  double stop_time = 0;
  while (solver.time() < 0.4) {
    solver.step(0.4);
    if (stop_time == 0 && solver.body(0).state().linear_velocity.x() < 1e-3) stop_time = solver.time();
  }
  const rigid::BodyState& st = solver.body(0).state();
  const double distance = st.position.x() - x0, expected = v0 * v0 / (2 * mu * g);
  test::figure("sliding distance", distance, "m");
  test::figure("v^2 / (2 mu g)", expected, "m");
  test::figure("stopping time / (v / (mu g))", stop_time / (v0 / (mu * g)));
  EXPECT_NEAR(distance / expected, 1.0, 0.1);
  EXPECT_NEAR(stop_time / (v0 / (mu * g)), 1.0, 0.1);
  EXPECT_LT(st.linear_velocity.norm(), 1e-3) << "it stays where it stopped";
  EXPECT_NEAR(st.position.z(), 0.5 * kBox, 0.05 * kSpacing) << "on the floor, not dug in";
}

// A floor moved as told (the tank with a `motion`) lifts the box resting on it: after
// 0.2 s at rest the tank speeds up evenly to 0.1 m/s upward over 0.2 s and goes on. The
// box rides along, as a body on a lift does: it rises with the floor, at its speed,
// and the floor does not give way to it.
TEST(Contact, AMovingFloorLiftsTheBoxOnIt) {
  test::TempDir dir;
  write_solids(dir);
  std::ofstream(dir.file("lift.toml")) << dry_scene(box({0.1, 0.1, 0}, 500), 1.0,
                                                    "motion = [[0.2, 0, 0, 0], [0.4, 0, 0, 0.1]]\n");
  sim::Solver solver(test::prepare_file(dir.file("lift.toml")), test::shared_context());
  ASSERT_EQ(solver.body_count(), 2);  // the tank, moved, and the box
  const int tank = solver.body_info(0).name == "box" ? 1 : 0, crate = 1 - tank;
  while (solver.time() < 0.2) solver.step(0.2);
  const Vec3d tank0 = solver.body(tank).state().position, box0 = solver.body(crate).state().position;
  while (solver.time() < 1.0) solver.step(1.0);
  const rigid::BodyState& t = solver.body(tank).state();
  const rigid::BodyState& b = solver.body(crate).state();
  const double lifted = t.position.z() - tank0.z(), rode = b.position.z() - box0.z();
  test::figure("floor lifted", lifted, "m");
  test::figure("box lifted", rode, "m");
  test::figure("box's vertical speed at the end", b.linear_velocity.z(), "m/s");
  // 0.2 s at the mean of 0 and 0.1 m/s, then 0.6 s at 0.1.
  EXPECT_NEAR(lifted, 0.5 * 0.2 * 0.1 + 0.6 * 0.1, 1e-9);
  // The contact's spring sits g / omega^2 deep at rest and (g + a) / omega^2 while the
  // floor speeds up: what the box lags the floor by is a small part of a spacing.
  EXPECT_NEAR(rode, lifted, 0.05 * kSpacing);
  EXPECT_NEAR(b.linear_velocity.z(), 0.1, 0.01);
  EXPECT_LT(std::hypot(b.position.x() - box0.x(), b.position.y() - box0.y()), 1e-4) << "straight up";
}

}  // namespace
}  // namespace bw

// The study's measurements and the stability checks on synthetic runs: each check
// finds what it is meant to find (a particle inside a solid, outside the domain, a
// non-finite position, a density error or an energy rise past the limits), and a
// clean run passes them all.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "common/error.h"
#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "study_checks.h"
#include "test_support.h"

namespace bw {
namespace {

TEST(WindingNumber, OneInsideZeroOutside) {
  const TriMesh box = mesh::box(Vec3d(0, 0, 0), Vec3d(1, 2, 3));
  EXPECT_NEAR(study::winding_number(box, Vec3d(0.5, 1, 1.5)), 1.0, 1e-9);
  EXPECT_NEAR(study::winding_number(box, Vec3d(0.99, 0.01, 2.99)), 1.0, 1e-9);
  EXPECT_NEAR(study::winding_number(box, Vec3d(1.01, 1, 1.5)), 0.0, 1e-9);
  EXPECT_NEAR(study::winding_number(box, Vec3d(-5, 7, 1)), 0.0, 1e-9);
  // A tank: the walls are the solid, the cavity is outside it.
  const TriMesh tank = mesh::open_box(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.1);
  EXPECT_NEAR(study::winding_number(tank, Vec3d(0.5, 0.5, 0.5)), 0.0, 1e-9) << "in the cavity";
  EXPECT_NEAR(study::winding_number(tank, Vec3d(-0.05, 0.5, 0.5)), 1.0, 1e-9) << "in a wall";
  EXPECT_NEAR(study::winding_number(tank, Vec3d(0.5, 0.5, -0.05)), 1.0, 1e-9) << "in the floor";
  EXPECT_NEAR(study::winding_number(tank, Vec3d(0.5, 0.5, 1.05)), 0.0, 1e-9) << "above the open top";
}

// A run folder with a tank (the open box [0, 1]^2 x [0, 1], walls 0.2) and frames
// the test fills in.
struct SyntheticRun {
  test::TempDir dir;
  RunRecord run;
  std::vector<FrameData> frames;

  SyntheticRun() {
    SampledSolid tank = sample::sample_mesh(mesh::open_box(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.2), {0.1, false, "tank", 1});
    write_particles(tank, dir.file("tank.h5"), "check test");
    std::ofstream(dir.file("scene.toml")) << "spacing = 0.1\n[time]\nend = 1\n[domain]\nmin = [-0.3, -0.3, -0.3]\n"
                                             "max = [1.3, 1.3, 2]\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0.5]\n"
                                             "[[solid]]\nparticles = \"tank.h5\"\n";
    std::ifstream in(dir.file("scene.toml"));
    run.scene_text.assign(std::istreambuf_iterator<char>(in), {});
    run.scene_path = dir.file("scene.toml");
    run.status = "complete";
    run.parameters = {{"spacing", 0.1}, {"smoothing_length", 0.2}, {"c0", 20}, {"rho0", 998}};
  }
  // A frame of particles at `points`, with energies (kinetic, potential) and a density error.
  void add(const std::vector<Vec3d>& points, double kinetic, double potential, double density_error) {
    FrameData f;
    f.frame = static_cast<int>(frames.size());
    f.time = 0.1 * f.frame;
    for (const Vec3d& p : points) {
      f.x.push_back(static_cast<float>(p.x()));
      f.y.push_back(static_cast<float>(p.y()));
      f.z.push_back(static_cast<float>(p.z()));
      f.p.push_back(static_cast<float>(998 * 9.81 * (0.5 - p.z())));
    }
    frames.push_back(f);
    FrameStats s;
    s.frame = f.frame;
    s.time = f.time;
    s.steps = 10 * f.frame;
    s.fluid = static_cast<std::int64_t>(points.size());
    s.kinetic_energy = kinetic;
    s.potential_energy = potential;
    s.density_error_max = density_error;
    s.wall_time = 2.0 * f.frame;
    run.frames.push_back(s);
  }
  std::string write() {
    write_run(run, dir.file("run.h5"));
    std::filesystem::create_directories(dir.file("frames"));
    for (const FrameData& f : frames) write_frame(f, frame_file_name(dir.file("frames"), f.frame));
    return dir.path();
  }
};

const std::vector<Vec3d> kInCavity = {{0.2, 0.2, 0.1}, {0.5, 0.5, 0.3}, {0.8, 0.7, 0.45}};

TEST(StabilityChecks, DistanceToSurfaceOfABox) {
  const TriMesh box = mesh::box(Vec3d(0, 0, 0), Vec3d(1, 2, 3));
  EXPECT_NEAR(study::distance_to_surface(box, Vec3d(0.5, 1, 1.5)), 0.5, 1e-12) << "centre: nearest face x";
  EXPECT_NEAR(study::distance_to_surface(box, Vec3d(0.9, 0.1, 2.95)), 0.05, 1e-12) << "near the top";
  EXPECT_NEAR(study::distance_to_surface(box, Vec3d(2, 3, 4)), std::sqrt(3.0), 1e-12) << "outside, nearest a corner";
  EXPECT_NEAR(study::distance_to_surface(box, Vec3d(-1, 1, 4)), std::sqrt(2.0), 1e-12) << "outside, nearest an edge";
}

TEST(StabilityChecks, CleanRunPasses) {
  SyntheticRun s;
  s.add(kInCavity, 0, 10, 0.0);
  s.add(kInCavity, 2, 7.9, 0.01);
  s.add(kInCavity, 1, 8.5, 0.02);
  const study::StabilityReport r = study::check_stability(s.write(), {});
  EXPECT_TRUE(r.stable()) << (r.failures.empty() ? "" : r.failures.front()) << (r.leaks.empty() ? "" : r.leaks.front());
  EXPECT_EQ(r.frames, 3);
  EXPECT_DOUBLE_EQ(r.run.wall_time, 4.0);
  EXPECT_DOUBLE_EQ(r.run.steps, 20);
  EXPECT_DOUBLE_EQ(r.run.density_error_worst, 0.02);
  EXPECT_NEAR(r.run.energy_drift, -0.05, 1e-12);
  EXPECT_DOUBLE_EQ(r.run.energy_growth, 0);
}

TEST(StabilityChecks, FindParticlesInSolidsOutsideTheDomainAndNotNumbers) {
  SyntheticRun s;
  s.add(kInCavity, 0, 10, 0.0);
  std::vector<Vec3d> bad = kInCavity;
  bad.push_back({-0.1, 0.5, 0.3});    // in a wall, a spacing deep
  bad.push_back({0.5, 0.5, -0.06});   // in the floor, behind its boundary particles
  bad.push_back({0.5, 0.3, -0.03});   // pressed against the floor's boundary particles: contact
  bad.push_back({0.5, 0.5, 3.0});     // above the domain
  bad.push_back({std::nan(""), 0.5, 0.5});
  s.add(bad, 0, 10, 0.0);
  const study::StabilityReport r = study::check_stability(s.write(), {});
  EXPECT_FALSE(r.stable());
  EXPECT_EQ(r.inside_solids, 2);
  EXPECT_NEAR(r.deepest, 1.0, 1e-6);
  EXPECT_EQ(r.outside_domain, 1);
  EXPECT_EQ(r.nonfinite, 1);
  EXPECT_EQ(r.first_bad_frame, 1);
  EXPECT_EQ(r.leaks.size(), 2u) << "in solids, outside the domain";
  EXPECT_EQ(r.failures.size(), 1u) << "not a number";
}

// A breakable box (0.4 m, 64 voxels of 0.1 m) in the tank, broken at frame 1 into its
// halves x < 0.5 and x > 0.5 (bodies 1 and 2), of which the second has flown 0.5 m up
// and turned 90 degrees about z: added to a run.
void add_broken_box(SyntheticRun& s) {
  write_particles(sample::sample_mesh(mesh::box(Vec3d(0, 0, 0), Vec3d(0.4, 0.4, 0.4)), {0.1, true, "box", 1}),
                  s.dir.file("box.h5"), "check test");
  s.run.scene_text += "[[solid]]\nparticles = \"box.h5\"\nbreakable = true\ntranslation = [0.3, 0.3, 0.5]\n";
  auto body = [](std::int32_t parent, std::int32_t voxels, const Vec3d& center) {
    BodyRecord b;
    b.name = parent < 0 ? "box" : "box." + std::to_string(voxels);
    b.solid = 1;
    b.parent = parent;
    b.mass = 2400 * 1e-3 * voxels;
    b.voxels = voxels;
    b.reference_center = center;
    return b;
  };
  s.run.bodies = {body(-1, 64, {0.5, 0.5, 0.7}), body(0, 32, {0.4, 0.5, 0.7}), body(0, 32, {0.6, 0.5, 0.7})};
  FractureEvent e;
  e.time = 0.05;
  e.parent = 0;
  e.seeds = {{0.41, 0.52, 0.73}, {0.62, 0.51, 0.72}};
  e.child_body = {1, 2};
  e.child_seed = {0, 1};
  e.child_component = {0, 0};
  s.run.fractures = {e};
  s.add(kInCavity, 0, 10, 0.0);
  s.frames.back().bodies.id = {0};
  s.frames.back().bodies.position = {{0.5, 0.5, 0.7}};
  s.frames.back().bodies.orientation = {Eigen::Quaterniond::Identity()};
  s.frames.back().bodies.linear_velocity = s.frames.back().bodies.angular_velocity = {Vec3d::Zero()};
  std::vector<Vec3d> points = kInCavity;
  points.push_back({0.6, 0.5, 0.7});    // where the second half was: water now
  points.push_back({0.6, 0.5, 1.2});    // in the second half, a spacing deep
  points.push_back({0.7, 0.5, 1.3});    // in it too, at (0.6, 0.4, 0.8) of its reference configuration
  points.push_back({0.6, 0.58, 1.2});   // against its face, 0.2 spacings deep: contact
  points.push_back({0.4, 0.5, 0.7});    // in the first half, at its crack: a spacing deep
  s.add(points, 0, 10, 0.0);
  BodyStates& b = s.frames.back().bodies;
  b.id = {1, 2};
  b.position = {{0.4, 0.5, 0.7}, {0.6, 0.5, 1.2}};
  b.orientation = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3d::UnitZ()))};
  b.linear_velocity = b.angular_velocity = {Vec3d::Zero(), Vec3d::Zero()};
}

TEST(StabilityChecks, FollowBodiesAndTheFragmentsOfTheirFractures) {
  SyntheticRun s;
  add_broken_box(s);
  const study::StabilityReport r = study::check_stability(s.write(), {});
  EXPECT_EQ(r.inside_solids, 3) << "in the halves a spacing deep; not where the second half was, not against its face";
  EXPECT_NEAR(r.deepest, 1.0, 1e-5);
  EXPECT_EQ(r.first_bad_frame, 1);
}

TEST(StabilityChecks, FragmentsThatSplittingCannotRebuildAreBadInput) {
  SyntheticRun s;
  add_broken_box(s);
  s.run.bodies[2].voxels = 31;
  EXPECT_THROW(study::check_stability(s.write(), {}), InputError);
  SyntheticRun t;
  add_broken_box(t);
  t.run.fractures[0].child_component = {0, 1};
  EXPECT_THROW(study::check_stability(t.write(), {}), InputError);
}

TEST(StabilityChecks, AllowTheCompressionOfTheFastestFluidsImpact) {
  // c0 = 20 m/s: fluid at 2 m/s may compress by 2 x 2 / 20 = 0.2, at 4 m/s by 0.4.
  SyntheticRun s;
  s.add(kInCavity, 0, 10, 0.0);
  s.add(kInCavity, 0, 10, 0.3);
  s.run.frames.back().speed_max = 2;
  study::StabilityReport r = study::check_stability(s.write(), {});
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_NE(r.failures[0].find("worst density error 0.3000 above 0.2000 (2 x the fastest fluid, 2.0 m/s"),
            std::string::npos)
      << r.failures[0];
  s.run.frames.front().speed_max = 4;  // the impact that compressed it came earlier
  r = study::check_stability(s.write(), {});
  EXPECT_TRUE(r.failures.empty()) << r.failures.front();
  EXPECT_DOUBLE_EQ(r.run.speed_worst, 4);
}

TEST(StabilityChecks, FindDensityErrorEnergyRiseLostParticlesAndStops) {
  SyntheticRun s;
  s.add(kInCavity, 0, 10, 0.0);
  s.add(kInCavity, 1, 9.5, 0.3);     // 10.5 J: 5% above the start; compressed 30%
  s.run.frames.back().removed = 2;
  s.run.status = "step 12 (t = 0.1 s): the fluid blew up";
  const study::StabilityReport r = study::check_stability(s.write(), {});
  EXPECT_NEAR(r.run.energy_growth, 0.05, 1e-12);
  ASSERT_EQ(r.failures.size(), 4u);
  EXPECT_NE(r.failures[0].find("did not finish: step 12"), std::string::npos) << r.failures[0];
  EXPECT_NE(r.failures[1].find("worst density error 0.3"), std::string::npos) << r.failures[1];
  EXPECT_NE(r.failures[2].find("energy rose 5.00e-02"), std::string::npos) << r.failures[2];
  EXPECT_NE(r.failures[3].find("energy ended 5.00e-02"), std::string::npos) << r.failures[3];
  ASSERT_EQ(r.leaks.size(), 1u);
  EXPECT_NE(r.leaks[0].find("2 particles left the domain"), std::string::npos) << r.leaks[0];
  // Within looser limits, only what no limit can excuse is left.
  const study::StabilityReport loose = study::check_stability(s.dir.path(), {0.5, 0.1, 0.1});
  EXPECT_EQ(loose.failures.size(), 1u);
  EXPECT_EQ(loose.leaks.size(), 1u);
}

TEST(Hydrostatic, PressureAgainstRhoGD) {
  SyntheticRun s;
  // A column of particles on the axis, pressure rho0 g (0.5 - z) (SyntheticRun::add).
  std::vector<Vec3d> column;
  for (int k = 0; k < 5; ++k) column.push_back({0.5, 0.5, 0.05 + 0.1 * k});
  s.add(column, 0, 10, 0);
  s.add(column, 0, 10, 0);
  const study::HydrostaticError e = study::hydrostatic_error(s.write(), Vec3d(0.5, 0.5, 0.25), 0.5, 0.11, 0.05);
  EXPECT_EQ(e.frames, 1) << "frames from t = 0.05 s";
  EXPECT_NEAR(e.expected, 998 * 9.81 * 0.25, 1e-9);
  // The probe's Shepard average of the particle at the point and the two 0.1 m
  // above and below it, in a linear pressure field, is the pressure at the point.
  EXPECT_NEAR(e.relative, 0.0, 1e-6);
}

}  // namespace
}  // namespace bw

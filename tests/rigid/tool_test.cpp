// bw-sim with dynamic solids, end to end: the same scene twice gives bit-identical
// frames; frames hold the bodies' states and the run file their records; every bad
// input of a dynamic solid exits with 2 and one line naming the scene file and the
// key, writing nothing.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/run_file.h"
#include "rigid_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string bw_sim() { return test::tool("bw-sim"); }

// A small open tank with a shallow pool and a box of density 600 above it.
void write_files(const test::TempDir& dir) {
  test::write_open_tank(dir.file("tank.h5"), {0.14, 0.1, 0.12}, 0.03, 0.01);
  test::write_box(dir.file("box.h5"), {0.06, 0.06, 0.04}, 0.01);
  test::write_box(dir.file("shell.h5"), {0.06, 0.06, 0.04}, 0.01, false);
}

const std::string kPool =
    "spacing = 0.01\n[time]\nend = 0.1\nframe_rate = 40\n[domain]\nmin = [-0.04, -0.04, -0.04]\n"
    "max = [0.18, 0.14, 0.16]\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [0.14, 0.1, 0.03]\n"
    "[[solid]]\nname = \"tank\"\nparticles = \"tank.h5\"\n";

std::string box(const std::string& name, const Vec3d& corner, const std::string& extra = "") {
  return fmt::format("[[solid]]\nname = \"{}\"\nparticles = \"box.h5\"\ndynamic = true\ndensity = 600\n"
                     "translation = [{}, {}, {}]\n{}",
                     name, corner.x(), corner.y(), corner.z(), extra);
}

TEST(BwSimBodies, SameSceneTwiceGivesBitIdenticalFramesWithTheBodies) {
  test::TempDir dir;
  write_files(dir);
  std::ofstream(dir.file("scene.toml")) << kPool << box("crate", {0.04, 0.02, 0.05})
                                        << "[output]\nfields = [\"velocity\", \"boundary\"]\n";
  for (const char* out : {"a", "b"}) {
    const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file(out) + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ASSERT_EQ(test::list_folder(dir.file("a/frames")), "000000.h5 000001.h5 000002.h5 000003.h5 000004.h5");
  for (int f = 0; f <= 4; ++f)
    EXPECT_TRUE(slurp(frame_file_name(dir.file("a/frames"), f)) == slurp(frame_file_name(dir.file("b/frames"), f)))
        << "frame " << f << " differs";

  // Frames: the body's state; it falls (0.1 s: into the water).
  const FrameData first = read_frame(frame_file_name(dir.file("a/frames"), 0));
  const FrameData last = read_frame(frame_file_name(dir.file("a/frames"), 4));
  ASSERT_EQ(first.bodies.size(), 1u);
  ASSERT_EQ(last.bodies.size(), 1u);
  EXPECT_EQ(last.bodies.id[0], 0);
  EXPECT_NEAR((first.bodies.position[0] - Vec3d(0.07, 0.05, 0.07)).norm(), 0, 1e-12);
  EXPECT_LT(last.bodies.position[0].z(), first.bodies.position[0].z() - 0.01);
  EXPECT_LT(last.bodies.linear_velocity[0].z(), 0);
  EXPECT_NEAR(last.bodies.orientation[0].norm(), 1, 1e-12);
  // The boundary field holds the box where it is now, after the tank's particles.
  EXPECT_EQ(last.bx.size(), first.bx.size());
  float lowest_last = 1, lowest_first = 1;
  for (std::size_t i = first.bx.size() - 1; i > 0 && first.bx[i] > 0.04f; --i) lowest_first = std::min(lowest_first, first.bz[i]);
  for (std::size_t i = last.bx.size() - 1; i > 0 && last.bx[i] > 0.04f; --i) lowest_last = std::min(lowest_last, last.bz[i]);
  EXPECT_LT(lowest_last, lowest_first - 0.01f);

  // The run file: the body's record and the solids' kinds; energies include it.
  const RunRecord run = read_run(dir.file("a/run.h5"));
  ASSERT_EQ(run.status, "complete");
  ASSERT_EQ(run.solids.size(), 2u);
  EXPECT_EQ(run.solids[0].kind, "static");
  EXPECT_EQ(run.solids[0].body, -1);
  EXPECT_EQ(run.solids[1].kind, "dynamic");
  EXPECT_EQ(run.solids[1].body, 0);
  ASSERT_EQ(run.bodies.size(), 1u);
  const BodyRecord& b = run.bodies[0];
  EXPECT_EQ(b.name, "crate");
  EXPECT_EQ(b.solid, 1);
  EXPECT_EQ(b.parent, -1);
  EXPECT_EQ(b.voxels, 6 * 6 * 4);
  EXPECT_NEAR(b.mass, 600 * 0.06 * 0.06 * 0.04, 1e-9);
  EXPECT_NEAR((b.reference_center - Vec3d(0.07, 0.05, 0.07)).norm(), 0, 1e-12);
  EXPECT_NEAR(b.inertia(2, 2), b.mass * (0.06 * 0.06 + 0.06 * 0.06) / 12, 1e-12);
  EXPECT_DOUBLE_EQ(b.created_time, 0);
  // Frame 0: the fluid at rest on the floor and the box at rest above it; the
  // potential energy counts the box, relative to the domain's minimum corner.
  const double fluid_potential_max = 14 * 10 * 3 * 998e-6 * 9.81 * (0.03 + 0.04);
  EXPECT_EQ(run.frames[0].kinetic_energy, 0);
  EXPECT_GT(run.frames[0].potential_energy, b.mass * 9.81 * (0.07 + 0.04));
  EXPECT_LT(run.frames[0].potential_energy, b.mass * 9.81 * (0.07 + 0.04) + fluid_potential_max);
}

// Each bad input: exit 2, one line on stderr naming the scene file and the key, no
// output folder.
void expect_bad_input(const std::string& scene_text, const std::string& expected) {
  test::TempDir dir;
  write_files(dir);
  std::ofstream(dir.file("scene.toml")) << scene_text;
  const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out"));
  EXPECT_EQ(r.exit_code, 2) << scene_text << "\n" << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("bw-sim: " + dir.file("scene.toml") + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.err;
  EXPECT_FALSE(test::exists(dir.file("out"))) << "nothing may be written for: " << r.err;
}

TEST(BwSimBodies, BadInputsExitWithTwoAndWriteNothing) {
  // A particle file without voxels.
  expect_bad_input(kPool + "[[solid]]\nparticles = \"shell.h5\"\ndynamic = true\ndensity = 600\n"
                           "translation = [0.04, 0.02, 0.05]\n",
                   "solid[1].particles: shell.h5 has no voxels; a dynamic solid needs its volume");
  // Densities that are not positive, or missing, or on a static solid.
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.05}).replace(
                               box("crate", {0.04, 0.02, 0.05}).find("600"), 3, "-500"),
                   "solid[1].density: -500 must be positive");
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.05}).replace(
                               box("crate", {0.04, 0.02, 0.05}).find("600"), 3, "0"),
                   "solid[1].density: 0 must be positive");
  expect_bad_input(kPool + "[[solid]]\nparticles = \"box.h5\"\ndynamic = true\ntranslation = [0.04, 0.02, 0.05]\n",
                   "solid[1].density: missing (required for a dynamic solid");
  expect_bad_input(kPool + "[[solid]]\nparticles = \"box.h5\"\ndensity = 600\ntranslation = [0.04, 0.02, 0.05]\n",
                   "solid[1].density: only for a dynamic or breakable solid");
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.05}, "restitution = 1.5\n"),
                   "solid[1].restitution: 1.5 is outside [0, 1]");
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.05}, "friction = -0.1\n"),
                   "solid[1].friction: -0.1 must not be negative");
  // Overlaps: a body half in the water, two bodies into each other, a body into the
  // tank's wall; naming which.
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.01}),
                   "solid[1]: the dynamic solid 'crate' starts overlapping the fluid of fluid.block[0] at (");
  expect_bad_input(kPool + box("a", {0.02, 0.02, 0.05}) + box("b", {0.06, 0.02, 0.07}),
                   "solid[1]: the dynamic solid 'a' starts overlapping solid[2] ('b') at (");
  expect_bad_input(kPool + box("crate", {-0.02, 0.02, 0.05}),
                   "solid[1]: the dynamic solid 'crate' starts overlapping solid[0] ('tank') at (");
  // A body inside another one, too far from its particles for the distance test.
  expect_bad_input(kPool + box("crate", {0.04, 0.02, 0.05}) +
                       "[[solid]]\nname = \"pebble\"\nparticles = \"box.h5\"\ndynamic = true\ndensity = 600\n"
                       "scale = 0.25\ntranslation = [0.0625, 0.0425, 0.065]\n",
                   "solid[1]: the dynamic solid 'crate' starts overlapping solid[2] ('pebble') at (");
}

TEST(BwSimBodies, TouchingAtRestDistanceIsAccepted) {
  test::TempDir dir;
  write_files(dir);
  // A box floating on the pool's particles, one spacing above them, and a second box
  // on top of it, their particle layers one contact distance apart.
  std::ofstream(dir.file("scene.toml")) << kPool << box("a", {0.04, 0.02, 0.03}) << box("b", {0.04, 0.02, 0.07});
  const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out") + " --end-time 0.025");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace bw

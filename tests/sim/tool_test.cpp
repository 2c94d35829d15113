// bw-sim end to end: the same scene twice gives bit-identical frames; every bad input
// exits with 2 and one line, writing nothing; a blow-up stops with 1 and a message
// naming the step, time and particle, keeping the frames written before.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {
namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string bw_sim() { return test::tool("bw-sim"); }

// A small dam break in a tank, written into `dir`.
void write_small_dambreak(const test::TempDir& dir, const std::string& extra_time = "") {
  test::write_tank(dir.file("tank.h5"), {20, 4, 16}, 0.01);
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.01\n[time]\nend = 0.15\nframe_rate = 40\n" << extra_time
                                        << "[domain]\nmin = [-0.05, -0.05, -0.05]\nmax = [0.26, 0.1, 0.22]\n"
                                           "[[fluid.block]]\nmin = [0.01, 0.01, 0.01]\nmax = [0.07, 0.04, 0.13]\n"
                                           "[[solid]]\nparticles = \"tank.h5\"\n"
                                           "[output]\nfields = [\"velocity\", \"density\", \"pressure\", \"id\", \"boundary\"]\n";
}

TEST(BwSim, SameSceneTwiceGivesBitIdenticalFrames) {
  test::TempDir dir;
  write_small_dambreak(dir);
  for (const char* out : {"a", "b"}) {
    const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file(out) + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << "--quiet prints nothing: " << r.err;
  }
  const std::string frames_a = test::list_folder(dir.file("a/frames"));
  ASSERT_EQ(frames_a, "000000.h5 000001.h5 000002.h5 000003.h5 000004.h5 000005.h5 000006.h5");
  ASSERT_EQ(frames_a, test::list_folder(dir.file("b/frames")));
  for (int f = 0; f <= 6; ++f) {
    const std::string a = slurp(frame_file_name(dir.file("a/frames"), f));
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == slurp(frame_file_name(dir.file("b/frames"), f))) << "frame " << f << " differs";
  }
  // The frames hold what the scene asked for, in the H5Part layout.
  const FrameData d = read_frame(frame_file_name(dir.file("a/frames"), 6));
  EXPECT_EQ(d.frame, 6);
  EXPECT_DOUBLE_EQ(d.time, 0.15);
  EXPECT_EQ(d.fluid_count(), 6u * 3u * 12u);
  const FrameFields fields = d.fields();
  EXPECT_TRUE(fields.velocity && fields.density && fields.pressure && fields.id && fields.boundary);
  const RunRecord run = read_run(dir.file("a/run.h5"));
  EXPECT_EQ(run.status, "complete");
  EXPECT_EQ(run.frames.size(), 7u);
  EXPECT_EQ(run.solids.size(), 1u);
  EXPECT_EQ(run.solids[0].kind, "static");
  EXPECT_NE(run.scene_text.find("[[fluid.block]]"), std::string::npos);
  EXPECT_FALSE(run.device.empty());
  EXPECT_FALSE(run.parameters.empty());
}

// A draw (fluid.seed) is a run of its own, bit-identical when repeated; its start, a
// thousandth of a spacing off the lattice, leaves the flow where the spacing resolves
// it: this small dam break's centre of mass and front within a tenth of a spacing
// after 0.15 s. (They move by 0.013 and 0.02 spacings: the start's offsets grow
// twentyfold in 0.15 s; an impact's peaks grow theirs to tens of percent,
// docs/scene.md "Draws".)
TEST(BwSim, ADrawRepeatsBitForBitAndLeavesTheFlowWhereItWas) {
  test::TempDir dir;
  write_small_dambreak(dir);
  for (const char* out : {"lattice", "a", "b"}) {
    const std::string draw = std::string(out) == "lattice" ? "" : " --set fluid.seed=3";
    const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file(out) + " --quiet" + draw);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string last_a = slurp(frame_file_name(dir.file("a/frames"), 6));
  EXPECT_TRUE(last_a == slurp(frame_file_name(dir.file("b/frames"), 6))) << "the same seed, the same bytes";
  EXPECT_FALSE(last_a == slurp(frame_file_name(dir.file("lattice/frames"), 6))) << "a draw is another run";
  EXPECT_NE(read_run(dir.file("a/run.h5")).scene_text.find("seed"), std::string::npos) << "the run records its draw";
  auto centre_and_front = [](const FrameData& d) {
    Vec3d centre = Vec3d::Zero();
    double front = -1e9;
    for (std::size_t i = 0; i < d.fluid_count(); ++i) {
      centre += Vec3d(d.x[i], d.y[i], d.z[i]) / static_cast<double>(d.fluid_count());
      front = std::max(front, static_cast<double>(d.x[i]));
    }
    return std::make_pair(centre, front);
  };
  const auto [centre, front] = centre_and_front(read_frame(frame_file_name(dir.file("lattice/frames"), 6)));
  const auto [centre_draw, front_draw] = centre_and_front(read_frame(frame_file_name(dir.file("a/frames"), 6)));
  test::figure("centre of mass, draw - lattice (spacings)", (centre_draw - centre).norm() / 0.01);
  test::figure("front, draw - lattice (spacings)", (front_draw - front) / 0.01);
  EXPECT_LT((centre_draw - centre).norm(), 1e-3);
  EXPECT_LT(std::abs(front_draw - front), 1e-3);
}

// A particles file from before bw-sample recorded its surface rule runs as before;
// when its cells are not those bw-sample marks now (an older sampler left out the rows
// behind concave edges), bw-sim says so in one line; when they are, it says nothing.
TEST(BwSim, WarnsOfASolidSampledBeforeTheConcaveEdgeRule) {
  test::TempDir dir;
  write_small_dambreak(dir);
  SampledSolid tank = read_particles(dir.file("tank.h5"));
  EXPECT_EQ(tank.surface_rule, kSurfaceRule);
  tank.surface_rule = 1;
  write_particles(tank, dir.file("tank.h5"), "bw-sample (test)");
  EXPECT_EQ(read_particles(dir.file("tank.h5")).surface_rule, 1);
  const std::string run = bw_sim() + " " + dir.file("scene.toml") + " --end-time 0.025 --quiet -o ";
  const auto complete = test::run(run + dir.file("complete"));
  ASSERT_EQ(complete.exit_code, 0) << complete.err;
  EXPECT_TRUE(complete.err.empty()) << "the cells are the sampler's: " << complete.err;

  tank.surface.erase(tank.surface.begin(), tank.surface.begin() + 10);
  write_particles(tank, dir.file("tank.h5"), "bw-sample (test)");
  const auto r = test::run(run + dir.file("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  for (const char* word : {"warning", "tank.h5", "lacks 10 of the", "concave edges", "sample it again"})
    EXPECT_NE(r.err.find(word), std::string::npos) << "lacks '" << word << "': " << r.err;
}

// A --quiet run that has nothing to warn of prints nothing.
void expect_silent_run(const std::string& command) {
  const auto r = test::run(command);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// A preview that ends before an emitter starts runs, and says the emitter does nothing;
// a run long enough for it says nothing.
TEST(BwSim, WarnsOfAnEmitterThatStartsAfterTheEnd) {
  test::TempDir dir;
  write_small_dambreak(dir);
  std::ofstream(dir.file("scene.toml"), std::ios::app)
      << "[[fluid.emitter]]\nshape = \"disc\"\ncenter = [0.15, 0.025, 0.15]\nnormal = [0, 0, -1]\nradius = 0.01\n"
         "speed = 0.5\nstart = 0.1\n";
  const std::string run = bw_sim() + " " + dir.file("scene.toml") + " --quiet -o ";
  const auto preview = test::run(run + dir.file("preview") + " --end-time 0.075");
  ASSERT_EQ(preview.exit_code, 0) << preview.err;
  EXPECT_EQ(preview.err, "bw-sim: warning: " + dir.file("scene.toml") +
                             ": fluid.emitter[0] starts at 0.1 s, and the run ends at 0.075 s (--end-time): it emits "
                             "nothing\n");
  expect_silent_run(run + dir.file("whole"));
}

// --resume takes the output folder: a file or a missing folder is named as such, and a
// complete run has nothing to go on from.
TEST(BwSim, ResumeNamesWhatItWasGiven) {
  test::TempDir dir;
  write_small_dambreak(dir);
  const auto first = test::run(bw_sim() + " " + dir.file("scene.toml") + " -q -o " + dir.file("out") + " --end-time 0.05");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::pair<std::string, std::string> cases[] = {
      {dir.file("out/run.h5"),
       "--resume " + dir.file("out/run.h5") + ": is a file; give the output folder of the run (" + dir.file("out") + ")"},
      {dir.file("none"), "--resume " + dir.file("none") + ": no such folder"},
      {dir.file("out"), "checkpoint.h5: no checkpoint to resume from (the run in that folder is complete)"},
  };
  for (const auto& [folder, message] : cases) {
    const auto r = test::run(bw_sim() + " --resume " + folder);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  }
}

// A speed of sound below what the water can reach is said (the run goes on); the
// default, ten times that speed, says nothing. The column's top, at 0.13 m, can fall to
// the domain's floor at -0.05 m: sqrt(2 g 0.18) = 1.88 m/s; k = 100 Pa gives sqrt(7 k / rho0).
TEST(BwSim, WarnsOfASpeedOfSoundTheWaterOutruns) {
  test::TempDir dir;
  write_small_dambreak(dir);
  const std::string run = bw_sim() + " " + dir.file("scene.toml") + " --quiet --end-time 0.05 -o ";
  const auto slow = test::run(run + dir.file("slow") + " --set fluid.c0=1");
  ASSERT_EQ(slow.exit_code, 0) << slow.err;
  EXPECT_EQ(test::line_count(slow.err), 1) << slow.err;
  for (const char* words : {"warning", "fluid.c0 gives a speed of sound of 1 m/s, below the 1.88 m/s", "compress"})
    EXPECT_NE(slow.err.find(words), std::string::npos) << slow.err;
  const auto stiff = test::run(run + dir.file("stiff") + " --set fluid.k=100");
  EXPECT_NE(stiff.err.find("fluid.k gives a speed of sound of 0.837 m/s, below the 1.88 m/s"), std::string::npos)
      << stiff.err;
  expect_silent_run(run + dir.file("fine"));
}

// One bw-sim at a time writes to a folder: a second, started while the first runs, is
// refused and touches nothing; the first goes on and stops cleanly.
TEST(BwSim, ASecondRunIntoTheSameFolderIsRefused) {
  test::TempDir dir;
  write_small_dambreak(dir);
  const std::string sim = bw_sim() + " " + dir.file("scene.toml") + " -q -o " + dir.file("out");
  const std::string script = sim + " --end-time 30 & first=$!; " +
                             "for i in $(seq 600); do [ -e " + dir.file("out/frames/000001.h5") +
                             " ] && break; sleep 0.05; done; " +
                             sim + " --end-time 0.05; echo second=$?; kill -TERM $first; wait $first; echo first=$?";
  const auto r = test::run("bash -c '" + script + "'");
  EXPECT_NE(r.out.find("second=2\n"), std::string::npos) << r.out << r.err;
  EXPECT_NE(r.out.find("first=143\n"), std::string::npos) << r.out << r.err;  // stopped by SIGTERM, checkpointed
  EXPECT_NE(r.err.find("bw-sim: " + dir.file("out") +
                       ": another bw-sim is writing to this folder; wait for it, stop it, or give another -o\n"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(test::exists(dir.file("out/checkpoint.h5")));
  EXPECT_TRUE(test::exists(dir.file("out/frames/000001.h5")));
}

TEST(BwSim, EndTimeOptionAndSummary) {
  test::TempDir dir;
  write_small_dambreak(dir);
  const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out") + " --end-time 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::list_folder(dir.file("out/frames")), "000000.h5 000001.h5 000002.h5");
  for (const char* word : {"steps", "particle-steps/s", "worst error", "energy"})
    EXPECT_NE(r.err.find(word), std::string::npos) << "summary lacks '" << word << "':\n" << r.err;
  // bw-info prints the per-frame statistics as JSON.
  const auto info = test::run(test::tool("bw-info") + " " + dir.file("out/run.h5") + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  for (const char* column : {"\"frames\"", "density_error_max", "dt_min", "kinetic_energy", "wall_time"})
    EXPECT_NE(info.out.find(column), std::string::npos) << column << " missing from:\n" << info.out.substr(0, 2000);
}

TEST(BwSim, ListsDevicesAndHelps) {
  const auto list = test::run(bw_sim() + " --device list");
  EXPECT_EQ(list.exit_code, 0) << list.err;
  EXPECT_GE(test::line_count(list.out), 1);
  const auto help = test::run(bw_sim() + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--device"), std::string::npos);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
}

// Each bad input: exit 2, one line on stderr naming what is wrong, no output folder.
void expect_bad_input(const std::string& scene_text, const std::string& expected, const std::string& options = "") {
  test::TempDir dir;
  test::write_tank(dir.file("tank.h5"), {4, 4, 4}, 0.01);
  test::write_thick_tank(dir.file("thick_tank.h5"), {4, 4, 4}, 0.01, 0.02);
  write_frame(FrameData{}, dir.file("frame.h5"));
  std::ofstream(dir.file("scene.toml")) << scene_text;
  const auto r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out") + " " + options);
  EXPECT_EQ(r.exit_code, 2) << scene_text << "\n" << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("bw-sim: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.err;
  EXPECT_FALSE(test::exists(dir.file("out"))) << "nothing may be written for: " << r.err;
}

const std::string kGood =
    "spacing = 0.01\n[time]\nend = 0.1\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [0.06, 0.06, 0.06]\n"
    "[[fluid.block]]\nmin = [0.01, 0.01, 0.01]\nmax = [0.03, 0.03, 0.03]\n";

// Fluid filling a tank whose walls are two spacings thick (as examples/spheric2.toml's,
// sampled on both faces), with `top` among the top-level keys.
std::string thick_tank_scene(const std::string& top) {
  return "spacing = 0.01\n" + top +
         "[time]\nend = 0.02\n[domain]\nmin = [-0.04, -0.04, -0.04]\nmax = [0.08, 0.08, 0.08]\n"
         "[[fluid.block]]\nmin = [0, 0, 0]\nmax = [0.04, 0.04, 0.04]\n[[solid]]\nparticles = \"thick_tank.h5\"\n";
}

// Wider than the walls are thick, the kernel takes in their far faces' particles and
// the fluid starts compressed with nothing overlapping: bw-sim says so, and not that a
// block overlaps a solid.
TEST(BwSim, RefusesAKernelWiderThanItsWalls) {
  test::TempDir dir;
  test::write_thick_tank(dir.file("thick_tank.h5"), {4, 4, 4}, 0.01, 0.02);
  std::ofstream(dir.file("scene.toml")) << thick_tank_scene("");
  const auto ok = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;  // at the default 2 spacings
  expect_bad_input(thick_tank_scene("smoothing_length = 0.04\n"),
                   "though no two particles are nearer than 1 spacings: smoothing_length 0.04 m (4 spacings)");
  // A draw's largest jitter brings neighbours as near as 0.8 spacings (draw 7's nearest
  // two are nearer than 0.95): still no overlap.
  std::string drawn = thick_tank_scene("smoothing_length = 0.04\n");
  drawn.insert(drawn.find("[[fluid.block]]"), "[fluid]\nseed = 7\njitter = 0.1\n");
  expect_bad_input(drawn, "though no two particles are nearer than 0.");
  // Walls 4.5 spacings thick put the inner faces' particles on the faces, half a spacing
  // from the fluid: an overlap, whichever particle the kernel compresses most.
  test::TempDir odd;
  test::write_thick_tank(odd.file("thick_tank.h5"), {4, 4, 4}, 0.01, 0.045);
  std::ofstream(odd.file("scene.toml")) << thick_tank_scene("smoothing_length = 0.035\n");
  const auto overlap = test::run(bw_sim() + " " + odd.file("scene.toml") + " -o " + odd.file("out"));
  EXPECT_EQ(overlap.exit_code, 2);
  EXPECT_NE(overlap.err.find("a fluid block overlaps a solid"), std::string::npos) << overlap.err;
}

// A solid sampled with its volume is solid inside: fluid may not start there, where
// no boundary particle is near enough to compress it. Beside it, or from a nozzle
// flush with its face, it may; and without voxels a closed box may hold water.
TEST(BwSim, RefusesFluidThatStartsInsideASolidsVolume) {
  test::TempDir dir;
  test::write_block(dir.file("wall.h5"), Vec3d(0.1, 0, 0), Vec3d(0.2, 0.1, 0.1), 0.01, true);
  test::write_block(dir.file("box.h5"), Vec3d(0.1, 0, 0), Vec3d(0.2, 0.1, 0.1), 0.01, false);
  const auto scene = [&](const std::string& solid, const std::string& block, const std::string& emitter) {
    std::ofstream(dir.file("scene.toml"))
        << "spacing = 0.01\n[time]\nend = 0.02\nframe_rate = 100\n[domain]\nmin = [-0.05, -0.05, -0.05]\nmax = [0.3, 0.15, 0.15]\n"
        << "[[fluid.block]]\n" << block << "\n[[fluid.emitter]]\nshape = \"disc\"\nradius = 0.01\nspeed = 1\n" << emitter
        << "\n[[solid]]\nparticles = \"" << solid << "\"\nname = \"wall\"\n";
    return test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out"));
  };
  const std::string beside = "min = [0, 0, 0]\nmax = [0.06, 0.06, 0.06]";
  const std::string within = "min = [0.13, 0.03, 0.03]\nmax = [0.17, 0.07, 0.07]";
  const std::string flush = "center = [0.2, 0.05, 0.05]\nnormal = [1, 0, 0]";
  const std::string buried = "center = [0.15, 0.05, 0.05]\nnormal = [1, 0, 0]";

  auto r = scene("wall.h5", within, flush);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("fluid.block[0]: lies inside solid[0] ('wall'): its centre (0.15, 0.05, 0.05) m is among the "
                       "solid's voxels"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(test::exists(dir.file("out")));
  r = scene("wall.h5", beside, buried);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("fluid.emitter[0]: 5 of its 5 points lie inside solid[0] ('wall'), the first at ("),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(test::exists(dir.file("out")));
  r = scene("wall.h5", beside, flush);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::remove_all(dir.file("out"));
  r = scene("box.h5", within, buried);  // a closed box without voxels: water inside it
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(BwSim, BadInputsExitWithTwoAndWriteNothing) {
  expect_bad_input("colour = 1\n" + kGood, "scene.toml: colour: unknown key");
  expect_bad_input("spacing = -0.01\n" + kGood.substr(kGood.find('\n') + 1), "spacing: -0.01 must be positive");
  expect_bad_input(kGood + "[[solid]]\nparticles = \"missing.h5\"\n", "solid[0].particles: missing.h5: no such file");
  expect_bad_input(kGood + "[[solid]]\nparticles = \"frame.h5\"\n", "solid[0].particles:");
  expect_bad_input(kGood + "[[solid]]\nparticles = \"tank.h5\"\nscale = 3\n", "coarser than");
  expect_bad_input(kGood + "[fluid]\nmax_particles = 0\n", "fluid.max_particles: 0 must be at least 1");
  expect_bad_input(kGood + "[[fluid.block]]\nmin = [0.015, 0.01, 0.01]\nmax = [0.035, 0.03, 0.03]\n",
                   "% compressed at (");  // a second block half a spacing into the first
  expect_bad_input(kGood.substr(0, kGood.find("[[fluid.block]]")) +
                       "[[fluid.block]]\nmin = [0.0, 0.0, 0.0]\nmax = [0.03, 0.03, 0.03]\n[[solid]]\nparticles = \"tank.h5\"\n",
                   "a fluid block overlaps a solid");
  expect_bad_input(kGood + "[fluid]\nmax_particles = 5\n", "fluid.max_particles: 5 is fewer than the 8 particles");
  expect_bad_input(kGood + "[output]\nfields = [\"temperature\"]\n", "output.fields: 'temperature' is not a field");
  expect_bad_input(kGood + "[time]\n", "scene.toml:");
  // bw-render's tables are checked before the run, not after it.
  expect_bad_input(kGood + "[render]\nwidth = 0\n", "scene.toml: render.width: 0 is outside [1, 16384]");
  expect_bad_input(kGood + "[camera]\nzoom = 2\n", "scene.toml: camera.zoom: unknown key");
  expect_bad_input(kGood + "[camera]\ntarget = [0, 0, 0]\n[[camera.key]]\ntime = 0.2\nposition = [0, -1, 1]\n"
                           "[[camera.key]]\ntime = 0.1\nposition = [1, -1, 1]\n",
                   "scene.toml: camera.key[1].time: 0.1 is not after camera.key[0].time = 0.2");
  expect_bad_input(kGood + "[camera]\ntrack = \"crate\"\nposition = [0, -1, 1]\n",
                   "scene.toml: camera.track: 'crate' is not a body of the scene (it has none:");
  expect_bad_input(kGood + "[render]\nsolids = \"wall_pressure\"\n",
                   "scene.toml: render.solids: \"wall_pressure\" colours the solids by a field the frames would not "
                   "hold; add \"wall_pressure\" to [output] fields");
  expect_bad_input(kGood, "scene.toml: light.intensity: must be >= 0", "--set light.intensity=-1");
  expect_bad_input(kGood, "--device: 'fastest'", "--device fastest");
  expect_bad_input(kGood, "--device 99", "--device 99");
  expect_bad_input(kGood, "--end-time", "--end-time -1");
  // An end time on the command line is held to the scene's limits, and named as given
  // (at 60 frames a second, 1e9 s overflows a frame count).
  expect_bad_input(kGood, "--end-time: 1000000000 s at 60 frames per second is more than 1000000 frames",
                   "--end-time 1e9");
  expect_bad_input(kGood, "--end-time: 0.01 s is shorter than one frame", "--end-time 0.01");
  expect_bad_input(kGood + "[[sensor]]\nname = \"floor\"\nat = [0.02, 0.02, 0]\nradius = 0.01\n"
                           "[output]\nsensor_rate = 100000\n",
                   "--end-time: 1000 s at 100000 sensor samples per second is more than 10000000 samples",
                   "--end-time 1000");
  // A fixed step between the diffusion's limit (2.3e-4 s at delta 1) and the CFL limit (6e-4 s).
  expect_bad_input(kGood + "[fluid]\ndiffusion = 1\n", "the density diffusion's limit at rest, time.diffusion_factor",
                   "--set time.dt_min=4e-4 --set time.dt_max=4e-4");
  expect_bad_input(kGood.substr(0, kGood.find("[time]")) + "[time]\nend = 0.001\nframe_rate = 10\n" +
                       kGood.substr(kGood.find("[domain]")),
                   "time.end: 0.001 s is shorter than one frame");
}

TEST(BwSim, MissingSceneAndOutput) {
  test::TempDir dir;
  auto r = test::run(bw_sim() + " " + dir.file("none.toml") + " -o " + dir.file("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.toml: no such file"), std::string::npos) << r.err;
  r = test::run(bw_sim() + " " + dir.file("none.toml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("-o OUTDIR"), std::string::npos) << r.err;
  EXPECT_FALSE(test::exists(dir.file("out")));
  std::ofstream(dir.file("file")) << "x";
  std::ofstream(dir.file("scene.toml")) << kGood;
  r = test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("file"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("exists and is not a folder"), std::string::npos) << r.err;
}

class BwSimBlowUp : public testing::TestWithParam<const char*> {};

// A wall pushing with 26 times its calibrated weight (gamma2 = gamma1 / 2 = 0.39)
// feeds energy into the fluid at every step: it explodes within a few milliseconds
// (about 1 ms with the continuity equation, 6 ms with the summation), so frames come
// every 1/8000 s for some to be written before it. The particle guard (a non-finite
// value or a runaway speed) stops it where the energy guard is off; the energy guard
// stops it sooner, at the first frame whose total is 10% above the start.
test::CommandResult run_blow_up(const test::TempDir& dir, const std::string& options) {
  write_small_dambreak(dir);
  return test::run(bw_sim() + " " + dir.file("scene.toml") + " -o " + dir.file("out") +
                   " --quiet --set fluid.gamma2=10 --set time.frame_rate=8000 --set fluid.density=" + options);
}

TEST_P(BwSimBlowUp, StopsWithOneLineAndKeepsEarlierFrames) {
  test::TempDir dir, guarded;
  const auto r = run_blow_up(dir, std::string(GetParam()) + " --set time.energy_limit=0");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  for (const char* word : {"bw-sim: step ", "(t = ", "particle ", "blew up"})
    EXPECT_NE(r.err.find(word), std::string::npos) << "'" << word << "' missing from: " << r.err;
  const RunRecord run = read_run(dir.file("out/run.h5"));

  const auto g = run_blow_up(guarded, GetParam());
  EXPECT_EQ(g.exit_code, 1) << g.err;
  EXPECT_EQ(test::line_count(g.err), 1) << g.err;
  for (const char* word : {"bw-sim: frame ", "the total energy is ", "time.energy_limit = 0.1", "blew up"})
    EXPECT_NE(g.err.find(word), std::string::npos) << "'" << word << "' missing from: " << g.err;
  const RunRecord stopped = read_run(guarded.file("out/run.h5"));
  EXPECT_EQ(g.err, "bw-sim: " + stopped.status + "\n");
  EXPECT_LT(stopped.frames.size(), run.frames.size()) << "the energy guard stops before the particles run away";
  const auto energy = [](const FrameStats& s) { return s.kinetic_energy + s.potential_energy + s.elastic_energy; };
  for (const FrameStats& s : stopped.frames)
    EXPECT_LE(energy(s) - energy(stopped.frames.front()), 0.1 * energy(stopped.frames.front())) << "frame " << s.frame;
  test::figure(std::string("frames written before the energy guard stopped it, ") + GetParam(),
               static_cast<double>(stopped.frames.size()));
  EXPECT_NE(run.status.find("blew up"), std::string::npos) << run.status;
  EXPECT_EQ(r.err, "bw-sim: " + run.status + "\n");
  ASSERT_GE(run.frames.size(), 2u);
  for (const FrameStats& s : run.frames) {
    const FrameData d = read_frame(frame_file_name(dir.file("out/frames"), s.frame));
    EXPECT_EQ(static_cast<std::int64_t>(d.fluid_count()), s.fluid) << "frame " << s.frame << " stays readable";
  }
  EXPECT_FALSE(test::exists(frame_file_name(dir.file("out/frames"), static_cast<int>(run.frames.size()))))
      << "no frame after the blow-up";
  test::figure(std::string("frames written before the blow-up, ") + GetParam(),
               static_cast<double>(run.frames.size()));
}

INSTANTIATE_TEST_SUITE_P(BothDensitySchemes, BwSimBlowUp, testing::Values("summation", "continuity"));

}  // namespace
}  // namespace bw

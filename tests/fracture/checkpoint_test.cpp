// Checkpoints and resume (sim/checkpoint.h): a breakable wall that a block of water
// and a jet break into fragments, stopped after a frame and resumed, writes the same
// frames (byte for byte) and run-file rows as a run that never stopped; checkpoints
// of another scene, version, end time or device are refused with one line; SIGTERM
// stops bw-sim after a whole frame with a checkpoint and how to go on.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "common/error.h"
#include "compute/device.h"
#include "fracture_fixtures.h"
#include "io/frame_file.h"
#include "io/h5.h"
#include "io/run_file.h"
#include "scene/scene.h"
#include "sim/checkpoint.h"
#include "sim/run.h"
#include "test_support.h"

namespace bw {
namespace {

constexpr double kEnd = 0.06;  // 6 frames at 100 per second; the wall breaks in the first two

std::string scene_text() {
  return test::fracture_scene(10.0, 0.45, kEnd,
                              "[fracture]\nmax_chunks = 8\n"
                              "[output]\nfields = [\"velocity\", \"density\", \"pressure\", \"id\", \"boundary\"]\n"
                              "[[fluid.emitter]]\nshape = \"disc\"\ncenter = [0.02, 0.15, 0.3]\nnormal = [1, 0, 0]\n"
                              "radius = 0.04\nspeed = 2\n");
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct Fixture {
  test::TempDir dir;
  scene::Scene scene;
  compute::DeviceInfo device = compute::choose_device("auto");
  Fixture() {
    test::write_fracture_solids(dir.file(""));
    std::ofstream(dir.file("scene.toml")) << scene_text();
    scene = scene::load_scene(dir.file("scene.toml"));
  }
  sim::RunSummary run(const std::string& out, int stop_after = -1, bool resume = false, const std::string& tool = "bw-sim",
                      const scene::Scene* other = nullptr, const compute::DeviceInfo* on = nullptr, double end = 0) {
    sim::RunOptions o;
    o.output = dir.file(out);
    o.progress = false;
    o.stop_after_frame = stop_after;
    o.resume = resume;
    o.tool = tool;
    o.end_time = end;
    sim::Simulation simulation(other ? *other : scene, on ? *on : device, o);
    return simulation.run();
  }
};

// Everything of two run files but the wall times.
void expect_same_run(const RunRecord& a, const RunRecord& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.scene_text, b.scene_text);
  EXPECT_EQ(a.device, b.device);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    FrameStats x = a.frames[i], y = b.frames[i];
    x.wall_time = y.wall_time = 0;
    EXPECT_EQ(std::memcmp(&x, &y, sizeof(x)), 0) << "row " << i;
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
    EXPECT_EQ(a.bodies[i].mass, b.bodies[i].mass);
    EXPECT_EQ(a.bodies[i].created_time, b.bodies[i].created_time);
    EXPECT_EQ(a.bodies[i].reference_center, b.bodies[i].reference_center);
  }
  ASSERT_EQ(a.fractures.size(), b.fractures.size());
  for (std::size_t i = 0; i < a.fractures.size(); ++i) {
    EXPECT_EQ(a.fractures[i].time, b.fractures[i].time);
    EXPECT_EQ(a.fractures[i].seeds, b.fractures[i].seeds);
    EXPECT_EQ(a.fractures[i].child_body, b.fractures[i].child_body);
  }
  EXPECT_EQ(a.parameters, b.parameters);
  ASSERT_EQ(a.summary.size(), b.summary.size());
  for (std::size_t i = 0; i < a.summary.size(); ++i)
    if (a.summary[i].first != "wall_time") {
      EXPECT_EQ(a.summary[i], b.summary[i]);
    }
}

void expect_same_frames(const std::string& a, const std::string& b, int frames) {
  for (int f = 0; f <= frames; ++f) {
    const std::string x = frame_file_name(a + "/frames", f), y = frame_file_name(b + "/frames", f);
    ASSERT_TRUE(test::exists(x) && test::exists(y)) << x << " " << y;
    EXPECT_EQ(bytes_of(x), bytes_of(y)) << "frame " << f;
  }
}

TEST(Checkpoint, ResumedRunIsBitIdenticalWithBodiesAndFracture) {
  Fixture fx;
  const sim::RunSummary whole = fx.run("whole");
  ASSERT_FALSE(whole.stopped);
  EXPECT_FALSE(test::exists(fx.dir.file("whole/checkpoint.h5")));
  const RunRecord reference = read_run(fx.dir.file("whole/run.h5"));
  ASSERT_FALSE(reference.fractures.empty());
  ASSERT_EQ(reference.frames.size(), 7u);

  // Stopped after frame 2: the wall has broken and its fragments move; then resumed.
  const sim::RunSummary first = fx.run("parts", 2);
  ASSERT_TRUE(first.stopped);
  ASSERT_TRUE(test::exists(fx.dir.file("parts/checkpoint.h5")));
  EXPECT_FALSE(test::exists(fx.dir.file("parts/frames/000003.h5")));
  {
    const RunRecord stopped = read_run(fx.dir.file("parts/run.h5"));
    EXPECT_EQ(stopped.frames.size(), 3u);
    EXPECT_NE(stopped.status.find("stopped"), std::string::npos) << stopped.status;
    ASSERT_FALSE(stopped.fractures.empty()) << "the wall should break before the checkpoint";
    EXPECT_GT(stopped.bodies.size(), 1u);
  }
  const sim::RunSummary second = fx.run("parts", -1, true);
  EXPECT_EQ(second.resumed_from, 2);
  EXPECT_FALSE(test::exists(fx.dir.file("parts/checkpoint.h5")));
  expect_same_frames(fx.dir.file("whole"), fx.dir.file("parts"), 6);
  expect_same_run(reference, read_run(fx.dir.file("parts/run.h5")));
  EXPECT_EQ(whole.steps, second.steps);
  EXPECT_EQ(whole.particle_steps, second.particle_steps);

  // Twice stopped, at frames 1 and 4 (before and after the fracture), the same again.
  fx.run("thrice", 1);
  fx.run("thrice", 4, true);
  fx.run("thrice", -1, true);
  expect_same_frames(fx.dir.file("whole"), fx.dir.file("thrice"), 6);
  expect_same_run(reference, read_run(fx.dir.file("thrice/run.h5")));
}

// The continuity equation's densities are state, and so are the loads the run file
// records: both go through a checkpoint, bit for bit; and the frames' wall pressure,
// whose means start again at every frame, of the static floor and of the wall's
// bodies before and after they break.
TEST(Checkpoint, ContinuityDensitiesLoadsAndSensorsResumeBitIdentical) {
  Fixture fx;
  fx.scene = scene::load_scene(
      fx.dir.file("scene.toml"),
      {"fluid.density=\"continuity\"", "output.loads=true", "output.sensor_rate=430",
       "output.fields=[\"velocity\", \"density\", \"pressure\", \"id\", \"boundary\", \"wall_pressure\"]"});
  // A sensor on the floor under the water's path: 430 samples a second, so that a
  // stop at a frame (every 0.01 s) falls inside a sample.
  scene::Sensor floor;
  floor.name = "floor";
  floor.at = Vec3d(0.2, 0.15, 0);
  floor.radius = 0.02;
  floor.solid = 0;
  fx.scene.sensors.push_back(floor);
  fx.run("whole");
  const RunRecord reference = read_run(fx.dir.file("whole/run.h5"));
  ASSERT_EQ(reference.loads.size(), reference.frames.size());
  ASSERT_EQ(reference.sensors.samples(), 25u);
  fx.run("parts", 2);
  fx.run("parts", -1, true);
  expect_same_frames(fx.dir.file("whole"), fx.dir.file("parts"), 6);
  const RunRecord resumed = read_run(fx.dir.file("parts/run.h5"));
  expect_same_run(reference, resumed);
  ASSERT_EQ(resumed.loads.size(), reference.loads.size());
  for (std::size_t f = 0; f < reference.loads.size(); ++f) EXPECT_EQ(resumed.loads[f], reference.loads[f]) << "frame " << f;
  EXPECT_EQ(resumed.sensors.pressure, reference.sensors.pressure);
  EXPECT_GT(*std::max_element(reference.sensors.pressure.begin(), reference.sensors.pressure.end()), 0.0)
      << "the water pushes on the floor";
  // The water, shot at 10 m/s, strikes the wall, then its pieces (the bodies'
  // particles, z > 0), in every frame after the first (measured 342 kPa at the most in
  // frame 1, 37 kPa in frame 6), and falls on the floor (z < 0) from frame 2 on.
  for (int f = 1; f <= 6; ++f) {
    const FrameData d = read_frame(frame_file_name(fx.dir.file("whole/frames"), f));
    ASSERT_EQ(d.bp.size(), d.bx.size());
    float on_floor = 0, on_wall = 0;
    for (std::size_t k = 0; k < d.bp.size(); ++k) {
      ASSERT_TRUE(std::isfinite(d.bp[k]));
      float& most = d.bz[k] < 0 ? on_floor : on_wall;
      most = std::max(most, d.bp[k]);
    }
    if (f >= 2) {
      EXPECT_GT(on_floor, 100.0f) << "frame " << f;
    }
    EXPECT_GT(on_wall, 1000.0f) << "frame " << f;
  }
}

// A solid moved as told (`motion`): a paddle behind still water pushes it 1.5 cm toward
// the wall in the first 30 ms, then stops. Its pose and the work it did go through a
// checkpoint taken while it moves, bit for bit.
TEST(Checkpoint, ResumedRunIsBitIdenticalWithAMovingSolid) {
  Fixture fx;
  std::ofstream(fx.dir.file("moving.toml"))
      << test::fracture_scene(0.0, 0.45, kEnd,
                              "[[solid]]\nname = \"paddle\"\nparticles = \"wall.h5\"\ntranslation = [0.02, 0.02, 0]\n"
                              "motion = [[0, 0.5, 0, 0], [0.03, 0.5, 0, 0], [0.03, 0, 0, 0]]\n");
  fx.scene = scene::load_scene(fx.dir.file("moving.toml"));
  fx.run("whole");
  const RunRecord reference = read_run(fx.dir.file("whole/run.h5"));
  fx.run("parts", 1);  // at 0.01 s, the paddle halfway through its push
  fx.run("parts", -1, true);
  expect_same_frames(fx.dir.file("whole"), fx.dir.file("parts"), 6);
  expect_same_run(reference, read_run(fx.dir.file("parts/run.h5")));
  ASSERT_FALSE(reference.frames.empty());
  EXPECT_GT(reference.frames.back().emitted_energy, 0.0) << "the paddle's work on the water";
}

// The same paddle hinged at its foot and swung toward the water while it slides: the
// pivot that its slide carries and the turn go through the checkpoint, bit for bit.
TEST(Checkpoint, ResumedRunIsBitIdenticalWithATurningSolid) {
  Fixture fx;
  std::ofstream(fx.dir.file("turning.toml"))
      << test::fracture_scene(0.0, 0.45, kEnd,
                              "[[solid]]\nname = \"paddle\"\nparticles = \"wall.h5\"\ntranslation = [0.02, 0.02, 0]\n"
                              "motion = [[0, 0.5, 0, 0], [0.03, 0.5, 0, 0], [0.03, 0, 0, 0]]\n"
                              "angular_motion = [[0, 0], [0.02, 3], [0.04, 0]]\naxis = [0, 1, 0]\npivot = [0.05, 0.17, 0]\n");
  fx.scene = scene::load_scene(fx.dir.file("turning.toml"));
  fx.run("whole");
  const RunRecord reference = read_run(fx.dir.file("whole/run.h5"));
  fx.run("parts", 1);  // at 0.01 s, the paddle sliding and turning
  fx.run("parts", -1, true);
  expect_same_frames(fx.dir.file("whole"), fx.dir.file("parts"), 6);
  expect_same_run(reference, read_run(fx.dir.file("parts/run.h5")));
  ASSERT_FALSE(reference.frames.empty());
  EXPECT_GT(reference.frames.back().emitted_energy, 0.0) << "the paddle's work on the water";
}

// One InputError line containing `what`.
void expect_refused(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "not refused: " << what;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(what), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(Checkpoint, OtherSceneVersionEndOrDeviceIsRefused) {
  Fixture fx;
  fx.run("run", 1, false, "bw-sim");
  const std::string ckpt = fx.dir.file("run/checkpoint.h5");
  ASSERT_TRUE(test::exists(ckpt));
  const std::string before = bytes_of(ckpt);

  const scene::Scene other = scene::load_scene(fx.dir.file("scene.toml"), {"solid[1].frc=0.5"});
  expect_refused([&] { fx.run("run", -1, true, "bw-sim", &other); }, "made for another scene");
  expect_refused([&] { fx.run("run", -1, true, "bw-sim-next"); }, "a run goes on only with the version it started with");
  expect_refused([&] { fx.run("run", -1, true, "bw-sim", nullptr, nullptr, 0.05); }, "the run goes to 0.06 s, not 0.05 s");
  compute::DeviceInfo elsewhere = fx.device;
  elsewhere.compute_units += 1;
  expect_refused([&] { fx.run("run", -1, true, "bw-sim", nullptr, &elsewhere); },
                 "a run goes on bit-identically only on the device it started on");
  // Nothing was written by the refusals; the checkpoint still resumes.
  EXPECT_EQ(bytes_of(ckpt), before);
  EXPECT_FALSE(test::exists(fx.dir.file("run/frames/000002.h5")));
  const sim::RunSummary done = fx.run("run", -1, true);
  EXPECT_EQ(done.frames, 7);
  expect_refused([&] { fx.run("run", -1, true); }, "no checkpoint to resume from (the run in that folder is complete)");
  // Another kind of file under the checkpoint's name.
  std::ofstream(ckpt) << "not a checkpoint";
  expect_refused([&] { fx.run("run", -1, true); }, ckpt);
}

// bw-sim end to end: SIGTERM stops it after a whole frame, with a checkpoint, the
// place it stopped and how to go on, and exit status 143; --resume finishes the run
// as if it had never stopped.
TEST(Checkpoint, SigtermStopsBwSimWithACheckpointAndResumeFinishes) {
  Fixture fx;
  const std::string sim = test::tool("bw-sim");
  const std::string scene = fx.dir.file("scene.toml");
  auto whole = test::run(sim + " " + scene + " -o " + fx.dir.file("whole") + " --quiet");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  // Stopped once frame 1 is on disk (so in frame 2 or later).
  const std::string out = fx.dir.file("stopped");
  auto stopped = test::run("(" + sim + " " + scene + " -o " + out + " --quiet & pid=$!; while [ ! -e " + out +
                           "/frames/000001.h5 ]; do sleep 0.02; done; kill -TERM $pid; wait $pid; echo status $?)");
  ASSERT_NE(stopped.out.find("status 143"), std::string::npos) << stopped.out << stopped.err;
  EXPECT_NE(stopped.err.find("bw-sim: stopped by SIGTERM after frame "), std::string::npos) << stopped.err;
  EXPECT_NE(stopped.err.find("go on with: bw-sim --resume " + out), std::string::npos) << stopped.err;
  ASSERT_TRUE(test::exists(out + "/checkpoint.h5"));
  const RunRecord partial = read_run(out + "/run.h5");
  for (std::size_t f = 0; f < partial.frames.size(); ++f) EXPECT_NO_THROW(read_frame(frame_file_name(out + "/frames", static_cast<int>(f))));
  // The checkpoint holds the run file's rows: make deletes a target whose recipe
  // stopped (.DELETE_ON_ERROR), and the run goes on without it.
  std::remove((out + "/run.h5").c_str());
  if (partial.frames.size() < 7) {
    auto resumed = test::run(sim + " --resume " + out + " --quiet");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  }
  expect_same_frames(fx.dir.file("whole"), out, 6);
  expect_same_run(read_run(fx.dir.file("whole/run.h5")), read_run(out + "/run.h5"));
  // Wrong uses: no checkpoint there, and a folder other than the run's.
  auto none = test::run(sim + " --resume " + fx.dir.file("whole") + " --quiet");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(test::line_count(none.err), 1) << none.err;
  auto other = test::run(sim + " --resume " + out + " -o " + fx.dir.file("elsewhere"));
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("a resumed run writes where it started"), std::string::npos) << other.err;
}

}  // namespace
}  // namespace bw

// bw-render end to end: images named by frame number, ranges, determinism, video,
// and every bad input with its exit code and one-line message.
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "render/image.h"
#include "render/video.h"
#include "synthetic.h"
#include "test_support.h"

namespace br = bw::render;
using bw::test::run;
using bw::Vec3d;

namespace {

const std::string kTool = bw::test::tool("bw-render");
const std::string kSmall = " --width 160 --height 120";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// OUT/run.h5 (a wall), OUT/frames/00000N.h5 for N in `frames`: a ball falling; with
// `loaded`, the wall's face loaded by a pressure that grows with the frame (frame 0:
// none, as bw-sim writes it).
void write_run(const bw::test::TempDir& dir, std::initializer_list<int> frames, bool loaded = false) {
  br::test::write_wall_run(dir.path());
  std::filesystem::create_directories(dir.file("frames"));
  for (int n : frames) {
    bw::FrameData f;
    f.frame = n;
    f.time = n / 30.0;
    br::test::add_ball(f, Vec3d(0, 0, 0.8 - 0.05 * n), 0.2, 0.04, 0.1, 7);
    if (loaded)
      br::test::add_wall_pressure(f, dir.path(),
                                  [n](const Vec3d& x) { return x.y() < 0.55 ? 1000.0 * n * (1 + x.z()) : 0.0; });
    bw::write_frame(f, bw::frame_file_name(dir.file("frames"), n));
  }
}

// Nothing was written under `folder` (which may not exist at all).
bool nothing_in(const std::string& folder) {
  return !bw::test::exists(folder) || bw::test::list_folder(folder).empty();
}

void expect_one_line_error(const bw::test::CommandResult& r, int code, const std::string& fragment) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("bw-render: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

}  // namespace

TEST(BwRender, OnePngPerFrameNamedByNumber) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 2, 3, 4});
  const auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("images") + " --frames 1:4:2" + kSmall);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(bw::test::list_folder(dir.file("images")), "000001.png 000003.png");
  const br::Image image = br::read_png(dir.file("images/000003.png"));
  EXPECT_EQ(image.width, 160);
  EXPECT_EQ(image.height, 120);
  // The settings used are kept in the image (PNG text chunks).
  const std::string png = slurp(dir.file("images/000003.png"));
  EXPECT_NE(png.find("bw-render "), std::string::npos);
  EXPECT_NE(png.find("frame 3, t = 0.1 s"), std::string::npos);
  EXPECT_NE(png.find("filter narrow-range"), std::string::npos);
  // Quiet output when stderr is not a terminal: the summary line, with ms per frame.
  EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("ms per frame"), std::string::npos) << r.err;
  EXPECT_TRUE(run(kTool + " " + dir.file("frames") + " -o " + dir.file("q") + " -q --frames 0" + kSmall).err.empty());
}

TEST(BwRender, SameFrameTwiceGivesTheSameBytes) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1});
  for (const char* out : {"a", "b"})
    ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file(out) + " --frames 1" + kSmall).exit_code, 0);
  const std::string a = slurp(dir.file("a/000001.png")), b = slurp(dir.file("b/000001.png"));
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
}

// Different ranges rendered apart agree with one run over all of them: the particle
// size, ground and fitted camera come from the folder's first frame.
TEST(BwRender, RangesRenderedApartMatchOneRun) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 2});
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file("all") + kSmall).exit_code, 0);
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file("part") + " --frames 2:" + kSmall).exit_code, 0);
  EXPECT_EQ(slurp(dir.file("all/000002.png")), slurp(dir.file("part/000002.png")));
}

// Spray is classified per frame with the reference frame's spacing: a sequence of
// a ball shedding drops rendered in parts matches one run; --spray off draws the
// drops as water, which changes the image.
TEST(BwRender, SprayRangesRenderedApartMatchOneRun) {
  bw::test::TempDir dir;
  br::test::write_wall_run(dir.path());
  std::filesystem::create_directories(dir.file("frames"));
  for (int n : {0, 1, 2}) {
    bw::FrameData f;
    f.frame = n;
    f.time = n / 30.0;
    br::test::add_ball(f, Vec3d(0, 0, 0.6), 0.2, 0.04, 0.1, 7);
    for (int k = 0; k < 12; ++k) {  // drops around the ball, farther out each frame
      const double a = 0.5236 * k, r = 0.3 + 0.05 * n;
      f.x.push_back(float(r * std::cos(a))), f.y.push_back(-0.1f), f.z.push_back(float(0.6 + r * std::sin(a)));
    }
    bw::write_frame(f, bw::frame_file_name(dir.file("frames"), n));
  }
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file("all") + kSmall).exit_code, 0);
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file("part") + " --frames 2:" + kSmall).exit_code, 0);
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + " -o " + dir.file("off") + " --frames 2 --spray off" + kSmall)
                .exit_code,
            0);
  EXPECT_EQ(slurp(dir.file("all/000002.png")), slurp(dir.file("part/000002.png")));
  EXPECT_NE(slurp(dir.file("all/000002.png")), slurp(dir.file("off/000002.png")));
}

// A scene with emitters starts nearly empty: particle size, ground and the fitted
// camera come from the first frame with particles, whatever the range.
TEST(BwRender, ReferenceFrameIsTheFirstWithParticles) {
  bw::test::TempDir dir;
  write_run(dir, {1, 2});
  bw::FrameData empty;
  bw::write_frame(empty, bw::frame_file_name(dir.file("frames"), 0));
  const auto all = run(kTool + " " + dir.file("frames") + " -o " + dir.file("all") + " -v" + kSmall);
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.err.find("reference    " + dir.file("frames") + "/000001.h5"), std::string::npos) << all.err;
  // Measured on the ball of frame 1 (a lattice of 4 cm, jittered), not the fallback.
  EXPECT_NE(all.err.find("(spacing 0.03"), std::string::npos) << all.err;
  const auto part = run(kTool + " " + dir.file("frames") + " -o " + dir.file("part") + " --frames 2 -v" + kSmall);
  ASSERT_EQ(part.exit_code, 0) << part.err;
  EXPECT_EQ(slurp(dir.file("all/000002.png")), slurp(dir.file("part/000002.png")));
}

TEST(BwRender, SceneTablesAndCommandLine) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  std::ofstream(dir.file("scene.toml")) << "[fluid]\nrho0 = 998\n[render]\nwidth = 96\nheight = 64\n"
                                           "[camera]\nposition = [0, -3, 1]\ntarget = [0, 0, 0.5]\n";
  auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --scene " + dir.file("scene.toml") + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(br::read_png(dir.file("i/000000.png")).width, 96);
  EXPECT_NE(r.err.find("camera       0,-3,1:0,0,0.5:45\n"), std::string::npos) << r.err;
  r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("j") + " --scene " + dir.file("scene.toml") +
          " --width 50 --camera 1,-3,1:0,0,0.5:30 -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(br::read_png(dir.file("j/000000.png")).width, 50);
  EXPECT_NE(r.err.find("camera       1,-3,1:0,0,0.5:30\n"), std::string::npos) << r.err;
}

// A camera with keys moves with the frames' times; each PNG records its own camera,
// and a part of the sequence renders its frames as the whole does.
TEST(BwRender, ACameraWithKeysMovesWithTheFramesTimes) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 2, 3});  // t = n / 30 s
  std::ofstream(dir.file("scene.toml")) << "[camera]\ntarget = [0, 0, 0.5]\ninterpolation = \"linear\"\n"
                                           "[[camera.key]]\ntime = 0\nposition = [0, -3, 1]\n"
                                           "[[camera.key]]\ntime = 0.1\nposition = [3, 0, 1]\nfov = 30\n";
  const std::string scene = " --scene " + dir.file("scene.toml") + kSmall;
  const auto all = run(kTool + " " + dir.file("frames") + " -o " + dir.file("all") + scene + " -v");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.err.find("moving       2 keys from t = 0 to 0.1 s, linear"), std::string::npos) << all.err;
  EXPECT_NE(slurp(dir.file("all/000000.png")).find("camera 0,-3,1:0,0,0.5:45 "), std::string::npos);
  EXPECT_NE(slurp(dir.file("all/000001.png")).find("camera 1,-2,1:0,0,0.5:40 "), std::string::npos);
  EXPECT_NE(slurp(dir.file("all/000003.png")).find("camera 3,0,1:0,0,0.5:30 "), std::string::npos);
  const auto part = run(kTool + " " + dir.file("frames") + " -o " + dir.file("part") + " --frames 2" + scene);
  ASSERT_EQ(part.exit_code, 0) << part.err;
  EXPECT_EQ(slurp(dir.file("all/000002.png")), slurp(dir.file("part/000002.png")));

  // Looking straight down along up at frame 2's time only (t = 1/15 s, between the
  // points where the scene's check samples the path): refused before any drawing.
  std::ofstream(dir.file("down.toml")) << "[camera]\ntarget = [0, 0, 0.5]\ninterpolation = \"linear\"\n"
                                          "[[camera.key]]\ntime = 0\nposition = [-2, 0, 1.5]\n"
                                          "[[camera.key]]\ntime = 0.1\nposition = [1, 0, 1.5]\n";
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("down") + " --scene " +
                            dir.file("down.toml") + kSmall),
                        2, "000002.h5: the camera at t = 0.0666667 s: up: is parallel to the viewing direction");
  EXPECT_TRUE(nothing_in(dir.file("down")));
}

// Without --scene, the look is that of the scene the run was made with (the run file
// keeps its text); --scene replaces it, --no-scene leaves the defaults and a fitted camera.
TEST(BwRender, RunsSceneTablesUnlessTold) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  bw::RunRecord record = bw::read_run(dir.file("run.h5"));
  record.scene_text = "spacing = 0.05\n[render]\nwidth = 72\nheight = 40\n"
                      "[camera]\nposition = [0, -3, 1]\ntarget = [0, 0, 0.5]\n";
  bw::write_run(record, dir.file("run.h5"));
  auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(br::read_png(dir.file("i/000000.png")).width, 72);
  EXPECT_NE(r.err.find("look         the scene of " + dir.file("run.h5")), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("camera       0,-3,1:0,0,0.5:45\n"), std::string::npos) << r.err;

  r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("j") + " --no-scene" + kSmall + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(br::read_png(dir.file("j/000000.png")).width, 160);
  EXPECT_NE(r.err.find("look         defaults"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(fitted)"), std::string::npos) << r.err;

  std::ofstream(dir.file("scene.toml")) << "[render]\nwidth = 48\nheight = 32\n";
  r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("k") + " --scene " + dir.file("scene.toml") + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(br::read_png(dir.file("k/000000.png")).width, 48);
  EXPECT_NE(r.err.find("(fitted)"), std::string::npos) << r.err;
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("k") + " --scene " +
                            dir.file("scene.toml") + " --no-scene"),
                        2, "--no-scene");

  // A run whose scene bw-render cannot draw (bw-sim refuses such scenes; an older run)
  // is named with the key, and nothing is drawn.
  record.scene_text = "[render]\nwidth = 0\n";
  bw::write_run(record, dir.file("run.h5"));
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("l")), 2,
                        dir.file("run.h5") + ": scene: render.width: 0 is outside [1, 16384]");
  EXPECT_TRUE(nothing_in(dir.file("l")));
}

// A breakable wall cut into fragments that the frame poses: drawn with the fragments
// file, counted as bodies without a mesh without it.
TEST(BwRender, FragmentsPlacedByTheirBodies) {
  bw::test::TempDir dir;
  write_run(dir, {});
  bw::FrameData f = br::test::splash_frame(3000);
  br::test::break_wall(dir.path(), f);
  bw::write_frame(f, bw::frame_file_name(dir.file("frames"), 0));
  auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("with") + " --fragments " +
               dir.file("fragments.h5") + " -v" + kSmall);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fragments 3"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("no mesh"), std::string::npos) << r.err;
  r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("without") + kSmall);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("up to 3 bodies per frame had no mesh to draw (give --fragments)"), std::string::npos)
      << r.err;
  EXPECT_NE(slurp(dir.file("with/000000.png")), slurp(dir.file("without/000000.png")));
}

// Water inside a tank: the dam break of examples/dambreak.toml, whose walls stand
// twice as high as its water column and more than twice the cavity's width. The
// fitted camera looks over the walls: it sees most of the water of the column
// (frame 0) and of the surge over the floor (frame 1) that the same camera sees
// with the tank taken away. A camera from which the front wall hides all the water
// draws none of it, and the summary says so.
TEST(BwRender, FittedCameraSeesTheWaterInATank) {
  bw::test::TempDir dir;
  br::test::write_tank_run(dir.path());
  std::filesystem::create_directories(dir.file("frames"));
  for (int n : {0, 1}) bw::write_frame(br::test::dambreak_frame(n), bw::frame_file_name(dir.file("frames"), n));
  bw::RunRecord no_solids;
  no_solids.status = "complete";
  bw::write_run(no_solids, dir.file("no-solids.h5"));
  const auto water_pixels = [&](const std::string& folder, int n) {
    const br::Image image = br::read_png(dir.file(folder + fmt::format("/{:06d}.png", n)));
    int water = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) water += image.pixel(x, y)[0] > 0;
    return water;
  };

  const auto fitted = run(kTool + " " + dir.file("frames") + " -o " + dir.file("tank") + " --view depth -v" + kSmall);
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  EXPECT_EQ(fitted.err.find("sees none of the water"), std::string::npos) << fitted.err;
  const std::string key = "  camera       ";
  const std::size_t at = fitted.err.find(key);
  ASSERT_NE(at, std::string::npos) << fitted.err;
  const std::string camera = fitted.err.substr(at + key.size(), fitted.err.find(' ', at + key.size()) - at - key.size());
  const auto bare = run(kTool + " " + dir.file("frames") + " -o " + dir.file("bare") + " --run " +
                        dir.file("no-solids.h5") + " --camera " + camera + " --view depth" + kSmall);
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  for (int n : {0, 1}) {
    const int in_tank = water_pixels("tank", n), without = water_pixels("bare", n);
    bw::test::figure(fmt::format("frame {}: water pixels in the tank / without it", n),
                     static_cast<double>(in_tank) / std::max(without, 1));
    EXPECT_GT(without, 200) << "frame " << n;
    EXPECT_GE(in_tank, 0.6 * without) << "frame " << n << ", camera " << camera;
  }

  const auto hidden = run(kTool + " " + dir.file("frames") + " -o " + dir.file("hidden") +
                          " --frames 0 --camera 0.3,-0.6,1.2:0.3,0.075,0.05:40 --view depth" + kSmall);
  ASSERT_EQ(hidden.exit_code, 0) << hidden.err;
  EXPECT_EQ(water_pixels("hidden", 0), 0);
  EXPECT_NE(hidden.err.find("the camera sees none of the water of the reference frame"), std::string::npos)
      << hidden.err;
}

// The solids coloured by the wall pressure: one scale for the folder, so a frame
// rendered alone is the frame rendered with the others, byte for byte; the scale
// the summary names is 0 to the loaded patches' 99th percentile (about
// 2 x 2000 Pa); given a range, the image changes; without the water, too.
TEST(BwRender, SolidsColouredByTheWallPressureKeepOneScaleForTheFolder) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 2}, true);
  const std::string base = kTool + " " + dir.file("frames") + kSmall + " --solids wall_pressure";
  const auto all = run(base + " -o " + dir.file("all"));
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.err.find("coloured by the wall pressure, 0 to 3"), std::string::npos) << all.err;
  EXPECT_NE(all.err.find("up to the 99th percentile of the loaded patches of the folder's 3 frames"),
            std::string::npos)
      << all.err;
  ASSERT_EQ(run(base + " -o " + dir.file("one") + " --frames 1").exit_code, 0);
  EXPECT_EQ(slurp(dir.file("all/000001.png")), slurp(dir.file("one/000001.png")));
  const auto ranged = run(base + " -o " + dir.file("ranged") + " --frames 1 --pressure-range 0:10000");
  ASSERT_EQ(ranged.exit_code, 0) << ranged.err;
  EXPECT_NE(ranged.err.find("0 to 1e+04 Pa (render.pressure_range)"), std::string::npos) << ranged.err;
  EXPECT_NE(slurp(dir.file("ranged/000001.png")), slurp(dir.file("one/000001.png")));
  ASSERT_EQ(run(base + " -o " + dir.file("dry") + " --frames 1 --no-water").exit_code, 0);
  EXPECT_NE(slurp(dir.file("dry/000001.png")), slurp(dir.file("one/000001.png")));
  ASSERT_EQ(run(kTool + " " + dir.file("frames") + kSmall + " -o " + dir.file("plain") + " --frames 1").exit_code, 0);
  EXPECT_NE(slurp(dir.file("plain/000001.png")), slurp(dir.file("one/000001.png")));
}

TEST(BwRender, SolidsColouredByAFieldTheFramesLackIsBadInput) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1});
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("out") + " --solids wall_pressure"),
                        2, "000000.h5: holds no wall pressure; add \"wall_pressure\" to the scene's [output] fields");
  EXPECT_TRUE(nothing_in(dir.file("out")));
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("out") + " --pressure-range 0:10"), 2,
                        "--pressure-range: only with --solids wall_pressure");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("out") +
                            " --solids wall_pressure --pressure-range 5:1"),
                        2, "--pressure-range '5:1': MAX must be above MIN");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("out") +
                            " --solids wall_pressure --pressure-range 0:x"),
                        2, "--pressure-range '0:x': expected MIN:MAX, two numbers in Pa");
  EXPECT_TRUE(nothing_in(dir.file("out")));
}

TEST(BwRender, Video) {
  if (br::find_on_path("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed";
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 2});
  const auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --video " + dir.file("ball.mp4") +
                     kSmall);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(slurp(dir.file("ball.mp4")).size(), 500u);
  EXPECT_NE(r.err.find("at 30 fps"), std::string::npos) << r.err;
  EXPECT_EQ(bw::test::list_folder(dir.path()).find(".tmp"), std::string::npos);
}

TEST(BwRender, VideoWithoutFfmpegFails) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  const auto r = run("PATH=/nonexistent " + kTool + " " + dir.file("frames") + " -o " + dir.file("i") +
                     " --video " + dir.file("v.mp4") + kSmall);
  expect_one_line_error(r, 1, "ffmpeg, which is not installed");
  EXPECT_FALSE(bw::test::exists(dir.file("i")));
  // A video in a folder that does not exist: refused before anything is made.
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --video " +
                            dir.file("no/v.mp4") + kSmall),
                        2, dir.file("no/v.mp4") + ": folder '" + dir.file("no") + "' does not exist");
  EXPECT_FALSE(bw::test::exists(dir.file("i")));
}

TEST(BwRender, MissingFrame) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1, 3});
  const auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --frames 0:3" + kSmall);
  expect_one_line_error(r, 2, "frame 2 is missing: " + dir.file("frames") + "/000002.h5");
  EXPECT_TRUE(nothing_in(dir.file("i")));
  expect_one_line_error(run(kTool + " " + dir.file("nowhere") + " -o " + dir.file("i")), 2, "no such folder");
  std::filesystem::create_directories(dir.file("empty"));
  expect_one_line_error(run(kTool + " " + dir.file("empty") + " -o " + dir.file("i")), 2, "holds no frame files");
}

TEST(BwRender, FrameOfTheWrongKind) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  std::filesystem::copy_file(dir.file("wall.h5"), dir.file("frames/000001.h5"));
  const auto r = run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + kSmall);
  expect_one_line_error(r, 2, "000001.h5");
  EXPECT_NE(r.err.find("particles"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in(dir.file("i")));
  std::ofstream(dir.file("frames/000002.h5")) << "not HDF5";
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --frames 2"), 2,
                        "000002.h5");
}

TEST(BwRender, EmptyRange) {
  bw::test::TempDir dir;
  write_run(dir, {0, 1});
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --frames 5:3"), 2,
                        "empty");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --frames 5:"), 2,
                        "empty");
}

TEST(BwRender, UnwritableOutputFolder) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  std::ofstream(dir.file("file")) << "x";
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("file/images")), 2,
                        dir.file("file/images"));
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("file")), 2, dir.file("file"));
}

TEST(BwRender, BadSceneAndOptions) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  std::ofstream(dir.file("scene.toml")) << "[render]\nwidht = 3\n";
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --scene " +
                            dir.file("scene.toml")),
                        2, "render.widht: unknown key");
  // The scene file is read as bw-sim reads it: the same errors.
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --scene " +
                            dir.file("none.toml")),
                        2, dir.file("none.toml") + ": no such file");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --scene " + dir.path()), 2,
                        dir.path() + ": is a folder, not a scene file");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --filter gauss"), 2,
                        "--filter");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --camera 1,2"), 2,
                        "--camera");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --video out.gif"), 2,
                        ".mp4, .mov or .mkv");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --device gpu"), 2,
                        "--device");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --device 99"), 2,
                        "--device 99");
  expect_one_line_error(run(kTool + " " + dir.file("frames") + " -o " + dir.file("i") + " --fragments " +
                            dir.file("wall.h5")),
                        2, "wall.h5");
}

// No EGL display, or no OpenGL 4.5: exit 1 with what was looked for. glvnd finds no
// vendor library when pointed at none; Mesa offers no 4.5 context when told to
// report an older version.
TEST(BwRender, NoDisplayOrNoOpenGl45) {
  bw::test::TempDir dir;
  write_run(dir, {0});
  const std::string args = fmt::format(" {} -o {}{}", dir.file("frames"), dir.file("i"), kSmall);
  auto r = run(fmt::format("__EGL_VENDOR_LIBRARY_FILENAMES={} {}{}", dir.file("none.json"), kTool, args));
  expect_one_line_error(r, 1, "no EGL display with OpenGL 4.5 core");
  EXPECT_NE(r.err.find("EGL_MESA_platform_surfaceless"), std::string::npos) << r.err;
  r = run("MESA_GL_VERSION_OVERRIDE=3.3 " + kTool + args);
  if (r.exit_code == 0) GTEST_SKIP() << "the EGL driver here is not Mesa";
  expect_one_line_error(r, 1, "no EGL display with OpenGL 4.5 core");
  EXPECT_FALSE(bw::test::exists(dir.file("i/000000.png")));
}

// A real client: headless Blender imports bw-export's files of a small fracture run
// (bw-sim breaking a wall, bw-voronoi replay, bw-export) and reports what it made of
// them; tests/export/blender_check.py compares that with the run's frame files: the
// number of objects, the animation's frames, the VDB's grids, a fragment's world
// matrix at a frame, the fragment hidden before its fracture and its parent after,
// and the scene's moving camera where bw-render puts it at three frames.
// Blender is one of the packages tools/install-deps.sh installs; without it the test
// fails and says so.
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "export/job.h"
#include "fracture_fixtures.h"
#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "io/run_file.h"
#include "render/render_settings.h"
#include "test_support.h"

namespace bw {
namespace {

std::string matrix_json(const Vec3d& p, const Eigen::Quaterniond& q) {
  const Mat3d r = q.normalized().toRotationMatrix();
  std::string rows;
  for (int i = 0; i < 3; ++i)
    rows += fmt::format("{}[{},{},{},{}]", i ? "," : "", r(i, 0), r(i, 1), r(i, 2), p[i]);
  return "[" + rows + ",[0,0,0,1]]";
}

// The scene's moving camera, fixed target, field of view changing (which glTF does not animate).
const char* const kCamera =
    "[camera]\ntarget = [0.3, 0.1, 0.2]\ninterpolation = \"linear\"\n[[camera.key]]\ntime = 0\nposition = [-0.5, -2, 1]\n"
    "[[camera.key]]\ntime = 0.03\nposition = [1.5, -1.5, 1.2]\nfov = 30\n";

// A wall broken by water: bw-sim into DIR/run, bw-voronoi replay, bw-export with `export_args` into DIR/export.
void fracture_run_exported(const test::TempDir& dir, const std::string& export_args) {
  test::write_fracture_solids(dir.file(""));
  std::ofstream(dir.file("scene.toml")) << test::fracture_scene(10.0, 0.45, 0.03,
                                                                std::string("[fracture]\nmax_chunks = 8\n") + kCamera);
  auto r = test::run(test::tool("bw-sim") + " " + dir.file("scene.toml") + " -o " + dir.file("run") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(test::tool("bw-voronoi") + " replay " + dir.file("run/run.h5") + " -o " + dir.file("run/fragments.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  r = test::run(test::tool("bw-export") + " " + dir.file("run/frames") + " -o " + dir.file("export") + " " + export_args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::cerr << r.err;
}

// The camera at `frames` as bw-render draws them, for the check scripts; its field of
// view is the first frame's throughout (glTF animates none).
std::string camera_views_json(const std::vector<FrameData>& frames, const std::vector<int>& at) {
  const render::CameraPath path = *render::parse_render_settings(kCamera, "camera").camera;
  std::string views;
  for (int f : at) {
    const render::Camera c = path.at(frames[static_cast<std::size_t>(f)].time);
    const Vec3d forward = (c.target - c.position).normalized();
    const Vec3d up = forward.cross(c.up).normalized().cross(forward);
    views += fmt::format(R"({}{{"frame":{},"position":[{},{},{}],"forward":[{},{},{}],"up":[{},{},{}],"fov_degrees":45}})",
                         views.empty() ? "" : ",", f, c.position.x(), c.position.y(), c.position.z(), forward.x(),
                         forward.y(), forward.z(), up.x(), up.y(), up.z());
  }
  return views;
}

// The line a check script prints ("PREFIX ok ..."), shown in the test's output.
std::string check_line(const test::CommandResult& r, const std::string& prefix) {
  const std::size_t at = r.out.find(prefix);
  const std::string line = at == std::string::npos ? "" : r.out.substr(at, r.out.find('\n', at) - at);
  std::cerr << (line.empty() ? r.out + r.err : line) << "\n";
  return line;
}

void require_blender() {
  const auto which = test::run("command -v blender");
  ASSERT_EQ(which.exit_code, 0) << "blender is not installed: tools/install-deps.sh installs it (Debian package "
                                   "blender); this test checks bw-export's files with it";
}

TEST(ExportBlender, BlenderImportsAFractureRun) {
  ASSERT_NO_FATAL_FAILURE(require_blender());
  test::TempDir dir;
  ASSERT_NO_FATAL_FAILURE(fracture_run_exported(dir, "--density"));

  const RunRecord run = read_run(dir.file("run/run.h5"));
  const FragmentSet fragments = read_fragments(dir.file("run/fragments.h5"));
  ASSERT_FALSE(run.fractures.empty());
  const int last = static_cast<int>(run.frames.size()) - 1;
  ASSERT_GE(last, 1);
  std::set<std::int32_t> seen;
  std::vector<FrameData> frames;
  for (int f = 0; f <= last; ++f) {
    frames.push_back(read_frame(frame_file_name(dir.file("run/frames"), f)));
    for (std::int32_t b : frames.back().bodies.id) seen.insert(b);
  }
  // The floor, the wall's own body (its solid's mesh) and every fragment seen.
  std::set<std::int32_t> with_mesh{0};
  for (const Fragment& f : fragments.fragments) with_mesh.insert(f.body);
  std::size_t objects = 1;
  for (std::int32_t b : seen) objects += with_mesh.count(b);

  // A fragment that is there in the last frame, made after frame 0.
  const FrameData& end = frames.back();
  std::size_t row = end.bodies.size();
  for (std::size_t i = 0; i < end.bodies.size() && row == end.bodies.size(); ++i)
    if (end.bodies.id[i] > 0 && with_mesh.count(end.bodies.id[i])) row = i;
  ASSERT_LT(row, end.bodies.size()) << "no fragment in the last frame";
  const std::int32_t body = end.bodies.id[row];
  const std::string name = run.bodies.at(static_cast<std::size_t>(body)).name;
  std::string poses = fmt::format(R"({{"name":"{}","body":{},"frame":{},"matrix":{}}})", name, body, last,
                                  matrix_json(end.bodies.position[row], end.bodies.orientation[row]));
  ASSERT_TRUE(frames.front().bodies.size() == 1 && frames.front().bodies.id[0] == 0);
  poses += fmt::format(R"(,{{"name":"{}","frame":0,"hidden":true}})", name);
  const bool wall_gone = std::find(end.bodies.id.begin(), end.bodies.id.end(), 0) == end.bodies.id.end();
  EXPECT_TRUE(wall_gone);
  if (wall_gone) poses += fmt::format(R"(,{{"name":"{}","frame":{},"hidden":true}})", run.bodies[0].name, last);
  const std::string views = camera_views_json(frames, {0, 1, last});
  std::ofstream(dir.file("expect.json")) << fmt::format(
      R"({{"fps":100,"objects":{},"frames":[0,{}],"grids":["surface","density"],"poses":[{}],"camera":[{}]}})",
      objects, last, poses, views);

  const std::string vdb = fmt::format("{}/water_{:06d}.vdb", dir.file("export"), last);
  const auto r = test::run("blender -b --factory-startup --python-exit-code 1 --python " + std::string(BW_SOURCE_DIR) +
                "/tests/export/blender_check.py -- --glb " + dir.file("export/solids.glb") + " --vdb " + vdb +
                " --expect " + dir.file("expect.json"));
  const std::string line = check_line(r, "blender-check:");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(line.rfind("blender-check: ok", 0), 0u) << r.out << r.err;
}

// bw-export's blender_scene.py, run by headless Blender, sets up the run: saved as a
// .blend and opened again, the scene has the run's frame rate and frames, the image
// size of [render], the scene's camera as the active one, and a water surface whose
// Volume to Mesh of the VDB sequence is, at each frame, bw-export's own mesh of that
// frame (the same volume and bounds); with --up y too, where the script turns the y-up
// grids back. Run from the text editor, it adds the same to the open file. And
// Cycles renders a frame of it.
TEST(ExportBlender, TheScriptSetsUpTheRunInBlender) {
  ASSERT_NO_FATAL_FAILURE(require_blender());
  test::TempDir dir;
  ASSERT_NO_FATAL_FAILURE(fracture_run_exported(dir, "--mesh obj"));
  const std::string script = dir.file("export/blender_scene.py");
  ASSERT_TRUE(std::filesystem::exists(script));
  auto r = test::run("blender -b --factory-startup --python-exit-code 1 --python " + script + " -- --save " +
                     dir.file("run.blend"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(check_line(r, "breakwater:").find("camera from solids.glb, saved"), std::string::npos) << r.out;

  const RunRecord run = read_run(dir.file("run/run.h5"));
  std::vector<FrameData> frames;
  for (std::size_t f = 0; f < run.frames.size(); ++f)
    frames.push_back(read_frame(frame_file_name(dir.file("run/frames"), static_cast<int>(f))));
  const int last = static_cast<int>(frames.size()) - 1;
  ASSERT_GE(last, 2);
  std::string water;
  for (int f : {0, 1, last})
    water += fmt::format(R"({}{{"frame":{},"file":"water_{:06d}.vdb","obj":"{}"}})", water.empty() ? "" : ",", f, f,
                         exporter::water_file_name(dir.file("export"), f, "obj"));
  const std::string check = " --python-exit-code 1 --python " + std::string(BW_SOURCE_DIR) +
                            "/tests/export/blender_scene_check.py -- --expect ";
  std::ofstream(dir.file("expect.json")) << fmt::format(
      R"({{"fps":100,"frames":[0,{}],"resolution":[1280,720],"camera":[{}],"water":[{}]}})", last,
      camera_views_json(frames, {0, 1, last}), water);
  r = test::run("blender -b " + dir.file("run.blend") + check + dir.file("expect.json"));
  EXPECT_EQ(check_line(r, "blender-scene-check:").rfind("blender-scene-check: ok", 0), 0u) << r.out << r.err;

  // Run from Blender's text editor, it adds the same to the file that is open.
  r = test::run("blender -b --factory-startup" + check + dir.file("expect.json") + " --run-as-text " + script);
  EXPECT_EQ(check_line(r, "blender-scene-check:").rfind("blender-scene-check: ok run as text, kept Camera, Cube, Light", 0),
            0u)
      << r.out << r.err;

  // Cycles draws a frame of it (small and with one sample: that it renders, not how well).
  r = test::run("blender -b " + dir.file("run.blend") +
                " --python-expr 'import bpy; s = bpy.context.scene; s.render.resolution_percentage = 5; "
                "s.cycles.samples = 1' -o " + dir.file("render_###") + " -F PNG -f 1");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("render_001.png"))) << r.out << r.err;

  // The water of --up y lands where the z-up mesh is.
  r = test::run(test::tool("bw-export") + " " + dir.file("run/frames") + " -o " + dir.file("export-y") +
                " --frames 1:1 --up y -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run("blender -b --factory-startup --python-exit-code 1 --python " + dir.file("export-y/blender_scene.py") +
                " -- --save " + dir.file("run-y.blend"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::ofstream(dir.file("expect-y.json"))
      << fmt::format(R"({{"frames":[1,1],"water":[{{"frame":1,"file":"water_000001.vdb","obj":"{}"}}]}})",
                     exporter::water_file_name(dir.file("export"), 1, "obj"));
  r = test::run("blender -b " + dir.file("run-y.blend") + check + dir.file("expect-y.json"));
  EXPECT_EQ(check_line(r, "blender-scene-check:").rfind("blender-scene-check: ok", 0), 0u) << r.out << r.err;
}

}  // namespace
}  // namespace bw

// A real client: headless Blender imports bw-export's files of a small fracture run
// (bw-sim breaking a wall, bw-voronoi replay, bw-export) and reports what it made of
// them; tests/export/blender_check.py compares that with the run's frame files: the
// number of objects, the animation's frames, the VDB's grids, a fragment's world
// matrix at a frame, the fragment hidden before its fracture and its parent after,
// and the scene's moving camera where bw-render puts it at three frames.
// Blender is one of the packages tools/install-deps.sh installs; without it the test
// fails and says so.
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>

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

TEST(ExportBlender, BlenderImportsAFractureRun) {
  const auto which = test::run("command -v blender");
  ASSERT_EQ(which.exit_code, 0) << "blender is not installed: tools/install-deps.sh installs it (Debian package "
                                   "blender); this test checks bw-export's files with it";
  test::TempDir dir;
  test::write_fracture_solids(dir.file(""));
  const std::string camera =
      "[camera]\ntarget = [0.3, 0.1, 0.2]\ninterpolation = \"linear\"\n[[camera.key]]\ntime = 0\nposition = [-0.5, -2, 1]\n"
      "[[camera.key]]\ntime = 0.03\nposition = [1.5, -1.5, 1.2]\nfov = 30\n";
  std::ofstream(dir.file("scene.toml")) << test::fracture_scene(10.0, 0.45, 0.03, "[fracture]\nmax_chunks = 8\n" + camera);
  auto r = test::run(test::tool("bw-sim") + " " + dir.file("scene.toml") + " -o " + dir.file("run") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(test::tool("bw-voronoi") + " replay " + dir.file("run/run.h5") + " -o " + dir.file("run/fragments.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  r = test::run(test::tool("bw-export") + " " + dir.file("run/frames") + " -o " + dir.file("export") + " --density");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::cerr << r.err;

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
  // The camera at frames 0, 1 and the last, as bw-render draws them; its field of view
  // is the first frame's throughout (glTF animates none).
  const render::CameraPath path = *render::parse_render_settings(camera, "camera").camera;
  std::string views;
  for (int f : {0, 1, last}) {
    const render::Camera c = path.at(frames[static_cast<std::size_t>(f)].time);
    const Vec3d forward = (c.target - c.position).normalized();
    const Vec3d up = forward.cross(c.up).normalized().cross(forward);
    views += fmt::format(R"({}{{"frame":{},"position":[{},{},{}],"forward":[{},{},{}],"up":[{},{},{}],"fov_degrees":45}})",
                         views.empty() ? "" : ",", f, c.position.x(), c.position.y(), c.position.z(), forward.x(),
                         forward.y(), forward.z(), up.x(), up.y(), up.z());
  }
  std::ofstream(dir.file("expect.json")) << fmt::format(
      R"({{"fps":100,"objects":{},"frames":[0,{}],"grids":["surface","density"],"poses":[{}],"camera":[{}]}})",
      objects, last, poses, views);

  const std::string vdb = fmt::format("{}/water_{:06d}.vdb", dir.file("export"), last);
  r = test::run("blender -b --factory-startup --python-exit-code 1 --python " + std::string(BW_SOURCE_DIR) +
                "/tests/export/blender_check.py -- --glb " + dir.file("export/solids.glb") + " --vdb " + vdb +
                " --expect " + dir.file("expect.json"));
  const std::size_t at = r.out.find("blender-check:");
  const std::string line = at == std::string::npos ? "" : r.out.substr(at, r.out.find('\n', at) - at);
  std::cerr << (line.empty() ? r.out + r.err : line) << "\n";
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(line.rfind("blender-check: ok", 0), 0u) << r.out << r.err;
}

}  // namespace
}  // namespace bw

// bw-export end to end on a small run: the files it writes, frame ranges, and bad
// inputs refused with one line, exit status 2 and nothing written.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "export/wall_points.h"
#include "export_fixture.h"
#include "io/frame_file.h"
#include "test_support.h"

namespace bw {
namespace {

std::string export_cmd(const std::string& args) { return test::tool("bw-export") + " " + args; }

TEST(ExportTool, WritesWaterPerFrameAndOneGltf) {
  test::TempDir dir;
  const RunRecord run = test::write_export_run(dir.path());
  const auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --mesh ply -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::list_folder(dir.file("out")),
            "blender_scene.py solids.glb water_000000.ply water_000000.vdb water_000001.ply water_000001.vdb "
            "water_000002.ply water_000002.vdb");
  EXPECT_NE(r.err.find("spacing 0.05 m (" + dir.file("run.h5") + ":/parameters/spacing)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(fmt::format("0 static, {} bodies", run.bodies.size())), std::string::npos) << r.err;
}

TEST(ExportTool, FrameRangesSplitTheWater) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --frames 1:2 --no-solids -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(test::list_folder(dir.file("out")), "water_000001.vdb water_000002.vdb");
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --frames 0 --no-solids -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --no-water --obj -q"));
  EXPECT_EQ(r.exit_code, 2);  // unknown option
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --no-water -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::list_folder(dir.file("out")),
            "blender_scene.py solids.glb water_000000.vdb water_000001.vdb water_000002.vdb");
}

TEST(ExportTool, BadInputsWriteNothing) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  const std::string out = " -o " + dir.file("out");
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {dir.file("nowhere") + out, "nowhere: no such folder of frames"},
      {dir.file("frames") + out + " --frames 1:7", "frame 3 is missing: " + dir.file("frames") + "/000003.h5"},
      {dir.file("frames") + out + " --frames 2:1", "--frames '2:1': the range is empty (first > last)"},
      {dir.file("frames") + out + " --no-water --no-solids", "nothing to export"},
      {dir.file("frames") + out + " --radius 0.01 --voxel 0.01",
       "bw-export: --radius 0.01 m is under 1.5 voxels of 0.01 m"},
      // OpenVDB's smallest voxel (its transform throws below it), given or from the radius.
      {dir.file("frames") + out + " --voxel 1e-6",
       "bw-export: the voxel edge 1e-06 m (--voxel) is under 1.5e-05 m, the smallest OpenVDB takes"},
      {dir.file("frames") + out + " --radius 1e-6", "the voxel edge 5e-07 m (--voxel)"},
      {dir.file("frames") + out + " --radius 0.05 --voxel 0.0005", "--radius 0.05 m spans 100 voxels of 0.0005 m, more than 64"},
      {dir.file("frames") + out + " --no-water --density", "--density asks for the water, which --no-water leaves out"},
      {dir.file("frames") + out + " --wall-pressure",
       "000000.h5: holds no wall pressure; add \"wall_pressure\" to the scene's [output] fields"},
      {dir.file("frames") + out + " --fragments " + dir.file("u.h5"), "u.h5: is a 'particles' file, expected a 'fragments' file"},
      {dir.file("frames") + out + " --run " + dir.file("frames/000000.h5"), "000000.h5: is a 'frame' file, expected a 'run' file"},
      {dir.file("frames") + out + " --scene " + dir.file("bad.toml"),
       "bad.toml: camera.key[1].time: 0 is not after camera.key[0].time = 1 (the camera of solids.glb and the look of "
       "blender_scene.py come from it)"},
      {dir.file("frames") + out + " --scene " + dir.file("missing.toml"), "missing.toml"},
      // Drawable at every sampled point, but looking down along up at frame 1's time (t = 0.05 s).
      {dir.file("frames") + out + " --scene " + dir.file("down.toml"),
       "000001.h5: the camera at t = 0.05 s: up: is parallel to the viewing direction"},
      {dir.file("frames") + out + " --scene " + dir.file("bad.toml") + " --no-solids",
       "its camera and look go into solids.glb and blender_scene.py, which --no-solids leaves out"},
      {dir.file("frames") + out + " --scene " + dir.file("bad.toml") + " --no-camera", "excludes"},
  };
  std::ofstream(dir.file("down.toml")) << "[camera]\ntarget = [0, 0, 0.5]\ninterpolation = \"linear\"\n"
                                          "[[camera.key]]\ntime = 0\nposition = [-1, 0, 1.5]\n"
                                          "[[camera.key]]\ntime = 0.15\nposition = [2, 0, 1.5]\n";
  std::ofstream(dir.file("bad.toml")) << "[camera]\ntarget = [0, 0, 0]\n[[camera.key]]\ntime = 1\nposition = [0, -1, 1]\n"
                                         "[[camera.key]]\ntime = 0\nposition = [1, -1, 1]\n";
  for (const Case& c : cases) {
    const auto r = test::run(export_cmd(c.args));
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_EQ(test::exists(dir.file("out")) ? test::list_folder(dir.file("out")) : "", "") << c.args;
  }
}

// --wall-pressure: per frame the boundary particles with their wall pressure as
// OpenVDB points, beside the water and the solids; in Houdini's up axis with --up y.
TEST(ExportTool, TheWallPressureGoesOutAsPoints) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  for (int n = 0; n < 3; ++n) {
    FrameData f = read_frame(frame_file_name(dir.file("frames"), n));
    for (int k = 0; k < 50; ++k) {
      f.bx.push_back(0.02f * static_cast<float>(k)), f.by.push_back(0.5f), f.bz.push_back(0.1f);
      f.bp.push_back(static_cast<float>(1000 * n + k)), f.bsolid.push_back(0);
    }
    write_frame(f, frame_file_name(dir.file("frames"), n));
  }
  const auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --wall-pressure --up y"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::list_folder(dir.file("out")),
            "blender_scene.py solids.glb wall_pressure_000000.vdb wall_pressure_000001.vdb wall_pressure_000002.vdb "
            "water_000000.vdb water_000001.vdb water_000002.vdb");
  EXPECT_NE(r.err.find("wall_pressure_NNNNNN.vdb, points \"wall_pressure\" (P, pressure, solid), up to 50 a frame"),
            std::string::npos)
      << r.err;
  const std::vector<exporter::WallPoint> points = exporter::read_wall_points(dir.file("out/wall_pressure_000002.vdb"));
  ASSERT_EQ(points.size(), 50u);
  for (const exporter::WallPoint& p : points) {
    const int k = static_cast<int>(std::lround(p.position.x() / 0.02));
    EXPECT_EQ(p.pressure, static_cast<float>(2000 + k));
    EXPECT_NEAR(p.position.y(), 0.1, 1e-6);   // z up becomes y up
    EXPECT_NEAR(p.position.z(), -0.5, 1e-6);
  }
}

// The scene's camera goes into solids.glb: the run's by default, --scene's when given,
// bw-render's fit when the scene has none, none with --no-camera; a field of view that
// changes is said (glTF animates none).
TEST(ExportTool, TheScenesCameraGoesIntoTheGltf) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("fitted") + " --no-water -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("camera       from the fit to " + dir.file("frames") + "/000000.h5 (as bw-render's), fixed"),
            std::string::npos)
      << r.err;
  EXPECT_NE(test::file_bytes(dir.file("fitted/solids.glb")).find("\"cameras\""), std::string::npos);
#ifdef BW_TEST_WITH_RENDER
  // The very camera bw-render fits and draws with.
  const auto rendered = test::run(test::tool("bw-render") + " " + dir.file("frames") + " -o " + dir.file("images") +
                                  " --frames 2 -v");
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
  const std::string key = "  camera       ";
  const std::size_t at = rendered.err.find(key);
  ASSERT_NE(at, std::string::npos) << rendered.err;
  const std::string camera = rendered.err.substr(at + key.size(), rendered.err.find(' ', at + key.size()) - at - key.size());
  EXPECT_NE(r.err.find("at frame 0    " + camera + " (as bw-render --camera takes it)"), std::string::npos)
      << "bw-render: " << camera << "\n" << r.err;
#endif

  std::ofstream(dir.file("moving.toml")) << "[camera]\ntarget = [0, 0, 0]\nfov = 40\n"
                                            "[[camera.key]]\ntime = 0\nposition = [0, -2, 1]\n"
                                            "[[camera.key]]\ntime = 1\nposition = [2, -2, 1]\nfov = 20\n";
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("moving") + " --no-water --scene " +
                           dir.file("moving.toml")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("camera       from " + dir.file("moving.toml") + ", moving (2 keys)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the camera's field of view changes over the frames"), std::string::npos) << r.err;
  const std::string glb = test::file_bytes(dir.file("moving/solids.glb"));
  EXPECT_NE(glb.find("\"cameras\":[{\"name\":\"camera\""), std::string::npos);
  EXPECT_NE(glb.find("\"fov_degrees\":40}"), std::string::npos);

  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("left") + " --no-water --no-camera -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::file_bytes(dir.file("left/solids.glb")).find("\"cameras\""), std::string::npos);
}

// [camera] track: the camera looks at a body's centre in each frame, in bw-export's
// glTF as in bw-render's images; a frame without the body (a fragment before its
// fracture) is refused before anything is written.
TEST(ExportTool, ATrackingCameraLooksAtTheBodyInEachFrame) {
  test::TempDir dir;
  const RunRecord run = test::write_export_run(dir.path());
  std::ofstream(dir.file("track.toml")) << "[camera]\ntrack = \"u.1\"\nposition = [0.5, -3, 1.5]\nfov = 35\n";
  const auto target_in = [&](int frame) {
    const FrameData f = read_frame(frame_file_name(dir.file("frames"), frame));
    for (std::size_t i = 0; i < f.bodies.size(); ++i)
      if (run.bodies.at(static_cast<std::size_t>(f.bodies.id[i])).name == "u.1")
        return fmt::format("0.5,-3,1.5:{:g},{:g},{:g}:35", f.bodies.position[i].x(), f.bodies.position[i].y(),
                           f.bodies.position[i].z());
    return std::string("(no u.1)");
  };
  const std::string scene = " --scene " + dir.file("track.toml");
  auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("e") + " --no-water --frames 1:2 -v" + scene));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fixed, looking at body 'u.1'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at frame 1    " + target_in(1) + " "), std::string::npos) << target_in(1) << "\n" << r.err;
  // The camera node, after the bodies' (none static), is keyed: the body moves.
  const std::size_t nodes_at = r.err.find("0 static, ");
  ASSERT_NE(nodes_at, std::string::npos) << r.err;
  const int camera_node = std::stoi(r.err.substr(nodes_at + 10));
  EXPECT_NE(test::file_bytes(dir.file("e/solids.glb"))
                .find(fmt::format("\"target\":{{\"node\":{},\"path\":\"rotation\"}}", camera_node)),
            std::string::npos);

  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("all") + " --no-water" + scene));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("000000.h5: camera.track: the body 'u.1' is not in this frame (t = 0 s)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(test::exists(dir.file("all/solids.glb")));
  // bw-info lists the names to track.
  const auto info = test::run(test::tool("bw-info") + " " + dir.file("run.h5"));
  EXPECT_NE(info.out.find("bodies_names: u, u.0, u.1"), std::string::npos) << info.out;
  std::ofstream(dir.file("other.toml")) << "[camera]\ntrack = \"crate\"\nposition = [0.5, -3, 1.5]\n";
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("other") + " --no-water --scene " + dir.file("other.toml")));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("camera.track 'crate': " + dir.file("run.h5") + " has no body of that name (its bodies: u, u.0, u.1"),
            std::string::npos)
      << r.err;
#ifdef BW_TEST_WITH_RENDER
  r = test::run(test::tool("bw-render") + " " + dir.file("frames") + " -o " + dir.file("images") + " --frames 1:2" +
                scene + " --width 64 --height 48");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int f : {1, 2})
    EXPECT_NE(test::file_bytes(dir.file(fmt::format("images/{:06d}.png", f))).find("camera " + target_in(f) + " "),
              std::string::npos)
        << target_in(f);
  r = test::run(test::tool("bw-render") + " " + dir.file("frames") + " -o " + dir.file("refused") + " --frames 0" + scene);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("camera.track: the body 'u.1' is not in this frame"), std::string::npos) << r.err;
#endif
}

TEST(ExportTool, WithoutARunTheSpacingIsNeeded) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  std::filesystem::remove(dir.file("run.h5"));
  auto r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give --run or --spacing"), std::string::npos) << r.err;
  r = test::run(export_cmd(dir.file("frames") + " -o " + dir.file("out") + " --spacing 0.05 -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // No solids without a run; the Blender script sets up the water alone.
  EXPECT_EQ(test::list_folder(dir.file("out")), "blender_scene.py water_000000.vdb water_000001.vdb water_000002.vdb");
}

}  // namespace
}  // namespace bw

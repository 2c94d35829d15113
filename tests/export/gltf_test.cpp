// The solids' glTF: the change of axes is a rotation that commutes with the poses,
// the .glb is well formed, every body that appears gets a node, the fragments are
// hidden before the fracture and the parent after it.
#include <cstring>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "export/gltf.h"
#include "export_fixture.h"
#include "test_support.h"

namespace bw::exporter {
namespace {

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

std::vector<PoseFrame> poses(const std::string& dir) {
  std::vector<PoseFrame> out;
  for (int f = 0; f < 3; ++f) {
    FrameData d = read_frame(frame_file_name(dir + "/frames", f));
    out.push_back({f, d.time, std::move(d.bodies)});
  }
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Gltf, AxesChangeByARotation) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Vec3d(1, -2, 0.5).normalized()));
  const Vec3d v(0.3, -1.2, 2.0);
  const auto g = to_gltf(q);
  const Eigen::Quaterniond qg(g[3], g[0], g[1], g[2]);
  // Rotating then changing axes is changing axes then rotating by the converted q.
  EXPECT_LT((to_gltf(Vec3d(q * v)) - qg * to_gltf(v)).norm(), 1e-12);
  EXPECT_EQ(to_gltf(Vec3d(0, 0, 1)), Vec3d(0, 1, 0));  // z-up is glTF's +y
  EXPECT_LT((to_gltf(Vec3d(0, 1, 0)) - Vec3d(0, 0, -1)).norm(), 1e-15);
}

TEST(Gltf, BodiesAppearAndDisappearWithTheFracture) {
  test::TempDir dir;
  const RunRecord run = test::write_export_run(dir.path());
  const SolidSet set = SolidSet::load(dir.file("run.h5"), dir.file("fragments.h5"));
  GltfStats stats;
  const std::vector<std::uint8_t> glb = build_glb(set, poses(dir.path()), "run.h5", &stats);
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(u32(glb, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(u32(glb, 4), 2u);
  EXPECT_EQ(u32(glb, 8), glb.size());
  const std::uint32_t json_length = u32(glb, 12);
  EXPECT_EQ(json_length % 4, 0u);
  EXPECT_EQ(u32(glb, 16), 0x4E4F534Au);  // "JSON"
  const std::string json(glb.begin() + 20, glb.begin() + 20 + json_length);
  EXPECT_EQ(u32(glb, 20 + json_length) % 4, 0u);
  EXPECT_EQ(u32(glb, 24 + json_length), 0x004E4942u);  // "BIN"
  EXPECT_EQ(20 + json_length + 8 + u32(glb, 20 + json_length), glb.size());

  // No static solid; body 0 and its children, one node each.
  EXPECT_EQ(stats.static_nodes, 0u);
  EXPECT_EQ(stats.body_nodes, run.bodies.size());
  EXPECT_EQ(stats.bodies_without_mesh, 0u);
  EXPECT_EQ(count(json, "\"kind\":\"body\""), run.bodies.size());
  // Every body is missing from some frame: each has translation, rotation and scale.
  EXPECT_EQ(count(json, "\"path\":\"translation\""), run.bodies.size());
  EXPECT_EQ(count(json, "\"path\":\"scale\""), run.bodies.size());
  EXPECT_EQ(count(json, "\"interpolation\":\"STEP\""), run.bodies.size());
  EXPECT_NE(json.find("\"frames\":[0,2]"), std::string::npos) << json.substr(0, 400);
  EXPECT_NE(json.find("\"name\":\"u.0\""), std::string::npos);
  // The children start hidden.
  EXPECT_EQ(count(json, "\"scale\":[0,0,0]"), run.bodies.size() - 1);
}

// glTF's camera looks down its local -z with +y up: the node's rotation takes those
// axes to the view's, in glTF's axes.
TEST(Gltf, ACameraNodeLooksWhereTheSceneCameraLooks) {
  render::Camera c;
  c.position = Vec3d(2.5, -3.0, 1.6);
  c.target = Vec3d(0.2, 0.4, 0.3);
  const auto r = gltf_camera_rotation(c);
  const Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
  EXPECT_NEAR(q.norm(), 1, 1e-12);
  const Vec3d forward = (c.target - c.position).normalized();
  EXPECT_LT((q * Vec3d(0, 0, -1) - to_gltf(forward)).norm(), 1e-12);
  // The image's up is the scene's up, tilted to be square to the view.
  const Vec3d up = to_gltf(forward.cross(Vec3d(0, 0, 1)).cross(forward).normalized());
  EXPECT_LT((q * Vec3d(0, 1, 0) - up).norm(), 1e-12);
}

TEST(Gltf, AMovingCameraHasAKeyAtEveryFrame) {
  test::TempDir dir;
  const RunRecord run = test::write_export_run(dir.path());
  const SolidSet set = SolidSet::load(dir.file("run.h5"), dir.file("fragments.h5"));
  const std::vector<PoseFrame> frames = poses(dir.path());
  render::CameraKey a, b;
  a.time = frames.front().time, b.time = frames.back().time;
  a.camera.position = Vec3d(0, -3, 1), b.camera.position = Vec3d(3, 0, 1);
  a.camera.target = b.camera.target = Vec3d(0, 0, 0.2);
  b.camera.fov_degrees = 30;
  const GltfCamera camera{render::CameraPath({a, b}, render::CameraInterpolation::kLinear), 2.0};
  GltfStats stats;
  const std::vector<std::uint8_t> glb = build_glb(set, frames, "run.h5", &stats, &camera);
  const std::string json(glb.begin() + 20, glb.begin() + 20 + u32(glb, 12));
  EXPECT_TRUE(stats.camera);
  EXPECT_EQ(stats.fov_first, 45);
  EXPECT_EQ(stats.fov_least, 30);
  EXPECT_EQ(count(json, "\"cameras\":[{\"name\":\"camera\",\"type\":\"perspective\""), 1u);
  EXPECT_NE(json.find("\"aspectRatio\":2,"), std::string::npos);
  EXPECT_NE(json.find("\"yfov\":" + fmt::format("{}", 45 * M_PI / 180)), std::string::npos);
  EXPECT_NE(json.find("{\"name\":\"camera\",\"camera\":0,\"translation\":[0,1,3],"), std::string::npos) << json;
  EXPECT_EQ(count(json, "\"path\":\"translation\""), run.bodies.size() + 1);
  EXPECT_EQ(stats.keyframes, (run.bodies.size() + 1) * frames.size());

  // A fixed camera: a node where it stands, no animation of its own.
  const GltfCamera fixed{render::CameraPath::fixed(a.camera), 1.5};
  build_glb(set, frames, "run.h5", &stats, &fixed);
  EXPECT_TRUE(stats.camera);
  EXPECT_EQ(stats.keyframes, run.bodies.size() * frames.size());
}

TEST(Gltf, WithoutFragmentsTheChildrenHaveNoMesh) {
  test::TempDir dir;
  const RunRecord run = test::write_export_run(dir.path(), false);
  const SolidSet set = SolidSet::load(dir.file("run.h5"), "");
  GltfStats stats;
  build_glb(set, poses(dir.path()), "run.h5", &stats);
  EXPECT_EQ(stats.body_nodes, 1u);
  EXPECT_EQ(stats.bodies_without_mesh, run.bodies.size() - 1);
}

TEST(Gltf, FragmentsOfACheckAreRefused) {
  test::TempDir dir;
  test::write_export_run(dir.path());
  FragmentSet check = read_fragments(dir.file("fragments.h5"));
  for (Fragment& f : check.fragments) f.body = -1;
  write_fragments(check, dir.file("check.h5"));
  try {
    SolidSet::load(dir.file("run.h5"), dir.file("check.h5"));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fragment 0 belongs to no body"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bw::exporter

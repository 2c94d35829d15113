// A moving camera: keys read from [camera], interpolated between them. No OpenGL.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "io/frame_file.h"
#include "render/camera_path.h"
#include "render/framing.h"
#include "render/render_settings.h"
#include "test_support.h"

namespace br = bw::render;
using bw::Vec3d;

namespace {

std::string error_of(const std::function<void()>& f) { return bw::test::input_error_of(f); }

br::CameraKey key(double time, Vec3d position, double fov = 45) {
  br::CameraKey k;
  k.time = time;
  k.camera.position = position;
  k.camera.target = Vec3d(0, 0, 0);
  k.camera.fov_degrees = fov;
  return k;
}

// Speed of the position along the path, by central differences.
double speed(const br::CameraPath& path, double t, double dt = 1e-6) {
  return (path.at(t + dt).position - path.at(t - dt).position).norm() / (2 * dt);
}

}  // namespace

TEST(CameraPath, PassesThroughItsKeysAndHoldsStillOutsideThem) {
  for (auto interpolation : {br::CameraInterpolation::kSmooth, br::CameraInterpolation::kLinear}) {
    const br::CameraPath path({key(0.5, {1, -3, 1}, 40), key(1.0, {2, -3, 2}, 30), key(2.5, {3, -1, 1}, 50)},
                              interpolation);
    EXPECT_TRUE(path.animated());
    for (const auto& k : path.keys()) {
      EXPECT_EQ(path.at(k.time).position, k.camera.position);
      EXPECT_EQ(path.at(k.time).fov_degrees, k.camera.fov_degrees);
    }
    EXPECT_EQ(path.at(0).position, Vec3d(1, -3, 1));
    EXPECT_EQ(path.at(-1e9).position, Vec3d(1, -3, 1));
    EXPECT_EQ(path.at(7).position, Vec3d(3, -1, 1));
  }
  const br::CameraPath fixed = br::CameraPath::fixed(key(0, {1, 2, 3}).camera);
  EXPECT_FALSE(fixed.animated());
  EXPECT_EQ(fixed.at(123.0).position, Vec3d(1, 2, 3));
}

TEST(CameraPath, LinearMovesAtConstantSpeed) {
  const br::CameraPath path({key(0, {0, -4, 0}), key(2, {4, -4, 2}, 65)}, br::CameraInterpolation::kLinear);
  EXPECT_NEAR((path.at(0.5).position - Vec3d(1, -4, 0.5)).norm(), 0, 1e-12);
  EXPECT_NEAR(path.at(1).fov_degrees, 55, 1e-12);
  EXPECT_NEAR(speed(path, 0.3), std::sqrt(5.0), 1e-6);
  EXPECT_NEAR(speed(path, 1.7), std::sqrt(5.0), 1e-6);
}

// Smooth: eases in and out, continuous in speed through inner keys, and never goes
// past the keys on either side of it, coordinate by coordinate.
TEST(CameraPath, SmoothEasesInAndOutWithoutOvershoot) {
  // Two keys: the smoothstep 3 s^2 - 2 s^3 between them.
  const br::CameraPath two({key(0, {0, -4, 0}), key(1, {1, -4, 0})}, br::CameraInterpolation::kSmooth);
  EXPECT_NEAR(two.at(0.25).position.x(), 3 * 0.0625 - 2 * 0.015625, 1e-12);
  EXPECT_NEAR(speed(two, 1e-4), 0, 1e-3);
  EXPECT_NEAR(speed(two, 1 - 1e-4), 0, 1e-3);

  // Up, across, down at uneven times: z rises and falls, and between the two keys at
  // one height it stays at that height (a spline through the keys would bulge above).
  const br::CameraPath path({key(0, {0, -4, 0}), key(0.3, {1, -4, 1}), key(1.5, {2, -4, 1}), key(1.7, {5, -4, 0})},
                            br::CameraInterpolation::kSmooth);
  double x_before = -1;
  for (int i = 0; i <= 1700; ++i) {
    const Vec3d p = path.at(i * 1e-3).position;
    EXPECT_GE(p.z(), 0.0);
    EXPECT_LE(p.z(), 1.0 + 1e-12);
    if (i >= 300 && i <= 1500) {
      EXPECT_NEAR(p.z(), 1.0, 1e-12) << "t = " << i * 1e-3;
    }
    EXPECT_GE(p.x(), x_before) << "x goes back at t = " << i * 1e-3;  // the keys' x rise: so does the path
    x_before = p.x();
  }
  // The velocity is continuous through the inner keys: left and right of each agree.
  for (double t : {0.3, 1.5}) {
    const double h = 1e-7;
    const Vec3d left = (path.at(t).position - path.at(t - h).position) / h;
    const Vec3d right = (path.at(t + h).position - path.at(t).position) / h;
    EXPECT_NEAR((left - right).norm(), 0, 1e-4 * (1 + left.norm())) << "t = " << t;
  }
}

TEST(CameraPath, ReadFromTheSceneWithTheTablesValuesAsDefaults) {
  const auto s = br::parse_render_settings(R"(
[camera]
target = [0.5, 0, 0.2]
fov = 40
interpolation = "linear"

[[camera.key]]
time = 0.1
position = [0, -2, 1]

[[camera.key]]
time = 0.9
position = [2, -2, 1]
target = [1.5, 0, 0.2]
fov = 30
)",
                                           "scene.toml");
  ASSERT_TRUE(s.camera);
  const br::CameraPath& path = *s.camera;
  ASSERT_EQ(path.keys().size(), 2u);
  EXPECT_EQ(path.interpolation(), br::CameraInterpolation::kLinear);
  EXPECT_EQ(path.keys()[0].camera.target, Vec3d(0.5, 0, 0.2));
  EXPECT_EQ(path.keys()[0].camera.fov_degrees, 40);
  EXPECT_EQ(path.keys()[1].camera.target, Vec3d(1.5, 0, 0.2));
  EXPECT_EQ(path.keys()[1].camera.fov_degrees, 30);
  EXPECT_EQ(path.keys()[1].camera.up, Vec3d(0, 0, 1));
  EXPECT_NEAR(path.at(0.5).fov_degrees, 35, 1e-12);
}

// A key may give the frame it is at instead of its time: frame F of a run is written
// at F / [time] frame_rate, the scene's own rate; keys by time and by frame mix.
TEST(CameraPath, KeysByFrameAreAtTheFramesTimes) {
  const auto s = br::parse_render_settings(R"(
[time]
frame_rate = 24
end = 3
[camera]
target = [0, 0, 0]
[[camera.key]]
frame = 12
position = [0, -2, 1]
[[camera.key]]
time = 1.25
position = [1, -2, 1]
[[camera.key]]
frame = 60
position = [2, -2, 1]
)",
                                           "scene.toml");
  ASSERT_TRUE(s.camera);
  const auto& keys = s.camera->keys();
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_DOUBLE_EQ(keys[0].time, 12.0 / 24);
  EXPECT_DOUBLE_EQ(keys[1].time, 1.25);
  EXPECT_DOUBLE_EQ(keys[2].time, 60.0 / 24);
  EXPECT_EQ(s.camera->at(60.0 / 24).position, Vec3d(2, -2, 1));
}

// With track, the target is a body's centre, frame by frame: the scene gives none.
TEST(CameraPath, ATrackedBodyIsTheTarget) {
  const auto s = br::parse_render_settings(
      "[camera]\ntrack = \"crate\"\n[[camera.key]]\ntime = 0\nposition = [0, -2, 1]\n"
      "[[camera.key]]\ntime = 1\nposition = [0, 0, 3]\n",  // passes over the origin looking down: fine, no target yet
      "s.toml");
  EXPECT_EQ(s.camera_track, "crate");
  ASSERT_TRUE(s.camera);
  EXPECT_TRUE(s.camera->animated());
  const auto error = [](const std::string& text) { return error_of([&] { br::parse_render_settings(text, "s.toml"); }); };
  EXPECT_EQ(error("[camera]\ntrack = \"crate\"\nposition = [0, -2, 1]\ntarget = [0, 0, 0]\n"),
            "s.toml: camera.target: not with camera.track, which aims the camera at the body");
  EXPECT_EQ(error("[camera]\ntrack = \"crate\"\n[[camera.key]]\ntime = 0\nposition = [0, -2, 1]\ntarget = [0, 0, 0]\n"),
            "s.toml: camera.key[0].target: not with camera.track, which aims the camera at the body");
  EXPECT_EQ(error("[camera]\ntrack = \"\"\nposition = [0, -2, 1]\n"), "s.toml: camera.track: expected the name of a body");
  EXPECT_EQ(error("[camera]\ntrack = \"crate\"\n"),
            "s.toml: camera.position: required when a [camera] table is given");

  // In a frame: the body's centre is the target; a frame without it is refused.
  br::TrackedBody crate{"crate", 3, Vec3d(0, 0, 0)};
  bw::BodyStates bodies;
  bodies.id = {1, 3};
  bodies.position = {Vec3d(9, 9, 9), Vec3d(0.5, 0.2, 0.1)};
  bodies.orientation.resize(2);
  const br::Camera c = br::frame_camera(*s.camera, crate, 0.5, bodies, "f.h5");
  EXPECT_EQ(c.target, Vec3d(0.5, 0.2, 0.1));
  EXPECT_EQ(c.position, s.camera->at(0.5).position);
  bodies.id = {1, 2};
  EXPECT_EQ(error_of([&] { br::frame_camera(*s.camera, crate, 0.5, bodies, "f.h5"); }),
            "f.h5: camera.track: the body 'crate' is not in this frame (t = 0.5 s): not made yet, or broken");
  // Straight above its target, looking down along up: refused in that frame.
  bodies.id = {3, 2};
  bodies.position = {Vec3d(0, 0, 0), Vec3d(9, 9, 9)};
  EXPECT_EQ(error_of([&] { br::frame_camera(*s.camera, crate, 1.0, bodies, "f.h5"); }),
            "f.h5: the camera at t = 1 s: up: is parallel to the viewing direction");
}

TEST(CameraPath, BadKeysAreNamed) {
  const auto error = [](const std::string& text) { return error_of([&] { br::parse_render_settings(text, "s.toml"); }); };
  const std::string base = "[camera]\ntarget = [0, 0, 0]\n";
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 1\nposition = [0, -1, 1]\n[[camera.key]]\ntime = 1\nposition = [1, -1, 1]\n"),
            "s.toml: camera.key[1].time: 1 is not after camera.key[0].time = 1");
  EXPECT_EQ(error(base + "[[camera.key]]\nposition = [0, -1, 1]\n"),
            "s.toml: camera.key[0].time: required (the simulation time of the key, s; or its frame)");
  // Keys by frame count in the file's own [time] frame_rate.
  EXPECT_EQ(error(base + "[[camera.key]]\nframe = 3\nposition = [0, -1, 1]\n"),
            "s.toml: camera.key[0].frame: needs [time] frame_rate in this file, the rate its frames count in");
  EXPECT_EQ(error("[time]\nframe_rate = 30\n" + base + "[[camera.key]]\nframe = 3\ntime = 0.1\nposition = [0, -1, 1]\n"),
            "s.toml: camera.key[0]: give time or frame, not both");
  EXPECT_EQ(error("[time]\nframe_rate = 20\n" + base +
                  "[[camera.key]]\ntime = 1\nposition = [0, -1, 1]\n[[camera.key]]\nframe = 10\nposition = [1, -1, 1]\n"),
            "s.toml: camera.key[1].frame: 10 (t = 0.5 s) is not after camera.key[0] (t = 1 s)");
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\n"),
            "s.toml: camera.key[0].position: required in every key when [camera] has no position");
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [0, -1, 1]\nzoom = 2\n"),
            "s.toml: camera.key[0].zoom: unknown key (see docs/rendering.md)");
  EXPECT_EQ(error(base + "[camera.key]\ntime = 0\n"),
            "s.toml: camera.key: expected an array of tables, each [[camera.key]] with a time");
  EXPECT_EQ(error(base + "position = [0, -1, 1]\ninterpolation = \"cubic\"\n"),
            "s.toml: camera.interpolation: 'cubic' is not one of smooth, linear");
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [0, -1, 1]\nfov = 190\n"),
            "s.toml: camera.key[0].fov: 190 is outside (0, 180) degrees");
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [0, 0, 0]\n"),
            "s.toml: camera.key[0].target: equals the position");
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [1e300, 0, 0]\n"),
            "s.toml: camera.key[0].position: more than 1e+09 m from the origin");
  // Each key is fine, but the camera flies through its target half way.
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [-1, 0, 0]\n[[camera.key]]\ntime = 2\nposition = [1, 0, 0]\n"),
            "s.toml: camera.key[0] to camera.key[1]: at t = 1 s, target: equals the position");
  // ... or looks straight down along its up on the way.
  EXPECT_EQ(error(base + "[[camera.key]]\ntime = 0\nposition = [-1, 0, 1]\n[[camera.key]]\ntime = 2\nposition = [1, 0, 1]\n"),
            "s.toml: camera.key[0] to camera.key[1]: at t = 1 s, up: is parallel to the viewing direction");
}

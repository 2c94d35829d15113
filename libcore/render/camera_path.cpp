#include "render/camera_path.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

namespace bw::render {
namespace {

// A camera as ten numbers: position, target, up, field of view.
using Channels = std::array<double, 10>;

Channels channels_of(const Camera& c) {
  return {c.position.x(), c.position.y(), c.position.z(), c.target.x(), c.target.y(),
          c.target.z(),   c.up.x(),       c.up.y(),       c.up.z(),     c.fov_degrees};
}

Camera camera_of(const Channels& v) {
  Camera c;
  c.position = Vec3d(v[0], v[1], v[2]);
  c.target = Vec3d(v[3], v[4], v[5]);
  c.up = Vec3d(v[6], v[7], v[8]);
  c.fov_degrees = v[9];
  return c;
}

// Fritsch-Butland slope at an inner key from the secants on either side (weighted
// harmonic mean, as PCHIP): zero where the data turn, so no overshoot.
double monotone_slope(double d_before, double d_after, double h_before, double h_after) {
  if (d_before * d_after <= 0) return 0;
  const double w1 = 2 * h_after + h_before, w2 = h_after + 2 * h_before;
  return (w1 + w2) / (w1 / d_before + w2 / d_after);
}

}  // namespace

std::string camera_problem(const Camera& c, bool with_target) {
  if (!(c.fov_degrees > 0 && c.fov_degrees < 180))
    return fmt::format("fov: {} is outside (0, 180) degrees", c.fov_degrees);
  // Beyond this the renderer's single precision has no room left for the scene.
  constexpr double kFarthest = 1e9;
  if (!(c.position.norm() < kFarthest)) return fmt::format("position: more than {:g} m from the origin", kFarthest);
  if (!(c.up.norm() > 0)) return "up: is the zero vector";
  if (!with_target) return {};
  if (!(c.target.norm() < kFarthest)) return fmt::format("target: more than {:g} m from the origin", kFarthest);
  const Vec3d view = c.target - c.position;
  if (!(view.norm() > 0)) return "target: equals the position";
  if (!(c.up.normalized().cross(view.normalized()).norm() > 1e-6)) return "up: is parallel to the viewing direction";
  return {};
}

std::optional<CameraInterpolation> parse_camera_interpolation(const std::string& name) {
  if (name == "smooth") return CameraInterpolation::kSmooth;
  if (name == "linear") return CameraInterpolation::kLinear;
  return std::nullopt;
}

const char* camera_interpolation_name(CameraInterpolation interpolation) {
  return interpolation == CameraInterpolation::kSmooth ? "smooth" : "linear";
}

CameraPath CameraPath::fixed(const Camera& camera) { return CameraPath({CameraKey{0, camera}}, CameraInterpolation::kSmooth); }

CameraPath::CameraPath(std::vector<CameraKey> keys, CameraInterpolation interpolation)
    : keys_(std::move(keys)), interpolation_(interpolation) {
  const std::size_t n = keys_.size();
  slopes_.assign(n, Channels{});  // the first and the last stay flat
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const Channels a = channels_of(keys_[k - 1].camera), b = channels_of(keys_[k].camera),
                   c = channels_of(keys_[k + 1].camera);
    const double h0 = keys_[k].time - keys_[k - 1].time, h1 = keys_[k + 1].time - keys_[k].time;
    for (std::size_t i = 0; i < a.size(); ++i)
      slopes_[k][i] = monotone_slope((b[i] - a[i]) / h0, (c[i] - b[i]) / h1, h0, h1);
  }
}

Camera CameraPath::at(double time) const {
  if (!(time > keys_.front().time)) return keys_.front().camera;
  if (time >= keys_.back().time) return keys_.back().camera;
  const auto after = std::upper_bound(keys_.begin(), keys_.end(), time,
                                      [](double t, const CameraKey& key) { return t < key.time; });
  const std::size_t k = static_cast<std::size_t>(after - keys_.begin()) - 1;
  const double h = keys_[k + 1].time - keys_[k].time, s = (time - keys_[k].time) / h;
  const Channels a = channels_of(keys_[k].camera), b = channels_of(keys_[k + 1].camera);
  Channels v;
  if (interpolation_ == CameraInterpolation::kLinear) {
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = a[i] + s * (b[i] - a[i]);
  } else {
    // Cubic Hermite basis on [0, 1].
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (std::size_t i = 0; i < v.size(); ++i)
      v[i] = h00 * a[i] + h10 * h * slopes_[k][i] + h01 * b[i] + h11 * h * slopes_[k + 1][i];
  }
  return camera_of(v);
}

}  // namespace bw::render

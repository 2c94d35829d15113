// A camera that moves: keys at times of the simulation, interpolated between them.
//
// Every quantity of a key (position, target, up, field of view) is interpolated on
// its own, coordinate by coordinate. "smooth" is a monotone cubic (Fritsch-Carlson,
// as PCHIP) through the keys, flat at the first and the last: the camera eases in and
// out, its path is continuous in speed, and no coordinate overshoots the keys on
// either side (a camera between two keys at the same height stays at that height).
// "linear" moves at constant speed between keys. Before the first key and after the
// last the camera holds still. The camera depends on the time alone, so parts of a
// sequence rendered apart agree with one rendered whole.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace bw::render {

struct Camera {
  Vec3d position = Vec3d(0, -4, 1.5);
  Vec3d target = Vec3d(0, 0, 0.5);
  Vec3d up = Vec3d(0, 0, 1);
  double fov_degrees = 45;   // vertical field of view
};

// Empty when a camera can be drawn with; else what is wrong, naming the key
// ("fov: 190 is outside (0, 180) degrees", "target: equals the position"). Without
// `with_target` (a camera whose target is a body's centre, known per frame), only
// what does not depend on the target.
std::string camera_problem(const Camera& camera, bool with_target = true);

enum class CameraInterpolation { kSmooth, kLinear };
// "smooth", "linear"; std::nullopt for anything else.
std::optional<CameraInterpolation> parse_camera_interpolation(const std::string& name);
const char* camera_interpolation_name(CameraInterpolation interpolation);

struct CameraKey {
  double time = 0;   // s, simulation time
  Camera camera;
};

class CameraPath {
 public:
  CameraPath() = default;
  // A camera that does not move.
  static CameraPath fixed(const Camera& camera);
  // Keys in strictly increasing time, at least one (checked by the caller).
  CameraPath(std::vector<CameraKey> keys, CameraInterpolation interpolation);

  Camera at(double time) const;
  bool animated() const { return keys_.size() > 1; }
  const std::vector<CameraKey>& keys() const { return keys_; }
  CameraInterpolation interpolation() const { return interpolation_; }

 private:
  std::vector<CameraKey> keys_ = {CameraKey{}};
  CameraInterpolation interpolation_ = CameraInterpolation::kSmooth;
  // Smooth: the slope of each of the ten channels at each key (per second).
  std::vector<std::array<double, 10>> slopes_;
};

}  // namespace bw::render

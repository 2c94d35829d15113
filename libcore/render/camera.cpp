#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace bw::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Room around the box in a fitted view: 15% more distance than a tight fit.
constexpr double kFitMargin = 1.15;

double radians(double degrees) { return degrees * kPi / 180.0; }

}  // namespace

Vec3d view_direction(double azimuth_degrees, double elevation_degrees) {
  const double az = radians(azimuth_degrees), el = radians(elevation_degrees);
  return Vec3d(std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el));
}

Mat4d look_at(const Vec3d& position, const Vec3d& target, const Vec3d& up) {
  const Vec3d f = (target - position).normalized();
  const Vec3d s = f.cross(up).normalized();
  const Vec3d u = s.cross(f);
  Mat4d m = Mat4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(position);
  m(1, 3) = -u.dot(position);
  m(2, 3) = f.dot(position);
  return m;
}

Mat4d perspective(double fov_degrees, double aspect, double near, double far) {
  const double t = 1.0 / std::tan(radians(fov_degrees) / 2);
  Mat4d m = Mat4d::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2 * far * near / (near - far);
  m(3, 2) = -1;
  return m;
}

Mat4d orthographic(double l, double r, double b, double t, double near, double far) {
  Mat4d m = Mat4d::Identity();
  m(0, 0) = 2 / (r - l);
  m(1, 1) = 2 / (t - b);
  m(2, 2) = -2 / (far - near);
  m(0, 3) = -(r + l) / (r - l);
  m(1, 3) = -(t + b) / (t - b);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

Camera fit_camera(const Aabb& box, double fov_degrees, double aspect, double azimuth_degrees,
                  double elevation_degrees) {
  Camera c;
  c.fov_degrees = fov_degrees;
  if (box.empty()) return c;
  const Vec3d center = 0.5 * (box.min + box.max);
  const Vec3d back = view_direction(azimuth_degrees, elevation_degrees);
  const Vec3d f = -back;
  const Vec3d s = f.cross(Vec3d(0, 0, 1)).normalized();
  const Vec3d u = s.cross(f);
  const double tan_v = std::tan(radians(fov_degrees) / 2), tan_h = tan_v * aspect;
  // Every corner inside the view: a corner at offset o from the centre, seen from
  // distance D along f, sits at depth D + o.f and must satisfy |o.s| <= tan_h (D + o.f)
  // and |o.u| <= tan_v (D + o.f).
  double distance = 1e-3;
  for (int i = 0; i < 8; ++i) {
    const Vec3d corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                       (i & 4) ? box.max.z() : box.min.z());
    const Vec3d o = corner - center;
    distance = std::max({distance, std::abs(o.dot(s)) / tan_h - o.dot(f), std::abs(o.dot(u)) / tan_v - o.dot(f)});
  }
  distance *= kFitMargin;
  c.target = center;
  c.position = center + distance * back;
  c.up = Vec3d(0, 0, 1);
  return c;
}

void clip_planes(const Camera& camera, const Aabb& box, double& near, double& far) {
  const Vec3d f = (camera.target - camera.position).normalized();
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  if (!box.empty()) {
    for (int i = 0; i < 8; ++i) {
      const Vec3d corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                         (i & 4) ? box.max.z() : box.min.z());
      const double d = (corner - camera.position).dot(f);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  const double scale = std::max((camera.target - camera.position).norm(), 1e-3);
  if (!(hi > 0)) hi = 10 * scale;
  // Depth buffers are 32-bit float; a near plane above 1e-4 of the far plane keeps
  // their resolution fine enough for meshes that touch.
  far = hi * 1.05 + 1e-3;
  near = std::max(lo * 0.95, far * 1e-4);
}

}  // namespace bw::render

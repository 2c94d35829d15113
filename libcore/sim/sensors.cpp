#include "sim/sensors.h"

#include <cmath>

#include <fmt/format.h>

#include "common/error.h"

namespace bw::sim {
namespace {

// A particle lies on a face when its surface normals agree this well (rigid.cl's
// BW_FACE_FLATNESS): edges and corners carry the loads of two or three faces.
constexpr double kFaceFlatness = 0.9;
// Face particles turn at most this far from the sensor's normal (cos 25 degrees).
constexpr double kFacing = 0.906;
// Boundary particles lie within half a spacing of their mesh's faces (bw-sample):
// the face's layer is within this many spacings of the sensor's plane.
constexpr double kLayer = 0.75;

double weight_along_face(double d2, double h2) {
  const double t = 1 - d2 / h2;
  return t > 0 ? t * t * t : 0;
}

}  // namespace

SensorWeights sensor_weights(const BoundarySet& b, const scene::Sensor& sensor, double h, const std::string& where) {
  const ParticleArrays& p = b.particles;
  const std::size_t n = p.size();
  const double h2 = h * h;
  auto position = [&](std::size_t k) { return Vec3d(p.x[k], p.y[k], p.z[k]); };
  auto normal_of = [&](std::size_t k) { return Vec3d(b.nx[k], b.ny[k], b.nz[k]); };
  auto on_face = [&](std::size_t k) {
    return b.flatness[k] >= kFaceFlatness && (sensor.solid < 0 || b.solid[k] == static_cast<std::uint32_t>(sensor.solid));
  };
  // Why a sensor finds no face where particles are: a part thinner than a cell has
  // none (its faces' normals cancel; setup.cpp's surface_normals).
  auto thin_hint = [&]() -> std::string {
    for (std::size_t k = 0; k < n; ++k)
      if ((sensor.solid < 0 || b.solid[k] == static_cast<std::uint32_t>(sensor.solid)) &&
          normal_of(k).squaredNorm() == 0 && (position(k) - sensor.at).squaredNorm() < h2)
        return "; the particles there are of a part thinner than a cell, which has no face to read: sample it with "
               "a finer spacing";
    return "";
  };
  SensorWeights out;
  out.name = sensor.name;
  out.at = sensor.at;
  out.radius = sensor.radius;
  out.normal = sensor.normal;
  if (!(out.normal.norm() > 0)) {
    Vec3d sum = Vec3d::Zero();
    for (std::size_t k = 0; k < n; ++k)
      if (on_face(k) && (position(k) - sensor.at).squaredNorm() < h2) sum += normal_of(k);
    if (!(sum.norm() > 0))
      fail_input("{}: no face of {} within h = {:.4g} m of at = ({:.4g}, {:.4g}, {:.4g}) (a sensor sits on a face "
                 "of a static solid){}",
                 where, sensor.solid < 0 ? std::string("any static solid") : fmt::format("solid {}", sensor.solid), h,
                 sensor.at.x(), sensor.at.y(), sensor.at.z(), thin_hint());
    out.normal = sum.normalized();
  }
  const Vec3d nrm = out.normal;
  // The face's particles near the disc, with their patch areas.
  std::vector<std::uint32_t> face;
  std::vector<double> area;
  const double reach = sensor.radius + h;
  for (std::size_t k = 0; k < n; ++k) {
    if (!on_face(k) || normal_of(k).dot(nrm) < kFacing) continue;
    const Vec3d d = position(k) - sensor.at;
    const double spacing = b.solid_spacing[b.solid[k]];
    const double across = d.dot(nrm);
    if (std::abs(across) > kLayer * spacing || (d - across * nrm).squaredNorm() >= reach * reach) continue;
    face.push_back(static_cast<std::uint32_t>(k));
    area.push_back(spacing * spacing);
  }
  std::vector<double> weight(face.size(), 0.0);
  const std::vector<Vec3d> points = disc_points(sensor.at, nrm, sensor.radius);
  for (const Vec3d& q : points) {
    double total = 0;
    std::vector<double> w(face.size(), 0.0);
    for (std::size_t j = 0; j < face.size(); ++j) {
      const Vec3d d = position(face[j]) - q;
      const double across = d.dot(nrm);
      w[j] = weight_along_face((d - across * nrm).squaredNorm(), h2);
      total += w[j];
    }
    if (!(total > 0))
      fail_input("{}: the point ({:.4g}, {:.4g}, {:.4g}) of its disc has no particle of a face facing ({:.3g}, "
                 "{:.3g}, {:.3g}) within h = {:.4g} m (a sensor sits on a face of a static solid, inside its edges){}",
                 where, q.x(), q.y(), q.z(), nrm.x(), nrm.y(), nrm.z(), h, thin_hint());
    for (std::size_t j = 0; j < face.size(); ++j) weight[j] += w[j] / total / static_cast<double>(points.size());
  }
  for (std::size_t j = 0; j < face.size(); ++j) {
    if (!(weight[j] > 0)) continue;
    out.particle.push_back(face[j]);
    out.weight.push_back(weight[j] / area[j]);
  }
  return out;
}

}  // namespace bw::sim

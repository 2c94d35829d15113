#include "analysis/measure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/error.h"
#include "io/frame_range.h"

namespace bw::analysis {

std::vector<std::string> list_frames(const std::string& folder) {
  std::vector<std::string> frames;
  for (const auto& [number, path] : require_frame_files(folder)) frames.push_back(path);
  return frames;
}

Field parse_field(const std::string& name) {
  if (name == "p" || name == "pressure") return Field::pressure;
  if (name == "rho" || name == "density") return Field::density;
  if (name == "speed") return Field::speed;
  if (name == "vx") return Field::vx;
  if (name == "vy") return Field::vy;
  if (name == "vz") return Field::vz;
  fail_input("field '{}': expected p, rho, speed, vx, vy or vz", name);
}

const char* field_name(Field field) {
  switch (field) {
    case Field::pressure: return "p";
    case Field::density: return "rho";
    case Field::speed: return "speed";
    case Field::vx: return "vx";
    case Field::vy: return "vy";
    case Field::vz: return "vz";
  }
  return "?";
}

double probe(const FrameData& frame, Field field, const Vec3d& point, double h) {
  const bool needs_velocity = field == Field::speed || field == Field::vx || field == Field::vy || field == Field::vz;
  if ((field == Field::pressure && frame.p.empty()) || (field == Field::density && frame.rho.empty()) ||
      (needs_velocity && frame.vx.empty())) {
    fail_input("frame {}: holds no '{}' field; add it to the scene's [output] fields", frame.frame, field_name(field));
  }
  const double h2 = h * h;
  double weighted = 0, weights = 0;
  for (std::size_t i = 0; i < frame.x.size(); ++i) {
    const Vec3d d(frame.x[i] - point.x(), frame.y[i] - point.y(), frame.z[i] - point.z());
    const double r2 = d.squaredNorm();
    if (r2 >= h2) continue;
    const double w = (h2 - r2) * (h2 - r2) * (h2 - r2);  // poly6 up to its constant
    double value = 0;
    switch (field) {
      case Field::pressure: value = frame.p[i]; break;
      case Field::density: value = frame.rho[i]; break;
      case Field::speed: value = std::sqrt(double(frame.vx[i]) * frame.vx[i] + double(frame.vy[i]) * frame.vy[i] + double(frame.vz[i]) * frame.vz[i]); break;
      case Field::vx: value = frame.vx[i]; break;
      case Field::vy: value = frame.vy[i]; break;
      case Field::vz: value = frame.vz[i]; break;
    }
    weighted += w * value;
    weights += w;
  }
  return weights > 0 ? weighted / weights : std::numeric_limits<double>::quiet_NaN();
}

std::vector<Vec3d> Sensor::samples() const {
  const double d = offset < 0 ? 0.5 * h : offset;
  const Vec3d n = normal.normalized();
  return disc_points(point + d * n, n, radius);
}

double sensor_pressure(const FrameData& frame, const Sensor& sensor) {
  const double d = sensor.offset < 0 ? 0.5 * sensor.h : sensor.offset;
  const double hydrostatic = sensor.rho0 * sensor.gravity.dot(sensor.normal.normalized()) * d;
  double sum = 0;
  int count = 0;
  for (const Vec3d& q : sensor.samples()) {
    const double p = probe(frame, Field::pressure, q, sensor.h);
    if (!std::isfinite(p)) continue;
    sum += p - hydrostatic;
    ++count;
  }
  return count ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

double surface_elevation(const FrameData& frame, double x, double y, double radius, double gap, double bottom) {
  std::vector<double> heights;
  for (std::size_t i = 0; i < frame.x.size(); ++i) {
    const double dx = frame.x[i] - x, dy = frame.y[i] - y;
    if (dx * dx + dy * dy <= radius * radius) heights.push_back(frame.z[i]);
  }
  std::sort(heights.begin(), heights.end());
  if (heights.empty()) return std::numeric_limits<double>::quiet_NaN();
  double top = std::isfinite(bottom) ? bottom : heights.front();
  for (const double z : heights) {
    if (z - top > gap) break;  // from the bottom: the line is dry; above the lowest: spray
    top = z;
  }
  return top >= heights.front() ? top : std::numeric_limits<double>::quiet_NaN();
}

WallLoad wall_load(const FrameData& frame, int solid, const std::string& where) {
  require_wall_pressure(frame.fields(), where);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  WallLoad w;
  w.peak = w.mean = kNaN;
  w.at = Vec3d::Constant(kNaN);
  double sum = 0;
  for (std::size_t k = 0; k < frame.bp.size(); ++k) {
    if (frame.bsolid[k] != solid || frame.bp[k] == 0.0f) continue;
    const double p = frame.bp[k];
    if (w.loaded == 0 || p > w.peak) {
      w.peak = p;
      w.at = Vec3d(frame.bx[k], frame.by[k], frame.bz[k]);
    }
    sum += p;
    ++w.loaded;
  }
  if (w.loaded) w.mean = sum / static_cast<double>(w.loaded);
  return w;
}

}  // namespace bw::analysis

#include "rigid/motion.h"

#include <algorithm>
#include <stdexcept>

namespace bw::rigid {

Motion::Motion(std::vector<double> times, std::vector<Vec3d> velocities)
    : times_(std::move(times)), velocities_(std::move(velocities)) {
  if (times_.size() != velocities_.size()) throw std::invalid_argument("motion: as many times as velocities");
  if (!std::is_sorted(times_.begin(), times_.end())) throw std::invalid_argument("motion: times must not decrease");
}

Vec3d Motion::velocity(double t) const {
  if (times_.empty()) return Vec3d::Zero();
  // The first key after t; the key before it starts t's segment.
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (after == times_.begin()) return velocities_.front();
  if (after == times_.end()) return velocities_.back();
  const std::size_t k = static_cast<std::size_t>(after - times_.begin());
  const double t0 = times_[k - 1], t1 = times_[k];
  const double s = (t - t0) / (t1 - t0);  // t1 > t0: t lies in [t0, t1)
  return velocities_[k - 1] + s * (velocities_[k] - velocities_[k - 1]);
}

Vec3d Motion::travelled(double t) const {
  if (times_.empty()) return Vec3d::Zero();
  if (t <= times_.front()) return (t - times_.front()) * velocities_.front();
  Vec3d sum = Vec3d::Zero();
  for (std::size_t k = 1; k < times_.size(); ++k) {
    const double t0 = times_[k - 1], t1 = std::min(times_[k], t);
    if (t1 > t0) {
      const Vec3d v1 = velocities_[k - 1] + (t1 - t0) / (times_[k] - t0) * (velocities_[k] - velocities_[k - 1]);
      sum += 0.5 * (t1 - t0) * (velocities_[k - 1] + v1);
    }
    if (times_[k] >= t) return sum;
  }
  return sum + (t - times_.back()) * velocities_.back();
}

Vec3d Motion::displacement(double t0, double t1) const { return travelled(t1) - travelled(t0); }

double Motion::top_speed() const {
  double top = 0;
  for (const Vec3d& v : velocities_) top = std::max(top, v.norm());
  return top;
}

Vec3d PrescribedMotion::advance(double t, double dt, Vec3d& point, Eigen::Quaterniond& orientation) {
  const Vec3d moved = translation.displacement(t, t + dt);
  const Vec3d turned = turn.displacement(t, t + dt);
  const double angle = turned.norm();
  const Vec3d arm = point - pivot;
  pivot += moved;
  if (angle > 0) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, turned / angle));
    point = pivot + q * arm;
    orientation = (q * orientation).normalized();
  } else {
    point += moved;
  }
  return turned;
}

Vec3d PrescribedMotion::velocity(const Vec3d& x, double t) const {
  return translation.velocity(t) + turn.velocity(t).cross(x - pivot);
}

double PrescribedMotion::top_speed(const std::vector<Vec3d>& points) const {
  double reach = 0;
  for (const Vec3d& x : points) reach = std::max(reach, (x - pivot).norm());
  return translation.top_speed() + turn.top_speed() * reach;
}

}  // namespace bw::rigid

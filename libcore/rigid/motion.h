// Prescribed motion (docs/scene.md, "Moving solids"): a vector given at times (a
// velocity, an angular velocity), linear between them, the first one's before the
// first time and the last one's after the last. Two keys at one time make a jump.
// Positions and angles follow by exact integration, so that a solid lands where its
// keys say at any time step.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "common/geometry.h"

namespace bw::rigid {

class Motion {
 public:
  Motion() = default;
  // times non-decreasing, as many as velocities (the scene checks both).
  Motion(std::vector<double> times, std::vector<Vec3d> velocities);

  bool empty() const { return times_.empty(); }
  const std::vector<double>& times() const { return times_; }
  const std::vector<Vec3d>& velocities() const { return velocities_; }

  // At a jump, the later key's velocity.
  Vec3d velocity(double t) const;
  // The integral of the velocity over [t0, t1].
  Vec3d displacement(double t0, double t1) const;
  // The largest speed it reaches.
  double top_speed() const;

 private:
  // The integral of the velocity from the first key's time to t (negative before it).
  Vec3d travelled(double t) const;

  std::vector<double> times_;
  std::vector<Vec3d> velocities_;
};

// A solid moved as told: a translation (`motion`: the velocity of the pivot, of every
// point when it does not turn) and a turn about a fixed axis through the pivot
// (`angular_motion`: angular velocity vectors along that axis). Turns about one axis
// add up exactly, so a pose carried step by step is where the keys say at any step.
struct PrescribedMotion {
  Motion translation;
  Motion turn;                  // every key along one axis (the scene's `axis`)
  Vec3d pivot = Vec3d::Zero();  // where the pivot is (world), carried by advance()

  bool empty() const { return translation.empty() && turn.empty(); }
  // Carries a rigid pose (a point of the solid and its orientation) and the pivot from
  // t to t + dt. Returns the turn's angle vector (rad, along the axis).
  Vec3d advance(double t, double dt, Vec3d& point, Eigen::Quaterniond& orientation);
  // The velocity at time t of the solid's point now at x (the pivot where it is now).
  Vec3d velocity(const Vec3d& x, double t) const;
  Vec3d angular_velocity(double t) const { return turn.velocity(t); }
  // The largest speed any of these points reaches (bounds: translation plus turn).
  double top_speed(const std::vector<Vec3d>& points) const;
};

}  // namespace bw::rigid

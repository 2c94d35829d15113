// A prescribed translation (docs/scene.md, `[[solid]]` `motion`): the velocity given
// at times, linear between them, the first one's before the first time and the last
// one's after the last. Two keys at one time make a jump. Positions follow by exact
// integration, so that a solid lands where its keys say at any time step.
#pragma once

#include <vector>

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

}  // namespace bw::rigid

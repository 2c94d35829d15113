// Rigid bodies on the host: mass properties from voxels, the pose convention of
// docs/formats.md, and a time step that stays stable for fast-spinning bodies.
//
// A body's geometry is given in its reference configuration (world coordinates of
// its root solid at time 0). With c_ref the centre of mass there, a reference point
// x_ref is at  R(orientation) (x_ref - c_ref) + position  in the world.
#pragma once

#include <vector>

#include "common/geometry.h"

namespace bw::rigid {

struct MassProperties {
  double mass = 0;                 // kg
  Vec3d center = Vec3d::Zero();    // centre of mass, reference configuration (m)
  Mat3d inertia = Mat3d::Zero();   // about the centre, reference frame (kg m^2)
};

// Mass properties of a set of cubic voxels of edge `spacing` centred at `centers`,
// each of uniform `density`: exact for the union of the cubes (each cube adds its
// own m s^2 / 6 to the diagonal).
MassProperties voxel_mass_properties(const std::vector<Vec3d>& centers, double spacing, double density);

struct BodyState {
  Vec3d position = Vec3d::Zero();                                    // centre of mass, world
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // reference -> world
  Vec3d linear_velocity = Vec3d::Zero();
  Vec3d angular_velocity = Vec3d::Zero();                           // world frame
};

class Body {
 public:
  Body() = default;
  // A body at rest in its reference configuration (position = mass.center).
  explicit Body(const MassProperties& mass);

  const MassProperties& mass() const { return mass_; }
  BodyState& state() { return state_; }
  const BodyState& state() const { return state_; }

  Mat3d rotation() const { return state_.orientation.toRotationMatrix(); }
  Mat3d world_inertia() const;
  Mat3d world_inverse_inertia() const;
  // World position of a reference point; velocity of the body at a world point.
  Vec3d to_world(const Vec3d& reference_point) const;
  Vec3d velocity_at(const Vec3d& world_point) const;
  // Linear and angular momentum (about the world origin) and kinetic energy.
  Vec3d linear_momentum() const { return mass_.mass * state_.linear_velocity; }
  Vec3d angular_momentum() const;
  double kinetic_energy() const;

  // One step of length dt under a force through the centre of mass and a torque
  // about it (world frame): a kick of the linear and angular momentum, then
  // advance_pose. Symplectic: a free body keeps its angular momentum exactly and
  // its energy without drift, also when it tumbles.
  void step(const Vec3d& force, const Vec3d& torque, double dt);
  // Moves the body with its current momenta for dt: the position along the linear
  // velocity, the orientation by the free rotation (Strang splitting into exact
  // rotations about the principal axes: Dullweber, Leimkuhler, McLachlan 1997).
  void advance_pose(double dt);

 private:
  void rotate_about_principal_axis(int axis, double dt, Vec3d& momentum_principal, Mat3d& principal_to_world) const;

  MassProperties mass_;
  Mat3d inverse_inertia_ = Mat3d::Zero();      // reference frame
  Vec3d principal_moments_ = Vec3d::Ones();    // eigenvalues of the inertia
  Mat3d principal_axes_ = Mat3d::Identity();   // principal frame -> reference frame (a rotation)
  BodyState state_;
};

}  // namespace bw::rigid

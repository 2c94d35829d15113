#include "rigid/body.h"

#include <Eigen/Eigenvalues>

#include "common/error.h"

namespace bw::rigid {
namespace {

}  // namespace

MassProperties voxel_mass_properties(const std::vector<Vec3d>& centers, double spacing, double density) {
  MassProperties props;
  if (centers.empty()) return props;
  const double m = density * spacing * spacing * spacing;
  // Sums relative to the first voxel keep the second moments well conditioned.
  const Vec3d ref = centers.front();
  Vec3d first = Vec3d::Zero();
  Mat3d second = Mat3d::Zero();
  for (const Vec3d& c : centers) {
    const Vec3d d = c - ref;
    first += d;
    second += d * d.transpose();
  }
  const double n = static_cast<double>(centers.size());
  props.mass = m * n;
  const Vec3d mean = first / n;
  props.center = ref + mean;
  // Covariance about the centre of mass, then I = tr(S) 1 - S, plus each cube's own
  // inertia m s^2 / 6 about its centre.
  const Mat3d covariance = m * (second - n * mean * mean.transpose());
  props.inertia = covariance.trace() * Mat3d::Identity() - covariance;
  props.inertia.diagonal().array() += props.mass * spacing * spacing / 6.0;
  return props;
}

Body::Body(const MassProperties& mass) : mass_(mass) {
  if (!(mass.mass > 0)) fail_input("rigid body: mass {} must be positive", mass.mass);
  inverse_inertia_ = mass.inertia.inverse();
  const Eigen::SelfAdjointEigenSolver<Mat3d> eigen(mass.inertia);
  principal_moments_ = eigen.eigenvalues();
  principal_axes_ = eigen.eigenvectors();
  if (principal_axes_.determinant() < 0) principal_axes_.col(2) *= -1;  // a rotation, not a reflection
  state_.position = mass.center;
}

Mat3d Body::world_inertia() const {
  const Mat3d r = rotation();
  return r * mass_.inertia * r.transpose();
}

Mat3d Body::world_inverse_inertia() const {
  const Mat3d r = rotation();
  return r * inverse_inertia_ * r.transpose();
}

Vec3d Body::to_world(const Vec3d& reference_point) const {
  return state_.orientation * (reference_point - mass_.center) + state_.position;
}

Vec3d Body::velocity_at(const Vec3d& world_point) const {
  return state_.linear_velocity + state_.angular_velocity.cross(world_point - state_.position);
}

Vec3d Body::angular_momentum() const {
  return world_inertia() * state_.angular_velocity + state_.position.cross(linear_momentum());
}

double Body::kinetic_energy() const {
  return 0.5 * mass_.mass * state_.linear_velocity.squaredNorm() +
         0.5 * state_.angular_velocity.dot(world_inertia() * state_.angular_velocity);
}

void Body::step(const Vec3d& force, const Vec3d& torque, double dt) {
  state_.linear_velocity += dt / mass_.mass * force;
  const Vec3d momentum = world_inertia() * state_.angular_velocity + dt * torque;
  state_.angular_velocity = world_inverse_inertia() * momentum;
  advance_pose(dt);
}

void Body::rotate_about_principal_axis(int axis, double dt, Vec3d& momentum_principal,
                                       Mat3d& principal_to_world) const {
  // The flow of L_axis^2 / (2 I_axis): the body turns about that principal axis by
  // dt L_axis / I_axis; its momentum, seen from the body, turns the other way.
  const double angle = dt * momentum_principal[axis] / principal_moments_[axis];
  const Mat3d turn = Eigen::AngleAxisd(angle, Vec3d::Unit(axis)).toRotationMatrix();
  momentum_principal = turn.transpose() * momentum_principal;
  principal_to_world = principal_to_world * turn;
}

void Body::advance_pose(double dt) {
  state_.position += dt * state_.linear_velocity;
  const Vec3d momentum = world_inertia() * state_.angular_velocity;
  if (momentum.squaredNorm() == 0) return;
  Mat3d principal_to_world = rotation() * principal_axes_;
  Vec3d pi = principal_to_world.transpose() * momentum;
  // Symmetric splitting 1 2 3 2 1: second order, symplectic, exact in momentum.
  rotate_about_principal_axis(0, dt / 2, pi, principal_to_world);
  rotate_about_principal_axis(1, dt / 2, pi, principal_to_world);
  rotate_about_principal_axis(2, dt, pi, principal_to_world);
  rotate_about_principal_axis(1, dt / 2, pi, principal_to_world);
  rotate_about_principal_axis(0, dt / 2, pi, principal_to_world);
  state_.orientation = Eigen::Quaterniond(principal_to_world * principal_axes_.transpose());
  state_.orientation.normalize();
  state_.angular_velocity = world_inverse_inertia() * momentum;
}

}  // namespace bw::rigid

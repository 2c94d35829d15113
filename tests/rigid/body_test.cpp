#include <gtest/gtest.h>

#include <cmath>

#include "rigid/body.h"
#include "rigid/contact.h"
#include "test_support.h"

namespace {

using bw::Mat3d;
using bw::Vec3d;
using bw::rigid::Body;
using bw::rigid::voxel_mass_properties;

std::vector<Vec3d> box_voxels(int nx, int ny, int nz, double s, const Vec3d& origin) {
  std::vector<Vec3d> v;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) v.push_back(origin + s * Vec3d(i + 0.5, j + 0.5, k + 0.5));
  return v;
}

TEST(VoxelMassProperties, BoxOfVoxelsIsExact) {
  // 10 x 6 x 4 voxels of 0.1 m: a 1 x 0.6 x 0.4 box of density 500.
  const auto props = voxel_mass_properties(box_voxels(10, 6, 4, 0.1, {3, 4, 5}), 0.1, 500);
  const double m = 500 * 1 * 0.6 * 0.4;
  EXPECT_NEAR(props.mass, m, 1e-9);
  EXPECT_NEAR((props.center - Vec3d(3.5, 4.3, 5.2)).norm(), 0, 1e-12);
  EXPECT_NEAR(props.inertia(0, 0), m / 12 * (0.36 + 0.16), 1e-9);
  EXPECT_NEAR(props.inertia(1, 1), m / 12 * (1 + 0.16), 1e-9);
  EXPECT_NEAR(props.inertia(2, 2), m / 12 * (1 + 0.36), 1e-9);
  EXPECT_NEAR(props.inertia(0, 1), 0, 1e-9);
}

TEST(RigidBody, FallsExactlyUnderGravity) {
  Body body(voxel_mass_properties(box_voxels(2, 2, 2, 0.1, {0, 0, 0}), 0.1, 1000));
  const double m = body.mass().mass, dt = 1e-3;
  const Vec3d start = body.state().position;
  for (int i = 0; i < 1000; ++i) body.step(Vec3d(0, 0, -9.81 * m), Vec3d::Zero(), dt);
  EXPECT_NEAR(body.state().linear_velocity.z(), -9.81, 1e-9);
  // Symplectic Euler: z = -g dt^2 n (n + 1) / 2.
  EXPECT_NEAR(body.state().position.z() - start.z(), -9.81 * 1e-6 * 1000 * 1001 / 2, 1e-9);
  EXPECT_NEAR(body.state().orientation.angularDistance(Eigen::Quaterniond::Identity()), 0, 1e-15);
}

// A free asymmetric body spinning about an axis near its intermediate axis tumbles
// (Dzhanibekov effect); its angular momentum must stay fixed and its energy must
// not grow.
TEST(RigidBody, FreeTumblingKeepsMomentumAndDoesNotGainEnergy) {
  Body body(voxel_mass_properties(box_voxels(8, 4, 2, 0.05, {0, 0, 0}), 0.05, 1000));
  body.state().angular_velocity = Vec3d(0.05, 20, 0.05);
  const Vec3d l0 = body.angular_momentum();
  const double e0 = body.kinetic_energy();
  double e_max = e0, l_err = 0;
  const double dt = 1e-3;
  int flips = 0;
  double previous = 1;
  for (int i = 0; i < 20000; ++i) {
    body.step(Vec3d::Zero(), Vec3d::Zero(), dt);
    const double spin_y = (body.rotation().transpose() * body.state().angular_velocity).y();
    if (spin_y * previous < 0) ++flips;
    if (spin_y != 0) previous = spin_y;
    e_max = std::max(e_max, body.kinetic_energy());
    l_err = std::max(l_err, (body.angular_momentum() - l0).norm() / l0.norm());
  }
  bw::test::figure("tumbling: worst relative angular momentum error", l_err);
  bw::test::figure("tumbling: energy growth", (e_max - e0) / e0);
  EXPECT_LT(l_err, 1e-9);  // round-off over 20000 steps
  // Symplectic: the energy oscillates by O(dt^2) and does not drift.
  EXPECT_LE(e_max, e0 * (1 + 1e-3));
  EXPECT_NEAR(body.kinetic_energy() / e0, 1.0, 1e-3);
  // The unstable intermediate axis makes it tumble: the spin flips about the y axis
  // again and again (a damping integrator would settle on the z axis instead).
  EXPECT_GT(flips, 2);
}

TEST(RigidBody, TorqueSpinsUpAndPosesMapReferencePoints) {
  Body body(voxel_mass_properties(box_voxels(4, 4, 4, 0.1, {-0.2, -0.2, -0.2}), 0.1, 100));
  const double izz = body.mass().inertia(2, 2);
  const double dt = 1e-4;
  double t = 0;
  for (int i = 0; i < 10000; ++i, t += dt) body.step(Vec3d::Zero(), Vec3d(0, 0, izz), dt);
  // Angular acceleration 1 rad/s^2 for 1 s: w = 1, angle ~ 0.5 rad.
  EXPECT_NEAR(body.state().angular_velocity.z(), 1.0, 1e-9);
  const double angle = 2 * std::atan2(body.state().orientation.z(), body.state().orientation.w());
  EXPECT_NEAR(angle, 0.5, 1e-3);
  // A reference point on the x axis turned by that angle about the centre.
  const Vec3d p = body.to_world(Vec3d(0.1, 0, 0));
  EXPECT_NEAR(p.x(), 0.1 * std::cos(angle), 1e-12);
  EXPECT_NEAR(p.y(), 0.1 * std::sin(angle), 1e-12);
  EXPECT_NEAR((body.velocity_at(p) - Vec3d(-p.y(), p.x(), 0)).norm(), 0, 1e-9);
}

TEST(ContactDamping, ContinuousZetaGivesItsRestitution) {
  for (const double e : {0.1, 0.3, 0.5, 0.9}) EXPECT_NEAR(bw::rigid::restitution_of(bw::rigid::damping_ratio(e)), e, 1e-12);
  EXPECT_DOUBLE_EQ(bw::rigid::damping_ratio(1.0), 0.0);
  EXPECT_DOUBLE_EQ(bw::rigid::damping_ratio(0.0), 1.0);
}

TEST(ContactDamping, SteppedBounceEndsWithTheRestitutionAskedFor) {
  // As the simulator steps a contact, the continuous zeta bounces too high (the
  // clamp that never pulls, and the step); the stepped zeta gives e.
  for (const double h : {0.41, 0.5}) {
    EXPECT_GT(bw::rigid::stepped_restitution(bw::rigid::damping_ratio(0.3), h), 0.33);
    for (const double e : {0.2, 0.3, 0.5, 0.8}) {
      const double zeta = bw::rigid::damping_ratio_for_step(e, h);
      EXPECT_NEAR(bw::rigid::stepped_restitution(zeta, h), e, 1e-6) << "e " << e << ", omega dt " << h;
    }
  }
  // With small steps it tends to the clamped continuous bounce, which loses less
  // than the linear formula says (the dashpot cannot pull at the end of the bounce):
  // zeta above the continuous one.
  EXPECT_GT(bw::rigid::damping_ratio_for_step(0.3, 0.01), bw::rigid::damping_ratio(0.3));
  EXPECT_NEAR(bw::rigid::damping_ratio_for_step(1.0, 0.5), 0.0, 1e-3);
  // Restitution 0 gets the zeta of the least bounce the step allows.
  const double least = bw::rigid::stepped_restitution(bw::rigid::damping_ratio_for_step(0.0, 0.5), 0.5);
  EXPECT_GT(least, 0.0);
  EXPECT_LT(least, 0.15);
}

}  // namespace

// Prescribed motion (rigid/motion.h): the velocity between keys and the exact
// displacement over any interval, so that a moved solid lands where its keys say
// whatever its time steps.
#include <cmath>

#include <gtest/gtest.h>

#include "rigid/motion.h"

namespace bw::rigid {
namespace {

// At rest until 1 s, then up to 2 m/s in x by 2 s, a jump to 1 m/s in z at 3 s.
Motion ramp_and_jump() {
  return Motion({1, 2, 3, 3}, {Vec3d::Zero(), Vec3d(2, 0, 0), Vec3d(2, 0, 0), Vec3d(0, 0, 1)});
}

TEST(Motion, VelocityIsLinearBetweenKeysAndHeldOutside) {
  const Motion m = ramp_and_jump();
  EXPECT_EQ(m.velocity(0.5), Vec3d::Zero());
  EXPECT_EQ(m.velocity(1.5), Vec3d(1, 0, 0));
  EXPECT_EQ(m.velocity(2.5), Vec3d(2, 0, 0));
  EXPECT_EQ(m.velocity(3), Vec3d(0, 0, 1)) << "at a jump, the later key";
  EXPECT_EQ(m.velocity(10), Vec3d(0, 0, 1));
  EXPECT_DOUBLE_EQ(m.top_speed(), 2);
  EXPECT_EQ(Motion().velocity(1), Vec3d::Zero());
}

TEST(Motion, DisplacementIsTheExactIntegral) {
  const Motion m = ramp_and_jump();
  EXPECT_TRUE(m.displacement(0, 1).isZero());
  EXPECT_TRUE(m.displacement(0, 2).isApprox(Vec3d(1, 0, 0)));       // the ramp: 1 s at 1 m/s on average
  EXPECT_TRUE(m.displacement(0, 5).isApprox(Vec3d(3, 0, 2)));       // + 1 s at 2 m/s, then 2 s up at 1 m/s
  EXPECT_TRUE(m.displacement(1.5, 2.5).isApprox(Vec3d(1.75, 0, 0)));  // 0.5 s from 1 to 2 m/s, 0.5 s at 2
  // Any partition of [0, 5] adds up to the whole.
  Vec3d sum = Vec3d::Zero();
  for (int k = 0; k < 700; ++k) sum += m.displacement(5.0 * k / 700, 5.0 * (k + 1) / 700);
  EXPECT_LT((sum - Vec3d(3, 0, 2)).norm(), 1e-12);
  const Motion constant({0}, {Vec3d(0, 0, 4)});
  EXPECT_TRUE(constant.displacement(0.1, 0.35).isApprox(Vec3d(0, 0, 1)));
}

TEST(Motion, RefusesKeysOutOfOrder) {
  EXPECT_THROW(Motion({0, 1}, {Vec3d::Zero()}), std::invalid_argument);
  EXPECT_THROW(Motion({1, 0}, {Vec3d::Zero(), Vec3d::Zero()}), std::invalid_argument);
}

// A flap hinged at (1, 0, 0) about y, swinging with omega = 2 cos(t) (keys 1 ms apart,
// linear between them) while its hinge slides at 0.1 m/s in x: stepped 1 000 times
// with uneven steps, its points and orientation are where the keys' integrals put them.
TEST(PrescribedMotion, TurnAndTranslationComposeExactly) {
  std::vector<double> times;
  std::vector<Vec3d> rates;
  for (int k = 0; k <= 2000; ++k) {
    times.push_back(k * 1e-3);
    rates.push_back(2 * std::cos(k * 1e-3) * Vec3d::UnitY());
  }
  PrescribedMotion m;
  m.translation = Motion({0}, {Vec3d(0.1, 0, 0)});
  m.turn = Motion(times, rates);
  m.pivot = Vec3d(1, 0, 0);
  // The keys' own integral; 2 sin(1.5) within linear interpolation's error, dt^2 / 8
  // max|omega''| over 1.5 s.
  const double angle = m.turn.displacement(0, 1.5).y();
  EXPECT_NEAR(angle, 2 * std::sin(1.5), 1e-6 / 8 * 2 * 1.5);
  Vec3d tip(1, 0, 0.5);  // the flap's top, 0.5 m above the hinge
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  double t = 0;
  for (int k = 0; k < 1000; ++k) {
    const double dt = 1.5 * (k % 2 == 0 ? 0.6 : 1.4) / 1000;  // uneven steps adding up to 1.5 s
    m.advance(t, dt, tip, q);
    t += dt;
  }
  EXPECT_NEAR(t, 1.5, 1e-12);
  const Vec3d hinge(1.15, 0, 0);
  EXPECT_LT((m.pivot - hinge).norm(), 1e-12);
  const Vec3d expected = hinge + 0.5 * Vec3d(std::sin(angle), 0, std::cos(angle));  // about +y: z turns toward +x
  EXPECT_LT((tip - expected).norm(), 1e-12);
  EXPECT_LT(q.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(angle, Vec3d::UnitY()))), 1e-12);
  // Velocity of a point: the hinge's plus omega x arm.
  const Vec3d v = m.velocity(tip, 1.5);
  const Vec3d expected_v = Vec3d(0.1, 0, 0) + m.turn.velocity(1.5).cross(tip - hinge);
  EXPECT_LT((v - expected_v).norm(), 1e-12);
  EXPECT_NEAR(m.angular_velocity(1.5).y(), 2 * std::cos(1.5), 1e-6);
  // The top speed bounds every point's: 0.1 + 2 rad/s x 0.5 m.
  EXPECT_NEAR(m.top_speed({hinge, tip}), 0.1 + 2 * 0.5, 1e-9);
}

}  // namespace
}  // namespace bw::rigid

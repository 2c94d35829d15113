// Prescribed motion (rigid/motion.h): the velocity between keys and the exact
// displacement over any interval, so that a moved solid lands where its keys say
// whatever its time steps.
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

}  // namespace
}  // namespace bw::rigid

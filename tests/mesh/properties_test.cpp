#include <gtest/gtest.h>

#include <numbers>

#include "mesh/properties.h"
#include "mesh/shapes.h"

namespace {

using bw::Mat3d;
using bw::Vec3d;
using bw::mesh::mass_properties;

constexpr double kPi = std::numbers::pi;

TEST(MassProperties, BoxIsExact) {
  // 2 x 3 x 4 box, far from the origin to exercise the conditioning.
  const Vec3d offset(1e5, -2e5, 3e5);
  const auto props = mass_properties(bw::mesh::box(offset, offset + Vec3d(2, 3, 4), 2));
  EXPECT_NEAR(props.volume, 24.0, 1e-8);
  EXPECT_NEAR(props.area, 2 * (6 + 8 + 12), 1e-8);
  EXPECT_NEAR((props.centroid - (offset + Vec3d(1, 1.5, 2))).norm(), 0, 1e-8);
  // I = m/12 (b^2 + c^2) etc. for density 1.
  Mat3d expected = Mat3d::Zero();
  expected.diagonal() << 24.0 / 12 * (9 + 16), 24.0 / 12 * (4 + 16), 24.0 / 12 * (4 + 9);
  EXPECT_LT((props.inertia - expected).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(MassProperties, SphereConvergesToAnalytic) {
  const double r = 0.7;
  const auto props = mass_properties(bw::mesh::icosphere({1, 2, 3}, r, 5));
  const double volume = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(props.volume / volume, 1.0, 2e-3);
  EXPECT_NEAR((props.centroid - Vec3d(1, 2, 3)).norm(), 0, 1e-9);
  const double moment = 0.4 * props.volume * r * r;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(props.inertia(i, i) / moment, 1.0, 3e-3);
  EXPECT_LT(std::abs(props.inertia(0, 1)) + std::abs(props.inertia(0, 2)) + std::abs(props.inertia(1, 2)), 1e-6);
}

TEST(MassProperties, TorusVolumeAndFlippedSign) {
  const double R = 1.0, r = 0.25;
  auto mesh = bw::mesh::torus({0, 0, 0}, R, r, 400, 200);
  const double volume = 2 * kPi * kPi * R * r * r;
  EXPECT_NEAR(mass_properties(mesh).volume / volume, 1.0, 1e-3);
  bw::mesh::flip_faces(mesh);
  EXPECT_NEAR(mass_properties(mesh).volume / volume, -1.0, 1e-3);
}

TEST(MassProperties, RotatedBoxHasRotatedInertia) {
  auto mesh = bw::mesh::box({-1, -0.5, -0.25}, {1, 0.5, 0.25});
  const Mat3d rot = Eigen::AngleAxisd(0.7, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3d before = mass_properties(mesh).inertia;
  bw::mesh::transform(mesh, rot, Vec3d(4, 5, 6));
  const auto after = mass_properties(mesh);
  EXPECT_LT((after.inertia - rot * before * rot.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR((after.centroid - Vec3d(4, 5, 6)).norm(), 0, 1e-12);
}

}  // namespace

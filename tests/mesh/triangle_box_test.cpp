// The separating-axis triangle-box test against a brute-force reference: clip the
// triangle by the six planes of the box (Sutherland-Hodgman) and see whether
// anything is left.
#include <gtest/gtest.h>

#include <random>

#include "mesh/triangle_box.h"

namespace {

using bw::Vec3d;

bool clip_reference(const Vec3d& center, const Vec3d& half, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  std::vector<Vec3d> poly = {a, b, c};
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = -1; side <= 1; side += 2) {
      // Keep side * (p[axis] - center[axis]) <= half[axis].
      const double limit = half[axis];
      std::vector<Vec3d> out;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3d& p = poly[i];
        const Vec3d& q = poly[(i + 1) % poly.size()];
        const double dp = side * (p[axis] - center[axis]) - limit;
        const double dq = side * (q[axis] - center[axis]) - limit;
        if (dp <= 0) out.push_back(p);
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
      }
      poly = std::move(out);
      if (poly.empty()) return false;
    }
  }
  return true;
}

TEST(TriangleBox, AgreesWithClippingOnRandomCases) {
  std::mt19937_64 rng(20231122);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  std::uniform_real_distribution<double> size(0.05, 1.5);
  int overlaps = 0, disagreements = 0;
  const int cases = 200000;
  for (int i = 0; i < cases; ++i) {
    const Vec3d center(coord(rng) * 0.3, coord(rng) * 0.3, coord(rng) * 0.3);
    const Vec3d half(size(rng), size(rng), size(rng));
    const Vec3d a(coord(rng), coord(rng), coord(rng));
    // Mix of large and small triangles.
    const double scale = (i % 3 == 0) ? 0.1 : 1.0;
    const Vec3d b = a + scale * Vec3d(coord(rng), coord(rng), coord(rng));
    const Vec3d c = a + scale * Vec3d(coord(rng), coord(rng), coord(rng));
    const bool sat = bw::mesh::triangle_box_overlap(center, half, a, b, c);
    const bool ref = clip_reference(center, half, a, b, c);
    overlaps += ref;
    disagreements += sat != ref;
  }
  // Both outcomes must be well represented for the comparison to mean anything.
  EXPECT_GT(overlaps, cases / 10);
  EXPECT_LT(overlaps, cases * 9 / 10);
  EXPECT_EQ(disagreements, 0);
}

TEST(TriangleBox, TouchingCountsAsOverlap) {
  const Vec3d center(0.5, 0.5, 0.5), half(0.5, 0.5, 0.5);
  // A triangle in the plane x = 1 (the box's face), x = 1 + 1e-12 (just outside).
  EXPECT_TRUE(bw::mesh::triangle_box_overlap(center, half, {1, 0.2, 0.2}, {1, 0.8, 0.2}, {1, 0.2, 0.8}));
  EXPECT_FALSE(bw::mesh::triangle_box_overlap(center, half, {1 + 1e-12, 0.2, 0.2}, {1 + 1e-12, 0.8, 0.2},
                                              {1 + 1e-12, 0.2, 0.8}));
  // Touching only at a corner of the box.
  EXPECT_TRUE(bw::mesh::triangle_box_overlap(center, half, {1, 1, 1}, {2, 1, 1}, {1, 2, 1}));
  // A big triangle slicing through the box with no vertex inside.
  EXPECT_TRUE(bw::mesh::triangle_box_overlap(center, half, {-5, -5, 0.5}, {10, -5, 0.5}, {-5, 10, 0.5}));
  // A triangle whose bounding box overlaps the box but which misses it (edge axis).
  EXPECT_FALSE(bw::mesh::triangle_box_overlap(center, half, {1.2, -0.5, 0.5}, {2.5, 0.8, 0.5}, {1.8, -0.6, 0.6}));
}

}  // namespace

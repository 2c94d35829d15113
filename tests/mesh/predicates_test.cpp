#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/predicates.h"

namespace {

using bw::mesh::orient2d;
using bw::mesh::orient2d_perturbed;
__extension__ typedef __int128 int128;  // exact reference arithmetic

// Kettner et al., "Classroom examples of robustness problems in geometric
// computations": p = (0.5 + i u, 0.5 + j u) against the line through (12, 12) and
// (24, 24), u = 2^-53. Naive floating point gets many of these signs wrong; the
// reference is exact integer arithmetic on the coordinates scaled by 2^53.
TEST(Predicates, ExactOnNearlyCollinearPoints) {
  const double b[2] = {12, 12};
  const double c[2] = {24, 24};
  const int128 scale = static_cast<int128>(1) << 53;
  int positive = 0, negative = 0, zero = 0, naive_wrong = 0;
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j) {
      const double a[2] = {0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53};
      const int128 ax = scale / 2 + i, ay = scale / 2 + j;
      const int128 bx = 12 * scale, by = 12 * scale, cx = 24 * scale, cy = 24 * scale;
      const int128 det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
      const int expected = (det > 0) - (det < 0);
      const int s = orient2d(a, b, c);
      ASSERT_EQ(s, expected) << "i=" << i << " j=" << j;
      const double naive = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      naive_wrong += ((naive > 0) - (naive < 0)) != expected;
      positive += s > 0, negative += s < 0, zero += s == 0;
    }
  EXPECT_GT(positive, 0);
  EXPECT_GT(negative, 0);
  EXPECT_GT(zero, 0);
  // The case is hard: plain floating point fails on it.
  EXPECT_GT(naive_wrong, 0);
}

TEST(Predicates, PerturbedNeverZeroAndAntisymmetric) {
  const double a[2] = {0, 0}, b[2] = {1, 1}, q[2] = {0.5, 0.5};
  ASSERT_EQ(orient2d(a, b, q), 0);
  const int s = orient2d_perturbed(a, b, q);
  EXPECT_NE(s, 0);
  EXPECT_EQ(orient2d_perturbed(b, a, q), -s);
  // Vertical and horizontal edges through q.
  const double v0[2] = {0.5, 0}, v1[2] = {0.5, 1}, h0[2] = {0, 0.5}, h1[2] = {1, 0.5};
  EXPECT_NE(orient2d_perturbed(v0, v1, q), 0);
  EXPECT_EQ(orient2d_perturbed(v0, v1, q), -orient2d_perturbed(v1, v0, q));
  EXPECT_NE(orient2d_perturbed(h0, h1, q), 0);
  EXPECT_EQ(orient2d_perturbed(h0, h1, q), -orient2d_perturbed(h1, h0, q));
}

// Around a vertex shared by a fan of triangles that covers its neighbourhood once,
// a point on the vertex is inside exactly one triangle of the fan.
TEST(Predicates, PointOnSharedVertexIsInsideExactlyOneFanTriangle) {
  const double center[2] = {0.25, 0.75};
  const int n = 7;
  std::vector<std::array<double, 2>> ring;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * M_PI * i / n + 0.1;
    ring.push_back({center[0] + std::cos(angle), center[1] + std::sin(angle)});
  }
  int inside = 0;
  for (int i = 0; i < n; ++i) {
    const double* a = center;
    const double* b = ring[i].data();
    const double* c = ring[(i + 1) % n].data();
    const int o = orient2d(a, b, c);
    ASSERT_NE(o, 0);
    inside += orient2d_perturbed(a, b, center) == o && orient2d_perturbed(b, c, center) == o &&
              orient2d_perturbed(c, a, center) == o;
  }
  EXPECT_EQ(inside, 1);
}

}  // namespace

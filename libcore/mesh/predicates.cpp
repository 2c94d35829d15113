#include "mesh/predicates.h"

#include <cmath>

#include <gmpxx.h>

namespace bw::mesh {
namespace {

// Shewchuk's bound for the first stage of orient2d: when |det| exceeds it, the
// floating-point sign is the exact sign.
constexpr double kEpsilon = 1.1102230246251565e-16;  // 2^-53
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;

int sign_of(double x) { return (x > 0) - (x < 0); }

int orient2d_exact(const double a[2], const double b[2], const double c[2]) {
  // Doubles convert to rationals exactly; the determinant is then exact.
  const mpq_class ax(a[0]), ay(a[1]), bx(b[0]), by(b[1]), cx(c[0]), cy(c[1]);
  const mpq_class det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  return sgn(det);
}

}  // namespace

int orient2d(const double a[2], const double b[2], const double c[2]) {
  const double left = (b[0] - a[0]) * (c[1] - a[1]);
  const double right = (b[1] - a[1]) * (c[0] - a[0]);
  const double det = left - right;
  const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
  if (det > bound || -det > bound) return sign_of(det);
  return orient2d_exact(a, b, c);
}

int orient2d_perturbed(const double a[2], const double b[2], const double q[2]) {
  const int s = orient2d(a, b, q);
  if (s != 0) return s;
  // det(q + (eps, eps^2)) = det(q) - (b_v - a_v) eps + (b_u - a_u) eps^2.
  if (b[1] != a[1]) return b[1] > a[1] ? -1 : 1;
  return sign_of(b[0] - a[0]);
}

}  // namespace bw::mesh

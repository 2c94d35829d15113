// Exact geometric predicates on double coordinates.
//
// orient2d is decided in floating point when the result is certain (Shewchuk's
// error bound) and exactly with rational arithmetic otherwise, so the sign is always
// right, also for points exactly on a line.
#pragma once

namespace bw::mesh {

// Sign of the area of triangle (a, b, c) in the plane: +1 counter-clockwise,
// -1 clockwise, 0 collinear. Points are (u, v) pairs.
int orient2d(const double a[2], const double b[2], const double c[2]);

// orient2d(a, b, q) with q perturbed symbolically by (eps, eps^2) (simulation of
// simplicity): never 0 unless a == b. Two triangles that share an edge (a, b) and
// (b, a) give opposite signs, so a perturbed point is inside exactly one of them:
// rays through vertices and along edges are counted once.
int orient2d_perturbed(const double a[2], const double b[2], const double q[2]);

}  // namespace bw::mesh

#include "mesh/triangle_box.h"

#include <algorithm>
#include <cmath>

namespace bw::mesh {

bool triangle_box_overlap(const Vec3d& center, const Vec3d& half, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                          bool closed) {
  // An interval [lo, hi] is separated from [-r, r]: strictly for closed boxes, with
  // contact for open ones.
  auto separated = [closed](double lo, double hi, double r) { return closed ? (lo > r || hi < -r) : (lo >= r || hi <= -r); };
  // Move the box to the origin.
  const Vec3d v0 = a - center;
  const Vec3d v1 = b - center;
  const Vec3d v2 = c - center;

  // Box face normals: the triangle's bounding box against the box.
  for (int i = 0; i < 3; ++i) {
    if (separated(std::min({v0[i], v1[i], v2[i]}), std::max({v0[i], v1[i], v2[i]}), half[i])) return false;
  }

  // The nine axes e_i x edge.
  const Vec3d edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  for (const Vec3d& e : edges) {
    for (int i = 0; i < 3; ++i) {
      Vec3d axis = Vec3d::Zero();
      axis[(i + 1) % 3] = -e[(i + 2) % 3];
      axis[(i + 2) % 3] = e[(i + 1) % 3];
      const double p0 = axis.dot(v0);
      const double p1 = axis.dot(v1);
      const double p2 = axis.dot(v2);
      const double r = half.dot(axis.cwiseAbs());
      if (r > 0 && separated(std::min({p0, p1, p2}), std::max({p0, p1, p2}), r)) return false;
    }
  }

  // The triangle's plane.
  const Vec3d normal = edges[0].cross(edges[1]);
  const double r = half.dot(normal.cwiseAbs());
  const double d = normal.dot(v0);
  return !separated(d, d, r);
}

}  // namespace bw::mesh

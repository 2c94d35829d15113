// The point of a triangle closest to a given point (Ericson, Real-Time Collision
// Detection 5.1.5): by the Voronoi regions of its vertices, edges and face.
#pragma once

#include "common/geometry.h"

namespace bw::mesh {

Vec3d closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

inline double point_triangle_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return (p - closest_point_on_triangle(p, a, b, c)).norm();
}

}  // namespace bw::mesh

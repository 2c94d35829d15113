// Plain geometric types shared by every part: positions are double precision on the
// host (meshes, voxels, rigid bodies); the simulator's device buffers are float.
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace bw {

using Vec3d = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Mat3d = Eigen::Matrix3d;
using Triangle = std::array<std::int32_t, 3>;

// Axis-aligned box; empty (min > max) until a point is added.
struct Aabb {
  Vec3d min = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d max = Vec3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  void add(const Vec3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Vec3d extent() const { return empty() ? Vec3d::Zero() : Vec3d(max - min); }
};

// An indexed triangle mesh. Triangles are counter-clockwise seen from outside
// (outward normals) when the mesh is consistently oriented and has positive volume.
//   vertices:  #V positions
//   triangles: #F triples of indices into vertices
struct TriMesh {
  std::vector<Vec3d> vertices;
  std::vector<Triangle> triangles;

  Aabb bounds() const {
    Aabb box;
    for (const Vec3d& v : vertices) box.add(v);
    return box;
  }
};

// Points that stand for equal areas of the disc of `radius` about `centre` in the
// plane of unit normal `normal` (a pressure sensor's membrane): 1 + 6 + 12 points,
// the centre for the disc r < R sqrt(1/19), the rings for the annuli up to R sqrt(7/19)
// and R, each ring at the radius that halves its annulus' area (sqrt(4/19) R,
// sqrt(13/19) R). Only the centre when radius is 0.
inline std::vector<Vec3d> disc_points(const Vec3d& centre, const Vec3d& normal, double radius) {
  if (!(radius > 0)) return {centre};
  // Two unit vectors in the disc's plane.
  const Vec3d a = (std::abs(normal.x()) < 0.9 ? Vec3d::UnitX() : Vec3d::UnitY()).cross(normal).normalized();
  const Vec3d b = normal.cross(a);
  std::vector<Vec3d> out{centre};
  const std::pair<int, double> rings[] = {{6, std::sqrt(4.0 / 19)}, {12, std::sqrt(13.0 / 19)}};
  for (const auto& [count, fraction] : rings)
    for (int j = 0; j < count; ++j) {
      const double angle = 2 * std::numbers::pi * (j + 0.5 * (count == 12)) / count;
      out.push_back(centre + fraction * radius * (std::cos(angle) * a + std::sin(angle) * b));
    }
  return out;
}

}  // namespace bw

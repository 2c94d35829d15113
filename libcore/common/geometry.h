// Plain geometric types shared by every part: positions are double precision on the
// host (meshes, voxels, rigid bodies); the simulator's device buffers are float.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
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

}  // namespace bw

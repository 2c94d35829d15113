// Closed, outward-oriented meshes of simple shapes, for tests, benchmarks and the
// example scenes.
#pragma once

#include <vector>

#include "common/geometry.h"

namespace bw::mesh {

// Box [min, max] with each face split into n x n quads (two triangles each).
TriMesh box(const Vec3d& min, const Vec3d& max, int n = 1);
// Sphere by subdividing an icosahedron `levels` times: 20 * 4^levels triangles.
TriMesh icosphere(const Vec3d& center, double radius, int levels);
// Torus around the z axis: major radius R, minor radius r, nu x nv quads.
TriMesh torus(const Vec3d& center, double major_radius, double minor_radius, int nu, int nv);
// Cylinder along z from z0 to z1 with `segments` sides.
TriMesh cylinder(const Vec3d& base_center, double radius, double height, int segments);
// Prism: a simple polygon in the xy plane (counter-clockwise, any shape without
// self-intersections) extruded along z from z0 to z1. An L-shape, a house with a
// gable roof (polygon in a vertical plane, then rotated), a dam cross-section.
TriMesh extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1);
// Applies x -> rotation * x + translation to every vertex.
void transform(TriMesh& mesh, const Mat3d& rotation, const Vec3d& translation);
// Appends the faces of `other` (disjoint union).
void append(TriMesh& mesh, const TriMesh& other);

}  // namespace bw::mesh

// Closed, outward-oriented meshes of simple shapes, for tests, benchmarks and the
// example scenes.
#pragma once

#include <functional>
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
// An open-topped tank: the solid between the box [inner_min, inner_max] (open at the
// top face z = inner_max.z) and that box grown by `wall` on every side but the top.
// One closed, outward-oriented surface: outer faces, rim, inner faces.
TriMesh open_box(const Vec3d& inner_min, const Vec3d& inner_max, double wall);
// A sealed tank: the solid between the box [inner_min, inner_max] and that box grown
// by `wall` on every side. Two closed surfaces: the outer one facing out, the
// cavity's facing into it.
TriMesh sealed_box(const Vec3d& inner_min, const Vec3d& inner_max, double wall);
// A terrain block: the top surface z = height(x, y) sampled on nx x ny quads over
// [min_xy, max_xy], closed by four vertical sides and a flat bottom at z_bottom
// (which must lie below every height).
TriMesh heightfield(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, int nx, int ny, double z_bottom,
                    const std::function<double(double, double)>& height);
// Applies x -> rotation * x + translation to every vertex.
void transform(TriMesh& mesh, const Mat3d& rotation, const Vec3d& translation);
// Appends the faces of `other` (disjoint union).
void append(TriMesh& mesh, const TriMesh& other);

}  // namespace bw::mesh

// Private to libcore/voronoi (included by the cgal_*.cpp files only): the CGAL types
// the module uses and the conversions between them and bw::TriMesh at its border.
#pragma once

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "common/geometry.h"
#include "voronoi/solid.h"

namespace bw::voronoi::detail {

// Exact predicates, double coordinates. Corefinement with this kernel computes its
// intersection points exactly and rounds them when it writes the output mesh.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

inline Point to_point(const Vec3d& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3d to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

// Builds a halfedge mesh with the same vertex and face order. Throws InputError
// naming the first face that cannot be added (a non-manifold configuration).
SurfaceMesh to_surface_mesh(const TriMesh& mesh);

}  // namespace bw::voronoi::detail

namespace bw::voronoi {

struct Solid::Impl {
  TriMesh mesh;
  Aabb bounds;
  double volume = 0;
  detail::SurfaceMesh surface;
  detail::Tree tree;  // over `surface`'s faces, with distance queries accelerated
  // Where the solid is not locally convex (exact predicates): edges whose two faces
  // meet at a reflex angle (by edge index of `surface`), and their end vertices.
  std::vector<bool> concave_edge;
  std::vector<bool> reflex_vertex;
};

}  // namespace bw::voronoi

// Exact queries on a closed mesh with CGAL: side of a point, distance to the
// surface, self-intersections.
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <algorithm>
#include <iterator>

#include "common/error.h"
#include "mesh/properties.h"
#include "voronoi/cgal_mesh.h"

namespace bw::voronoi {
namespace detail {

SurfaceMesh to_surface_mesh(const TriMesh& mesh) {
  SurfaceMesh out;
  out.reserve(static_cast<SurfaceMesh::size_type>(mesh.vertices.size()),
              static_cast<SurfaceMesh::size_type>(3 * mesh.triangles.size() / 2),
              static_cast<SurfaceMesh::size_type>(mesh.triangles.size()));
  std::vector<SurfaceMesh::Vertex_index> vertex;
  vertex.reserve(mesh.vertices.size());
  for (const Vec3d& v : mesh.vertices) vertex.push_back(out.add_vertex(to_point(v)));
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (out.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == SurfaceMesh::null_face()) {
      fail_input("face {} ({} {} {}) makes the mesh non-manifold", f, t[0], t[1], t[2]);
    }
  }
  return out;
}

}  // namespace detail

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::K;
using detail::SurfaceMesh;
using Point_3 = detail::Point;

Solid::Solid(TriMesh mesh) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.surface = detail::to_surface_mesh(mesh);
  s.mesh = std::move(mesh);
  s.bounds = s.mesh.bounds();
  s.volume = mesh::mass_properties(s.mesh).volume;
  s.tree.insert(faces(s.surface).first, faces(s.surface).second, s.surface);
  s.tree.build();
  s.tree.accelerate_distance_queries();
  const SurfaceMesh& m = s.surface;
  s.concave_edge.assign(m.number_of_edges(), false);
  s.reflex_vertex.assign(m.number_of_vertices(), false);
  for (const auto e : m.edges()) {
    const auto h = m.halfedge(e);
    const auto o = m.opposite(h);
    // The far corner of the face across the edge lies outside (on the positive
    // side of) this face's plane exactly when the edge is reflex.
    const Point_3& a = m.point(m.source(h));
    const Point_3& b = m.point(m.target(h));
    const Point_3& c = m.point(m.target(m.next(h)));
    const Point_3& d = m.point(m.target(m.next(o)));
    if (CGAL::orientation(a, b, c, d) == CGAL::POSITIVE) {
      s.concave_edge[e.idx()] = true;
      s.reflex_vertex[m.source(h).idx()] = true;
      s.reflex_vertex[m.target(h).idx()] = true;
    }
  }
}

Solid::~Solid() = default;
Solid::Solid(Solid&&) noexcept = default;
Solid& Solid::operator=(Solid&&) noexcept = default;

const TriMesh& Solid::mesh() const { return impl_->mesh; }
const Aabb& Solid::bounds() const { return impl_->bounds; }
double Solid::volume() const { return impl_->volume; }

std::size_t Solid::concave_edges() const {
  return static_cast<std::size_t>(std::count(impl_->concave_edge.begin(), impl_->concave_edge.end(), true));
}

double Solid::length_scale() const {
  const Aabb& box = impl_->bounds;
  const double coordinate = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  return std::max(box.extent().norm(), coordinate);
}

Side Solid::side(const Vec3d& p) const {
  // Side_of_triangle_mesh over the prebuilt tree: ray parity with exact predicates;
  // rays through edges or vertices are replaced by other rays, so the answer is exact.
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> inside(impl_->tree);
  switch (inside(detail::to_point(p))) {
    case CGAL::ON_BOUNDED_SIDE: return Side::inside;
    case CGAL::ON_BOUNDARY: return Side::boundary;
    default: return Side::outside;
  }
}

double Solid::distance(const Vec3d& p) const {
  return std::sqrt(CGAL::to_double(impl_->tree.squared_distance(detail::to_point(p))));
}

std::vector<std::pair<std::int32_t, std::int32_t>> Solid::self_intersections(std::size_t max_pairs,
                                                                             std::size_t* total) const {
  using Face = SurfaceMesh::Face_index;
  std::vector<std::pair<Face, Face>> pairs;
  PMP::self_intersections(impl_->surface, std::back_inserter(pairs));
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  for (const auto& [a, b] : pairs) {
    // Faces were added in the order of mesh().triangles, so their indices agree.
    const auto fa = static_cast<std::int32_t>(a.idx()), fb = static_cast<std::int32_t>(b.idx());
    out.emplace_back(std::min(fa, fb), std::max(fa, fb));
  }
  std::sort(out.begin(), out.end());
  if (total) *total = out.size();
  if (out.size() > max_pairs) out.resize(max_pairs);
  return out;
}

}  // namespace bw::voronoi

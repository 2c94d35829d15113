// A closed triangle mesh prepared for exact geometric queries: which side of the
// surface a point lies on, its distance to the surface, and the faces that intersect
// each other. The CGAL structures behind it (a halfedge mesh and an AABB tree) stay
// inside libcore/voronoi; this header includes std and Eigen only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "common/geometry.h"

namespace bw::voronoi {

enum class Side { inside, boundary, outside };

class Solid {
 public:
  // Precondition: `mesh` bounds a volume and faces outwards (check_solid_mesh in
  // check.h says so): closed, edge- and vertex-manifold, consistently oriented,
  // positive volume, finite coordinates. Throws InputError when the halfedge mesh
  // cannot be built from it.
  explicit Solid(TriMesh mesh);
  ~Solid();
  Solid(Solid&&) noexcept;
  Solid& operator=(Solid&&) noexcept;
  Solid(const Solid&) = delete;
  Solid& operator=(const Solid&) = delete;

  const TriMesh& mesh() const;
  const Aabb& bounds() const;
  double volume() const;
  // The length that relative tolerances are fractions of: the larger of the
  // bounding-box diagonal and the largest absolute coordinate (rounding errors grow
  // with the coordinates, not only with the size).
  double length_scale() const;

  // Edges where the solid is not locally convex: their two faces meet at a reflex
  // angle (exact predicates; flat edges are not counted).
  std::size_t concave_edges() const;

  // Exact: a point on a face, edge or vertex is on the boundary.
  Side side(const Vec3d& p) const;
  // Distance from p to the nearest point of the surface.
  double distance(const Vec3d& p) const;

  // Pairs of faces (indices into mesh().triangles) that intersect other than along
  // the edge or vertex they share, with exact predicates; a degenerate face (zero
  // area) counts as intersecting itself. At most `max_pairs` are returned;
  // `*total` receives how many there are.
  std::vector<std::pair<std::int32_t, std::int32_t>> self_intersections(std::size_t max_pairs,
                                                                        std::size_t* total) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::voronoi

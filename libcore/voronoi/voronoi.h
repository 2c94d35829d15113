// Cutting a solid into the Voronoi cells of seeds (method.md section 4).
//
// The cell of seed i is the convex polyhedron of the points nearer to seed i than to
// any other seed: the intersection of the half-spaces bounded by the bisector planes
// of i and its Delaunay neighbours, closed by a box around the solid. Each cell is
// built in exact rational arithmetic, rounded to doubles once (a vertex that
// neighbouring cells share rounds to the same double in both), and intersected with
// the solid by corefinement with exact predicates and exactly computed intersection
// points (CGAL Polygon Mesh Processing). The result of each cell is split into its
// edge-connected components: a cell of a non-convex solid can fall apart into
// several fragments.
//
// Every cell is cut independently, in parallel; a cell that fails (CGAL throws, or
// the intersection would not be a manifold mesh) is reported with its seed and the
// other cells go on. A cell boundary that passes exactly through a reflex vertex or
// a concave edge of the solid (symmetric seeds in a solid with a notch) could make
// two parts of a fragment touch along an edge; the seeds are then moved by a tiny
// deterministic amount (CutResult::seed_nudge) before cutting.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "io/fragments_file.h"
#include "voronoi/solid.h"

namespace bw::voronoi {

struct CutOptions {
  int threads = 0;  // worker threads; 0: one per hardware thread
  // Called after each cell with (cells done, cells in all), from one thread at a time.
  std::function<void(std::size_t, std::size_t)> progress;
};

struct CellFailure {
  std::int32_t seed = -1;
  std::string message;
};

struct CutResult {
  // Ordered by seed, then by component. Components of a cell are numbered from 0 in
  // order of decreasing volume (ties: by the lexicographic order of their lowest
  // vertex). Each mesh is closed and faces outwards; `volume` is its enclosed volume
  // and `body` is -1.
  std::vector<Fragment> fragments;
  std::vector<CellFailure> failures;  // ordered by seed
  // 0, or how far (at most, per coordinate) the seeds were moved because a cell's
  // boundary passed exactly through a reflex vertex or concave edge of the solid.
  double seed_nudge = 0;
  double cell_seconds = 0;            // building the cells (wall clock, all threads)
  double clip_seconds = 0;            // intersecting them with the solid
};

// The Voronoi cells of the seeds listed in `active` (indices into `seeds`; the others
// take no part), each intersected with the solid. Fragment::seed is an index into
// `seeds`. A seed may lie outside the solid: its cell still takes its share, and
// gives no fragment when it misses the solid. Throws InputError when two active
// seeds coincide.
// Precondition: the solid's mesh does not intersect itself
// (Solid::self_intersections is empty); where it does, the cells that meet the
// crossing faces fail.
CutResult cut(const Solid& solid, std::span<const Vec3d> seeds, std::span<const std::int32_t> active,
              const CutOptions& options = {});

// The Voronoi cell of seed `index` among the active seeds, bounded by `box`, as a
// closed convex mesh facing outwards (what cut() intersects the solid with). For
// tests and inspection. Precondition: `box` contains the seed in its interior.
TriMesh voronoi_cell(std::span<const Vec3d> seeds, std::span<const std::int32_t> active, std::int32_t index,
                     const Aabb& box);

}  // namespace bw::voronoi

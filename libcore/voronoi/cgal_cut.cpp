// Voronoi cells with CGAL (Delaunay neighbours, exact half-space intersection) and
// their intersection with the solid (corefinement). See voronoi.h.
#include <CGAL/Convex_hull_3/dual/halfspace_intersection_3.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <exception>
#include <memory>
#include <mutex>

#include <fmt/format.h>

#include "common/error.h"
#include "common/terminal.h"
#include "mesh/properties.h"
#include "voronoi/cgal_mesh.h"
#include "voronoi/parallel.h"
#include "voronoi/seeds.h"
#include "voronoi/voronoi.h"

namespace bw::voronoi {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::K;
using detail::Point;
using detail::SurfaceMesh;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::int32_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;

// The box that closes the cells reaches this fraction of the solid's largest extent
// beyond its bounding box on every side, so that no face of the box comes near the
// solid and the corefinement never meets the box.
constexpr double kBoxMarginFraction = 0.25;

Aabb cell_box_for(const Aabb& solid_bounds) {
  const double margin = kBoxMarginFraction * std::max(solid_bounds.extent().maxCoeff(), 1e-300);
  Aabb box = solid_bounds;
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

// For every active seed (by position in `active`), the positions of its Delaunay
// neighbours: the only seeds whose bisector planes bound its Voronoi cell.
std::vector<std::vector<std::int32_t>> delaunay_neighbours(std::span<const Vec3d> seeds,
                                                           std::span<const std::int32_t> active) {
  std::vector<std::vector<std::int32_t>> neighbours(active.size());
  if (active.size() < 2) return neighbours;
  Delaunay dt;
  std::vector<Delaunay::Vertex_handle> handle(active.size());
  Delaunay::Vertex_handle hint;
  for (std::size_t a = 0; a < active.size(); ++a) {
    const auto before = dt.number_of_vertices();
    const Delaunay::Vertex_handle v = dt.insert(detail::to_point(seeds[active[a]]), hint);
    if (dt.number_of_vertices() == before) {
      fail_input("seed {} coincides with seed {}", active[a], active[static_cast<std::size_t>(v->info())]);
    }
    v->info() = static_cast<std::int32_t>(a);
    handle[a] = hint = v;
  }
  std::vector<Delaunay::Vertex_handle> adjacent;
  for (std::size_t a = 0; a < active.size(); ++a) {
    adjacent.clear();
    dt.finite_adjacent_vertices(handle[a], std::back_inserter(adjacent));
    for (const auto& v : adjacent) neighbours[a].push_back(v->info());
    std::sort(neighbours[a].begin(), neighbours[a].end());
  }
  return neighbours;
}

EK::Point_3 exact_point(const Vec3d& v) { return {v.x(), v.y(), v.z()}; }

// The closed convex cell of `seed`: half-spaces of the bisector planes with the
// neighbours and of the box, intersected in exact arithmetic (Epeck). Each vertex is
// rounded from its exact value, so a vertex shared by two cells becomes the same
// double in both, and symmetric set-ups (seeds mirrored in a plane of the mesh) give
// cells that meet the mesh exactly where they should. Rounding from Epeck's interval
// approximations instead builds the cells five times faster (measured: 0.57 s
// instead of 2.7 s for 400 seeds on two threads) but lets shared vertices differ in
// their last bits. Returned as the convex hull of the rounded vertices (closed,
// outward, triangulated, no degenerate face).
SurfaceMesh cell_mesh(const Vec3d& seed, std::span<const Vec3d> neighbours, const Aabb& box) {
  const EK::Point_3 s = exact_point(seed);
  std::vector<EK::Plane_3> planes;
  planes.reserve(neighbours.size() + 6);
  // The seed lies on the negative side of each plane, as halfspace_intersection_3 wants.
  for (const Vec3d& n : neighbours) {
    const EK::Point_3 q = exact_point(n);
    planes.emplace_back(CGAL::midpoint(s, q), q - s);
  }
  for (int axis = 0; axis < 3; ++axis) {
    EK::RT lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    lo[axis] = -1;
    hi[axis] = 1;
    planes.emplace_back(lo[0], lo[1], lo[2], EK::RT(box.min[axis]));   // -x + min <= 0
    planes.emplace_back(hi[0], hi[1], hi[2], EK::RT(-box.max[axis]));  //  x - max <= 0
  }
  CGAL::Surface_mesh<EK::Point_3> exact_cell;
  CGAL::halfspace_intersection_3(planes.begin(), planes.end(), exact_cell, boost::make_optional(s));
  std::vector<Point> corners;
  corners.reserve(exact_cell.number_of_vertices());
  for (const auto v : exact_cell.vertices()) {
    const EK::Point_3& p = exact_cell.point(v);
    corners.emplace_back(CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
                         CGAL::to_double(CGAL::exact(p.z())));
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  SurfaceMesh hull;
  CGAL::convex_hull_3(corners.begin(), corners.end(), hull);
  return hull;
}

std::vector<Vec3d> neighbour_points(std::span<const Vec3d> seeds, std::span<const std::int32_t> active,
                                    const std::vector<std::int32_t>& positions) {
  std::vector<Vec3d> points;
  points.reserve(positions.size());
  for (const std::int32_t a : positions) points.push_back(seeds[active[static_cast<std::size_t>(a)]]);
  return points;
}

TriMesh to_trimesh(const SurfaceMesh& m) {
  TriMesh out;
  std::vector<std::int32_t> index(m.number_of_vertices() + m.number_of_removed_vertices(), -1);
  for (const auto v : m.vertices()) {
    index[v.idx()] = static_cast<std::int32_t>(out.vertices.size());
    out.vertices.push_back(detail::to_vec(m.point(v)));
  }
  for (const auto f : m.faces()) {
    Triangle t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (k < 3) t[k] = index[v.idx()];
      ++k;
    }
    if (k != 3) fail_run("a face with {} corners in a triangle mesh", k);
    out.triangles.push_back(t);
  }
  return out;
}

// Puts a mesh in a canonical order: vertices sorted by coordinates, each triangle
// starting at its smallest index (orientation kept), triangles sorted. CGAL's output
// order depends on memory addresses; this makes the same cut give the same file.
void canonicalize(TriMesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::int32_t> order(nv);
  for (std::size_t i = 0; i < nv; ++i) order[i] = static_cast<std::int32_t>(i);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    const Vec3d& p = mesh.vertices[static_cast<std::size_t>(a)];
    const Vec3d& q = mesh.vertices[static_cast<std::size_t>(b)];
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  std::vector<std::int32_t> rank(nv);
  std::vector<Vec3d> vertices(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    rank[static_cast<std::size_t>(order[i])] = static_cast<std::int32_t>(i);
    vertices[i] = mesh.vertices[static_cast<std::size_t>(order[i])];
  }
  mesh.vertices = std::move(vertices);
  for (Triangle& t : mesh.triangles) {
    for (auto& i : t) i = rank[static_cast<std::size_t>(i)];
    const auto first = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + first, t.end());
  }
  std::sort(mesh.triangles.begin(), mesh.triangles.end());
}

// Splits the result of one cell into edge-connected components, as fragments.
std::vector<Fragment> split_components(SurfaceMesh& part, std::int32_t seed) {
  using Face = SurfaceMesh::Face_index;
  const auto by_face = part.add_property_map<Face, std::size_t>("f:bw_component", 0).first;
  const std::size_t count = PMP::connected_components(part, by_face);

  std::vector<Fragment> fragments(count);
  const std::size_t nv = part.number_of_vertices() + part.number_of_removed_vertices();
  std::vector<std::int32_t> index(nv, -1);
  std::vector<std::vector<Face>> faces_of(count);
  for (const Face f : part.faces()) faces_of[by_face[f]].push_back(f);
  for (std::size_t c = 0; c < count; ++c) {
    TriMesh& mesh = fragments[c].mesh;
    std::vector<std::uint32_t> touched;
    for (const Face f : faces_of[c]) {
      Triangle t{};
      int k = 0;
      for (const auto v : CGAL::vertices_around_face(part.halfedge(f), part)) {
        if (index[v.idx()] < 0) {
          index[v.idx()] = static_cast<std::int32_t>(mesh.vertices.size());
          mesh.vertices.push_back(detail::to_vec(part.point(v)));
          touched.push_back(v.idx());
        }
        if (k < 3) t[k] = index[v.idx()];
        ++k;
      }
      if (k != 3) fail_run("a face with {} corners in the cut mesh", k);
      mesh.triangles.push_back(t);
    }
    for (const std::uint32_t v : touched) index[v] = -1;
    canonicalize(mesh);
    fragments[c].seed = seed;
    fragments[c].volume = mesh::mass_properties(mesh).volume;
  }
  std::vector<Vec3d> low(count);  // the lowest vertex: the first, once canonical
  for (std::size_t c = 0; c < count; ++c) low[c] = fragments[c].mesh.vertices.front();
  std::vector<std::size_t> order(count);
  for (std::size_t c = 0; c < count; ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (fragments[a].volume != fragments[b].volume) return fragments[a].volume > fragments[b].volume;
    return std::lexicographical_compare(low[a].data(), low[a].data() + 3, low[b].data(), low[b].data() + 3);
  });
  std::vector<Fragment> sorted;
  sorted.reserve(count);
  for (std::size_t c = 0; c < count; ++c) {
    sorted.push_back(std::move(fragments[order[c]]));
    sorted.back().component = static_cast<std::int32_t>(c);
  }
  return sorted;
}

// One line from an exception, whatever threw it.
std::string describe_failure(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const CGAL::Failure_exception& e) {
    std::string what = e.message().empty() ? e.expression() : e.message() + " (" + e.expression() + ")";
    return fmt::format("CGAL {} failed: {} at {}:{}", e.library(), what, e.filename(), e.line_number());
  } catch (const std::bad_alloc&) {
    return "out of memory";
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    return what;
  } catch (...) {
    return "unknown failure";
  }
}

// Cells per group (see cut()). Measured on 100 seeds in 20 k triangles (icosphere
// and torus, one thread): 8 to 12 take a third of the time of no groups; 4 and 25
// are slower again (more group cuts, or larger pieces).
constexpr std::size_t kGroupCells = 8;

// A group's hull is scaled by 1 + kGroupHullGrowth about the mean of its seeds, so
// that it holds the group's cells strictly: its faces stay clear of theirs and the
// corefinement never meets two nearly coincident faces.
constexpr double kGroupHullGrowth = 0.01;

// The cells (positions into active) sorted along the axis on which their seeds
// spread most, and split at the median.
std::vector<std::vector<std::size_t>> split_in_halves(std::vector<std::size_t> cells, std::span<const Vec3d> seeds,
                                                      std::span<const std::int32_t> active) {
  auto seed = [&](std::size_t a) -> const Vec3d& { return seeds[static_cast<std::size_t>(active[a])]; };
  Aabb box;
  for (const std::size_t a : cells) box.add(seed(a));
  int axis = 0;
  box.extent().maxCoeff(&axis);
  std::sort(cells.begin(), cells.end(), [&](std::size_t x, std::size_t y) {
    return seed(x)[axis] != seed(y)[axis] ? seed(x)[axis] < seed(y)[axis] : x < y;
  });
  const auto middle = cells.begin() + static_cast<std::ptrdiff_t>(cells.size() / 2);
  return {std::vector<std::size_t>(cells.begin(), middle), std::vector<std::size_t>(middle, cells.end())};
}

// Convex hull of the group's cells, grown by kGroupHullGrowth.
SurfaceMesh group_hull(const std::vector<std::size_t>& group, const std::vector<SurfaceMesh>& cells,
                       std::span<const Vec3d> seeds, std::span<const std::int32_t> active) {
  Vec3d centre = Vec3d::Zero();
  for (const std::size_t a : group) centre += seeds[static_cast<std::size_t>(active[a])];
  centre /= static_cast<double>(group.size());
  std::vector<Point> points;
  for (const std::size_t a : group)
    for (const auto v : cells[a].vertices()) {
      const Vec3d p = detail::to_vec(cells[a].point(v));
      points.push_back(detail::to_point(centre + (1 + kGroupHullGrowth) * (p - centre)));
    }
  SurfaceMesh hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  return hull;
}

// Each corefinement looks for self-intersections among the faces it cuts and throws
// when it finds one (a solid that was not checked, or one that rounding spoiled)
// rather than producing a wrong fragment.
const auto kSelfIntersectionCheck = CGAL::parameters::throw_on_self_intersection(true);

// Nudges of the seeds, as a fraction of Solid::length_scale(): 1e-13 moves a
// bisector plane by far less than the checks' tolerance (kDistanceTolerance, 1e-9)
// for seeds at least 1e-4 of the size apart, and by about a thousand units in the
// last place of the coordinates, enough to leave any exact coincidence. Each further
// round multiplies it by 10.
constexpr double kSeedNudge = 1e-13;
constexpr int kNudgeRounds = 3;

// True when the solid touches the cell's boundary where it is not locally convex: a
// reflex vertex on a face of the cell, or a concave edge crossing an edge of the
// cell (not a diagonal of a flat face). Exact predicates.
char touches_reflex_features(const SurfaceMesh& cell, const Solid::Impl& s) {
  const SurfaceMesh& m = s.surface;
  std::vector<detail::Tree::Primitive_id> hits;
  for (const auto f : cell.faces()) {
    const auto h = cell.halfedge(f);
    const Point& a = cell.point(cell.source(h));
    const Point& b = cell.point(cell.target(h));
    const Point& c = cell.point(cell.target(cell.next(h)));
    const K::Triangle_3 triangle(a, b, c);
    hits.clear();
    s.tree.all_intersected_primitives(triangle, std::back_inserter(hits));
    for (const auto g : hits)
      for (const auto v : CGAL::vertices_around_face(m.halfedge(g), m)) {
        if (!s.reflex_vertex[v.idx()]) continue;
        const Point& p = m.point(v);
        if (CGAL::orientation(a, b, c, p) == CGAL::COPLANAR && CGAL::do_intersect(triangle, p)) return 1;
      }
  }
  for (const auto e : cell.edges()) {
    const auto h = cell.halfedge(e);
    const Point& p = cell.point(cell.source(h));
    const Point& q = cell.point(cell.target(h));
    const Point& r = cell.point(cell.target(cell.next(h)));
    const Point& t = cell.point(cell.target(cell.next(cell.opposite(h))));
    if (CGAL::orientation(p, q, r, t) == CGAL::COPLANAR) continue;
    const K::Segment_3 edge(p, q);
    hits.clear();
    s.tree.all_intersected_primitives(edge, std::back_inserter(hits));
    for (const auto g : hits)
      for (const auto hg : CGAL::halfedges_around_face(m.halfedge(g), m)) {
        if (!s.concave_edge[m.edge(hg).idx()]) continue;
        if (CGAL::do_intersect(edge, K::Segment_3(m.point(m.source(hg)), m.point(m.target(hg))))) return 1;
      }
  }
  return 0;
}

}  // namespace

TriMesh voronoi_cell(std::span<const Vec3d> seeds, std::span<const std::int32_t> active, std::int32_t index,
                     const Aabb& box) {
  const auto it = std::find(active.begin(), active.end(), index);
  if (it == active.end()) fail_input("seed {} is not among the active seeds", index);
  const auto a = static_cast<std::size_t>(it - active.begin());
  const auto neighbours = delaunay_neighbours(seeds, active);
  return to_trimesh(cell_mesh(seeds[static_cast<std::size_t>(index)], neighbour_points(seeds, active, neighbours[a]), box));
}

CutResult cut(const Solid& solid, std::span<const Vec3d> seeds, std::span<const std::int32_t> active,
              const CutOptions& options) {
  for (const std::int32_t i : active)
    if (i < 0 || static_cast<std::size_t>(i) >= seeds.size()) fail_input("seed index {} is out of range", i);
  const int threads = detail::thread_count(options.threads);
  const std::size_t n = active.size();
  CutResult result;

  // 1. Cells, exactly, then rounded. A cell whose boundary passes exactly through a
  // reflex vertex or a concave edge of the solid can meet it in a non-manifold way
  // (two parts touching along an edge or at a point), which CGAL 5.5's corefinement
  // does not always survive. Symmetric seeds in meshes with symmetric notches do
  // that; then every seed is moved by a tiny pseudo-random amount (deterministic)
  // and the cells are built again, up to kNudgeRounds times.
  Stopwatch clock;
  const Aabb box = cell_box_for(solid.bounds());
  std::vector<Vec3d> moved(seeds.begin(), seeds.end());  // the seeds the cells are built from
  std::vector<SurfaceMesh> cells(n);
  std::vector<std::string> failure(n);
  std::vector<char> touching(n, 0);
  for (int round = 0;; ++round) {
    const auto neighbours = delaunay_neighbours(moved, active);
    detail::parallel_for(n, threads, [&](std::size_t a) {
      failure[a].clear();
      touching[a] = 0;
      try {
        cells[a] = cell_mesh(moved[static_cast<std::size_t>(active[a])], neighbour_points(moved, active, neighbours[a]), box);
        touching[a] = touches_reflex_features(cells[a], solid.impl());
      } catch (...) {
        failure[a] = "building the Voronoi cell: " + describe_failure(std::current_exception());
      }
    });
    const bool touch = std::any_of(touching.begin(), touching.end(), [](char t) { return t != 0; });
    if (!touch) break;
    if (round == kNudgeRounds) {
      for (std::size_t a = 0; a < n; ++a)
        if (touching[a] && failure[a].empty())
          failure[a] = "the cell's boundary passes exactly through a reflex vertex or concave edge of the solid, "
                       "also after moving the seeds";
      break;
    }
    result.seed_nudge = kSeedNudge * std::pow(10.0, round) * solid.length_scale();
    std::mt19937_64 rng(static_cast<std::uint64_t>(round) + 1);
    for (const std::int32_t i : active) {
      const auto k = static_cast<std::size_t>(i);
      for (int axis = 0; axis < 3; ++axis) moved[k][axis] = seeds[k][axis] + result.seed_nudge * (2 * uniform01(rng) - 1);
    }
  }
  result.cell_seconds = clock.seconds();

  // 2. Each cell intersected with the solid, then split into components. Cutting
  // every cell from the whole solid would cost the whole solid per cell. Instead the
  // cells are gathered into groups of neighbours (recursive median splits of their
  // seeds), the solid is cut once per group down to a convex hull that holds the
  // group's cells strictly, and each cell is cut from its group's piece: inside the
  // hull the piece is the solid, and the piece's new faces never touch the cell.
  // (Cutting pieces from pieces, recursively, was measured slower: each level's cut
  // crosses the previous level's long thin cap triangles, and the exactly computed
  // intersection points multiply.)
  clock.restart();
  std::vector<std::vector<Fragment>> pieces(n);
  std::vector<std::size_t> built;
  for (std::size_t a = 0; a < n; ++a)
    if (failure[a].empty()) built.push_back(a);
  std::vector<std::vector<std::size_t>> groups;
  if (built.size() > kGroupCells) {
    std::vector<std::vector<std::size_t>> todo{built};
    while (!todo.empty()) {
      std::vector<std::size_t> g = std::move(todo.back());
      todo.pop_back();
      if (g.size() <= kGroupCells) {
        groups.push_back(std::move(g));
        continue;
      }
      for (auto& half : split_in_halves(std::move(g), moved, active)) todo.push_back(std::move(half));
    }
  }
  // The piece of the solid each cell is cut from: its group's piece, or the whole
  // solid (few cells, or the group's piece could not be cut).
  std::vector<std::shared_ptr<const SurfaceMesh>> piece_of(
      n, std::shared_ptr<const SurfaceMesh>(&solid.impl().surface, [](const SurfaceMesh*) {}));
  detail::parallel_for(groups.size(), threads, [&](std::size_t g) {
    try {
      SurfaceMesh hull = group_hull(groups[g], cells, moved, active);
      // A hull that touches the solid where it is not convex: no piece, as for a cell.
      if (touches_reflex_features(hull, solid.impl())) return;
      auto piece = std::make_shared<SurfaceMesh>(solid.impl().surface);
      if (PMP::corefine_and_compute_intersection(*piece, hull, *piece, kSelfIntersectionCheck) &&
          piece->number_of_faces() > 0) {
        for (const std::size_t a : groups[g]) piece_of[a] = piece;
      }
    } catch (...) {
      // The cells of this group are cut from the whole solid.
    }
  });

  std::mutex progress_mutex;
  std::size_t done = 0;
  detail::parallel_for(n, threads, [&](std::size_t a) {
    if (failure[a].empty()) {
      try {
        SurfaceMesh part = *piece_of[a];
        if (!PMP::corefine_and_compute_intersection(part, cells[a], part, kSelfIntersectionCheck)) {
          failure[a] = "the intersection of the cell with the solid is not a manifold mesh (the cell's boundary "
                       "meets the solid along an edge or at a vertex from two sides)";
        } else if (part.number_of_faces() > 0) {
          pieces[a] = split_components(part, active[a]);
        }
      } catch (...) {
        failure[a] = "intersecting the cell with the solid: " + describe_failure(std::current_exception());
      }
      cells[a] = SurfaceMesh();
      piece_of[a].reset();
    }
    if (options.progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress(++done, n);
    }
  });
  result.clip_seconds = clock.seconds();

  std::vector<std::size_t> order(n);
  for (std::size_t a = 0; a < n; ++a) order[a] = a;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return active[x] < active[y]; });
  for (const std::size_t a : order) {
    for (Fragment& f : pieces[a]) result.fragments.push_back(std::move(f));
    if (!failure[a].empty()) result.failures.push_back({active[a], failure[a]});
  }
  return result;
}

}  // namespace bw::voronoi

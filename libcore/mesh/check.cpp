#include "mesh/check.h"

#include <algorithm>

#include <fmt/format.h>

#include "common/union_find.h"

namespace bw::mesh {
namespace {

struct HalfEdge {
  std::uint64_t key;     // (min index << 32) | max index
  std::int32_t face;
  bool forward;          // traversed from the smaller index to the larger
  bool operator<(const HalfEdge& o) const { return key != o.key ? key < o.key : face < o.face; }
};

}  // namespace

std::string MeshReport::summary() const {
  std::vector<std::string> problems;
  auto add = [&](std::size_t n, const char* what) {
    if (n) problems.push_back(fmt::format("{} {}", n, what));
  };
  add(bad_indices, "faces with invalid indices");
  add(nonfinite_vertices, "non-finite vertices");
  add(boundary_edges, "boundary edges");
  add(nonmanifold_edges, "non-manifold edges");
  add(misoriented_edges, "inconsistently oriented edges");
  if (problems.empty()) return "closed and consistently oriented";
  std::string text;
  for (std::size_t i = 0; i < problems.size(); ++i) text += (i ? ", " : "") + problems[i];
  return text;
}

MeshReport check_mesh(const TriMesh& mesh) {
  MeshReport report;
  report.vertices = mesh.vertices.size();
  report.triangles = mesh.triangles.size();
  for (const Vec3d& v : mesh.vertices) report.nonfinite_vertices += !v.allFinite();

  const Aabb box = mesh.bounds();
  const double diag2 = box.empty() ? 0.0 : box.extent().squaredNorm();
  const auto nv = static_cast<std::int64_t>(mesh.vertices.size());

  std::vector<HalfEdge> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= nv || t[1] >= nv || t[2] >= nv) {
      ++report.bad_indices;
      continue;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++report.degenerate_faces;
    } else {
      const Vec3d& a = mesh.vertices[t[0]];
      const Vec3d& b = mesh.vertices[t[1]];
      const Vec3d& c = mesh.vertices[t[2]];
      const double area2 = (b - a).cross(c - a).squaredNorm() * 0.25;
      if (area2 <= kDegenerateAreaFraction * kDegenerateAreaFraction * diag2 * diag2) ++report.degenerate_faces;
    }
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(t[k]);
      const auto b = static_cast<std::uint32_t>(t[(k + 1) % 3]);
      if (a == b) continue;
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      edges.push_back({key, static_cast<std::int32_t>(f), a < b});
    }
  }
  std::sort(edges.begin(), edges.end());

  UnionFind components(mesh.triangles.size());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    const std::size_t count = j - i;
    if (count == 1) ++report.boundary_edges;
    if (count > 2) ++report.nonmanifold_edges;
    if (count == 2 && edges[i].forward == edges[i + 1].forward) ++report.misoriented_edges;
    const std::int32_t first_face = edges[i].face;
    for (auto k = edges.begin() + static_cast<std::ptrdiff_t>(i) + 1; k != edges.begin() + static_cast<std::ptrdiff_t>(j); ++k) {
      components.unite(first_face, k->face);
    }
    i = j;
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    report.components += components.find(static_cast<std::int32_t>(f)) == static_cast<std::int32_t>(f);
  }
  return report;
}

}  // namespace bw::mesh

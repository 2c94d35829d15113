// Vertex manifoldness of a triangle mesh (check.h).
#include <algorithm>
#include <numeric>

#include "common/union_find.h"
#include "voronoi/check.h"

namespace bw::voronoi {
namespace {

struct EdgeUse {
  std::uint64_t key;          // (smaller vertex << 32) | larger vertex
  std::int32_t corner_low;    // the face's corner at the smaller vertex
  std::int32_t corner_high;   // and at the larger one
  bool operator<(const EdgeUse& o) const { return key < o.key; }
};

}  // namespace

std::size_t count_nonmanifold_vertices(const TriMesh& mesh) {
  const std::size_t nf = mesh.triangles.size();
  // Corners 3f + k; two corners at one vertex are joined when their faces share an
  // edge at that vertex. A vertex whose corners form more than one group has faces
  // that meet only at the vertex (two fans).
  UnionFind corners(3 * nf);
  std::vector<EdgeUse> edges;
  edges.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(t[k]), b = static_cast<std::uint32_t>(t[(k + 1) % 3]);
      if (a == b) continue;
      const auto ca = static_cast<std::int32_t>(3 * f + k), cb = static_cast<std::int32_t>(3 * f + (k + 1) % 3);
      if (a < b) edges.push_back({(std::uint64_t{a} << 32) | b, ca, cb});
      else edges.push_back({(std::uint64_t{b} << 32) | a, cb, ca});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 1; i < edges.size(); ++i) {
    if (edges[i].key != edges[i - 1].key) continue;
    corners.unite(edges[i].corner_low, edges[i - 1].corner_low);
    corners.unite(edges[i].corner_high, edges[i - 1].corner_high);
  }
  constexpr std::int32_t kNone = -1;
  std::vector<std::int32_t> group(mesh.vertices.size(), kNone);
  std::vector<bool> bad(mesh.vertices.size(), false);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[f][k]);
      const std::int32_t root = corners.find(static_cast<std::int32_t>(3 * f + k));
      if (group[v] == kNone) group[v] = root;
      else if (group[v] != root) bad[v] = true;
    }
  return static_cast<std::size_t>(std::count(bad.begin(), bad.end(), true));
}

}  // namespace bw::voronoi

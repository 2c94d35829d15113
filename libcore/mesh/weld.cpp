#include "mesh/weld.h"

#include <bit>
#include <cmath>
#include <unordered_map>

namespace bw::mesh {
namespace {

struct ExactKey {
  std::uint64_t x, y, z;
  bool operator==(const ExactKey&) const = default;
};

struct ExactKeyHash {
  std::size_t operator()(const ExactKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= k.y + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= k.z + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

std::uint64_t bits(double value) { return std::bit_cast<std::uint64_t>(value == 0.0 ? 0.0 : value); }

// remap[v] = the vertex v merges into (remap[v] <= v).
std::vector<std::int32_t> exact_representatives(const std::vector<Vec3d>& vertices) {
  std::unordered_map<ExactKey, std::int32_t, ExactKeyHash> first;
  first.reserve(vertices.size());
  std::vector<std::int32_t> remap(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const Vec3d& p = vertices[v];
    auto [it, inserted] = first.try_emplace(ExactKey{bits(p.x()), bits(p.y()), bits(p.z())}, static_cast<std::int32_t>(v));
    remap[v] = it->second;
  }
  return remap;
}

std::vector<std::int32_t> tolerant_representatives(const std::vector<Vec3d>& vertices, double tolerance) {
  // Hash grid of cell size `tolerance`; a vertex looks for an earlier representative
  // in the 27 cells around it.
  std::unordered_map<ExactKey, std::vector<std::int32_t>, ExactKeyHash> grid;
  std::vector<std::int32_t> remap(vertices.size());
  const double tol2 = tolerance * tolerance;
  auto cell_of = [&](const Vec3d& p) {
    return Eigen::Vector3<std::int64_t>(static_cast<std::int64_t>(std::floor(p.x() / tolerance)),
                                        static_cast<std::int64_t>(std::floor(p.y() / tolerance)),
                                        static_cast<std::int64_t>(std::floor(p.z() / tolerance)));
  };
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const Vec3d& p = vertices[v];
    const auto c = cell_of(p);
    std::int32_t found = -1;
    for (int dz = -1; dz <= 1 && found < 0; ++dz)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = grid.find(ExactKey{static_cast<std::uint64_t>(c.x() + dx), static_cast<std::uint64_t>(c.y() + dy),
                                       static_cast<std::uint64_t>(c.z() + dz)});
          if (it == grid.end()) continue;
          for (std::int32_t r : it->second) {
            if ((vertices[r] - p).squaredNorm() <= tol2 && (found < 0 || r < found)) found = r;
          }
        }
    if (found >= 0) {
      remap[v] = found;
    } else {
      remap[v] = static_cast<std::int32_t>(v);
      grid[ExactKey{static_cast<std::uint64_t>(c.x()), static_cast<std::uint64_t>(c.y()),
                    static_cast<std::uint64_t>(c.z())}]
          .push_back(static_cast<std::int32_t>(v));
    }
  }
  return remap;
}

}  // namespace

WeldStats weld_vertices(TriMesh& mesh, double tolerance) {
  WeldStats stats;
  const std::vector<std::int32_t> remap =
      tolerance > 0 ? tolerant_representatives(mesh.vertices, tolerance) : exact_representatives(mesh.vertices);
  // Merge, drop collapsed faces, then keep only the vertices faces use, in order.
  std::vector<Triangle> faces;
  faces.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    const Triangle m{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (m[0] == m[1] || m[1] == m[2] || m[0] == m[2]) {
      ++stats.collapsed_faces;
      continue;
    }
    faces.push_back(m);
  }
  std::vector<std::int32_t> new_index(mesh.vertices.size(), -1);
  for (const Triangle& t : faces)
    for (auto v : t) new_index[v] = 0;
  std::vector<Vec3d> vertices;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (new_index[v] < 0) continue;
    new_index[v] = static_cast<std::int32_t>(vertices.size());
    vertices.push_back(mesh.vertices[v]);
  }
  for (Triangle& t : faces)
    for (auto& v : t) v = new_index[v];
  std::size_t representatives = 0;
  for (std::size_t v = 0; v < remap.size(); ++v) representatives += remap[v] == static_cast<std::int32_t>(v);
  stats.merged_vertices = mesh.vertices.size() - representatives;
  stats.unused_vertices = representatives - vertices.size();
  mesh.vertices = std::move(vertices);
  mesh.triangles = std::move(faces);
  return stats;
}

}  // namespace bw::mesh

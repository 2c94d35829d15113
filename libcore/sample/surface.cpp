#include <omp.h>

#include <algorithm>
#include <cmath>

#include "mesh/triangle_box.h"
#include "sample/sampler.h"

namespace bw::sample {
namespace {

// Triangles are tested in grid coordinates (cell (i,j,k) = [i, i+1] x ...), where
// every cell boundary is an exact integer: two neighbouring cells see the same
// plane between them, so a triangle lying on it is found by both.
Vec3d to_grid(const Vec3d& p, const SampleGrid& grid) { return (p - grid.origin) / grid.spacing; }

// Slack when turning a triangle's bounds into a cell range: candidates only, the
// exact test decides.
constexpr double kRangeSlack = 1e-9;

}  // namespace

std::vector<CellIndex> surface_cells(const TriMesh& mesh, const SampleGrid& grid) {
  const std::int64_t nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  const auto nf = static_cast<std::int64_t>(mesh.triangles.size());
  std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(omp_get_max_threads()));

#pragma omp parallel
  {
    std::vector<std::uint64_t>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
    const Vec3d half(0.5, 0.5, 0.5);
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t f = 0; f < nf; ++f) {
      const Triangle& t = mesh.triangles[static_cast<std::size_t>(f)];
      const Vec3d a = to_grid(mesh.vertices[t[0]], grid);
      const Vec3d b = to_grid(mesh.vertices[t[1]], grid);
      const Vec3d c = to_grid(mesh.vertices[t[2]], grid);
      const Vec3d lo = a.cwiseMin(b).cwiseMin(c);
      const Vec3d hi = a.cwiseMax(b).cwiseMax(c);
      std::int64_t from[3], to[3];
      const std::int64_t n[3] = {nx, ny, nz};
      for (int k = 0; k < 3; ++k) {
        // A cell i overlaps [lo, hi] when i <= hi and i + 1 >= lo.
        from[k] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(lo[k] - kRangeSlack)) - 1);
        to[k] = std::min<std::int64_t>(n[k] - 1, static_cast<std::int64_t>(std::floor(hi[k] + kRangeSlack)));
      }
      for (std::int64_t z = from[2]; z <= to[2]; ++z)
        for (std::int64_t y = from[1]; y <= to[1]; ++y)
          for (std::int64_t x = from[0]; x <= to[0]; ++x) {
            const Vec3d center(static_cast<double>(x) + 0.5, static_cast<double>(y) + 0.5, static_cast<double>(z) + 0.5);
            if (mesh::triangle_box_overlap(center, half, a, b, c)) {
              mine.push_back(static_cast<std::uint64_t>((z * ny + y) * nx + x));
            }
          }
    }
  }

  std::size_t total = 0;
  for (const auto& v : found) total += v.size();
  std::vector<std::uint64_t> ids;
  ids.reserve(total);
  for (auto& v : found) {
    ids.insert(ids.end(), v.begin(), v.end());
    std::vector<std::uint64_t>().swap(v);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

  std::vector<CellIndex> cells(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::uint64_t id = ids[i];
    cells[i] = {static_cast<std::int32_t>(id % static_cast<std::uint64_t>(nx)),
                static_cast<std::int32_t>((id / static_cast<std::uint64_t>(nx)) % static_cast<std::uint64_t>(ny)),
                static_cast<std::int32_t>(id / (static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny)))};
  }
  return cells;
}

}  // namespace bw::sample

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "mesh/predicates.h"
#include "sample/sampler.h"

namespace bw::sample {
namespace {

// One crossing of a row of cell centres (a line along x) with a triangle.
struct Crossing {
  std::uint64_t row;   // k * ny + j
  double x;            // in grid units
  std::int8_t sign;    // +1 where the surface faces +x (the ray leaves), -1 where it enters
  bool operator<(const Crossing& o) const {
    if (row != o.row) return row < o.row;
    if (x != o.x) return x < o.x;
    return sign < o.sign;
  }
};

}  // namespace

std::vector<CellIndex> interior_cells(const TriMesh& mesh, const SampleGrid& grid) {
  const std::int64_t nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  const auto nf = static_cast<std::int64_t>(mesh.triangles.size());
  std::vector<std::vector<Crossing>> found(static_cast<std::size_t>(omp_get_max_threads()));

  // 1. Each triangle, projected on the yz plane, against the row centres it covers.
#pragma omp parallel
  {
    std::vector<Crossing>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t f = 0; f < nf; ++f) {
      const Triangle& t = mesh.triangles[static_cast<std::size_t>(f)];
      Vec3d p[3];
      for (int k = 0; k < 3; ++k) p[k] = to_grid_coordinates(mesh.vertices[t[k]], grid);
      const double a[2] = {p[0].y(), p[0].z()}, b[2] = {p[1].y(), p[1].z()}, c[2] = {p[2].y(), p[2].z()};
      // The x component of the face normal; 0: the face is parallel to the rays and
      // a perturbed ray never hits it.
      const int orientation = mesh::orient2d(a, b, c);
      if (orientation == 0) continue;
      const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      const double ylo = std::min({a[0], b[0], c[0]}), yhi = std::max({a[0], b[0], c[0]});
      const double zlo = std::min({a[1], b[1], c[1]}), zhi = std::max({a[1], b[1], c[1]});
      // Centres j + 0.5 inside [ylo, yhi], with one cell of slack: the exact test decides.
      const std::int64_t j0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(ylo - 0.5)) - 1);
      const std::int64_t j1 = std::min<std::int64_t>(ny - 1, static_cast<std::int64_t>(std::ceil(yhi - 0.5)) + 1);
      const std::int64_t k0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(zlo - 0.5)) - 1);
      const std::int64_t k1 = std::min<std::int64_t>(nz - 1, static_cast<std::int64_t>(std::ceil(zhi - 0.5)) + 1);
      const double xlo = std::min({p[0].x(), p[1].x(), p[2].x()}), xhi = std::max({p[0].x(), p[1].x(), p[2].x()});
      for (std::int64_t k = k0; k <= k1; ++k)
        for (std::int64_t j = j0; j <= j1; ++j) {
          const double q[2] = {static_cast<double>(j) + 0.5, static_cast<double>(k) + 0.5};
          if (mesh::orient2d_perturbed(a, b, q) != orientation || mesh::orient2d_perturbed(b, c, q) != orientation ||
              mesh::orient2d_perturbed(c, a, q) != orientation) {
            continue;
          }
          // Barycentric weights from the sub-areas give the x of the crossing.
          const double wa = (b[0] - q[0]) * (c[1] - q[1]) - (b[1] - q[1]) * (c[0] - q[0]);
          const double wb = (c[0] - q[0]) * (a[1] - q[1]) - (c[1] - q[1]) * (a[0] - q[0]);
          const double wc = area - wa - wb;
          // (The exact orientation is non-zero; a rounded area of 0 means a sliver.)
          const double x = area != 0 ? std::clamp((wa * p[0].x() + wb * p[1].x() + wc * p[2].x()) / area, xlo, xhi)
                                     : 0.5 * (xlo + xhi);
          mine.push_back({static_cast<std::uint64_t>(k * ny + j), x, static_cast<std::int8_t>(orientation)});
        }
    }
  }

  std::size_t total = 0;
  for (const auto& v : found) total += v.size();
  std::vector<Crossing> crossings;
  crossings.reserve(total);
  for (auto& v : found) {
    crossings.insert(crossings.end(), v.begin(), v.end());
    std::vector<Crossing>().swap(v);
  }
  std::sort(crossings.begin(), crossings.end());

  // 2. Rows in parallel: the winding number at centre x is the sum of the signs of
  // the crossings beyond x (towards +x).
  std::vector<std::size_t> row_starts;
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    if (i == 0 || crossings[i].row != crossings[i - 1].row) row_starts.push_back(i);
  }
  row_starts.push_back(crossings.size());
  const auto rows = static_cast<std::int64_t>(row_starts.size() - 1);
  const std::int64_t chunks = std::min<std::int64_t>(rows, 64 * omp_get_max_threads());
  std::vector<std::vector<CellIndex>> parts(static_cast<std::size_t>(std::max<std::int64_t>(chunks, 0)));

#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t chunk = 0; chunk < chunks; ++chunk) {
    std::vector<CellIndex>& out = parts[static_cast<std::size_t>(chunk)];
    const std::int64_t r0 = rows * chunk / chunks, r1 = rows * (chunk + 1) / chunks;
    for (std::int64_t r = r0; r < r1; ++r) {
      const std::size_t begin = row_starts[static_cast<std::size_t>(r)];
      const std::size_t end = row_starts[static_cast<std::size_t>(r) + 1];
      const std::uint64_t row = crossings[begin].row;
      const auto j = static_cast<std::int32_t>(row % static_cast<std::uint64_t>(ny));
      const auto k = static_cast<std::int32_t>(row / static_cast<std::uint64_t>(ny));
      // Sweep from +x to -x so the winding number is a running sum.
      std::size_t next = end;  // crossings [next, end) lie beyond the current centre
      int winding = 0;
      std::vector<CellIndex> row_cells;
      for (std::int64_t i = nx - 1; i >= 0; --i) {
        const double x = static_cast<double>(i) + 0.5;
        while (next > begin && crossings[next - 1].x > x) winding += crossings[--next].sign;
        if (winding != 0) row_cells.push_back({static_cast<std::int32_t>(i), j, k});
      }
      out.insert(out.end(), row_cells.rbegin(), row_cells.rend());
    }
  }

  std::vector<CellIndex> cells;
  for (auto& part : parts) cells.insert(cells.end(), part.begin(), part.end());
  return cells;
}

}  // namespace bw::sample

#include "render/particle_spacing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace bw::render {
namespace {

struct CellKey {
  std::int64_t i, j, k;
  bool operator==(const CellKey& o) const { return i == o.i && j == o.j && k == o.k; }
};
struct CellHash {
  std::size_t operator()(const CellKey& c) const {
    return static_cast<std::size_t>(c.i * 73856093LL ^ c.j * 19349663LL ^ c.k * 83492791LL);
  }
};

// Rings of cells searched around a query before giving up on it: a particle farther
// than this many cells from every other is spray and says nothing about the spacing.
constexpr int kMaxRings = 4;

}  // namespace

double estimate_particle_spacing(const float* x, const float* y, const float* z, std::size_t count,
                                 std::size_t max_queries) {
  if (count < 2 || max_queries == 0) return 0;
  // Particles with a non-finite coordinate are left out.
  const auto finite = [&](std::size_t n) { return std::isfinite(x[n]) && std::isfinite(y[n]) && std::isfinite(z[n]); };
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t n = 0; n < count; ++n) {
    if (!finite(n)) continue;
    const double p[3] = {x[n], y[n], z[n]};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  // Cell edge: the spacing the particles would have if they filled their bounding
  // box (an upper bound for a filled block, larger for a splash), but not thinner
  // than the flattest side allows.
  double volume = 1, extent_max = 0;
  for (int a = 0; a < 3; ++a) extent_max = std::max(extent_max, hi[a] - lo[a]);
  if (!(extent_max > 0)) return 0;
  for (int a = 0; a < 3; ++a) volume *= std::max(hi[a] - lo[a], extent_max * 1e-3);
  const double cell = std::cbrt(volume / static_cast<double>(count));

  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> grid;
  grid.reserve(count);
  auto key_of = [&](std::size_t n) {
    return CellKey{static_cast<std::int64_t>(std::floor((x[n] - lo[0]) / cell)),
                   static_cast<std::int64_t>(std::floor((y[n] - lo[1]) / cell)),
                   static_cast<std::int64_t>(std::floor((z[n] - lo[2]) / cell))};
  };
  for (std::size_t n = 0; n < count; ++n)
    if (finite(n)) grid[key_of(n)].push_back(static_cast<std::uint32_t>(n));

  const std::size_t stride = std::max<std::size_t>(1, count / max_queries);
  std::vector<double> nearest;
  for (std::size_t q = 0; q < count; q += stride) {
    if (!finite(q)) continue;
    const CellKey c = key_of(q);
    double best2 = std::numeric_limits<double>::infinity();
    for (int ring = 1; ring <= kMaxRings; ++ring) {
      for (std::int64_t di = -ring; di <= ring; ++di)
        for (std::int64_t dj = -ring; dj <= ring; ++dj)
          for (std::int64_t dk = -ring; dk <= ring; ++dk) {
            // Only the shell of this ring: the inner cells were searched before.
            if (std::max({std::abs(di), std::abs(dj), std::abs(dk)}) != ring && ring > 1) continue;
            auto it = grid.find({c.i + di, c.j + dj, c.k + dk});
            if (it == grid.end()) continue;
            for (std::uint32_t m : it->second) {
              if (m == q) continue;
              const double dx = x[m] - x[q], dy = y[m] - y[q], dz = z[m] - z[q];
              const double d2 = dx * dx + dy * dy + dz * dz;
              if (d2 > 0) best2 = std::min(best2, d2);
            }
          }
      // Every point within `ring` cells is now known: a neighbour that close is final.
      if (best2 <= (ring * cell) * (ring * cell)) break;
    }
    if (std::isfinite(best2)) nearest.push_back(std::sqrt(best2));
  }
  if (nearest.empty()) return 0;
  const auto mid = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), mid, nearest.end());
  return *mid;
}

}  // namespace bw::render

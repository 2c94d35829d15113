#include "render/particle_classes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace bw::render {

std::vector<int> count_neighbours(const float* x, const float* y, const float* z, std::size_t count,
                                  double radius) {
  std::vector<int> neighbours(count, 0);
  if (count == 0 || !(radius > 0)) return neighbours;
  const auto finite = [&](std::size_t n) { return std::isfinite(x[n]) && std::isfinite(y[n]) && std::isfinite(z[n]); };
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t n = 0; n < count; ++n) {
    if (!finite(n)) continue;
    const double p[3] = {x[n], y[n], z[n]};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  if (lo[0] > hi[0]) return neighbours;
  // Cells of the search radius: a query reads its cell and the 26 around it. The
  // grid is a sorted list of (cell, particle), not an array over the box, which a
  // scattered splash would make huge; sorting pairs is deterministic.
  std::int64_t dims[3];
  for (int a = 0; a < 3; ++a)
    dims[a] = static_cast<std::int64_t>(std::min(std::floor((hi[a] - lo[a]) / radius), 1e6)) + 1;
  auto cell_of = [&](std::size_t n, std::int64_t c[3]) {
    const double p[3] = {x[n], y[n], z[n]};
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>((p[a] - lo[a]) / radius), 0, dims[a] - 1);
  };
  auto key = [&](const std::int64_t c[3]) { return (c[2] * dims[1] + c[1]) * dims[0] + c[0]; };
  std::vector<std::pair<std::int64_t, std::uint32_t>> order;
  order.reserve(count);
  for (std::size_t n = 0; n < count; ++n) {
    if (!finite(n)) continue;
    std::int64_t c[3];
    cell_of(n, c);
    order.emplace_back(key(c), static_cast<std::uint32_t>(n));
  }
  std::sort(order.begin(), order.end());
  const double r2 = radius * radius;
  for (std::size_t n = 0; n < count; ++n) {
    if (!finite(n)) continue;
    std::int64_t c[3];
    cell_of(n, c);
    int found = 0;
    for (std::int64_t dk = -1; dk <= 1; ++dk)
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const std::int64_t k = c[2] + dk, j = c[1] + dj;
        if (k < 0 || k >= dims[2] || j < 0 || j >= dims[1]) continue;
        // The three cells along x are consecutive keys: one search for the row.
        const std::int64_t i0 = std::max<std::int64_t>(c[0] - 1, 0), i1 = std::min(c[0] + 1, dims[0] - 1);
        const std::int64_t row[3] = {i0, j, k};
        auto first = std::lower_bound(order.begin(), order.end(), std::make_pair(key(row), std::uint32_t{0}));
        const std::int64_t end_key = key(row) + (i1 - i0);
        for (auto it = first; it != order.end() && it->first <= end_key; ++it) {
          const std::uint32_t m = it->second;
          if (m == n) continue;
          const double dx = x[m] - x[n], dy = y[m] - y[n], dz = z[m] - z[n];
          found += dx * dx + dy * dy + dz * dz <= r2;
        }
      }
    neighbours[n] = found;
  }
  return neighbours;
}

std::vector<ParticleClass> classify_particles(const float* x, const float* y, const float* z, std::size_t count,
                                              const ClassifyParams& params) {
  const std::vector<int> neighbours = count_neighbours(x, y, z, count, params.radius_spacings * params.spacing);
  std::vector<ParticleClass> classes(count, ParticleClass::kWater);
  for (std::size_t n = 0; n < count; ++n) {
    const int k = neighbours[n];
    if (k <= params.spray_neighbours)
      classes[n] = ParticleClass::kSpray;
    else if (k <= params.foam_neighbours)
      classes[n] = ParticleClass::kFoam;
  }
  return classes;
}

}  // namespace bw::render

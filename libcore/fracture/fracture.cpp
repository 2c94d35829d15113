#include "fracture/fracture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <unordered_map>

#include "common/union_find.h"

namespace bw::fracture {
namespace {

// A dense table of the cells' box up to this many entries (4 bytes each); sorted keys
// beyond.
constexpr std::int64_t kDenseCells = std::int64_t{1} << 24;

constexpr std::array<std::array<int, 3>, 6> kFaces = {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};

// Voxel index of a cell, or -1.
class CellMap {
 public:
  explicit CellMap(const std::vector<CellIndex>& cells) {
    if (cells.empty()) return;
    lo_ = hi_ = cells[0];
    for (const CellIndex& c : cells)
      for (int a = 0; a < 3; ++a) lo_[a] = std::min(lo_[a], c[a]), hi_[a] = std::max(hi_[a], c[a]);
    for (int a = 0; a < 3; ++a) dims_[a] = std::int64_t(hi_[a]) - lo_[a] + 1;
    const std::int64_t volume = dims_[0] * dims_[1] * dims_[2];
    dense_ = volume <= kDenseCells;
    if (dense_) {
      table_.assign(static_cast<std::size_t>(volume), -1);
      for (std::size_t i = 0; i < cells.size(); ++i) table_[static_cast<std::size_t>(key(cells[i]))] = static_cast<std::int32_t>(i);
    } else {
      sorted_.reserve(cells.size());
      for (std::size_t i = 0; i < cells.size(); ++i) sorted_.emplace_back(key(cells[i]), static_cast<std::int32_t>(i));
      std::sort(sorted_.begin(), sorted_.end());
    }
  }
  std::int32_t find(const CellIndex& c) const {
    if (table_.empty() && sorted_.empty()) return -1;
    for (int a = 0; a < 3; ++a)
      if (c[a] < lo_[a] || c[a] > hi_[a]) return -1;
    const std::int64_t k = key(c);
    if (dense_) return table_[static_cast<std::size_t>(k)];
    const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<std::int64_t, std::int32_t>(k, -1));
    return it != sorted_.end() && it->first == k ? it->second : -1;
  }

 private:
  std::int64_t key(const CellIndex& c) const {
    return ((std::int64_t(c[2]) - lo_[2]) * dims_[1] + (std::int64_t(c[1]) - lo_[1])) * dims_[0] + (std::int64_t(c[0]) - lo_[0]);
  }
  CellIndex lo_{0, 0, 0}, hi_{0, 0, 0};
  std::array<std::int64_t, 3> dims_{0, 0, 0};
  bool dense_ = true;
  std::vector<std::int32_t> table_;
  std::vector<std::pair<std::int64_t, std::int32_t>> sorted_;
};

CellIndex offset(const CellIndex& c, int dx, int dy, int dz) { return {c[0] + dx, c[1] + dy, c[2] + dz}; }

// Runs body(begin, end) over [0, n) in contiguous slices, one per thread.
template <class F>
void parallel_slices(std::size_t n, int threads, F body) {
  const int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t count = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(t), n / 4096 + 1));
  if (count == 1) {
    body(std::size_t{0}, n);
    return;
  }
  std::vector<std::thread> pool;
  const std::size_t per = (n + count - 1) / count;
  for (std::size_t k = 1; k < count; ++k)
    pool.emplace_back([&, k] { body(std::min(n, k * per), std::min(n, (k + 1) * per)); });
  body(std::size_t{0}, std::min(n, per));
  for (auto& th : pool) th.join();
}

}  // namespace

std::vector<std::int32_t> nearest_seeds(const std::vector<Vec3d>& centers, const std::vector<Vec3d>& seeds,
                                        int threads) {
  std::vector<std::int32_t> label(centers.size(), -1);
  if (seeds.empty()) return label;
  // Seeds as floats in one array would lose ties; double keeps them exact.
  parallel_slices(centers.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Vec3d& c = centers[v];
      double best = std::numeric_limits<double>::infinity();
      std::int32_t which = -1;
      for (std::size_t s = 0; s < seeds.size(); ++s) {
        const double d = (seeds[s] - c).squaredNorm();
        if (d < best) best = d, which = static_cast<std::int32_t>(s);
      }
      label[v] = which;
    }
  });
  return label;
}

std::vector<std::int32_t> particle_voxels(const Piece& piece) {
  const CellMap map(piece.cells);
  std::vector<std::int32_t> out(piece.particles.size(), -1);
  for (std::size_t p = 0; p < piece.particles.size(); ++p) {
    const CellIndex& c = piece.particle_cells[p];
    std::int32_t v = map.find(c);
    if (v < 0) {
      double best = std::numeric_limits<double>::infinity();
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const std::int32_t u = map.find(offset(c, dx, dy, dz));
            if (u < 0) continue;
            const double d = (piece.centers[static_cast<std::size_t>(u)] - piece.particles[p]).squaredNorm();
            if (d < best || (d == best && u < v)) best = d, v = u;
          }
    }
    if (v < 0) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t u = 0; u < piece.centers.size(); ++u) {
        const double d = (piece.centers[u] - piece.particles[p]).squaredNorm();
        if (d < best) best = d, v = static_cast<std::int32_t>(u);
      }
    }
    out[p] = v;
  }
  return out;
}

std::vector<Fragment> split(const Piece& piece, const std::vector<Vec3d>& seeds, double voxel_size, double density,
                            int threads) {
  const std::size_t n = piece.size();
  const std::vector<std::int32_t> label = nearest_seeds(piece.centers, seeds, threads);
  const CellMap map(piece.cells);
  // Face-connected components of each cell.
  UnionFind sets(n);
  for (std::size_t v = 0; v < n; ++v) {
    for (int a = 0; a < 3; ++a) {
      CellIndex c = piece.cells[v];
      ++c[a];
      const std::int32_t u = map.find(c);
      if (u >= 0 && label[static_cast<std::size_t>(u)] == label[v]) sets.unite(static_cast<std::int32_t>(v), u);
    }
  }
  // Components by seed, then by decreasing size (ties: the smaller first voxel).
  std::vector<std::int32_t> root(n), size(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    root[v] = sets.find(static_cast<std::int32_t>(v));
    ++size[static_cast<std::size_t>(root[v])];
  }
  std::vector<std::int32_t> roots;
  for (std::size_t v = 0; v < n; ++v)
    if (root[v] == static_cast<std::int32_t>(v)) roots.push_back(static_cast<std::int32_t>(v));
  std::sort(roots.begin(), roots.end(), [&](std::int32_t a, std::int32_t b) {
    const auto sa = static_cast<std::size_t>(a), sb = static_cast<std::size_t>(b);
    if (label[sa] != label[sb]) return label[sa] < label[sb];
    if (size[sa] != size[sb]) return size[sa] > size[sb];
    return a < b;
  });
  std::vector<std::int32_t> fragment_of_root(n, -1);
  std::vector<Fragment> out(roots.size());
  for (std::size_t f = 0; f < roots.size(); ++f) {
    const auto r = static_cast<std::size_t>(roots[f]);
    fragment_of_root[r] = static_cast<std::int32_t>(f);
    out[f].seed = label[r];
    out[f].component = (f > 0 && out[f - 1].seed == label[r]) ? out[f - 1].component + 1 : 0;
  }
  std::vector<std::int32_t> frag(n);
  for (std::size_t v = 0; v < n; ++v) {
    frag[v] = fragment_of_root[static_cast<std::size_t>(root[v])];
    Piece& p = out[static_cast<std::size_t>(frag[v])].piece;
    p.cells.push_back(piece.cells[v]);
    p.centers.push_back(piece.centers[v]);
    if (!piece.anchor.empty()) p.anchor.push_back(piece.anchor[v]);
  }
  // The parent's particles go with the voxel they belong to.
  const std::vector<std::int32_t> pv = particle_voxels(piece);
  std::vector<std::uint8_t> has_particle(n, 0);
  for (std::size_t i = 0; i < piece.particles.size(); ++i) {
    if (pv[i] < 0) continue;
    const auto v = static_cast<std::size_t>(pv[i]);
    Piece& p = out[static_cast<std::size_t>(frag[v])].piece;
    p.particles.push_back(piece.particles[i]);
    p.normals.push_back(piece.normals[i]);
    p.flatness.push_back(piece.flatness.empty() ? 1.0 : piece.flatness[i]);
    p.particle_cells.push_back(piece.particle_cells[i]);
    if (piece.particle_cells[i] == piece.cells[v]) has_particle[v] = 1;
  }
  // New particles on the crack faces: at the centres of voxels facing another fragment.
  for (std::size_t v = 0; v < n; ++v) {
    Vec3d sum = Vec3d::Zero();
    int faces = 0;
    for (const auto& d : kFaces) {
      const std::int32_t u = map.find(offset(piece.cells[v], d[0], d[1], d[2]));
      if (u < 0 || frag[static_cast<std::size_t>(u)] == frag[v]) continue;
      sum += (piece.centers[static_cast<std::size_t>(u)] - piece.centers[v]).normalized();
      ++faces;
    }
    if (faces == 0 || has_particle[v]) continue;
    Piece& p = out[static_cast<std::size_t>(frag[v])].piece;
    const double length = sum.norm();
    p.particles.push_back(piece.centers[v]);
    p.normals.push_back(length > 1e-12 ? Vec3d(sum / length) : Vec3d::Zero());
    p.flatness.push_back(length / faces);
    p.particle_cells.push_back(piece.cells[v]);
  }
  parallel_slices(out.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      Fragment& fr = out[f];
      fr.mass = rigid::voxel_mass_properties(fr.piece.centers, voxel_size, density);
      fr.anchored = std::any_of(fr.piece.anchor.begin(), fr.piece.anchor.end(), [](std::uint8_t a) { return a != 0; });
    }
  });
  return out;
}

std::vector<double> bond_counts(const std::vector<Vec3d>& particles, double spacing, double h) {
  std::unordered_map<std::int64_t, std::vector<std::int32_t>> cells;
  auto coords = [&](const Vec3d& p) { return Eigen::Array3i((p.array() / h).floor().cast<int>()); };
  auto key = [](const Eigen::Array3i& c) {
    constexpr std::int64_t kOffset = 1 << 20;
    return ((c.z() + kOffset) << 42) | ((c.y() + kOffset) << 21) | (c.x() + kOffset);
  };
  for (std::size_t i = 0; i < particles.size(); ++i) cells[key(coords(particles[i]))].push_back(static_cast<std::int32_t>(i));
  const double norm = 15.0 / (std::numbers::pi * std::pow(h, 6)) * spacing * spacing * spacing;
  std::vector<double> out(particles.size(), 0.0);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Eigen::Array3i c = coords(particles[i]);
    double sum = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(key(c + Eigen::Array3i(dx, dy, dz)));
          if (it == cells.end()) continue;
          for (const std::int32_t j : it->second) {
            const double r = (particles[static_cast<std::size_t>(j)] - particles[i]).norm();
            if (r < h) sum += (h - r) * (h - r) * (h - r);
          }
        }
    out[i] = norm * sum;
  }
  return out;
}

std::vector<std::int32_t> select_seeds(std::vector<Candidate> candidates, const std::vector<Vec3d>& particles,
                                       double min_distance, std::size_t max_count) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.strength != b.strength ? a.strength > b.strength : a.particle < b.particle;
  });
  std::vector<std::int32_t> out;
  const double d2 = min_distance * min_distance;
  for (const Candidate& c : candidates) {
    if (out.size() >= max_count) break;
    const Vec3d& x = particles[static_cast<std::size_t>(c.particle)];
    bool far = true;
    for (const std::int32_t t : out)
      if ((particles[static_cast<std::size_t>(t)] - x).squaredNorm() < d2) {
        far = false;
        break;
      }
    if (far) out.push_back(c.particle);
  }
  return out;
}

}  // namespace bw::fracture

#include "fracture/fracture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <unordered_map>

#include "common/error.h"
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

// Runs body(begin, end) over [0, n) in contiguous slices, one per thread (at most
// one per `grain` items).
template <class F>
void parallel_slices(std::size_t n, int threads, F body, std::size_t grain = 4096) {
  const int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t count = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(t), n / grain + 1));
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
  const std::size_t n = centers.size();
  std::vector<std::int32_t> label(n, -1);
  if (seeds.empty() || n == 0) return label;
  // Centres in blocks of about kBlock of them; per block, only the seeds that can be
  // nearest to a point of its box (nearer to the box than the least farthest-corner
  // distance of any seed) are compared. Candidates keep their index order, so a tie
  // goes to the lower seed index as in a plain search.
  constexpr double kBlock = 512;
  Vec3d lo = centers[0], hi = centers[0];
  for (const Vec3d& c : centers) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const Vec3d extent = (hi - lo).cwiseMax(Vec3d::Constant(1e-9));
  const double edge = std::max(std::cbrt(extent.prod() * kBlock / static_cast<double>(n)), extent.maxCoeff() / 256);
  std::vector<std::pair<std::int64_t, std::int32_t>> keyed(n);
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Array3i c = ((centers[v] - lo).array() / edge).floor().cast<int>();
    keyed[v] = {(std::int64_t(c.z()) * 1024 + c.y()) * 1024 + c.x(), static_cast<std::int32_t>(v)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> group{0};
  for (std::size_t i = 1; i < n; ++i)
    if (keyed[i].first != keyed[i - 1].first) group.push_back(i);
  group.push_back(n);
  parallel_slices(group.size() - 1, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> candidates;
    for (std::size_t g = begin; g < end; ++g) {
      Vec3d bmin = centers[static_cast<std::size_t>(keyed[group[g]].second)], bmax = bmin;
      for (std::size_t i = group[g]; i < group[g + 1]; ++i) {
        const Vec3d& c = centers[static_cast<std::size_t>(keyed[i].second)];
        bmin = bmin.cwiseMin(c), bmax = bmax.cwiseMax(c);
      }
      double bound = std::numeric_limits<double>::infinity();
      for (const Vec3d& q : seeds) {
        const Vec3d far = (q - bmin).cwiseAbs().cwiseMax((q - bmax).cwiseAbs());
        bound = std::min(bound, far.squaredNorm());
      }
      candidates.clear();
      for (std::size_t k = 0; k < seeds.size(); ++k) {
        const Vec3d near = (bmin - seeds[k]).cwiseMax(Vec3d::Zero()) + (seeds[k] - bmax).cwiseMax(Vec3d::Zero());
        if (near.squaredNorm() <= bound) candidates.push_back(static_cast<std::uint32_t>(k));
      }
      for (std::size_t i = group[g]; i < group[g + 1]; ++i) {
        const auto v = static_cast<std::size_t>(keyed[i].second);
        const Vec3d& c = centers[v];
        double best = std::numeric_limits<double>::infinity();
        std::int32_t which = -1;
        for (const std::uint32_t k : candidates) {
          const double d = (seeds[k] - c).squaredNorm();
          if (d < best) best = d, which = static_cast<std::int32_t>(k);
        }
        label[v] = which;
      }
    }
  }, 8);
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

std::int32_t nearest_seed(const Vec3d& point, const std::vector<Vec3d>& seeds) {
  double best = std::numeric_limits<double>::infinity();
  std::int32_t which = -1;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const double d = (seeds[k] - point).squaredNorm();
    if (d < best) best = d, which = static_cast<std::int32_t>(k);
  }
  return which;
}

std::vector<Fragment> split(const Piece& piece, const std::vector<Vec3d>& seeds, double voxel_size, double density,
                            int threads) {
  const FaceNeighbours neighbours = face_neighbours(piece);
  return fragments(piece, neighbours, components(neighbours, nearest_seeds(piece.centers, seeds, threads)), voxel_size,
                   density, threads);
}

FaceNeighbours face_neighbours(const Piece& piece) {
  const std::size_t n = piece.size();
  FaceNeighbours out(n);
  if (n == 0) return out;
  CellIndex lo = piece.cells[0], hi = lo;
  for (const CellIndex& c : piece.cells)
    for (std::size_t a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  std::array<std::int64_t, 3> dims{};
  for (std::size_t a = 0; a < 3; ++a) dims[a] = std::int64_t(hi[a]) - lo[a] + 1;
  if (dims[0] * dims[1] * dims[2] > kDenseCells) {
    const CellMap map(piece.cells);
    for (std::size_t v = 0; v < n; ++v)
      for (std::size_t f = 0; f < kFaces.size(); ++f)
        out[v][f] = map.find(offset(piece.cells[v], kFaces[f][0], kFaces[f][1], kFaces[f][2]));
    return out;
  }
  // A dense table of the cells' box, looked up by index steps.
  std::vector<std::int32_t> table(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]), -1);
  std::vector<std::int64_t> key(n);
  for (std::size_t v = 0; v < n; ++v) {
    const CellIndex& c = piece.cells[v];
    key[v] = ((std::int64_t(c[2]) - lo[2]) * dims[1] + (std::int64_t(c[1]) - lo[1])) * dims[0] + (std::int64_t(c[0]) - lo[0]);
    table[static_cast<std::size_t>(key[v])] = static_cast<std::int32_t>(v);
  }
  const std::array<std::int64_t, 3> stride{1, dims[0], dims[0] * dims[1]};
  for (std::size_t v = 0; v < n; ++v) {
    const CellIndex& c = piece.cells[v];
    for (std::size_t a = 0; a < 3; ++a) {
      out[v][2 * a] = c[a] < hi[a] ? table[static_cast<std::size_t>(key[v] + stride[a])] : -1;
      out[v][2 * a + 1] = c[a] > lo[a] ? table[static_cast<std::size_t>(key[v] - stride[a])] : -1;
    }
  }
  return out;
}

Components components(const FaceNeighbours& neighbours, const std::vector<std::int32_t>& label) {
  const std::size_t n = neighbours.size();
  if (label.size() != n) fail_run("fracture: {} labels for {} voxels", label.size(), n);
  // Face-connected components of each cell (the +x, +y, +z neighbours suffice).
  UnionFind sets(n);
  for (std::size_t v = 0; v < n; ++v)
    for (const std::size_t f : {0u, 2u, 4u}) {
      const std::int32_t u = neighbours[v][f];
      if (u >= 0 && label[static_cast<std::size_t>(u)] == label[v]) sets.unite(static_cast<std::int32_t>(v), u);
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
  Components out;
  std::vector<std::int32_t> fragment_of_root(n, -1);
  for (std::size_t f = 0; f < roots.size(); ++f) {
    const auto r = static_cast<std::size_t>(roots[f]);
    fragment_of_root[r] = static_cast<std::int32_t>(f);
    out.seed.push_back(label[r]);
    out.component.push_back(f > 0 && out.seed[f - 1] == label[r] ? out.component[f - 1] + 1 : 0);
    out.size.push_back(size[r]);
  }
  out.fragment.resize(n);
  for (std::size_t v = 0; v < n; ++v) out.fragment[v] = fragment_of_root[static_cast<std::size_t>(root[v])];
  return out;
}

std::vector<Fragment> fragments(const Piece& piece, const FaceNeighbours& neighbours, const Components& parts,
                                double voxel_size, double density, int threads) {
  const std::size_t n = piece.size();
  const std::vector<std::int32_t>& frag = parts.fragment;
  const std::size_t nf = parts.size.size();
  // Voxels and particles listed by fragment (counting sorts, in index order), so that
  // each fragment is then built on its own, fragments shared out over the threads.
  auto by_fragment = [&](const std::vector<std::int32_t>& of) {
    std::vector<std::uint32_t> start(nf + 1, 0), list;
    for (const std::int32_t f : of)
      if (f >= 0) ++start[static_cast<std::size_t>(f) + 1];
    for (std::size_t f = 0; f < nf; ++f) start[f + 1] += start[f];
    list.resize(start[nf]);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < of.size(); ++i)
      if (of[i] >= 0) list[fill[static_cast<std::size_t>(of[i])]++] = static_cast<std::uint32_t>(i);
    return std::pair{start, list};
  };
  const auto [vstart, voxels] = by_fragment(frag);
  // The parent's particles go with the voxel they belong to.
  const std::vector<std::int32_t> pv = particle_voxels(piece);
  std::vector<std::int32_t> particle_fragment(piece.particles.size(), -1);
  std::vector<std::uint8_t> has_particle(n, 0);
  for (std::size_t i = 0; i < piece.particles.size(); ++i) {
    if (pv[i] < 0) continue;
    const auto v = static_cast<std::size_t>(pv[i]);
    particle_fragment[i] = frag[v];
    if (piece.particle_cells[i] == piece.cells[v]) has_particle[v] = 1;
  }
  const auto [pstart, particles] = by_fragment(particle_fragment);
  std::vector<Fragment> out(nf);
  const int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(t), n / 4096 + 1);
  auto work = [&](std::size_t first) {
    for (std::size_t f = first; f < nf; f += count) {
      Fragment& fr = out[f];
      Piece& p = fr.piece;
      fr.seed = parts.seed[f];
      fr.component = parts.component[f];
      const std::size_t v0 = vstart[f], v1 = vstart[f + 1];
      p.cells.reserve(v1 - v0);
      p.centers.reserve(v1 - v0);
      for (std::size_t k = v0; k < v1; ++k) {
        const std::size_t v = voxels[k];
        p.cells.push_back(piece.cells[v]);
        p.centers.push_back(piece.centers[v]);
        if (!piece.anchor.empty()) p.anchor.push_back(piece.anchor[v]);
      }
      for (std::size_t k = pstart[f]; k < pstart[f + 1]; ++k) {
        const std::size_t i = particles[k];
        fr.source.push_back(static_cast<std::int32_t>(i));
        p.particles.push_back(piece.particles[i]);
        p.normals.push_back(piece.normals[i]);
        p.flatness.push_back(piece.flatness.empty() ? 1.0 : piece.flatness[i]);
        p.particle_cells.push_back(piece.particle_cells[i]);
      }
      // New particles on the crack faces: at the centres of voxels facing another
      // fragment.
      for (std::size_t k = v0; k < v1; ++k) {
        const std::size_t v = voxels[k];
        if (has_particle[v]) continue;
        Vec3d sum = Vec3d::Zero();
        int faces = 0;
        for (std::size_t d = 0; d < kFaces.size(); ++d) {
          const std::int32_t u = neighbours[v][d];
          if (u < 0 || frag[static_cast<std::size_t>(u)] == frag[v]) continue;
          sum += (piece.centers[static_cast<std::size_t>(u)] - piece.centers[v]).normalized();
          ++faces;
        }
        if (faces == 0) continue;
        fr.source.push_back(-1);
        const double length = sum.norm();
        p.particles.push_back(piece.centers[v]);
        p.normals.push_back(length > 1e-12 ? Vec3d(sum / length) : Vec3d::Zero());
        p.flatness.push_back(length / faces);
        p.particle_cells.push_back(piece.cells[v]);
      }
      fr.mass = rigid::voxel_mass_properties(p.centers, voxel_size, density);
      fr.anchored = std::any_of(p.anchor.begin(), p.anchor.end(), [](std::uint8_t a) { return a != 0; });
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < count; ++k) pool.emplace_back(work, k);
  work(0);
  for (auto& th : pool) th.join();
  return out;
}

std::vector<double> bond_counts(const std::vector<Vec3d>& particles, double spacing, double h) {
  // Particles sorted into cells of edge h; each cell looks its 27 neighbours up once.
  const std::size_t n = particles.size();
  std::vector<double> out(n, 0.0);
  if (n == 0) return out;
  auto key = [](const Eigen::Array3i& c) {
    constexpr std::int64_t kOffset = 1 << 20;
    return ((std::int64_t(c.z()) + kOffset) << 42) | ((std::int64_t(c.y()) + kOffset) << 21) | (std::int64_t(c.x()) + kOffset);
  };
  std::vector<std::pair<std::int64_t, std::int32_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i)
    keyed[i] = {key((particles[i].array() / h).floor().cast<int>()), static_cast<std::int32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::int64_t> cell_keys;
  std::vector<std::size_t> cell_first;
  for (std::size_t i = 0; i < n; ++i)
    if (i == 0 || keyed[i].first != keyed[i - 1].first) cell_keys.push_back(keyed[i].first), cell_first.push_back(i);
  cell_first.push_back(n);
  const double norm = 15.0 / (std::numbers::pi * std::pow(h, 6)) * spacing * spacing * spacing;
  const double h2 = h * h;
  for (std::size_t c = 0; c < cell_keys.size(); ++c) {
    const std::int32_t i0 = keyed[cell_first[c]].second;
    const Eigen::Array3i cc = (particles[static_cast<std::size_t>(i0)].array() / h).floor().cast<int>();
    std::array<std::pair<std::size_t, std::size_t>, 27> ranges{};
    int nr = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::int64_t k = key(cc + Eigen::Array3i(dx, dy, dz));
          const auto it = std::lower_bound(cell_keys.begin(), cell_keys.end(), k);
          if (it == cell_keys.end() || *it != k) continue;
          const auto m = static_cast<std::size_t>(it - cell_keys.begin());
          ranges[static_cast<std::size_t>(nr++)] = {cell_first[m], cell_first[m + 1]};
        }
    for (std::size_t a = cell_first[c]; a < cell_first[c + 1]; ++a) {
      const std::size_t i = static_cast<std::size_t>(keyed[a].second);
      const Vec3d& x = particles[i];
      double sum = 0;
      for (int r = 0; r < nr; ++r)
        for (std::size_t b = ranges[static_cast<std::size_t>(r)].first; b < ranges[static_cast<std::size_t>(r)].second; ++b) {
          const double r2 = (particles[static_cast<std::size_t>(keyed[b].second)] - x).squaredNorm();
          if (r2 < h2) {
            const double q = h - std::sqrt(r2);
            sum += q * q * q;
          }
        }
      out[i] = norm * sum;
    }
  }
  return out;
}

std::vector<std::vector<double>> fragment_bond_counts(const std::vector<Fragment>& fragments, double spacing, double h,
                                                      int threads) {
  std::vector<std::vector<double>> out(fragments.size());
  std::size_t total = 0;
  bool cells = true;
  for (const Fragment& f : fragments) {
    total += f.piece.particles.size();
    cells = cells && f.piece.particle_cells.size() == f.piece.particles.size();
  }
  const int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(t), total / 4096 + 1);
  auto in_threads = [&](auto&& work) {  // fragments interleaved, so that each thread gets large and small ones
    std::vector<std::thread> pool;
    for (std::size_t k = 1; k < count; ++k) pool.emplace_back(work, k);
    work(0);
    for (auto& th : pool) th.join();
  };
  if (!cells) {
    in_threads([&](std::size_t first) {
      for (std::size_t f = first; f < fragments.size(); f += count)
        out[f] = bond_counts(fragments[f].piece.particles, spacing, h);
    });
    return out;
  }
  // Particles sit one per cell at the centres of their cells of the root solid's grid
  // (bw-sample's, and the crack faces' at their voxels' centres; no two fragments
  // share a cell), so a particle's bonds are found at fixed cell offsets, those
  // within h of its own cell's centre, in one table of every fragment's cells.
  std::vector<CellIndex> all;
  std::vector<std::pair<std::int32_t, std::int32_t>> owner;  // (fragment, particle) per cell of `all`
  all.reserve(total);
  owner.reserve(total);
  for (std::size_t f = 0; f < fragments.size(); ++f)
    for (std::size_t i = 0; i < fragments[f].piece.particle_cells.size(); ++i) {
      all.push_back(fragments[f].piece.particle_cells[i]);
      owner.emplace_back(static_cast<std::int32_t>(f), static_cast<std::int32_t>(i));
    }
  const CellMap map(all);
  const int reach = static_cast<int>(std::ceil(h / spacing));
  std::vector<std::array<int, 3>> offsets;
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        if (std::sqrt(double(dx * dx + dy * dy + dz * dz)) * spacing < h * (1 + 1e-9)) offsets.push_back({dx, dy, dz});
  const double norm = 15.0 / (std::numbers::pi * std::pow(h, 6)) * spacing * spacing * spacing;
  const double h2 = h * h;
  in_threads([&](std::size_t first) {
    for (std::size_t f = first; f < fragments.size(); f += count) {
      const Piece& p = fragments[f].piece;
      std::vector<double>& b = out[f];
      b.assign(p.particles.size(), 0.0);
      for (std::size_t i = 0; i < p.particles.size(); ++i) {
        double sum = 0;
        for (const auto& o : offsets) {
          const std::int32_t k = map.find(offset(p.particle_cells[i], o[0], o[1], o[2]));
          if (k < 0 || owner[static_cast<std::size_t>(k)].first != static_cast<std::int32_t>(f)) continue;
          const auto j = static_cast<std::size_t>(owner[static_cast<std::size_t>(k)].second);
          const double r2 = (p.particles[j] - p.particles[i]).squaredNorm();
          if (r2 < h2) {
            const double q = h - std::sqrt(r2);
            sum += q * q * q;
          }
        }
        b[i] = norm * sum;
      }
    }
  });
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

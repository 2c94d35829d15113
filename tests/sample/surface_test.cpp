// Surface sampling covers the mesh and stays on it (method.md 2.1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unordered_map>

#include "mesh/closest_point.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "test_support.h"

namespace {

using bw::Vec3d;

// Nearest-point queries over a point set with a hash grid of cell `cell`.
class PointGrid {
 public:
  PointGrid(const std::vector<Vec3d>& points, double cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[key(points[i])].push_back(i);
  }
  double nearest(const Vec3d& p) const {
    double best = INFINITY;
    const auto k = index(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(pack(k[0] + dx, k[1] + dy, k[2] + dz));
          if (it == cells_.end()) continue;
          for (auto i : it->second) best = std::min(best, (points_[i] - p).norm());
        }
    return best;
  }

 private:
  std::array<std::int64_t, 3> index(const Vec3d& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)), static_cast<std::int64_t>(std::floor(p.y() / cell_)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }
  static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x + (1 << 20)) << 42) | (static_cast<std::uint64_t>(y + (1 << 20)) << 21) |
           static_cast<std::uint64_t>(z + (1 << 20));
  }
  std::uint64_t key(const Vec3d& p) const {
    const auto k = index(p);
    return pack(k[0], k[1], k[2]);
  }
  const std::vector<Vec3d>& points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

void check_coverage(const bw::TriMesh& mesh, double spacing, const std::string& name) {
  bw::sample::SampleOptions options;
  options.spacing = spacing;
  options.source = name;
  const bw::SampledSolid solid = bw::sample::sample_mesh(mesh, options);
  const std::vector<Vec3d> particles = solid.surface_positions();
  ASSERT_FALSE(particles.empty());

  // 1. Every point of every triangle lies within one spacing of a particle.
  PointGrid grid(particles, spacing);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_gap = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    std::vector<Vec3d> probes = {a, b, c, (a + b + c) / 3, (a + b) / 2, (b + c) / 2, (c + a) / 2};
    for (int k = 0; k < 8; ++k) {
      double s = u(rng), r = u(rng);
      if (s + r > 1) s = 1 - s, r = 1 - r;
      probes.push_back(a + s * (b - a) + r * (c - a));
    }
    for (const Vec3d& p : probes) worst_gap = std::max(worst_gap, grid.nearest(p));
  }
  bw::test::figure(name + ": farthest mesh point from a particle / spacing", worst_gap / spacing);
  EXPECT_LE(worst_gap, spacing);

  // 2. No particle is farther than a spacing from the mesh (brute force).
  double worst_off = 0;
  for (const Vec3d& p : particles) {
    double d = INFINITY;
    for (const auto& t : mesh.triangles) {
      d = std::min(d, bw::mesh::point_triangle_distance(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
    }
    worst_off = std::max(worst_off, d);
  }
  bw::test::figure(name + ": farthest particle from the mesh / spacing", worst_off / spacing);
  // A cell that a triangle touches has its centre within half a cell diagonal.
  EXPECT_LE(worst_off, 0.5 * std::sqrt(3.0) * spacing * (1 + 1e-9));
}

TEST(SurfaceSampling, CoversASphere) { check_coverage(bw::mesh::icosphere({0.3, -0.2, 0.1}, 0.5, 3), 0.04, "sphere"); }

TEST(SurfaceSampling, CoversATorus) { check_coverage(bw::mesh::torus({0, 0, 0}, 0.6, 0.2, 48, 24), 0.035, "torus"); }

TEST(SurfaceSampling, CoversLargeTrianglesAndSlivers) {
  // Few large triangles span many cells; a cylinder's caps are fans of slivers.
  check_coverage(bw::mesh::cylinder({0, 0, 0}, 0.5, 0.8, 64), 0.03, "cylinder");
  check_coverage(bw::mesh::box({0, 0, 0}, {1.3, 0.7, 0.9}), 0.05, "box");
}

TEST(SurfaceSampling, IsDeterministicAndSorted) {
  const auto mesh = bw::mesh::icosphere({0, 0, 0}, 1, 3);
  const auto grid = bw::sample::grid_for(mesh.bounds(), 0.05);
  const auto first = bw::sample::surface_cells(mesh, grid);
  const auto second = bw::sample::surface_cells(mesh, grid);
  EXPECT_EQ(first, second);
  for (std::size_t i = 1; i < first.size(); ++i) {
    const auto& a = first[i - 1];
    const auto& b = first[i];
    EXPECT_TRUE(std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]));
  }
}

}  // namespace

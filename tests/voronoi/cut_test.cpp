// Cutting solids into Voronoi cells: exact partitions, cells that fall apart,
// degenerate seed sets, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.h"
#include "mesh/check.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "voronoi/check.h"
#include "voronoi/seeds.h"
#include "voronoi/voronoi.h"

namespace {

using bw::Fragment;
using bw::TriMesh;
using bw::Vec3d;
namespace bv = bw::voronoi;

std::vector<std::int32_t> all(std::size_t n) {
  std::vector<std::int32_t> v(n);
  std::iota(v.begin(), v.end(), 0);
  return v;
}

bv::CutResult cut_all(const bv::Solid& solid, const std::vector<Vec3d>& seeds, int threads = 0) {
  bv::CutOptions options;
  options.threads = threads;
  return bv::cut(solid, seeds, all(seeds.size()), options);
}

double volume_sum(const std::vector<Fragment>& fragments) {
  double sum = 0;
  for (const Fragment& f : fragments) sum += bw::mesh::mass_properties(f.mesh).volume;
  return sum;
}

void expect_closed(const std::vector<Fragment>& fragments) {
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const auto report = bw::mesh::check_mesh(fragments[i].mesh);
    EXPECT_TRUE(report.bounds_volume()) << "fragment " << i << ": " << report.summary();
    EXPECT_EQ(bv::count_nonmanifold_vertices(fragments[i].mesh), 0u) << "fragment " << i;
    EXPECT_GT(fragments[i].volume, 0) << "fragment " << i;
    EXPECT_EQ(fragments[i].volume, bw::mesh::mass_properties(fragments[i].mesh).volume) << "fragment " << i;
  }
}

TEST(VoronoiCut, CubeWithEightSeedsGivesEightClosedOctantsWhoseVolumesAddUpExactly) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}));
  std::vector<Vec3d> seeds;
  for (double z : {0.25, 0.75})
    for (double y : {0.25, 0.75})
      for (double x : {0.25, 0.75}) seeds.emplace_back(x, y, z);
  const bv::CutResult r = cut_all(solid, seeds);
  EXPECT_TRUE(r.failures.empty());
  ASSERT_EQ(r.fragments.size(), 8u);
  expect_closed(r.fragments);
  double sum = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    const Fragment& f = r.fragments[i];
    EXPECT_EQ(f.seed, static_cast<std::int32_t>(i));
    EXPECT_EQ(f.component, 0);
    EXPECT_EQ(f.body, -1);
    // The octant of its seed, exactly: every cut point is a multiple of 0.5.
    const bw::Aabb box = f.mesh.bounds();
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(box.min[k], seeds[i][k] - 0.25);
      EXPECT_EQ(box.max[k], seeds[i][k] + 0.25);
    }
    // No rounded point: every intersection lands on a multiple of 1/4.
    for (const Vec3d& v : f.mesh.vertices)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(v[k] * 4, std::round(v[k] * 4)) << "fragment " << i;
    // The volume sums tetrahedra of sixths: rounding there is all that is left.
    EXPECT_NEAR(f.volume, 0.125, 1e-16);
    sum += f.volume;
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

// A U-shaped prism: the cell of the seed in the left arm reaches over the notch
// into the right arm, and the solid cuts that cell in two.
TEST(VoronoiCut, CellThatTheSolidCutsInTwoGivesTwoFragments) {
  const std::vector<Eigen::Vector2d> u = {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const bv::Solid solid(bw::mesh::extrude(u, 0, 1));
  ASSERT_DOUBLE_EQ(solid.volume(), 7.0);
  const std::vector<Vec3d> seeds = {{0.5, 2.5, 0.5}, {1.5, 0.5, 0.5}};
  const bv::CutResult r = cut_all(solid, seeds);
  EXPECT_TRUE(r.failures.empty());
  ASSERT_EQ(r.fragments.size(), 3u);
  expect_closed(r.fragments);
  EXPECT_EQ(r.fragments[0].seed, 0);
  EXPECT_EQ(r.fragments[1].seed, 0);
  EXPECT_EQ(r.fragments[2].seed, 1);
  // Components from 0 in decreasing volume: the left arm, then the tip of the right
  // arm above the bisector y = (x + 2) / 2, whose area over x in [2, 3] is 0.75.
  EXPECT_EQ(r.fragments[0].component, 0);
  EXPECT_EQ(r.fragments[1].component, 1);
  EXPECT_NEAR(r.fragments[1].volume, 0.75, 1e-12);
  EXPECT_GE(r.fragments[1].mesh.bounds().min.x(), 2.0);
  EXPECT_LE(r.fragments[0].mesh.bounds().max.x(), 1.0);
  EXPECT_NEAR(volume_sum(r.fragments), 7.0, 1e-12);
}

TEST(VoronoiCut, TorusRandomSeedsFillTheSolid) {
  const bv::Solid solid(bw::mesh::torus({0, 0, 0}, 1.0, 0.35, 48, 16));
  const std::vector<Vec3d> seeds = bv::random_seeds(solid, 12, 5);
  const bv::CutResult r = cut_all(solid, seeds);
  EXPECT_TRUE(r.failures.empty());
  EXPECT_GE(r.fragments.size(), 12u);
  expect_closed(r.fragments);
  EXPECT_LT(std::abs(volume_sum(r.fragments) - solid.volume()) / solid.volume(), 1e-12);
  const auto checks = bv::check_fragments(solid, seeds, all(seeds.size()), r.fragments, r.failures, 0);
  for (const auto& c : checks) EXPECT_EQ(c.status, bv::CheckStatus::pass) << c.name << ": " << c.detail;
}

TEST(VoronoiCut, OneSeedGivesTheWholeSolid) {
  const TriMesh ball = bw::mesh::icosphere({1, 2, 3}, 0.5, 2);
  const bv::Solid solid(ball);
  const bv::CutResult r = cut_all(solid, {{1.1, 2, 3}});
  ASSERT_EQ(r.fragments.size(), 1u);
  expect_closed(r.fragments);
  EXPECT_NEAR(r.fragments[0].volume, solid.volume(), 1e-15);
  EXPECT_EQ(r.fragments[0].mesh.triangles.size(), ball.triangles.size());
}

// Seeds on a line, in a plane, and on a lattice (every Voronoi vertex shared by many
// cells): the Delaunay triangulation is degenerate, the cells are still exact.
TEST(VoronoiCut, DegenerateSeedSetsStillPartitionTheSolid) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}, 2));
  const std::vector<std::vector<Vec3d>> sets = {
      {{0.5, 0.5, 0.5}, {0.25, 0.5, 0.5}},
      {{0.2, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.8, 0.5, 0.5}},
      {{0.25, 0.25, 0.5}, {0.75, 0.25, 0.5}, {0.25, 0.75, 0.5}, {0.75, 0.75, 0.5}, {0.5, 0.5, 0.5}},
      [] {
        std::vector<Vec3d> lattice;
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) lattice.emplace_back((i + 0.5) / 3, (j + 0.5) / 3, (k + 0.5) / 3);
        return lattice;
      }()};
  for (std::size_t s = 0; s < sets.size(); ++s) {
    SCOPED_TRACE("seed set " + std::to_string(s));
    const bv::CutResult r = cut_all(solid, sets[s]);
    EXPECT_TRUE(r.failures.empty()) << r.failures.front().message;
    EXPECT_EQ(r.fragments.size(), sets[s].size());
    expect_closed(r.fragments);
    EXPECT_NEAR(volume_sum(r.fragments), 1.0, 1e-14);
  }
  // Lattice cells are the 27 small cubes.
  const bv::CutResult lattice = cut_all(solid, sets.back());
  for (const Fragment& f : lattice.fragments) EXPECT_NEAR(f.volume, 1.0 / 27, 1e-15);
}

// An L-shaped prism and two seeds mirrored in the plane x + y = 2, which holds the
// concave edge of the L: the cell of the first seed would be two prisms touching
// along that edge. The seeds are nudged and the cut goes through.
TEST(VoronoiCut, CellBoundaryThroughAConcaveEdgeIsNudged) {
  const std::vector<Eigen::Vector2d> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const bv::Solid solid(bw::mesh::extrude(l, 0, 1));
  EXPECT_EQ(solid.concave_edges(), 1u);
  const std::vector<Vec3d> seeds = {{1.8, 0.5, 0.5}, {1.5, 0.2, 0.5}};
  const bv::CutResult r = cut_all(solid, seeds);
  EXPECT_TRUE(r.failures.empty()) << r.failures.front().message;
  EXPECT_GT(r.seed_nudge, 0);
  EXPECT_LT(r.seed_nudge, 1e-11);
  expect_closed(r.fragments);
  EXPECT_GE(r.fragments.size(), 2u);
  EXPECT_NEAR(volume_sum(r.fragments), 3.0, 1e-12);
  const auto checks = bv::check_fragments(solid, seeds, all(seeds.size()), r.fragments, r.failures, 0);
  for (const auto& c : checks) EXPECT_EQ(c.status, bv::CheckStatus::pass) << c.name << ": " << c.detail;
  // Seeds in general position are not moved.
  EXPECT_EQ(cut_all(solid, {{1.8, 0.5, 0.5}, {1.5, 0.21, 0.5}}).seed_nudge, 0.0);
  EXPECT_EQ(bv::Solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}, 2)).concave_edges(), 0u);
}

TEST(VoronoiCut, SameFragmentsOnOneThreadAndOnSeveral) {
  const bv::Solid solid(bw::mesh::icosphere({0, 0, 0}, 1, 3));
  const std::vector<Vec3d> seeds = bv::random_seeds(solid, 30, 11);
  const bv::CutResult one = cut_all(solid, seeds, 1);
  const bv::CutResult four = cut_all(solid, seeds, 4);
  ASSERT_EQ(one.fragments.size(), four.fragments.size());
  for (std::size_t i = 0; i < one.fragments.size(); ++i) {
    EXPECT_EQ(one.fragments[i].seed, four.fragments[i].seed);
    EXPECT_EQ(one.fragments[i].mesh.vertices, four.fragments[i].mesh.vertices) << "fragment " << i;
    EXPECT_EQ(one.fragments[i].mesh.triangles, four.fragments[i].mesh.triangles) << "fragment " << i;
  }
}

TEST(VoronoiCut, RepeatedSeedIsRejectedByTheCut) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}));
  const std::vector<Vec3d> seeds = {{0.5, 0.5, 0.5}, {0.2, 0.2, 0.2}, {0.5, 0.5, 0.5}};
  EXPECT_THROW(cut_all(solid, seeds), bw::InputError);
}

// The cells themselves: convex, closed, and together exactly the box they are
// bounded by.
TEST(VoronoiCell, CellsOfRandomSeedsTileTheirBox) {
  const bv::Solid unit(bw::mesh::box({0, 0, 0}, {1, 1, 1}));
  const std::vector<Vec3d> seeds = bv::random_seeds(unit, 40, 3);
  bw::Aabb box;
  box.add({-0.5, -0.5, -0.5});
  box.add({1.5, 1.5, 1.5});
  double sum = 0;
  for (std::int32_t i = 0; i < 40; ++i) {
    const TriMesh cell = bv::voronoi_cell(seeds, all(seeds.size()), i, box);
    ASSERT_TRUE(bw::mesh::check_mesh(cell).bounds_volume());
    const double v = bw::mesh::mass_properties(cell).volume;
    EXPECT_GT(v, 0);
    sum += v;
    // Every corner of the cell is at least as near to its seed as to any other.
    for (const Vec3d& p : cell.vertices)
      for (const Vec3d& q : seeds) EXPECT_LE((p - seeds[static_cast<std::size_t>(i)]).norm(), (p - q).norm() + 1e-12);
  }
  EXPECT_NEAR(sum, 8.0, 1e-12);
}

}  // namespace

namespace {

// Cut without the input check: two overlapping cubes in one mesh. CGAL throws for
// the cells whose faces meet the crossing faces; each is reported with its seed, and
// the cells far from the overlap are cut.
TEST(VoronoiCut, CellsThatFailAreReportedAndTheOthersAreCut) {
  TriMesh mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  bw::mesh::append(mesh, bw::mesh::box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}));
  const bv::Solid solid(mesh);
  // A lattice of spacing 0.3 over both cubes: cell faces at 0.3, 0.6, 0.9 and 1.2
  // cross the lines where the cubes' faces cross.
  std::vector<Vec3d> seeds;
  auto in = [](const Vec3d& p, double lo, double hi) { return (p.array() > lo).all() && (p.array() < hi).all(); };
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const Vec3d p(0.15 + 0.3 * i, 0.15 + 0.3 * j, 0.15 + 0.3 * k);
        if (in(p, 0, 1) || in(p, 0.5, 1.5)) seeds.push_back(p);
      }
  const bv::CutResult r = cut_all(solid, seeds);
  ASSERT_FALSE(r.failures.empty());
  for (const bv::CellFailure& f : r.failures) {
    EXPECT_GE(f.seed, 0);
    EXPECT_FALSE(f.message.empty());
  }
  EXPECT_NE(r.failures.front().message.find("intersecting the cell with the solid"), std::string::npos)
      << r.failures.front().message;
  // The corner cell is far from the overlap: cut, closed, the cube [0, 0.3]^3.
  ASSERT_FALSE(r.fragments.empty());
  EXPECT_EQ(r.fragments.front().seed, 0);
  expect_closed({r.fragments.front()});
  EXPECT_NEAR(r.fragments.front().volume, 0.027, 1e-15);
  // A cell either failed or gave fragments, never both.
  for (const bv::CellFailure& f : r.failures)
    for (const Fragment& fragment : r.fragments) EXPECT_NE(fragment.seed, f.seed);
}

}  // namespace

// The prefracture check: input validation, seeds that cannot take part, and fragment
// checks that catch what is wrong with fragments.
#include <gtest/gtest.h>

#include <fstream>
#include <numeric>

#include "common/error.h"
#include "io/fragments_file.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "test_support.h"
#include "voronoi/check.h"
#include "voronoi/seeds.h"

namespace {

using bw::Fragment;
using bw::TriMesh;
using bw::Vec3d;
namespace bv = bw::voronoi;

const bv::CheckItem& find(const std::vector<bv::CheckItem>& checks, const std::string& name) {
  for (const auto& c : checks)
    if (c.name == name) return c;
  throw std::runtime_error("no check " + name);
}

std::vector<std::int32_t> all(std::size_t n) {
  std::vector<std::int32_t> v(n);
  std::iota(v.begin(), v.end(), 0);
  return v;
}

bv::CheckResult check(TriMesh mesh, std::vector<Vec3d> seeds) {
  bv::SeedChoice choice;
  choice.points = std::move(seeds);
  bv::CheckOptions options;
  options.source = "test.obj";
  return bv::prefracture_check(std::move(mesh), choice, options);
}

std::vector<Vec3d> octant_seeds() {
  std::vector<Vec3d> seeds;
  for (double z : {0.25, 0.75})
    for (double y : {0.25, 0.75})
      for (double x : {0.25, 0.75}) seeds.emplace_back(x, y, z);
  return seeds;
}

TEST(PrefractureCheck, CubePassesEveryCheck) {
  const bv::CheckResult r = check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), octant_seeds());
  EXPECT_TRUE(r.passed()) << r.text();
  ASSERT_EQ(r.checks.size(), 8u);
  for (const auto& c : r.checks) EXPECT_EQ(c.status, bv::CheckStatus::pass) << c.name << ": " << c.detail;
  EXPECT_EQ(r.fragments.size(), 8u);
  EXPECT_LT(r.figures.relative_error, 1e-15);
  EXPECT_TRUE(r.warnings.empty());
  const std::string json = r.report().to_json();
  EXPECT_NE(json.find("\"result\": \"pass\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"volumes_add_up\""), std::string::npos) << json;
}

TEST(PrefractureCheck, SeedsOutsideTheMeshAreIgnoredWithAWarning) {
  std::vector<Vec3d> seeds = octant_seeds();
  seeds.insert(seeds.begin() + 2, Vec3d(2, 0.5, 0.5));   // outside
  seeds.push_back(Vec3d(1, 0.5, 0.5));                    // on a face
  seeds.push_back(Vec3d(0.25, 0.25, 0.25));               // repeats seed 0
  std::vector<std::string> warned;
  bv::SeedChoice choice;
  choice.points = seeds;
  bv::CheckOptions options;
  options.source = "cube.obj";
  options.warn = [&](const std::string& w) { warned.push_back(w); };
  const bv::CheckResult r = bv::prefracture_check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), choice, options);
  EXPECT_TRUE(r.passed()) << r.text();
  ASSERT_EQ(warned.size(), 3u);
  EXPECT_EQ(warned, r.warnings);
  EXPECT_EQ(warned[0], "seed 2 at (2, 0.5, 0.5) lies outside the mesh: ignored");
  EXPECT_EQ(warned[1], "seed 9 at (1, 0.5, 0.5) lies on the surface of the mesh: ignored");
  EXPECT_EQ(warned[2], "seed 10 at (0.25, 0.25, 0.25) repeats seed 0: ignored");
  EXPECT_EQ(r.sorting.active.size(), 8u);
  EXPECT_EQ(r.fragments.size(), 8u);
  for (const Fragment& f : r.fragments) EXPECT_TRUE(f.seed != 2 && f.seed < 9) << f.seed;
  // The fragments file keeps every seed given, so that indices match the input.
  EXPECT_EQ(r.fragment_set().seeds.size(), seeds.size());
}

// More seeds than a scene lets a solid become bodies are refused before any work,
// given or drawn, in one line naming the input.
TEST(PrefractureCheck, MoreSeedsThanTheLimitAreBadInput) {
  const std::string expected = "test.obj: 1000001 seeds; a check cuts at most 1000000";
  try {
    check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), std::vector<Vec3d>(bv::kMaxSeeds + 1, Vec3d(0.5, 0.5, 0.5)));
    FAIL();
  } catch (const bw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
  bv::SeedChoice drawn;
  drawn.random = bv::kMaxSeeds + 1;
  bv::CheckOptions options;
  options.source = "test.obj";
  try {
    bv::prefracture_check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), drawn, options);
    FAIL();
  } catch (const bw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

TEST(PrefractureCheck, NoSeedInsideIsBadInput) {
  EXPECT_THROW(check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), {{2, 2, 2}, {-1, 0, 0}}), bw::InputError);
  EXPECT_THROW(check(bw::mesh::box({0, 0, 0}, {1, 1, 1}), {}), bw::InputError);
}

TEST(PrefractureCheck, MeshesThatCannotBeCutAreBadInput) {
  TriMesh open = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  try {
    check(open, octant_seeds());
    FAIL() << "an open mesh was accepted";
  } catch (const bw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.obj: the mesh does not bound a volume: 3 boundary edges"),
              std::string::npos)
        << e.what();
  }
  // Two cubes that touch at one corner: closed, but not manifold at that vertex.
  TriMesh corner = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  TriMesh other = bw::mesh::box({1, 1, 1}, {2, 2, 2});
  const auto offset = static_cast<std::int32_t>(corner.vertices.size());
  for (const Vec3d& v : other.vertices)
    if (v != Vec3d(1, 1, 1)) corner.vertices.push_back(v);
  for (bw::Triangle t : other.triangles) {
    for (auto& i : t) {
      const Vec3d p = other.vertices[static_cast<std::size_t>(i)];
      if (p == Vec3d(1, 1, 1)) {
        i = static_cast<std::int32_t>(std::find(corner.vertices.begin(), corner.vertices.end(), p) - corner.vertices.begin());
      } else {
        i = offset + static_cast<std::int32_t>(std::count_if(other.vertices.begin(), other.vertices.begin() + i,
                                                             [](const Vec3d& q) { return q != Vec3d(1, 1, 1); }));
      }
    }
    corner.triangles.push_back(t);
  }
  ASSERT_TRUE(bw::mesh::check_mesh(corner).closed());
  EXPECT_EQ(bv::count_nonmanifold_vertices(corner), 1u);
  EXPECT_THROW(check(corner, {{0.5, 0.5, 0.5}}), bw::InputError);
  // Inconsistent orientation.
  TriMesh twisted = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  std::swap(twisted.triangles[0][1], twisted.triangles[0][2]);
  EXPECT_THROW(check(twisted, {{0.5, 0.5, 0.5}}), bw::InputError);
}

TEST(PrefractureCheck, InsideOutMeshIsTurnedRight) {
  TriMesh cube = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  bw::mesh::flip_faces(cube);
  const bv::CheckResult r = check(cube, octant_seeds());
  EXPECT_TRUE(r.passed()) << r.text();
  EXPECT_TRUE(r.input.flipped);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("faced inwards"), std::string::npos);
  for (const Fragment& f : r.fragments) EXPECT_GT(f.volume, 0);
}

// Two overlapping boxes in one mesh: closed and manifold, but its faces cross. The
// check fails and the fragments are not cut.
TEST(PrefractureCheck, SelfIntersectingInputFailsTheCheck) {
  TriMesh mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  bw::mesh::append(mesh, bw::mesh::box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}));
  const bv::CheckResult r = check(mesh, {{0.25, 0.25, 0.25}});
  EXPECT_FALSE(r.passed());
  const auto& crossing = find(r.checks, "input_self_intersections");
  EXPECT_EQ(crossing.status, bv::CheckStatus::fail);
  EXPECT_GT(r.self_intersection_pairs, 0u);
  EXPECT_NE(crossing.detail.find("pairs of faces intersect"), std::string::npos) << crossing.detail;
  EXPECT_EQ(find(r.checks, "volumes_add_up").status, bv::CheckStatus::skipped);
  EXPECT_TRUE(r.fragments.empty());
  EXPECT_NE(r.text().find("FAIL  input is free of self-intersections"), std::string::npos) << r.text();
}

TEST(PrefractureCheck, RandomSeedsAreReproducible) {
  bv::SeedChoice choice;
  choice.random = 12;
  choice.random_seed = 99;
  bv::CheckOptions options;
  const TriMesh ball = bw::mesh::icosphere({0, 0, 0}, 1, 2);
  const bv::CheckResult a = bv::prefracture_check(ball, choice, options);
  const bv::CheckResult b = bv::prefracture_check(ball, choice, options);
  EXPECT_TRUE(a.passed()) << a.text();
  EXPECT_EQ(a.seeds, b.seeds);
  ASSERT_EQ(a.fragments.size(), b.fragments.size());
  for (std::size_t i = 0; i < a.fragments.size(); ++i) EXPECT_EQ(a.fragments[i].mesh.vertices, b.fragments[i].mesh.vertices);
}

// Each fragment check on fragments spoiled in the way it looks for.
class FragmentChecks : public ::testing::Test {
 protected:
  bv::Solid solid{bw::mesh::box({0, 0, 0}, {1, 1, 1})};
  std::vector<Vec3d> seeds = octant_seeds();
  std::vector<std::int32_t> active = all(8);
  std::vector<Fragment> fragments = bv::cut(solid, seeds, active).fragments;

  std::vector<bv::CheckItem> run(const std::vector<bv::CellFailure>& failures = {}) {
    return bv::check_fragments(solid, seeds, active, fragments, failures, 0);
  }
};

TEST_F(FragmentChecks, PassOnTheCut) {
  for (const auto& c : run()) EXPECT_EQ(c.status, bv::CheckStatus::pass) << c.name << ": " << c.detail;
}

TEST_F(FragmentChecks, MissingFragmentBreaksTheSum) {
  fragments.erase(fragments.begin() + 3);
  const auto checks = run();
  EXPECT_EQ(find(checks, "cells_cut").status, bv::CheckStatus::fail);
  EXPECT_NE(find(checks, "cells_cut").detail.find("seed 3"), std::string::npos) << find(checks, "cells_cut").detail;
  EXPECT_EQ(find(checks, "volumes_add_up").status, bv::CheckStatus::fail);
  EXPECT_NE(find(checks, "volumes_add_up").detail.find("relative error 0.125"), std::string::npos)
      << find(checks, "volumes_add_up").detail;
  EXPECT_EQ(find(checks, "fragments_closed").status, bv::CheckStatus::pass);
}

TEST_F(FragmentChecks, ReportedFailureFailsCellsCut) {
  const auto checks = run({{5, "CGAL threw"}});
  EXPECT_EQ(find(checks, "cells_cut").status, bv::CheckStatus::fail);
  EXPECT_NE(find(checks, "cells_cut").detail.find("seed 5: CGAL threw"), std::string::npos);
}

TEST_F(FragmentChecks, HoleInAFragment) {
  fragments[6].mesh.triangles.pop_back();
  const auto checks = run();
  const auto& c = find(checks, "fragments_closed");
  EXPECT_EQ(c.status, bv::CheckStatus::fail);
  EXPECT_NE(c.detail.find("fragment 6 (seed 6, component 0)"), std::string::npos) << c.detail;
}

TEST_F(FragmentChecks, InsideOutFragment) {
  bw::mesh::flip_faces(fragments[1].mesh);
  EXPECT_EQ(find(run(), "fragments_closed").status, bv::CheckStatus::fail);
}

TEST_F(FragmentChecks, FragmentReachingOutside) {
  // The octant at (1, 1, 1) moved by 0.01 along x: out of the cube, still in its cell.
  for (Vec3d& v : fragments[7].mesh.vertices) v += Vec3d(0.01, 0, 0);
  const auto checks = run();
  const auto& c = find(checks, "inside_mesh");
  EXPECT_EQ(c.status, bv::CheckStatus::fail);
  EXPECT_NE(c.detail.find("1 fragments reach outside; fragment 7 (seed 7) by 0.01 at (1.01, "), std::string::npos)
      << c.detail;
  EXPECT_EQ(find(checks, "within_cells").status, bv::CheckStatus::pass);
}

TEST_F(FragmentChecks, FragmentInAnotherCell) {
  // The octant at (0, 1, 1) moved by 0.01 along x: into the cell of seed 7.
  for (Vec3d& v : fragments[6].mesh.vertices) v += Vec3d(0.01, 0, 0);
  auto checks = run();
  EXPECT_EQ(find(checks, "inside_mesh").status, bv::CheckStatus::pass);
  EXPECT_EQ(find(checks, "within_cells").status, bv::CheckStatus::fail);
  EXPECT_NE(find(checks, "within_cells").detail.find("fragment 6 (seed 6) reaches 0.01 into the cell of seed 7"),
            std::string::npos)
      << find(checks, "within_cells").detail;
  // Two fragments that trade seeds both leave their cells.
  for (Vec3d& v : fragments[6].mesh.vertices) v -= Vec3d(0.01, 0, 0);
  std::swap(fragments[0].seed, fragments[1].seed);
  checks = run();
  EXPECT_NE(find(checks, "within_cells").detail.find("2 fragments leave their cells"), std::string::npos)
      << find(checks, "within_cells").detail;
}

TEST_F(FragmentChecks, TinyVolumeErrorStaysWithinTheTolerance) {
  // Scaling one fragment by 1 + 1e-8 about its centroid changes the sum by ~4e-9.
  const Vec3d c = bw::mesh::mass_properties(fragments[0].mesh).centroid;
  for (Vec3d& v : fragments[0].mesh.vertices) v = c + (1 + 1e-8) * (v - c);
  EXPECT_EQ(find(run(), "volumes_add_up").status, bv::CheckStatus::pass);
  for (Vec3d& v : fragments[0].mesh.vertices) v = c + (1 + 1e-5) * (v - c);
  EXPECT_EQ(find(run(), "volumes_add_up").status, bv::CheckStatus::fail);
}

TEST(Seeds, TextFilesWithCommentsCommasAndBlankLines) {
  bw::test::TempDir dir;
  std::ofstream(dir.file("seeds.txt")) << "# seeds\n0.1 0.2 0.3\n\n  +4,5,6e-1  # comma separated\n\t-1\t2 3\r\n";
  const auto seeds = bv::read_seeds(dir.file("seeds.txt"));
  ASSERT_EQ(seeds.size(), 3u);
  EXPECT_EQ(seeds[0], Vec3d(0.1, 0.2, 0.3));
  EXPECT_EQ(seeds[1], Vec3d(4, 5, 0.6));
  EXPECT_EQ(seeds[2], Vec3d(-1, 2, 3));
  // Written and read back bit for bit.
  const std::vector<Vec3d> odd = {{0.1 + 0.2, 1.0 / 3, -2e-300}};
  bv::write_seeds_text(odd, dir.file("back.txt"));
  EXPECT_EQ(bv::read_seeds(dir.file("back.txt")), odd);
}

TEST(Seeds, MalformedTextNamesFileAndLine) {
  bw::test::TempDir dir;
  auto message = [&](const std::string& text) {
    std::ofstream(dir.file("bad.txt")) << text;
    try {
      bv::read_seeds(dir.file("bad.txt"));
    } catch (const bw::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("1 2 3\n1 2\n").find("bad.txt:2: 2 numbers where a seed needs three"), std::string::npos);
  EXPECT_NE(message("1 2 x\n").find("bad.txt:1: 'x' is not a number"), std::string::npos);
  EXPECT_NE(message("1 2 nan\n").find("bad.txt:1: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(message("# nothing\n").find("no seeds"), std::string::npos);
  EXPECT_NE(message("1 2 3 4\n").find("4 numbers"), std::string::npos);
  EXPECT_THROW(bv::read_seeds(dir.file("missing.txt")), bw::InputError);
}

TEST(Seeds, FromAFragmentsFile) {
  bw::test::TempDir dir;
  bw::FragmentSet set;
  set.source = "x.obj";
  set.seeds = {{1, 2, 3}, {4, 5, 6}};
  bw::write_fragments(set, dir.file("f.h5"));
  EXPECT_EQ(bv::read_seeds(dir.file("f.h5")), set.seeds);
}

TEST(Seeds, RandomSeedsAreUniformInsideAndPortable) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {2, 1, 1}));
  const auto a = bv::random_seeds(solid, 2000, 42);
  EXPECT_EQ(a, bv::random_seeds(solid, 2000, 42));
  EXPECT_NE(a, bv::random_seeds(solid, 2000, 43));
  Vec3d mean = Vec3d::Zero();
  for (const Vec3d& p : a) {
    EXPECT_EQ(solid.side(p), bv::Side::inside);
    mean += p / 2000.0;
  }
  EXPECT_NEAR(mean.x(), 1.0, 0.05);
  EXPECT_NEAR(mean.y(), 0.5, 0.03);
  // std::mt19937_64 is specified bit for bit, and so is uniform01: the first draw
  // of seed 42 is the same on every platform.
  std::mt19937_64 rng(42);
  const std::uint64_t first = rng();
  EXPECT_EQ(first, 13930160852258120406ull);
  EXPECT_EQ(a[0].x(), 2.0 * static_cast<double>(first >> 11) * 0x1.0p-53);
  // A thin slab turned 45 degrees fills 1e-7 of its bounding box: the draws run out.
  TriMesh slab = bw::mesh::box({0, 0, 0}, {1, 1, 1e-7});
  bw::mesh::transform(slab, Eigen::AngleAxisd(0.7853981633974483, Vec3d::UnitX()).toRotationMatrix(), Vec3d::Zero());
  EXPECT_THROW(bv::random_seeds(bv::Solid(slab), 1, 1), bw::InputError);
}

TEST(Seeds, SortingKeepsOnlySeedsStrictlyInside) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}));
  const std::vector<Vec3d> seeds = {{0.5, 0.5, 0.5}, {1, 1, 1}, {3, 0, 0}, {0.5, 0.5, 0.5}, {-0.0, 0.5, 0.5}};
  const auto s = bv::sort_seeds(solid, seeds);
  EXPECT_EQ(s.active, std::vector<std::int32_t>{0});
  EXPECT_EQ(s.fate[1], bv::SeedFate::on_surface);
  EXPECT_EQ(s.fate[2], bv::SeedFate::outside);
  EXPECT_EQ(s.fate[3], bv::SeedFate::duplicate);
  EXPECT_EQ(s.same_as[3], 0);
  EXPECT_EQ(s.fate[4], bv::SeedFate::on_surface);
}

TEST(Solid, SideDistanceAndSelfIntersections) {
  const bv::Solid solid(bw::mesh::box({0, 0, 0}, {1, 1, 1}, 3));
  EXPECT_EQ(solid.side({0.5, 0.5, 0.5}), bv::Side::inside);
  EXPECT_EQ(solid.side({1.0 / 3, 0, 0.5}), bv::Side::boundary);
  EXPECT_EQ(solid.side({1.5, 0.5, 0.5}), bv::Side::outside);
  EXPECT_DOUBLE_EQ(solid.distance({1.5, 0.5, 0.5}), 0.5);
  EXPECT_DOUBLE_EQ(solid.distance({0.5, 0.5, 0.6}), 0.4);
  std::size_t total = 99;
  EXPECT_TRUE(solid.self_intersections(10, &total).empty());
  EXPECT_EQ(total, 0u);
}

}  // namespace

// The water's level set: where a block of particles' surface lies, with and without
// erosion; the mesh is closed and faces outwards, --up y turns it, bad settings are
// refused.
#include <filesystem>

#include <gtest/gtest.h>

#include "common/error.h"
#include "export/water.h"
#include "io/frame_file.h"
#include "mesh/properties.h"
#include "synthetic.h"
#include "test_support.h"

namespace bw::exporter {
namespace {

constexpr double kSpacing = 0.02;

FrameData block() {
  FrameData f;
  render::test::add_block(f, Vec3d(0, 0, 0), Vec3d(0.4, 0.3, 0.2), kSpacing, 0, 1);
  return f;
}

WaterOptions options(Up up = Up::kZ) {
  WaterOptions o;
  o.spacing = kSpacing;
  o.up = up;
  o.resolve("test");
  return o;
}

TEST(Water, DefaultsFollowTheSpacing) {
  const WaterOptions o = options();
  EXPECT_DOUBLE_EQ(o.radius, kSpacing);
  EXPECT_DOUBLE_EQ(o.voxel, kSpacing / 2);
  WaterOptions bad;
  bad.spacing = kSpacing;
  bad.radius = 0.01;
  bad.voxel = 0.01;
  EXPECT_THROW(bad.resolve("test"), InputError);
  WaterOptions none;
  EXPECT_THROW(none.resolve("test"), InputError);
}

// The block's particles span [0, 0.4] x [0, 0.3] x [0, 0.2] (centres); their volumes
// end half a spacing beyond.
constexpr double kBeyond = 0.87 * kSpacing;  // where the default surface lies

TEST(Water, BlockIsSlightlyFatterThanItsParticles) {
  const FrameData f = block();
  const WaterSurface s = WaterSurface::build(f.x.data(), f.y.data(), f.z.data(), f.fluid_count(), options());
  EXPECT_EQ(s.stats().particles, f.fluid_count());
  const double expected = static_cast<double>(f.fluid_count()) * kSpacing * kSpacing * kSpacing;
  test::figure("block volume / N spacing^3", s.volume() / expected);
  EXPECT_GT(s.volume() / expected, 1.05);
  EXPECT_LT(s.volume() / expected, 1.2);

  const TriMesh mesh = s.mesh();
  ASSERT_FALSE(mesh.triangles.empty());
  const double mesh_volume = mesh::mass_properties(mesh).volume;
  test::figure("mesh volume / level set volume", mesh_volume / s.volume());
  EXPECT_NEAR(mesh_volume / s.volume(), 1.0, 0.02);  // positive: faces point outwards
  const Aabb box = mesh.bounds();
  EXPECT_NEAR(box.max.x(), 0.4 + kBeyond, 0.1 * kSpacing);
  EXPECT_NEAR(box.min.z(), -kBeyond, 0.1 * kSpacing);
}

TEST(Water, ErodingGivesTheVolumeBack) {
  const FrameData f = block();
  WaterOptions o = options();
  o.erode = 0.4 * kSpacing;
  const WaterSurface s = WaterSurface::build(f.x.data(), f.y.data(), f.z.data(), f.fluid_count(), o);
  const double expected = static_cast<double>(f.fluid_count()) * kSpacing * kSpacing * kSpacing;
  test::figure("eroded block volume / N spacing^3", s.volume() / expected);
  EXPECT_NEAR(s.volume() / expected, 1.0, 0.05);
  EXPECT_NEAR(s.mesh().bounds().max.x(), 0.4 + 0.5 * kSpacing, 0.2 * kSpacing);
}

TEST(Water, UpYTurnsTheSurface) {
  const FrameData f = block();
  const TriMesh mesh =
      WaterSurface::build(f.x.data(), f.y.data(), f.z.data(), f.fluid_count(), options(Up::kY)).mesh();
  const Aabb box = mesh.bounds();
  // (x, y, z) -> (x, z, -y): the block's height (0.2) is along y, its depth along -z.
  EXPECT_NEAR(box.max.y(), 0.2 + kBeyond, 0.1 * kSpacing);
  EXPECT_NEAR(box.min.z(), -0.3 - kBeyond, 0.1 * kSpacing);
  EXPECT_NEAR(box.max.z(), kBeyond, 0.1 * kSpacing);
  EXPECT_GT(mesh::mass_properties(mesh).volume, 0);
}

TEST(Water, EmptyFrameWritesAnEmptyGrid) {
  test::TempDir dir;
  const WaterSurface s = WaterSurface::build(nullptr, nullptr, nullptr, 0, options());
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(s.mesh().triangles.empty());
  s.write_vdb(dir.file("empty.vdb"), true);
  EXPECT_TRUE(test::exists(dir.file("empty.vdb")));
  EXPECT_EQ(test::list_folder(dir.path()), "empty.vdb");
}

}  // namespace
}  // namespace bw::exporter

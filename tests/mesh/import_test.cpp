#include <gtest/gtest.h>

#include <fstream>

#include "common/error.h"
#include "mesh/check.h"
#include "mesh/import.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "test_support.h"

namespace {

using bw::mesh::export_mesh;
using bw::mesh::import_mesh;
using bw::test::TempDir;

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

class ImportFormats : public ::testing::TestWithParam<std::string> {};

// Every format round-trips a closed mesh: welding restores the shared vertices of
// formats that store each triangle's corners (STL), volumes agree.
TEST_P(ImportFormats, RoundTripKeepsAClosedMesh) {
  TempDir dir;
  const auto original = bw::mesh::torus({0.1, 0.2, 0.3}, 1.0, 0.4, 24, 12);
  const std::string path = dir.file("torus." + GetParam());
  export_mesh(original, path);
  bw::mesh::ImportStats stats;
  const auto mesh = import_mesh(path, {}, &stats);
  EXPECT_EQ(mesh.triangles.size(), original.triangles.size());
  EXPECT_EQ(mesh.vertices.size(), original.vertices.size());
  const auto report = bw::mesh::check_mesh(mesh);
  EXPECT_TRUE(report.bounds_volume()) << report.summary();
  // Formats holding single precision lose digits beyond 1e-7.
  EXPECT_NEAR(bw::mesh::mass_properties(mesh).volume, bw::mesh::mass_properties(original).volume, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Formats, ImportFormats, ::testing::Values("obj", "ply", "stl", "glb"));

TEST(Import, OffFileAndScale) {
  TempDir dir;
  write_text(dir.file("tet.off"),
             "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const auto mesh = import_mesh(dir.file("tet.off"), {.scale = 2.0});
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(bw::mesh::check_mesh(mesh).bounds_volume());
  EXPECT_NEAR(bw::mesh::mass_properties(mesh).volume, 8.0 / 6.0, 1e-12);
}

TEST(Import, MergesEveryMeshOfTheFile) {
  TempDir dir;
  write_text(dir.file("two.obj"),
             "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
             "o second\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n");
  bw::mesh::ImportStats stats;
  const auto mesh = import_mesh(dir.file("two.obj"), {}, &stats);
  EXPECT_EQ(stats.meshes, 2u);
  EXPECT_EQ(mesh.triangles.size(), 8u);
  EXPECT_EQ(bw::mesh::check_mesh(mesh).components, 2u);
  EXPECT_NEAR(bw::mesh::mass_properties(mesh).volume, 2.0 / 6.0, 1e-12);
}

TEST(Import, WeldToleranceMergesNearlyCoincidentVertices) {
  TempDir dir;
  // A tetrahedron whose faces repeat their corners with 1e-9 noise.
  write_text(dir.file("noisy.obj"),
             "v 0 0 0\nv 0 1 0\nv 1 0 0\n"
             "v 1e-9 0 0\nv 1 0 0\nv 0 0 1\n"
             "v 0 0 0\nv 0 0 1\nv 0 1e-9 1\n"
             "v 1 0 0\nv 0 1 0\nv 0 0 1\n"
             "f 1 2 3\nf 4 5 6\nf 7 8 2\nf 10 11 12\n");
  const auto exact = import_mesh(dir.file("noisy.obj"));
  EXPECT_FALSE(bw::mesh::check_mesh(exact).closed());
  const auto welded = import_mesh(dir.file("noisy.obj"), {.weld_tolerance = 1e-6});
  EXPECT_EQ(welded.vertices.size(), 4u);
  EXPECT_TRUE(bw::mesh::check_mesh(welded).closed());
}

TEST(Import, BadInputNamesTheFile) {
  TempDir dir;
  write_text(dir.file("empty.obj"), "");
  write_text(dir.file("garbage.stl"), "solid x\nthis is not an stl file at all\n");
  write_text(dir.file("nan.obj"), "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  write_text(dir.file("lines.obj"), "v 0 0 0\nv 1 0 0\nl 1 2\n");
  for (const char* name : {"missing.obj", "empty.obj", "garbage.stl", "nan.obj", "lines.obj"}) {
    const std::string path = dir.file(name);
    try {
      import_mesh(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const bw::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

}  // namespace

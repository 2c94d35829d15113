#include <gtest/gtest.h>

#include <limits>

#include "mesh/check.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"

namespace {

using bw::Vec3d;
using bw::mesh::check_mesh;

TEST(MeshCheck, ClosedBoxIsClosedAndOriented) {
  const auto report = check_mesh(bw::mesh::box({0, 0, 0}, {1, 2, 3}, 3));
  EXPECT_TRUE(report.closed());
  EXPECT_TRUE(report.consistently_oriented());
  EXPECT_TRUE(report.bounds_volume());
  EXPECT_EQ(report.components, 1u);
  EXPECT_EQ(report.degenerate_faces, 0u);
  EXPECT_EQ(report.summary(), "closed and consistently oriented");
}

TEST(MeshCheck, MissingFaceGivesBoundaryEdges) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  mesh.triangles.pop_back();
  const auto report = check_mesh(mesh);
  EXPECT_FALSE(report.closed());
  EXPECT_EQ(report.boundary_edges, 3u);
  EXPECT_NE(report.summary().find("3 boundary edges"), std::string::npos);
}

TEST(MeshCheck, FlippedFaceIsInconsistent) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  const auto report = check_mesh(mesh);
  EXPECT_TRUE(report.closed());
  EXPECT_FALSE(report.consistently_oriented());
  EXPECT_EQ(report.misoriented_edges, 3u);
}

TEST(MeshCheck, ThirdFaceOnAnEdgeIsNonManifold) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  const auto t = mesh.triangles[0];
  mesh.vertices.push_back({5, 5, 5});
  mesh.triangles.push_back({t[0], t[1], static_cast<std::int32_t>(mesh.vertices.size() - 1)});
  const auto report = check_mesh(mesh);
  EXPECT_EQ(report.nonmanifold_edges, 1u);
  EXPECT_FALSE(report.closed());
}

TEST(MeshCheck, CountsDegenerateNonFiniteAndBadIndices) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  mesh.vertices.push_back({0.5, 0.5, 0.5});
  mesh.vertices.push_back({0.6, 0.6, 0.6});
  mesh.vertices.push_back({0.7, 0.7, 0.7});  // collinear: zero area
  const auto n = static_cast<std::int32_t>(mesh.vertices.size());
  mesh.triangles.push_back({n - 3, n - 2, n - 1});
  mesh.triangles.push_back({0, 1, 99});
  mesh.vertices.push_back({std::numeric_limits<double>::quiet_NaN(), 0, 0});
  const auto report = check_mesh(mesh);
  EXPECT_EQ(report.degenerate_faces, 1u);
  EXPECT_EQ(report.bad_indices, 1u);
  EXPECT_EQ(report.nonfinite_vertices, 1u);
  EXPECT_FALSE(report.bounds_volume());
}

TEST(MeshCheck, CountsComponents) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  bw::mesh::append(mesh, bw::mesh::icosphere({3, 0, 0}, 1, 1));
  bw::mesh::append(mesh, bw::mesh::torus({0, 5, 0}, 1, 0.3, 12, 8));
  const auto report = check_mesh(mesh);
  EXPECT_EQ(report.components, 3u);
  EXPECT_TRUE(report.bounds_volume());
}

}  // namespace

namespace {

TEST(Shapes, OpenBoxSealedBoxAndHeightfieldBoundTheirVolumes) {
  const auto tank = bw::mesh::open_box({0, 0, 0}, {2, 1, 1}, 0.1);
  const auto report = bw::mesh::check_mesh(tank);
  EXPECT_TRUE(report.bounds_volume()) << report.summary();
  // Outer 2.2 x 1.2 x 1.1 minus the 2 x 1 x 1 cavity.
  EXPECT_NEAR(bw::mesh::mass_properties(tank).volume, 2.2 * 1.2 * 1.1 - 2.0, 1e-12);

  // A sealed tank: two surfaces, the cavity's facing into it.
  const auto sealed = bw::mesh::sealed_box({0, 0, 0}, {2, 1, 1}, 0.1);
  const auto sealed_report = bw::mesh::check_mesh(sealed);
  EXPECT_TRUE(sealed_report.bounds_volume()) << sealed_report.summary();
  EXPECT_EQ(sealed_report.components, 2u);
  EXPECT_NEAR(bw::mesh::mass_properties(sealed).volume, 2.2 * 1.2 * 1.2 - 2.0, 1e-12);

  const auto terrain = bw::mesh::heightfield({0, 0}, {2, 1}, 20, 10, -1,
                                             [](double x, double y) { return 0.5 + 0.25 * x + 0.1 * y * y; });
  EXPECT_TRUE(bw::mesh::check_mesh(terrain).bounds_volume());
  // Integral of (1.5 + x/4 + y^2/10) over [0,2] x [0,1]; the top is bilinear per
  // quad split into triangles, so y^2 is approximated: within 1e-3.
  EXPECT_NEAR(bw::mesh::mass_properties(terrain).volume, 3.0 + 0.5 + 2.0 / 30, 1e-3);
}

}  // namespace

// Volume sampling: the voxel volume converges to the mesh volume, exact inside tests
// on meshes lying on cell planes, and the checks that guard it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "test_support.h"

namespace {

using bw::Vec3d;
constexpr double kPi = std::numbers::pi;

bw::SampledSolid sample_volume(const bw::TriMesh& mesh, double spacing) {
  bw::sample::SampleOptions options;
  options.spacing = spacing;
  options.volume = true;
  options.source = "test mesh";
  return bw::sample::sample_mesh(mesh, options);
}

// Relative error of the voxel volume at 10, 20, 40 and 80 voxels across the
// mesh's largest extent. Returns the errors in that order.
std::vector<double> convergence(const bw::TriMesh& mesh, double exact_volume, const std::string& name) {
  const double extent = mesh.bounds().extent().maxCoeff();
  std::vector<double> errors;
  for (int across : {10, 20, 40, 80}) {
    const auto solid = sample_volume(mesh, extent / across);
    const double error = (solid.voxel_volume() - exact_volume) / exact_volume;
    bw::test::figure(name + " voxel volume error at " + std::to_string(across) + " voxels across", 100 * error, "%");
    errors.push_back(std::fabs(error));
  }
  return errors;
}

void expect_converges(const std::vector<double>& errors) {
  EXPECT_LT(errors[2], 0.03) << "within 3% at 40 voxels across";
  // 10 voxels across is too coarse to rank (errors there depend on luck).
  EXPECT_LT(errors[3], errors[1]) << "finer is better";
  EXPECT_LT(errors[3], 0.015);
}

TEST(VolumeSampling, SphereConverges) {
  const double r = 0.5;
  // Level 6 is fine enough that the mesh's own faceting (< 0.05%) is negligible.
  const auto mesh = bw::mesh::icosphere({0.123, -0.456, 0.789}, r, 6);
  expect_converges(convergence(mesh, bw::mesh::mass_properties(mesh).volume, "sphere"));
  EXPECT_NEAR(bw::mesh::mass_properties(mesh).volume / (4.0 / 3.0 * kPi * r * r * r), 1.0, 1e-3);
}

TEST(VolumeSampling, RotatedCubeConverges) {
  auto mesh = bw::mesh::box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  const bw::Mat3d rot = Eigen::AngleAxisd(0.4, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
  bw::mesh::transform(mesh, rot, Vec3d(0.01, 0.02, 0.03));
  expect_converges(convergence(mesh, 1.0, "rotated cube"));
}

TEST(VolumeSampling, TorusConverges) {
  const double R = 0.6, r = 0.2;
  const auto mesh = bw::mesh::torus({0, 0, 0}, R, r, 256, 128);
  expect_converges(convergence(mesh, bw::mesh::mass_properties(mesh).volume, "torus"));
}

// A cube whose faces lie on cell planes and whose (subdivided) edges and vertices
// project exactly onto the rays through cell centres: an inside test that counts a
// ray through an edge twice, or not at all, gets stripes of wrong voxels.
TEST(VolumeSampling, FacesOnCellPlanesAreExact) {
  const auto cube = bw::mesh::box({0, 0, 0}, {1, 1, 1}, 8);
  const auto solid = sample_volume(cube, 0.125);
  EXPECT_EQ(solid.grid.dims, (bw::CellIndex{8, 8, 8}));
  EXPECT_EQ(solid.voxels.size(), 512u);
  // The surface cells are exactly the outer shell.
  EXPECT_EQ(solid.surface.size(), 512u - 216u);
  for (const auto& c : solid.surface) {
    const bool shell = c[0] == 0 || c[0] == 7 || c[1] == 0 || c[1] == 7 || c[2] == 0 || c[2] == 7;
    EXPECT_TRUE(shell);
  }
}

// The same cube with the grid shifted by half a cell, so that the faces pass
// through the cell centres themselves. The symbolic perturbation makes the inside
// test half-open: every centre of [0, 1)^3 is inside, none else.
TEST(VolumeSampling, FacesThroughCellCentresAreHalfOpen) {
  auto mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1}, 8);
  // A tiny tetrahedron moves the bounding box (and so the grid origin) by -1/16.
  const double s = -1.0 / 16;
  bw::TriMesh tet;
  tet.vertices = {{s, s, s}, {s + 0.01, s, s}, {s, s + 0.01, s}, {s, s, s + 0.01}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  bw::mesh::append(mesh, tet);
  const auto solid = sample_volume(mesh, 0.125);
  EXPECT_EQ(solid.grid.origin, Vec3d(s, s, s));
  std::size_t in_cube = 0;
  for (const auto& c : solid.voxels) {
    const Vec3d p = solid.grid.cell_center(c);
    const bool inside = p.minCoeff() >= 0 && p.maxCoeff() < 1;
    EXPECT_TRUE(inside) << p.transpose();
    in_cube += inside;
  }
  EXPECT_EQ(in_cube, 512u);
}

// Faces meant to lie on cell planes (a tank's inner walls at 0 with the grid origin
// at -0.03) do so whatever the rounding of (0 - -0.03) / spacing, and their boundary
// particles stay inside the walls, never in the cavity the fluid fills.
TEST(SurfaceSampling, FacesOnInnerCellPlanesStayOnTheSolidSide) {
  const auto tank = bw::mesh::open_box({0, 0, 0}, {0.6, 0.15, 0.4}, 0.03);
  // Spacings that divide every dimension (0.6, 0.15, 0.4, 0.03) and one that does not.
  for (double spacing : {0.01, 0.005, 0.0075, 0.015}) {
    const bool aligned = spacing == 0.01 || spacing == 0.005;
    const auto solid = sample_volume(tank, spacing);
    std::size_t in_cavity = 0;
    for (const auto& p : solid.surface_positions()) {
      in_cavity += p.x() > 0 && p.x() < 0.6 && p.y() > 0 && p.y() < 0.15 && p.z() > 0;
    }
    EXPECT_EQ(in_cavity, 0u) << "spacing " << spacing;
    // Whole cells: the voxels fill the walls exactly.
    if (aligned) {
      EXPECT_NEAR(solid.voxel_volume(), bw::mesh::mass_properties(tank).volume, 1e-9) << spacing;
    }
  }
}

// Where a tank's floor meets its walls the faces on cell planes only graze the cells
// behind the edge, but those cells are in the solid within h of the fluid in the
// corner: each concave edge and corner of the cavity has its row of particles, half
// a cell behind both faces. A tank's rim (a convex edge) and a sheet's rim (one
// plane) stay as they were.
TEST(SurfaceSampling, ConcaveEdgesOnCellPlanesHaveTheirRow) {
  const double s = 0.01;
  // A pillar beside the tank takes the grid above its rim, where the cells over the
  // rim's corners are touched by two walls' faces and must stay empty.
  auto tank = bw::mesh::open_box({0, 0, 0}, {0.1, 0.06, 0.08}, 0.03);
  bw::mesh::append(tank, bw::mesh::box({0.2, 0, -0.03}, {0.25, 0.05, 0.2}));
  const auto solid = sample_volume(tank, s);
  auto near = [&](double a, double b) { return std::abs(a - b) < 1e-9; };
  std::size_t floor_edges = 0, wall_edges = 0, corners = 0, above_rim = 0;
  for (const auto& p : solid.surface_positions()) {
    const bool x_side = near(p.x(), -0.5 * s) || near(p.x(), 0.1 + 0.5 * s);
    const bool y_side = near(p.y(), -0.5 * s) || near(p.y(), 0.06 + 0.5 * s);
    const bool bottom = near(p.z(), -0.5 * s);
    corners += x_side && y_side && bottom;
    floor_edges += bottom && (x_side != y_side) && p.x() > -s && p.x() < 0.1 + s && p.y() > -s && p.y() < 0.06 + s;
    wall_edges += x_side && y_side && !bottom && p.z() > 0;
    above_rim += p.x() < 0.15 && p.z() > 0.08;
  }
  EXPECT_EQ(corners, 4u);
  EXPECT_EQ(floor_edges, 2u * 10u + 2u * 6u) << "the floor's four edges, one particle per cell along them";
  EXPECT_EQ(wall_edges, 4u * 8u) << "the four vertical edges up to the rim";
  EXPECT_EQ(above_rim, 0u);
  // Every such particle is a voxel's centre: in the solid, not in the cavity.
  std::size_t in_cavity = 0;
  for (const auto& p : solid.surface_positions())
    in_cavity += p.x() > 0 && p.x() < 0.1 && p.y() > 0 && p.y() < 0.06 && p.z() > 0;
  EXPECT_EQ(in_cavity, 0u);

  // A square sheet on a cell plane: its own cells and no row beyond its rim.
  bw::TriMesh sheet;
  sheet.vertices = {{0, 0, 0.05}, {0.1, 0, 0.05}, {0.1, 0.1, 0.05}, {0, 0.1, 0.05}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  bw::sample::SampleOptions options;
  options.spacing = s;
  options.source = "sheet";
  EXPECT_EQ(bw::sample::sample_mesh(sheet, options).surface.size(), 100u);
}

// A mesh read from a file comes with float vertices (assimp's): the SPHERIC box's
// face at x = 0.8245 m is then 0.82450002, 1.3e-6 of a 0.02 m cell beyond the plane
// 8 cells from its other face. Its particles still lie half a cell inside every face,
// none in the water in front of it, and the grid has the box's 8 x 20 x 8 cells.
TEST(SurfaceSampling, FacesOfAMeshInSinglePrecisionStayOnTheSolidSide) {
  const Vec3d lo(0.6645, 0.297, 0), hi(0.8245, 0.697, 0.16);
  auto box = bw::mesh::box(lo, hi);
  for (auto& v : box.vertices) v = v.cast<float>().cast<double>();
  const auto solid = sample_volume(box, 0.02);
  EXPECT_EQ(solid.grid.dims, (bw::CellIndex{8, 20, 8}));
  const Vec3d flo = lo.cast<float>().cast<double>(), fhi = hi.cast<float>().cast<double>();
  for (const auto& p : solid.surface_positions()) {
    for (int k = 0; k < 3; ++k) {
      const double inside = std::min(p[k] - flo[k], fhi[k] - p[k]);
      EXPECT_GT(inside, 0.009) << "axis " << k << ": particle at " << p.transpose();
    }
  }
  EXPECT_EQ(solid.voxels.size(), 8u * 20u * 8u);
}

TEST(VolumeSampling, InsideOutMeshGivesTheSameVoxelsAndIsStoredFlipped) {
  auto mesh = bw::mesh::torus({0, 0, 0}, 0.6, 0.2, 64, 32);
  const auto right = sample_volume(mesh, 0.03);
  bw::mesh::flip_faces(mesh);
  bw::sample::SampleOptions options;
  options.spacing = 0.03;
  options.volume = true;
  bw::sample::SampleReport report;
  const auto flipped = bw::sample::sample_mesh(mesh, options, &report);
  EXPECT_TRUE(report.flipped);
  EXPECT_EQ(right.voxels, flipped.voxels);
  EXPECT_GT(bw::mesh::mass_properties(flipped.mesh).volume, 0);
}

TEST(VolumeSampling, TorusHoleIsEmpty) {
  const auto solid = sample_volume(bw::mesh::torus({0, 0, 0}, 0.6, 0.2, 64, 32), 0.02);
  for (const auto& c : solid.voxels) {
    const Vec3d p = solid.grid.cell_center(c);
    EXPECT_GT(std::hypot(p.x(), p.y()), 0.6 - 0.2 - 0.02);
  }
}

template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const bw::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VolumeSampling, RefusesOpenMeshesAndHugeOutputs) {
  auto open = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  const std::string open_error = input_error([&] { sample_volume(open, 0.1); });
  EXPECT_NE(open_error.find("3 boundary edges"), std::string::npos) << open_error;
  EXPECT_NE(open_error.find("test mesh"), std::string::npos) << open_error;

  const auto cube = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  const std::string huge = input_error([&] { sample_volume(cube, 1e-5); });
  EXPECT_NE(huge.find("would need"), std::string::npos) << huge;
  EXPECT_NE(huge.find("available"), std::string::npos) << huge;

  const std::string bad_spacing = input_error([&] { sample_volume(cube, -1); });
  EXPECT_NE(bad_spacing.find("spacing"), std::string::npos) << bad_spacing;

  // A spacing far beyond the mesh's size can leave no cell on its surface: refused,
  // not written as a solid without particles.
  EXPECT_EQ(input_error([&] { sample_volume(cube, 1e9); }),
            "test mesh: spacing 1000000000 gives no surface particle; the mesh spans 1 m at most");
  EXPECT_FALSE(sample_volume(cube, 0.5).surface.empty());
}

}  // namespace

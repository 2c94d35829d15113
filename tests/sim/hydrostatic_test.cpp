// Hydrostatics: water at rest 0.5 m deep in a closed tank settles; the pressure at the
// bottom matches rho0 g times the depth, and the density error stays small.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/run_file.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

constexpr double kSpacing = 0.01;
constexpr double kDepth = 0.5;  // m of water: 50 layers

// The default (the continuity equation with the hydrostatic wall pressure, the pair that
// holds a deep column up as the missing fluid would) and the summation with its mirrored
// wall (docs/scene.md, "Density").
struct Model {
  const char* name;
  const char* fluid_keys;
  double fit_tolerance;  // of the fitted bottom pressure, relative
  bool layer_on_line;    // the layer touching the floor carries the fit's pressure
};

class Hydrostatic : public testing::TestWithParam<Model> {};

TEST_P(Hydrostatic, BottomPressureIsRhoGH) {
  test::TempDir dir;
  const Eigen::Vector3i n(10, 10, 54);
  test::write_tank(dir.file("tank.h5"), n, kSpacing);
  // A viscous fluid settles sooner; viscosity does not change the state at rest.
  std::ofstream(dir.file("column.toml")) << R"(
spacing = 0.01
[time]
end = 1.5
frame_rate = 100
[domain]
min = [-0.02, -0.02, -0.02]
max = [0.13, 0.13, 0.57]
[fluid]
c0 = 31.3
mu = 0.5
)" << GetParam().fluid_keys << R"(
[[fluid.block]]
min = [0.01, 0.01, 0.01]
max = [0.10, 0.10, 0.51]
[[solid]]
particles = "tank.h5"
[output]
fields = ["pressure", "density"]
)";
  const sim::RunSummary summary = test::run_scene(dir.file("column.toml"), dir.file("out"));
  const RunRecord run = read_run(dir.file("out/run.h5"));
  ASSERT_EQ(run.status, "complete");
  EXPECT_EQ(summary.removed, 0);

  // The pressure field of the fluid: a straight-line fit of p(z) over the particles
  // away from the walls (at least h from the side walls, the floor layer and the
  // surface), averaged over the last 0.5 s in 51 frames (the column still rings), taken
  // at the height of the bottom layer. With a mirrored wall the layer touching the floor
  // carries more: a single layer of boundary particles pushes with about half the
  // pressure the missing fluid would (docs/scene.md, "Physics"); it is reported apart.
  const double rho0 = 998, g = 9.81, h = 2 * kSpacing;
  const double wall_lo = 0.5 * kSpacing + h, wall_hi = (n.x() + 0.5) * kSpacing - h;
  double p_fit = 0, slope = 0, p_layer = 0, error_max = 0, top = 0;
  int frames = 0;
  for (int f = 100; f <= 150; ++f) {
    const FrameData d = read_frame(frame_file_name(dir.file("out/frames"), f));
    const float zmin = *std::min_element(d.z.begin(), d.z.end());
    const float zmax = *std::max_element(d.z.begin(), d.z.end());
    double sz = 0, sp = 0, szz = 0, szp = 0, zb = 0, pb = 0;
    int count = 0, nb = 0;
    for (std::size_t i = 0; i < d.z.size(); ++i) {
      error_max = std::max(error_max, double(d.rho[i]) / rho0 - 1);
      if (d.z[i] < zmin + 0.5 * kSpacing) {
        zb += d.z[i];
        pb += d.p[i];
        ++nb;
      }
      const bool interior = d.x[i] > wall_lo && d.x[i] < wall_hi && d.y[i] > wall_lo && d.y[i] < wall_hi;
      if (interior && d.z[i] > zmin + 1.5 * kSpacing && d.z[i] < zmax - 3 * kSpacing) {
        sz += d.z[i];
        sp += d.p[i];
        szz += double(d.z[i]) * d.z[i];
        szp += double(d.z[i]) * d.p[i];
        ++count;
      }
    }
    const double b1 = (count * szp - sz * sp) / (count * szz - sz * sz);
    const double b0 = (sp - b1 * sz) / count;
    zb /= nb;
    p_fit += b0 + b1 * zb;
    slope += -b1;
    p_layer += pb / nb;
    top += zmax;
    ++frames;
  }
  p_fit /= frames;
  slope /= frames;
  p_layer /= frames;
  top /= frames;
  const double expected = rho0 * g * (kDepth - 0.5 * kSpacing);
  test::figure("pressure at the bottom (fit of the fluid's pressure)", p_fit, "Pa");
  test::figure("rho0 g (H - spacing/2)", expected, "Pa");
  test::figure("bottom pressure / rho0 g H", p_fit / expected);
  test::figure("pressure gradient / rho0 g", slope / (rho0 * g));
  test::figure("pressure of the layer touching the floor", p_layer, "Pa");
  test::figure("top layer height (0.505 m at the start)", top, "m");
  test::figure("largest density error at rest (rho/rho0 - 1)", error_max);
  test::figure("worst density error over the run", summary.worst_density_error);
  const double k = rho0 * 31.3 * 31.3 / 7;
  test::figure("compression the Tait law needs at the bottom", std::pow(1 + expected / k, 1.0 / 7) - 1);
  EXPECT_NEAR(p_fit / expected, 1.0, GetParam().fit_tolerance);
  // A hydrostatic wall pushes as the fluid below would: no density step at the floor.
  if (GetParam().layer_on_line) {
    EXPECT_NEAR(p_layer / p_fit, 1.0, 0.02);
  }
  EXPECT_NEAR(slope / (rho0 * g), 1.0, 0.1);
  EXPECT_LT(error_max, 0.02);
  EXPECT_LT(summary.worst_density_error, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Models, Hydrostatic,
                         // The hydrostatic wall's fit reads the discrete gradient on the
                         // settled packing, 1.04 rho0 g here (docs/scene.md, "Density").
                         testing::Values(Model{"Summation", "density = \"summation\"\n", 0.03, false},
                                         Model{"ContinuityHydrostaticWall", "", 0.05, true}),
                         [](const testing::TestParamInfo<Model>& model) { return std::string(model.param.name); });

}  // namespace
}  // namespace bw

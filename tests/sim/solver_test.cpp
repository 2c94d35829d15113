// The solver's device kernels against brute force on the host: the grid finds exactly
// the neighbours an O(N^2) search finds, and Psi_b, densities, pressures and
// accelerations equal a double-precision O(N^2) evaluation of method.md's formulas.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "compute/device.h"
#include "sim/solver.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace bw::sim {
namespace {

compute::Context& context() {
  static compute::Context c(compute::choose_device("auto"));
  return c;
}

// A scene with a tank (when `tank` is set) and one block, prepared on the host.
Setup prepare_scene(const test::TempDir& dir, bool tank, const std::string& extra = "") {
  const double s = 0.01;
  if (tank) test::write_tank(dir.file("tank.h5"), {8, 6, 8}, s);
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.01\n[time]\nend = 0.1\n[domain]\nmin = [-0.02, -0.02, -0.02]\n"
                                           "max = [0.11, 0.09, 0.11]\n[fluid]\nc0 = 20\nmu = 0.1\nmu_b = 0.3\n" << extra
                                        << "[[fluid.block]]\nmin = [0.01, 0.01, 0.01]\nmax = [0.07, 0.05, 0.06]\n"
                                        << (tank ? "[[solid]]\nparticles = \"tank.h5\"\n" : "");
  return prepare(scene::load_scene(dir.file("scene.toml")), 0.1);
}

TEST(Grid, NeighboursEqualBruteForce) {
  test::TempDir dir;
  sim::Setup setup = prepare_scene(dir, false);
  const Parameters& p = setup.params;
  // Random particles over the whole domain and a little beyond (those are removed),
  // plus particles exactly on cell faces and on the domain's lower faces.
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-0.03, 0.12);
  ParticleArrays fluid;
  for (int i = 0; i < 4000; ++i) fluid.push(Vec3d(u(rng), u(rng), u(rng)), Vec3d::Zero());
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j) fluid.push(p.domain.min + p.h * Vec3d(i, j, 1), Vec3d::Zero());
  setup.fluid = fluid;
  setup.params.max_particles = static_cast<std::int64_t>(fluid.size());
  Solver solver(setup, context());
  const auto nb = solver.neighbour_lists(256);
  const std::size_t n = nb.x.size();
  std::size_t inside = 0;
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    const Vec3d q(fluid.x[i], fluid.y[i], fluid.z[i]);
    const Eigen::Vector3f qf = q.cast<float>();
    if ((qf.array() >= p.domain.min.cast<float>().array()).all() && (qf.array() < p.domain.max.cast<float>().array()).all())
      ++inside;
  }
  ASSERT_EQ(n, inside) << "particles outside the domain are removed, the others kept";
  EXPECT_EQ(solver.removed_count(), static_cast<std::int64_t>(fluid.size() - inside));
  const float h2 = static_cast<float>(p.h * p.h);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> expected;
    for (std::size_t j = 0; j < n; ++j) {
      const float dx = nb.x[i] - nb.x[j], dy = nb.y[i] - nb.y[j], dz = nb.z[i] - nb.z[j];
      if (dx * dx + dy * dy + dz * dz < h2) expected.push_back(static_cast<std::uint32_t>(j));
    }
    std::vector<std::uint32_t> got = nb.lists[i];
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, expected) << "particle " << i << " at " << nb.x[i] << " " << nb.y[i] << " " << nb.z[i];
    pairs += expected.size();
  }
  test::figure("particles", static_cast<double>(n));
  test::figure("mean neighbours (brute force)", static_cast<double>(pairs) / n);
}

// Density, Psi_b and acceleration by O(N^2) double sums of the formulas in
// shaders/fluid.cl (method.md 1, 2 with W_spiky for the density and its gradient for
// the pressure forces, divided by the lattice moment c).
struct Reference {
  std::vector<double> psi, rho, p;
  std::vector<Vec3d> a;
};

Reference brute_force(const Solver::Snapshot& S, const Parameters& P) {
  const double h = P.h, h2 = h * h, pi = std::numbers::pi;
  const double visc = 45 / (pi * std::pow(h, 6)), spiky = 15 / (pi * std::pow(h, 6));
  auto ws = [&](double r2) { return r2 < h2 ? spiky * std::pow(h - std::sqrt(r2), 3) : 0.0; };
  auto grad_s = [&](const Vec3d& x) {  // grad W_spiky(x) with respect to the first particle
    const double r = x.norm();
    return r < h && r > 0 ? Vec3d(-3 * spiky * (h - r) * (h - r) / r * x) : Vec3d::Zero();
  };
  const std::size_t n = S.x.size(), nb = S.bx.size();
  auto fx = [&](std::size_t i) { return Vec3d(S.x[i], S.y[i], S.z[i]); };
  auto bxv = [&](std::size_t b) { return Vec3d(S.bx[b], S.by[b], S.bz[b]); };
  Reference R;
  R.psi.resize(nb);
  // (Psi_b leaves out the far face of a wall two spacings thin, bw_psi_sum; this
  // test's tank has none within h.)
  for (std::size_t b = 0; b < nb; ++b) {
    double sum = 0;
    for (std::size_t k = 0; k < nb; ++k)
      if (S.bsolid[k] == S.bsolid[b]) sum += ws((bxv(b) - bxv(k)).squaredNorm());
    R.psi[b] = P.rho0 / sum;
  }
  R.rho.resize(n);
  R.p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    double sf = 0, sb = 0;
    for (std::size_t j = 0; j < n; ++j) sf += ws((fx(i) - fx(j)).squaredNorm());
    for (std::size_t b = 0; b < nb; ++b) sb += R.psi[b] * ws((fx(i) - bxv(b)).squaredNorm());
    R.rho[i] = P.kernel_mass * sf + P.gamma1 * sb;
    R.p[i] = std::max(0.0, P.k * (std::pow(R.rho[i] / P.rho0, P.gamma) - 1));
  }
  R.a.assign(n, P.gravity);
  for (std::size_t i = 0; i < n; ++i) {
    const double Pi = R.p[i] / (R.rho[i] * R.rho[i]);
    const Vec3d vi(S.vx[i], S.vy[i], S.vz[i]);
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3d x = fx(i) - fx(j);
      const double r = x.norm();
      if (j == i || r >= h) continue;
      const double Pj = R.p[j] / (R.rho[j] * R.rho[j]);
      const Vec3d vj(S.vx[j], S.vy[j], S.vz[j]);
      R.a[i] += -P.kernel_mass * (Pi + Pj) * grad_s(x) / P.gradient_moment +
                P.mu / R.rho[i] * P.kernel_mass * (vj - vi) / R.rho[j] * visc * (h - r);
    }
    for (std::size_t b = 0; b < nb; ++b) {
      const Vec3d x = fx(i) - bxv(b);
      const double r = x.norm();
      if (r >= h) continue;
      R.a[i] += -P.gamma2 * R.psi[b] * (Pi + R.p[i] / (P.rho0 * P.rho0)) * grad_s(x) / P.gradient_moment +
                P.mu_b / R.rho[i] * R.psi[b] / P.rho0 * (-vi) * visc * (h - r);
    }
  }
  return R;
}

// The summation, whose density the positions give (the continuity equation's rates
// are checked against the kernel sum's change in density_test).
TEST(Fluid, DensityAndForcesEqualBruteForce) {
  test::TempDir dir;
  sim::Setup setup = prepare_scene(dir, true, "density = \"summation\"\n");
  // Jitter the block and give it random velocities, so that every term is at work.
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0, 0.1 * setup.params.spacing), speed(0, 0.5);
  for (std::size_t i = 0; i < setup.fluid.size(); ++i) {
    setup.fluid.x[i] += static_cast<float>(jitter(rng));
    setup.fluid.y[i] += static_cast<float>(jitter(rng));
    setup.fluid.z[i] += static_cast<float>(jitter(rng));
    setup.fluid.vx[i] = static_cast<float>(speed(rng));
    setup.fluid.vy[i] = static_cast<float>(speed(rng));
    setup.fluid.vz[i] = static_cast<float>(speed(rng));
  }
  Solver solver(setup, context());
  const Solver::Snapshot S = solver.snapshot();
  const Parameters& P = solver.parameters();
  ASSERT_EQ(S.x.size(), setup.fluid.size());
  ASSERT_GT(S.bx.size(), 0u);
  const Reference R = brute_force(S, P);

  double psi_err = 0, rho_err = 0, p_scale = 0, p_err = 0, a_scale = 0, a_err = 0;
  for (std::size_t b = 0; b < S.bx.size(); ++b) psi_err = std::max(psi_err, std::abs(S.bpsi[b] / R.psi[b] - 1));
  for (std::size_t i = 0; i < S.x.size(); ++i) {
    rho_err = std::max(rho_err, std::abs(S.rho[i] / R.rho[i] - 1));
    p_scale = std::max(p_scale, R.p[i]);
    p_err = std::max(p_err, std::abs(S.p[i] - R.p[i]));
    a_scale = std::max(a_scale, R.a[i].norm());
    a_err = std::max(a_err, (Vec3d(S.ax[i], S.ay[i], S.az[i]) - R.a[i]).norm());
  }
  test::figure("Psi_b, largest relative error", psi_err);
  test::figure("density, largest relative error", rho_err);
  test::figure("pressure, largest error / largest pressure", p_err / p_scale);
  test::figure("acceleration, largest error / largest acceleration", a_err / a_scale);
  test::figure("largest acceleration", a_scale, "m/s^2");
  // Float sums of ~30 terms against double: a few units of float rounding, amplified
  // 7x by the Tait exponent for the pressure.
  EXPECT_LT(psi_err, 1e-5);
  EXPECT_LT(rho_err, 1e-5);
  EXPECT_LT(p_err / p_scale, 1e-3);
  EXPECT_LT(a_err / a_scale, 1e-3);
  EXPECT_GT(p_scale, 0) << "the jittered block must be under pressure somewhere";
}

TEST(Fluid, FullLatticeHasRestDensityAndBlocksWeighRho0PerVolume) {
  test::TempDir dir;
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.01\n[time]\nend = 0.1\n[domain]\nmin = [0, 0, 0]\n"
                                           "max = [0.2, 0.2, 0.2]\n[fluid]\nc0 = 20\ndensity = \"summation\"\n"
                                           "[[fluid.block]]\nmin = [0.02, 0.02, 0.02]\nmax = [0.12, 0.12, 0.12]\n";
  const sim::Setup setup = prepare(scene::load_scene(dir.file("scene.toml")), 0.1);
  Solver solver(setup, context());
  const Solver::Snapshot S = solver.snapshot();
  const double h = setup.params.h;
  // Particles at least h inside the block have a full neighbourhood.
  std::size_t interior = 0;
  double worst = 0;
  for (std::size_t i = 0; i < S.x.size(); ++i) {
    const Vec3d q(S.x[i], S.y[i], S.z[i]);
    if ((q.array() > 0.02 + h).all() && (q.array() < 0.12 - h).all()) {
      ++interior;
      worst = std::max(worst, std::abs(S.rho[i] / setup.params.rho0 - 1));
      EXPECT_LT(S.p[i], 1.0f) << "Pa: float rounding of rho only";
    }
  }
  ASSERT_GT(interior, 100u);
  test::figure("interior particles", static_cast<double>(interior));
  test::figure("largest |rho/rho0 - 1| inside a full lattice", worst);
  EXPECT_LT(worst, 1e-5);
  // And the block weighs rho0 times its volume: the particle mass is rho0 spacing^3,
  // the kernel mass (what the density sum weighs with) is not (docs/scene.md,
  // "Physics"). With the kernel mass, water weighed 0.81 rho0 and bodies floated low.
  const double mass = setup.params.mass * static_cast<double>(setup.fluid.size());
  test::figure("block mass / (rho0 x its volume)", mass / (setup.params.rho0 * 1e-3));
  EXPECT_NEAR(mass, setup.params.rho0 * 1e-3, 1e-9);
  EXPECT_NEAR(setup.params.kernel_mass, setup.params.rho0 / lattice_kernel_sum(0.01, h), 1e-15);
  EXPECT_LT(setup.params.kernel_mass, 0.82 * setup.params.mass);
}

// A draw of an ensemble (fluid.seed): the same lattice, each particle moved by a
// uniform offset of up to fluid.jitter spacings per axis, the same for the same seed
// and another for another seed.
TEST(Fluid, ADrawMovesEachBlockParticleBySeededOffsetsWithinItsJitter) {
  test::TempDir dir;
  const sim::Setup lattice = prepare_scene(dir, false);
  const sim::Setup draw = prepare_scene(dir, false, "seed = 7\njitter = 0.1\n");
  const sim::Setup again = prepare_scene(dir, false, "seed = 7\njitter = 0.1\n");
  const sim::Setup other = prepare_scene(dir, false, "seed = 8\njitter = 0.1\n");
  const sim::Setup small = prepare_scene(dir, false, "seed = 1\n");
  const std::size_t n = lattice.fluid.size();
  ASSERT_GT(n, 100u);
  ASSERT_EQ(draw.fluid.size(), n);
  ASSERT_EQ(small.fluid.size(), n);
  const double spacing = lattice.params.spacing;
  auto offset = [&](const sim::Setup& s, std::size_t i, int a) {
    const std::vector<float>* axes[3] = {&s.fluid.x, &s.fluid.y, &s.fluid.z};
    const std::vector<float>* base[3] = {&lattice.fluid.x, &lattice.fluid.y, &lattice.fluid.z};
    return (static_cast<double>((*axes[a])[i]) - (*base[a])[i]) / spacing;
  };
  double largest = 0, largest_small = 0;
  Vec3d mean = Vec3d::Zero();
  std::size_t moved_small = 0, differ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    bool any_small = false, any_other = false;
    for (int a = 0; a < 3; ++a) {
      largest = std::max(largest, std::abs(offset(draw, i, a)));
      mean[a] += offset(draw, i, a) / static_cast<double>(n);
      largest_small = std::max(largest_small, std::abs(offset(small, i, a)));
      any_small = any_small || offset(small, i, a) != 0;
      any_other = any_other || offset(other, i, a) != offset(draw, i, a);
    }
    moved_small += any_small;
    differ += any_other;
  }
  test::figure("largest offset at jitter 0.1 (spacings)", largest);
  test::figure("largest offset at the default jitter (spacings)", largest_small);
  EXPECT_LE(largest, 0.1 + 1e-5) << "float positions round within 1e-5 spacings here";
  // 3n uniform offsets in [-0.1, 0.1): the largest falls short of 0.09 with probability 0.9^(3n).
  EXPECT_GT(largest, 0.09);
  // Their mean is within 4 standard errors of 0: sigma 0.1 / sqrt(3) spacings.
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(mean[a]), 4 * 0.1 / std::sqrt(3.0 * static_cast<double>(n))) << a;
  EXPECT_LE(largest_small, 1e-3 + 1e-5);
  EXPECT_GT(largest_small, 0.5e-3);
  EXPECT_EQ(moved_small, n) << "every particle of a draw moves";
  EXPECT_EQ(draw.fluid.x, again.fluid.x);
  EXPECT_EQ(draw.fluid.y, again.fluid.y);
  EXPECT_EQ(draw.fluid.z, again.fluid.z);
  EXPECT_EQ(differ, n) << "another seed moves every particle otherwise";
}

// The fluid layer on a tank's floor: the particles below `below` and at least h inside
// the side walls' planes at lo and hi (in x and y), and their largest |rho/rho0 - 1|.
struct FloorLayer {
  std::size_t count = 0;
  double worst = 0;
};
FloorLayer floor_layer(const Solver::Snapshot& S, double rho0, double below, double lo, double hi, double h) {
  FloorLayer layer;
  for (std::size_t i = 0; i < S.x.size(); ++i)
    if (S.z[i] < below && S.x[i] > lo + h && S.x[i] < hi - h && S.y[i] > lo + h && S.y[i] < hi - h) {
      ++layer.count;
      layer.worst = std::max(layer.worst, std::abs(S.rho[i] / rho0 - 1));
    }
  return layer;
}

TEST(Fluid, FluidNextToAFlatWallHasRestDensity) {
  // The default gamma1 is calibrated for exactly this: the kernel sum one spacing from a
  // flat wall (the summation's; the continuity equation starts hydrostatic).
  test::TempDir dir;
  test::write_tank(dir.file("tank.h5"), {16, 16, 8}, 0.01);
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.01\n[time]\nend = 0.1\n[domain]\nmin = [-0.02, -0.02, -0.02]\n"
                                           "max = [0.19, 0.19, 0.11]\n[fluid]\nc0 = 20\ndensity = \"summation\"\n"
                                           "[[fluid.block]]\n"
                                           "min = [0.01, 0.01, 0.01]\nmax = [0.16, 0.16, 0.06]\n"
                                           "[[solid]]\nparticles = \"tank.h5\"\n";
  const sim::Setup setup = prepare(scene::load_scene(dir.file("scene.toml")), 0.1);
  test::figure("calibrated gamma1 at h = 2 spacings", setup.params.gamma1);
  EXPECT_NEAR(setup.params.gamma1, calibrated_gamma1(0.01, 0.02), 1e-12);
  Solver solver(setup, context());
  const Solver::Snapshot S = solver.snapshot();
  // The first layer above the floor, at least h from the side walls.
  const FloorLayer layer = floor_layer(S, setup.params.rho0, 0.02, 0.01, 0.16, setup.params.h);
  double worst_anywhere = 0;
  for (std::size_t i = 0; i < S.x.size(); ++i)
    worst_anywhere = std::max(worst_anywhere, S.rho[i] / setup.params.rho0 - 1);
  ASSERT_GT(layer.count, 50u);
  test::figure("largest |rho/rho0 - 1| one spacing from a flat wall", layer.worst);
  test::figure("largest rho/rho0 - 1 anywhere (edges, corners)", worst_anywhere);
  EXPECT_LT(layer.worst, 1e-5);
  EXPECT_LT(worst_anywhere, 0.01) << "fluid in edges and corners starts nearly at rest too";
}

TEST(Fluid, FluidNextToAWallTwoSpacingsThickHasRestDensity) {
  // The example tanks' walls are 0.04 m thick and sampled on both faces: at 0.02 m the
  // outer face's particles lie one spacing behind the inner face's. They are out of
  // the fluid's reach (h from its first layer) and must not change what the inner
  // face's particles stand for (Psi_b): when they counted, the wall weighed 13% less
  // than gamma1's calibration assumes, the floor layer started 1.5% light and, with the
  // continuity equation, a pool's bottom layer fell at 1-3 g at the start.
  test::TempDir dir;
  const double s = 0.02;
  test::write_thick_tank(dir.file("tank.h5"), {14, 14, 8}, s, 2 * s);
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.02\n[time]\nend = 0.1\n[domain]\nmin = [-0.06, -0.06, -0.06]\n"
                                           "max = [0.34, 0.34, 0.22]\n[fluid]\nc0 = 20\ndensity = \"summation\"\n"
                                           "[[fluid.block]]\nmin = [0, 0, 0]\nmax = [0.28, 0.28, 0.12]\n"
                                           "[[solid]]\nparticles = \"tank.h5\"\n";
  const sim::Setup setup = prepare(scene::load_scene(dir.file("scene.toml")), 0.1);
  Solver solver(setup, context());
  const Solver::Snapshot S = solver.snapshot();
  // Both faces are there: particles half a spacing and one and a half spacings below
  // the floor.
  std::size_t inner = 0, outer = 0;
  for (std::size_t b = 0; b < S.bz.size(); ++b) {
    inner += std::abs(S.bz[b] + 0.5 * s) < 1e-4;
    outer += std::abs(S.bz[b] + 1.5 * s) < 1e-4;
  }
  ASSERT_GT(inner, 100u);
  ASSERT_GT(outer, 100u);
  const FloorLayer layer = floor_layer(S, setup.params.rho0, s, 0, 0.28, setup.params.h);
  ASSERT_GT(layer.count, 50u);
  test::figure("largest |rho/rho0 - 1| one spacing from a wall two spacings thick", layer.worst);
  EXPECT_LT(layer.worst, 1e-5);
}

}  // namespace
}  // namespace bw::sim

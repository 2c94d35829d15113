// The SPH kernels of shaders/sph_common.h (the same code the device runs): each
// integrates to 1, gradients cancel over a full neighbourhood, the first moment of the
// gradient is -I and the viscosity Laplacian recovers lap(x^2) = 2; the lattice mass
// gives rho0 and the lattice gradient correction makes the first moment exactly -I;
// the Tait energy is the integral of p / rho^2.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sim/setup.h"
#include "sph_common.h"
#include "test_support.h"

namespace bw::sim {
namespace {

constexpr double kH = 0.04;  // support radius of the tests (m)

double poly6_coefficient(double h) { return 315.0 / (64.0 * std::numbers::pi * std::pow(h, 9)); }
double visc_coefficient(double h) { return 45.0 / (std::numbers::pi * std::pow(h, 6)); }

// 4 pi int_0^h r^2 f(r) dr by the midpoint rule (no sample at r = 0, where W_visc is
// singular but r^2 W_visc is not).
template <class F>
double radial_integral(F f, double h, int steps = 200000) {
  double sum = 0;
  const double dr = h / steps;
  for (int i = 0; i < steps; ++i) {
    const double r = (i + 0.5) * dr;
    sum += r * r * f(r);
  }
  return 4 * std::numbers::pi * sum * dr;
}

TEST(Kernels, IntegrateToOne) {
  const float h = static_cast<float>(kH), poly6 = static_cast<float>(poly6_coefficient(kH));
  const double i_poly6 = radial_integral([&](double r) { return bw_poly6(float(r * r), h * h, poly6); }, kH);
  const double i_spiky = radial_integral([&](double r) { return bw_spiky(float(r), h); }, kH);
  const double i_visc = radial_integral([&](double r) { return bw_visc(float(r), h); }, kH);
  test::figure("integral of W_poly6", i_poly6);
  test::figure("integral of W_spiky", i_spiky);
  test::figure("integral of W_visc", i_visc);
  constexpr double kTolerance = 1e-4;  // float kernels, fine quadrature
  EXPECT_NEAR(i_poly6, 1.0, kTolerance);
  EXPECT_NEAR(i_spiky, 1.0, kTolerance);
  EXPECT_NEAR(i_visc, 1.0, 1e-3);  // the h/(2r) singularity costs the midpoint rule a little
  EXPECT_EQ(bw_poly6(float(kH * kH), h * h, poly6), 0.0f);
  EXPECT_EQ(bw_spiky(h, h), 0.0f);
  EXPECT_EQ(bw_visc_lap(h * 1.01f, h, 1.0f), 0.0f);
}

TEST(Kernels, ViscosityLaplacianMatchesKernel) {
  // lap W = W'' + 2 W' / r for the radial W_visc, by central differences.
  const double h = kH, visc = visc_coefficient(kH);
  for (double a : {0.2, 0.4, 0.6, 0.8}) {
    const double r = a * h, d = 1e-2 * h;  // float kernel: a step well above rounding
    auto w = [&](double q) { return double(bw_visc(float(q), float(h))); };
    const double second = (w(r + d) - 2 * w(r) + w(r - d)) / (d * d);
    const double first = (w(r + d) - w(r - d)) / (2 * d);
    const double lap = second + 2 * first / r;
    EXPECT_NEAR(lap / (visc * (h - r)), 1.0, 2e-2) << "r = " << a << " h: " << lap << " vs " << visc * (h - r);
  }
}

// Sums over a full simple cubic lattice of spacing h / ratio around the origin.
struct LatticeSums {
  Vec3d grad_poly6 = Vec3d::Zero(), grad_spiky = Vec3d::Zero();
  double grad_scale = 0;      // sum of |grad W|, to judge the cancellation
  double w_poly6 = 0;         // spacing^3 sum W_poly6
  Mat3d moment = Mat3d::Zero();  // spacing^3 sum x_ij (x) grad W_poly6(x_ij)
  double laplacian = 0;       // spacing^3 sum x_ij.x^2 lap W_visc
};

LatticeSums lattice_sums(int ratio) {
  const double s = kH / ratio, h = kH;
  const float poly6 = static_cast<float>(poly6_coefficient(h)), visc = static_cast<float>(visc_coefficient(h));
  LatticeSums out;
  for (int k = -ratio; k <= ratio; ++k)
    for (int j = -ratio; j <= ratio; ++j)
      for (int i = -ratio; i <= ratio; ++i) {
        // x_ij = x_i - x_j with particle i at the origin.
        const Vec3d x = -s * Vec3d(i, j, k);
        const double r = x.norm();
        const double f6 = bw_poly6_grad_factor(float(r * r), float(h * h), poly6);
        const double fs = bw_spiky_grad_factor(float(r), float(h));
        out.grad_poly6 += f6 * x;
        out.grad_spiky += fs * x;
        out.grad_scale += std::abs(f6) * r;
        out.w_poly6 += s * s * s * bw_poly6(float(r * r), float(h * h), poly6);
        out.moment += s * s * s * x * (f6 * x).transpose();
        out.laplacian += s * s * s * x.x() * x.x() * bw_visc_lap(float(r), float(h), visc);
      }
  return out;
}

TEST(Kernels, GradientsSumToZeroOverAFullNeighbourhood) {
  for (int ratio : {2, 3, 4}) {
    const LatticeSums l = lattice_sums(ratio);
    test::figure("|sum grad W_poly6| / sum |grad W|, h = " + std::to_string(ratio) + " spacings",
                 l.grad_poly6.norm() / l.grad_scale);
    EXPECT_LT(l.grad_poly6.norm(), 1e-6 * l.grad_scale);
    EXPECT_LT(l.grad_spiky.norm(), 1e-6 * l.grad_scale);
  }
}

TEST(Kernels, LatticeSumsApproachTheIntegrals) {
  // Discretisation error of the lattice sums, by h in spacings (index): it shrinks
  // as h covers more spacings; the Laplacian's is largest (its kernel has a kink).
  const double w_tolerance[] = {0, 0, 0.02, 0.005, 0.002};
  const double moment_tolerance[] = {0, 0, 0.08, 0.02, 0.01};
  const double laplacian_tolerance[] = {0, 0, 0.05, 0.06, 0.02};
  for (int ratio : {2, 3, 4}) {
    const LatticeSums l = lattice_sums(ratio);
    const std::string at = ", h = " + std::to_string(ratio) + " spacings";
    test::figure("spacing^3 sum W_poly6" + at, l.w_poly6);
    test::figure("spacing^3 sum x (x) grad W_poly6, diagonal" + at, l.moment(0, 0));
    test::figure("spacing^3 sum x^2 lap W_visc" + at, l.laplacian);
    EXPECT_NEAR(l.w_poly6, 1.0, w_tolerance[ratio]);
    EXPECT_LT((l.moment + Mat3d::Identity()).cwiseAbs().maxCoeff(), moment_tolerance[ratio]) << l.moment;
    EXPECT_NEAR(l.laplacian / 2.0, 1.0, laplacian_tolerance[ratio]) << "lap(x^2) = 2";
  }
}

TEST(Kernels, LatticeMassGivesRestDensity) {
  for (double spacing : {0.01, 0.02}) {
    const double h = 2 * spacing, rho0 = 998;
    const double mass = rho0 / lattice_kernel_sum(spacing, h);
    // Recompute the density of a lattice particle with the float kernel the device uses.
    double rho = 0;
    for (int k = -2; k <= 2; ++k)
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i)
          rho += mass * bw_spiky(float(spacing * std::sqrt(double(i * i + j * j + k * k))), float(h));
    EXPECT_NEAR(rho / rho0, 1.0, 1e-6) << "spacing " << spacing;
    test::figure("particle mass at spacing " + std::to_string(spacing), mass, "kg");
    test::figure("particle mass / (rho0 spacing^3)", mass / (rho0 * spacing * spacing * spacing));
    // W_spiky is coarse at h = 2 spacings: its lattice sum is 24% above the integral.
    EXPECT_NEAR(mass / (rho0 * spacing * spacing * spacing), 1 / 1.2359, 1e-3);
  }
}

TEST(Kernels, GradientCorrectionMakesTheLatticeMomentExact) {
  for (int ratio : {2, 3, 4}) {
    const double spacing = kH / ratio;
    const double c = lattice_gradient_moment(spacing, kH);
    const double volume = 1.0 / lattice_kernel_sum(spacing, kH);
    Mat3d moment = Mat3d::Zero();
    for (int k = -ratio; k <= ratio; ++k)
      for (int j = -ratio; j <= ratio; ++j)
        for (int i = -ratio; i <= ratio; ++i) {
          const Vec3d x = -spacing * Vec3d(i, j, k);
          moment += volume / c * x * (bw_spiky_grad_factor(float(x.norm()), float(kH)) * x).transpose();
        }
    test::figure("spiky gradient moment c at h = " + std::to_string(ratio) + " spacings", c);
    EXPECT_LT((moment + Mat3d::Identity()).cwiseAbs().maxCoeff(), 1e-5) << moment;
  }
  EXPECT_NEAR(lattice_gradient_moment(0.01, 0.02), 0.7738, 1e-3);
}

TEST(Kernels, CalibratedBoundaryWeight) {
  // Mirrors the calibration by hand at h = 2 spacings, where only the layer one
  // spacing away (the wall's) is missing and spiky vanishes at 2 spacings.
  const double s = 0.01, h = 0.02;
  double own = 0, full = 0;
  for (int k = -2; k <= 2; ++k)
    for (int j = -2; j <= 2; ++j)
      for (int i = -2; i <= 2; ++i) {
        const double w = bw_spiky(float(s * std::sqrt(double(i * i + j * j + k * k))), float(h));
        full += w;
        if (k == 0) own += w;
      }
  test::figure("calibrated gamma1", calibrated_gamma1(s, h));
  EXPECT_NEAR(calibrated_gamma1(s, h), own / full, 1e-5);
}

TEST(Tait, PressureAndEnergy) {
  const float rho0 = 998, k = 1.0e5f;
  EXPECT_EQ(bw_tait(rho0, rho0, k, 7, 7), 0.0f);
  EXPECT_EQ(bw_tait(0.9f * rho0, rho0, k, 7, 7), 0.0f) << "negative pressure clamped";
  EXPECT_NEAR(bw_tait(1.01f * rho0, rho0, k, 7, 7), k * (std::pow(1.01, 7) - 1), 1e-3 * k * 0.07);
  EXPECT_NEAR(bw_tait(1.01f * rho0, rho0, k, 7, 7), bw_tait(1.01f * rho0, rho0, k, 7, 0), 1e-3) << "powi = pow";
  EXPECT_NEAR(bw_powi(1.3f, 7), std::pow(1.3, 7), 1e-5);
  // d e / d rho = p / rho^2, checked by central differences.
  for (double a : {1.005, 1.02, 1.1}) {
    const double rho = a * rho0, d = 1e-3 * rho0;
    const double de = (bw_tait_energy(float(rho + d), rho0, k, 7) - bw_tait_energy(float(rho - d), rho0, k, 7)) / (2 * d);
    const double p = bw_tait(float(rho), rho0, k, 7, 7);
    EXPECT_NEAR(de * rho * rho / p, 1.0, 0.02) << "rho / rho0 = " << a;
  }
  EXPECT_EQ(bw_tait_energy(0.95f * rho0, rho0, k, 7), 0.0f);
}

// The CFL limit's signal speed is the Tait law's sound speed, sqrt(dp/drho): checked
// against the law's own pressure by central differences, and with the walls' extra
// stiffness.
TEST(Tait, SignalSpeedIsTheSoundSpeedOfTheDensestParticle) {
  Parameters p;
  p.rho0 = 998;
  p.c0 = 30;
  p.gamma = 7;
  p.gamma1 = 1.2;
  p.gamma2 = 0.6;  // the mirrored wall: no extra stiffness
  const double k = p.rho0 * p.c0 * p.c0 / p.gamma;
  EXPECT_DOUBLE_EQ(signal_speed(p, p.rho0), p.c0);
  EXPECT_DOUBLE_EQ(signal_speed(p, 0.8 * p.rho0), p.c0) << "no pressure below rho0, no faster sound";
  EXPECT_NEAR(signal_speed(p, 2 * p.rho0), 8 * p.c0, 1e-9 * p.c0);
  for (double a : {1.01, 1.1, 1.5}) {
    const double rho = a * p.rho0, d = 1e-4 * p.rho0;
    const double dp = (bw_tait(float(rho + d), float(p.rho0), float(k), 7, 7) -
                       bw_tait(float(rho - d), float(p.rho0), float(k), 7, 7)) / (2 * d);
    EXPECT_NEAR(signal_speed(p, rho), std::sqrt(dp), 0.01 * std::sqrt(dp)) << "rho / rho0 = " << a;
  }
  p.gamma2 = p.gamma1;  // the hydrostatic wall pushes with twice its density term's energy gradient
  EXPECT_NEAR(signal_speed(p, p.rho0), std::sqrt(2.0) * p.c0, 1e-9);
  p.gamma1 = 0;  // walls that add no density
  EXPECT_DOUBLE_EQ(signal_speed(p, p.rho0), p.c0);
}

}  // namespace
}  // namespace bw::sim

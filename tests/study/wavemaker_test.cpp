// The wave flume study's scripts (Makefile.scenes `wavemaker`; docs/validation.md,
// "Waves from a wave maker"): the keys a paddle follows, and the report that reads
// gauges against linear theory, on signals whose answers are known.
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "test_support.h"

namespace bw {
namespace {

const std::string kSource = BW_SOURCE_DIR;
constexpr double kPi = std::numbers::pi;

// The numbers of the data lines (not comments, not the header) of a CSV text.
std::vector<std::vector<double>> rows(const std::string& text) {
  std::vector<std::vector<double>> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    out.push_back(row);
  }
  return out;
}

// Integrated as bw-sim does (velocity linear between keys), the piston's keys move it
// by (S / 2) sin(omega t) once the ramp is over, about where it started, and the
// flap's turn it by atan((S / 2) / h) sin(omega t); the last key stops the paddle.
TEST(WaveMaker, KeysIntegrateToTheStrokeAboutTheStart) {
  const std::string keys = kSource + "/tests/study/wavemaker-keys.sh ";
  for (const auto& [kind, amplitude] : {std::pair{"piston", 0.04}, std::pair{"flap", std::atan(0.04 / 0.5)}}) {
    SCOPED_TRACE(kind);
    const auto r = test::run(keys + kind + " --period 1.4 --stroke 0.08 --ramp 2 --duration 7 --depth 0.5");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto k = rows(r.out);
    ASSERT_GT(k.size(), 200u);
    double x = 0, lowest = 0, highest = 0, worst = 0;
    for (std::size_t i = 1; i < k.size(); ++i) {
      x += 0.5 * (k[i][0] - k[i - 1][0]) * (k[i][1] + k[i - 1][1]);
      if (k[i][0] < 2.8) continue;  // the ramp
      lowest = std::min(lowest, x), highest = std::max(highest, x);
      worst = std::max(worst, std::abs(x - amplitude * std::sin(2 * kPi / 1.4 * k[i][0])));
    }
    // Keys 1.4 / 40 s apart: the trapezoid's error on a sine, (2 pi / 40)^2 / 12 of it.
    EXPECT_NEAR(highest, amplitude, 0.003 * amplitude);
    EXPECT_NEAR(lowest, -amplitude, 0.003 * amplitude);
    EXPECT_LT(worst, 0.003 * amplitude);
    EXPECT_EQ(k.back()[1], 0.0) << "stopped at the end";
  }
  const auto bad = test::run(keys + "paddle --period 1.4 --stroke 0.08");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("paddle: expected piston or flap"), std::string::npos) << bad.err;
}

// Gauges 1 and 2 m from the paddle reading a wave of height H and period T that runs
// at celerity c: the report gives back T, H and c, and H's and c's errors against
// Biesel's height and linear dispersion.
TEST(WaveMaker, TheReportReadsPeriodHeightAndCelerity) {
  test::TempDir dir;
  // Linear theory for T = 1.4 s, h = 0.5 m (the report's header prints the same).
  constexpr double kPeriod = 1.4, kCelerity = 1.8365, kBiesel = 0.0942;
  const std::string report = kSource + "/tests/study/wavemaker-report.sh ";
  for (const auto& [name, height, celerity] :
       {std::tuple{"as theory says", kBiesel, kCelerity}, std::tuple{"low and fast", 0.8 * kBiesel, 1.1 * kCelerity}}) {
    SCOPED_TRACE(name);
    const std::string gauges = dir.file("gauges.csv");
    {
      std::ofstream out(gauges);
      out << "time,G1,G2\n";
      for (int i = 0; i <= 500; ++i) {
        const double t = 0.02 * i;
        auto eta = [&](double d) { return 0.5 + 0.5 * height * std::sin(2 * kPi / kPeriod * (t - d / celerity)); };
        out << fmt::format("{:.4f},{:.6f},{:.6f}\n", t, eta(1.0), eta(2.0));
      }
    }
    const auto r = test::run(report + gauges +
                             " --kind piston --period 1.4 --stroke 0.08 --depth 0.5 --paddle 0.1 --wall 8"
                             " --at G1=1.1 --at G2=2.1");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    double t1 = 0, h1 = 0, theory = 0, error = 0, c = 0, c_theory = 0, c_error = 0;
    const auto g = r.out.find("gauge G1 ");
    const auto p = r.out.find("celerity G1-G2 ");
    ASSERT_NE(g, std::string::npos) << r.out;
    ASSERT_NE(p, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + g, "gauge G1 x %*s d %*s window %*s %*s periods %*d T %lf H %lf theory %lf error %lf%%",
                          &t1, &h1, &theory, &error), 4);
    ASSERT_EQ(std::sscanf(r.out.c_str() + p, "celerity G1-G2 dx %*s lags %*d c %lf theory %lf error %lf%%", &c, &c_theory,
                          &c_error), 3);
    EXPECT_NEAR(t1, kPeriod, 1e-3);
    EXPECT_NEAR(theory, kBiesel, 1e-4);
    // Sampled 0.02 s apart: a crest is missed by at most 1 - cos(omega 0.01), 0.1%.
    EXPECT_NEAR(h1, height, 0.002 * height);
    EXPECT_NEAR(c_theory, kCelerity, 1e-4);
    EXPECT_NEAR(c, celerity, 0.005 * celerity);
    // The errors, to the printed figures' rounding.
    EXPECT_NEAR(error, 100 * (height / kBiesel - 1), 0.2);
    EXPECT_NEAR(c_error, 100 * (celerity / kCelerity - 1), 0.6);
  }
}

}  // namespace
}  // namespace bw

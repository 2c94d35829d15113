// The accuracy study, reduced: Martin & Moyce's dam break (examples/martin-moyce.toml)
// over the experiment's front series at two spacings a factor of two apart, measured
// as `make -f Makefile.scenes study` measures it. Halving the spacing must lower the
// front's error. The full study is docs/validation.md.
#include <string>

#include <gtest/gtest.h>

#include "study_checks.h"
#include "test_support.h"

namespace bw {
namespace {

// The experiment's last front point is at T = 3.33, t = 0.238 s for a = 0.1 m.
constexpr double kEnd = 0.25;
// Front among the particles within this height of the floor (Makefile.scenes's
// STUDY_FRONT_BAND), measured to the particles' outer edges.
constexpr double kBand = 0.02;

struct FrontError {
  double rms = 0, wall = 0;
  int points = 0;
};

FrontError front_error(const test::TempDir& dir, double spacing) {
  const std::string s = std::to_string(spacing);
  const std::string particles = dir.file("channel-" + s + ".h5");
  const auto sampled = test::run(test::tool("bw-sample") + " " + BW_SOURCE_DIR + "/examples/meshes/channel.obj -o " +
                                 particles + " --spacing " + s);
  EXPECT_EQ(sampled.exit_code, 0) << sampled.err;
  const std::string out = dir.file("run-" + s);
  const auto r = test::run(test::tool("bw-sim") + " " + BW_SOURCE_DIR + "/examples/martin-moyce.toml -o " + out +
                           " --quiet --set spacing=" + s + " --set 'solid[0].particles=" + particles +
                           "' --set time.end=" + std::to_string(kEnd));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  analysis::DamBreakSetup setup;
  setup.column_width = 0.1;
  setup.wall = setup.floor = -0.5 * spacing;
  setup.band = kBand + 0.5 * spacing;
  const auto e = study::dambreak_error(out, setup, std::string(BW_SOURCE_DIR) + "/examples/data/martin-moyce-1952.csv");
  return {e.front.rms, study::read_indicators(out).wall_time, e.front.points};
}

TEST(Study, FrontErrorFallsWhenTheSpacingIsHalved) {
  test::TempDir dir;
  const FrontError coarse = front_error(dir, 0.02);
  const FrontError fine = front_error(dir, 0.01);
  test::figure("front RMS (a) at spacing 0.02 m", coarse.rms);
  test::figure("front RMS (a) at spacing 0.01 m", fine.rms);
  test::figure("wall time at 0.02 m", coarse.wall, "s");
  test::figure("wall time at 0.01 m", fine.wall, "s");
  EXPECT_EQ(coarse.points, 15) << "every point of the experiment's front series";
  EXPECT_EQ(fine.points, 15);
  EXPECT_LT(fine.rms, coarse.rms);
}

}  // namespace
}  // namespace bw

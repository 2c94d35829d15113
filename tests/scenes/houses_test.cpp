// Scene 4 (examples/houses.toml) through Makefile.scenes at a reduced size: the
// weakest house breaks first, and the strongest last or not at all (issue 8,
// method.md 3: a higher FRC is a larger bond energy). Each house stands in its own
// lane of the flume and meets the same flood, so the order is the materials'.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "io/run_file.h"
#include "scenes_support.h"
#include "test_support.h"

namespace bw {
namespace {

// Scene 4 at a coarse spacing, long enough for the surge to reach the houses and
// go past them: the weakest house (the hut, FRC 0.33) breaks, and breaks first;
// the strongest (concrete, 0.97) breaks last or not at all.
TEST(Houses, WeakestBreaksFirstStrongestLast) {
  ASSERT_TRUE(test::has_breakable("houses")) << "examples/houses.toml: the houses are not breakable";
  test::TempDir out;
  const std::string spacing = "0.1";
  const std::string run_file = out.path() + "/scenes/houses/" + spacing + "-end1.5/run.h5";
  const auto made = test::make_scenes(run_file, out.path(), "SPACING=" + spacing + " END=1.5 CHECK_SEEDS=16");
  ASSERT_EQ(made.exit_code, 0) << made.out << made.err;
  const RunRecord run = read_run(run_file);
  ASSERT_EQ(run.status, "complete");

  // The first fracture event of each house, by solid name.
  const double never = std::numeric_limits<double>::infinity();
  std::map<std::string, double> first;
  for (const char* house : {"hut", "brick", "warehouse", "concrete"}) first[house] = never;
  for (const FractureEvent& e : run.fractures) {
    ASSERT_GE(e.parent, 0);
    ASSERT_LT(static_cast<std::size_t>(e.parent), run.bodies.size());
    const auto solid = static_cast<std::size_t>(run.bodies[static_cast<std::size_t>(e.parent)].solid);
    ASSERT_LT(solid, run.solids.size());
    auto it = first.find(run.solids[solid].name);
    ASSERT_NE(it, first.end()) << "a fracture of solid '" << run.solids[solid].name << "'";
    it->second = std::min(it->second, e.time);
  }
  for (const auto& [house, time] : first)
    test::figure("first fracture of " + house, std::isinf(time) ? -1 : time, "s (-1: never)");

  ASSERT_LT(first["hut"], never) << "the weakest house (FRC 0.33) does not break";
  for (const char* house : {"brick", "warehouse", "concrete"})
    EXPECT_LT(first["hut"], first[house]) << "the hut breaks first; " << house << " broke at " << first[house] << " s";
  for (const char* house : {"hut", "brick", "warehouse"})
    EXPECT_TRUE(std::isinf(first["concrete"]) || first["concrete"] > first[house])
        << "concrete breaks last or not at all: at " << first["concrete"] << " s, " << house << " at "
        << first[house] << " s";
}

}  // namespace
}  // namespace bw

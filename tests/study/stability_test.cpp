// The stability suite, reduced (tests/study/stability.cases, the "reduced" columns):
// every case that is not pending runs through bw-sim at a coarse spacing and must
// pass the checks of study_checks.h (stable; leaks: all but keeping its particles
// in, a known failure), or be refused with the message its line names. The full cases are `make -f Makefile.scenes stability`.
#include <cctype>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "study_checks.h"
#include "test_support.h"

namespace bw {
namespace {

struct Case {
  std::string name, expect, scene;
  std::vector<std::string> solids;
  std::string spacing, options;
};

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  const auto b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// The cases of the suite's file, with their reduced spacing and options.
std::vector<Case> read_cases() {
  const std::string path = std::string(BW_SOURCE_DIR) + "/tests/study/stability.cases";
  std::ifstream in(path);
  std::vector<Case> cases;
  std::string line;
  while (std::getline(in, line)) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, '|');) fields.push_back(trim(f));
    if (fields.size() != 8) {
      ADD_FAILURE() << path << ": expected 8 fields separated by '|': " << line;
      continue;
    }
    Case c{fields[0], fields[1], fields[2], {}, fields[6], fields[7]};
    std::stringstream solids(fields[3]);
    for (std::string s; solids >> s;) c.solids.push_back(s);
    cases.push_back(c);
  }
  return cases;
}

// Test names and failure messages show the case's name, not its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class Stability : public testing::TestWithParam<Case> {};

TEST_P(Stability, Case) {
  const Case& c = GetParam();
  if (c.expect == "pending") GTEST_SKIP() << c.name << " waits for a later version (docs/validation.md)";
  test::TempDir dir;
  std::string sets = " --set spacing=" + c.spacing;
  for (std::size_t i = 0; i < c.solids.size(); ++i) {
    const std::string particles = dir.file(c.solids[i] + ".h5");
    const auto sampled = test::run(test::tool("bw-sample") + " " + BW_SOURCE_DIR + "/examples/meshes/" + c.solids[i] +
                                   ".obj -o " + particles + " --spacing " + c.spacing + " --volume");
    ASSERT_EQ(sampled.exit_code, 0) << sampled.err;
    sets += " --set 'solid[" + std::to_string(i) + "].particles=" + particles + "'";
  }
  const auto r = test::run(test::tool("bw-sim") + " " + BW_SOURCE_DIR + "/" + c.scene + " -o " + dir.file("run") +
                           " --quiet" + sets + " " + c.options);
  if (c.expect.rfind("refused:", 0) == 0) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect.substr(8)), std::string::npos) << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_FALSE(test::exists(dir.file("run/run.h5"))) << "a refused scene writes nothing";
    return;
  }
  ASSERT_TRUE(c.expect == "stable" || c.expect == "leaks") << "unknown expectation " << c.expect;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const study::StabilityReport report = study::check_stability(dir.file("run"), {});
  test::figure(c.name + ": steps", report.run.steps);
  test::figure(c.name + ": wall time", report.run.wall_time, "s");
  test::figure(c.name + ": worst density error", report.run.density_error_worst);
  test::figure(c.name + ": energy drift (of the initial total)", report.run.energy_drift);
  test::figure(c.name + ": energy rise above the initial total", report.run.energy_growth);
  test::figure(c.name + ": particle positions inside solids", static_cast<double>(report.inside_solids));
  test::figure(c.name + ": particles lost", report.run.removed);
  for (const std::string& f : report.failures) ADD_FAILURE() << c.name << ": " << f;
  // A case expected to leak (a known failure of the solver, docs/validation.md) is
  // held to everything else.
  if (c.expect == "stable")
    for (const std::string& l : report.leaks) ADD_FAILURE() << c.name << ": " << l;
}

INSTANTIATE_TEST_SUITE_P(Suite, Stability, testing::ValuesIn(read_cases()),
                         [](const testing::TestParamInfo<Case>& param) {
                           std::string name = param.param.name;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace bw

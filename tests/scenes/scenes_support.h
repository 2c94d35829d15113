// Running Makefile.scenes from the tests: the source folder's Makefile with the
// tools of this build (NO_BUILD=1), into a folder of the test's.
#pragma once

#include <fstream>
#include <regex>
#include <string>

#include "test_support.h"

namespace bw::test {

// `make -f Makefile.scenes TARGET OUT=out OPTIONS` in the source folder, two jobs.
inline CommandResult make_scenes(const std::string& target, const std::string& out, const std::string& options) {
  return run("make -C " + std::string(BW_SOURCE_DIR) + " -f Makefile.scenes --no-print-directory -j 2 " + target +
             " BUILD=" + BW_BUILD_DIR + " NO_BUILD=1 OUT=" + out + " " + options);
}

// True when examples/NAME.toml has a breakable solid (a line `breakable = true`).
inline bool has_breakable(const std::string& name) {
  std::ifstream in(std::string(BW_SOURCE_DIR) + "/examples/" + name + ".toml");
  static const std::regex line(R"(^\s*breakable\s*=\s*true\b.*)");
  for (std::string l; std::getline(in, l);)
    if (std::regex_match(l, line)) return true;
  return false;
}

}  // namespace bw::test

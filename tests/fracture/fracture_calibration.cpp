// The fracture calibration (docs/scene.md, "Fracture"): the tests' breakable wall
// (0.06 x 0.3 x 0.3 m at 0.02 m, on a floor) hit by a 0.12 m cube of water along x at
// each speed, with the strong wall's material (frc 0.97) and the fragile plate's
// (0.45). Prints, per material and speed, whether it broke, when (after the water
// reached the wall) and into how many fragments. A study: prints figures, asserts
// nothing.
//   fracture-calibration [--speeds 2,3,4,5,6,8] [--set KEY=VALUE ...]
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/error.h"
#include "fracture_fixtures.h"

int main(int argc, char** argv) {
  CLI::App app("The fracture calibration: the tests' wall hit by a cube of water at each speed, for the strong "
               "wall's material (frc 0.97) and the fragile plate's (0.45)");
  std::vector<double> speeds = {2, 3, 4, 5, 6, 8};
  std::vector<std::string> sets;
  app.add_option("--speeds", speeds, "Impact speeds (m/s)")->delimiter(',')->capture_default_str();
  app.add_option("--set", sets, "Scene keys for every run, KEY=VALUE as TOML (e.g. fluid.density=\"summation\")");
  CLI11_PARSE(app, argc, argv);
  // --set KEY=VALUE: appended under the key's table, as bw-sim's --set would set it.
  std::string extra;
  for (const std::string& s : sets) {
    const std::size_t eq = s.find('='), dot = s.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq) {
      fmt::print(stderr, "fracture-calibration: --set {}: expected TABLE.KEY=VALUE\n", s);
      return 2;
    }
    extra += fmt::format("[{}]\n{}\n", s.substr(0, dot), s.substr(dot + 1));
  }
  const double gap = 0.08;    // m between the block and the wall (the fixture's default)
  const double after = 0.03;  // s of the run after the water reaches the wall
  fmt::print("| frc | speed (m/s) | broke | first fracture after contact (ms) | fragments |\n|---|---|---|---|---|\n");
  try {
    for (const double frc : {0.97, 0.45}) {
      for (const double v : speeds) {
        const double contact = gap / v, end = contact + after;
        const bw::test::FractureOutcome o = bw::test::run_fracture_scene(bw::test::fracture_scene(v, frc, end, extra, gap), end);
        fmt::print("| {} | {} | {} | {} | {} |\n", frc, v, o.first >= 0 ? "yes" : "no",
                   o.first >= 0 ? fmt::format("{:.1f}", 1e3 * (o.first - contact)) : "", bw::test::fragments(o));
        std::fflush(stdout);
      }
    }
  } catch (const bw::Error& e) {
    fmt::print(stderr, "fracture-calibration: {}\n", e.what());
    return 2;
  }
  return 0;
}

// study-record: one CSV row of what the accuracy study and the stability suite
// measure on a finished run (study_checks.h), for Makefile.scenes's study and
// stability targets. `--header` prints the column names instead.
//
//   study-record dambreak RUN --width 0.1 --band 0.02 --reference examples/data/martin-moyce-1952.csv
//   study-record hydrostatic RUN --point 0.05,0.05,0.05 --surface 0.2 --from 1.5
//   study-record stability RUN [--expect leaks]   (exit status 3 when a check fails)
//
// Common columns: status (complete, or stopped when the run ended on an error),
// wall_time (s), steps, simulated (s), fluid, removed, density_error_worst,
// energy_drift, energy_growth, spacing (m), c0 (m/s); then the mode's own:
// dambreak: front_rms, front_max (a), front_points, residual_rms (2a),
//   residual_points, front_shift (the delay dT of the experiment behind the run that
//   explains most of the front's error), front_rms_shifted (the RMS left after it)
//   and front_vs_finest (the RMS difference from the front of --finest, NaN without);
// hydrostatic: pressure, expected (Pa), pressure_error (relative), frames, and the
//   scene's floor sensor: floor_pressure, floor_expected (Pa), floor_error (relative;
//   NaN without a [[sensor]] named floor);
// stability: frames, nonfinite, outside_domain, inside_solids, verdict (stable;
//   leaks: only particles crossing solids or leaving the domain, as --expect leaks
//   allows; FAILED).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli/tool.h"
#include "study_checks.h"

namespace {

const char* kCommon = "status,wall_time,steps,simulated,fluid,removed,density_error_worst,energy_drift,energy_growth,"
                      "spacing,c0";

void print_common(const bw::study::RunIndicators& r) {
  std::printf("%s,%.6g,%.0f,%.6g,%.0f,%.0f,%.6g,%.6g,%.6g,%.6g,%.6g", r.complete() ? "complete" : "stopped",
              r.wall_time, r.steps, r.simulated_time, r.fluid, r.removed, r.density_error_worst, r.energy_drift,
              r.energy_growth, r.spacing, r.c0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"One CSV row of a finished run's cost, error and stability indicators (docs/validation.md).",
               "study-record"};
  bw::cli::setup(app,
                 "  study-record dambreak out/run --width 0.1 --band 0.02 --reference examples/data/martin-moyce-1952.csv\n"
                 "  study-record hydrostatic out/run --point 0.05,0.05,0.05 --surface 0.2 --from 1.5\n"
                 "  study-record stability out/run\n"
                 "  study-record stability --header\n");
  app.require_subcommand(1);
  std::string run;
  bool header = false;
  auto common = [&](CLI::App* sub) {
    sub->add_option("run", run, "Run folder (bw-sim -o): run.h5 and frames/");
    sub->add_flag("--header", header, "Print the column names and nothing else");
  };

  bw::analysis::DamBreakSetup dambreak;
  std::string reference;
  CLI::App* db = app.add_subcommand("dambreak", "Front and residual RMS against Martin & Moyce (bw-measure dambreak)");
  common(db);
  db->add_option("--width", dambreak.column_width, "Column width a (m)")->check(bw::cli::kPositive);
  db->add_option("--wall", dambreak.wall, "x of the back wall (m)");
  db->add_option("--floor", dambreak.floor, "z of the floor (m)");
  db->add_option("--band", dambreak.band, "Particles this close to the floor or wall count (m)")->check(bw::cli::kPositive);
  db->add_option("--reference", reference, "The experiment's CSV")->check(CLI::ExistingFile);
  std::string finest;
  double finest_spacing = 0;
  db->add_option("--finest", finest, "A run of the same scene at a finer spacing: the front_vs_finest column")
      ->check(CLI::ExistingDirectory);
  db->add_option("--finest-spacing", finest_spacing, "Its spacing (m): its front is measured to its particles' edges")
      ->check(bw::cli::kPositive);

  std::vector<double> point;
  double surface = 0, radius = 0, from = -1;
  CLI::App* hs = app.add_subcommand("hydrostatic", "Pressure at a point against rho0 g d");
  common(hs);
  hs->add_option("--point", point, "x,y,z of the probe (m)")->delimiter(',')->expected(3);
  hs->add_option("--surface", surface, "Height of the resting surface (m)");
  hs->add_option("--radius", radius, "Probe radius (m); default the run's smoothing length")->check(bw::cli::kPositive);
  hs->add_option("--from", from, "Average the frames at or after this time (s); default half the run");

  bw::study::StabilityLimits limits;
  std::string expect = "stable";
  CLI::App* st = app.add_subcommand("stability", "The stability checks; exit status 3 when one fails");
  common(st);
  st->add_option("--expect", expect, "stable, or leaks: particles crossing solids or leaving the domain are reported, "
                                     "not failed (a known failure, tests/study/stability.cases)")
      ->check(CLI::IsMember({"stable", "leaks"}))
      ->capture_default_str();
  st->add_option("--density-error", limits.density_error, "Largest worst density error")->capture_default_str();
  st->add_option("--energy-growth", limits.energy_growth, "Largest relative rise of the total energy")
      ->capture_default_str();

  return bw::cli::run(app, argc, argv, [&]() -> int {
    if (header) {
      if (db->parsed())
        std::printf("%s,front_rms,front_max,front_points,residual_rms,residual_points,front_shift,front_rms_shifted,"
                    "front_vs_finest\n",
                    kCommon);
      if (hs->parsed()) std::printf("%s,pressure,expected,pressure_error,frames,floor_pressure,floor_expected,floor_error\n", kCommon);
      if (st->parsed()) std::printf("%s,frames,nonfinite,outside_domain,inside_solids,verdict\n", kCommon);
      return bw::kExitOk;
    }
    if (run.empty()) bw::fail_input("no run folder given (see --help)");
    if (db->parsed()) {
      if (!(dambreak.column_width > 0) || !(dambreak.band > 0) || reference.empty())
        bw::fail_input("dambreak: --width, --band and --reference are required");
      const auto r = bw::study::read_indicators(run);
      const auto d = bw::study::dambreak_error(run, dambreak, reference);
      const auto& e = d.comparison;
      double vs_finest = std::numeric_limits<double>::quiet_NaN();
      // The finest run has no error against itself: nan, not 0.
      if (!finest.empty() && !std::filesystem::equivalent(finest, run)) {
        if (!(finest_spacing > 0)) bw::fail_input("dambreak: --finest needs --finest-spacing");
        bw::analysis::DamBreakSetup other = dambreak;
        // The same convention as this run's: its --wall, --floor and --band move by
        // the change of half a spacing.
        const double shift = 0.5 * (finest_spacing - r.spacing);
        other.wall -= shift;
        other.floor -= shift;
        other.band += shift;
        vs_finest = bw::study::front_difference(run, dambreak, finest, other, reference);
      }
      print_common(r);
      std::printf(",%.6g,%.6g,%d,%.6g,%d,%.3g,%.6g,%.6g\n", e.front.rms, e.front.max, e.front.points, e.residual.rms,
                  e.residual.points, d.front_shift, d.front_rms_shifted, vs_finest);
      return bw::kExitOk;
    }
    if (hs->parsed()) {
      if (point.size() != 3 || !(surface > 0)) bw::fail_input("hydrostatic: --point and --surface are required");
      const auto r = bw::study::read_indicators(run);
      const double start = from >= 0 ? from : 0.5 * r.simulated_time;
      const auto e = bw::study::hydrostatic_error(run, {point[0], point[1], point[2]}, surface,
                                                  radius > 0 ? radius : r.h, start);
      print_common(r);
      std::printf(",%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g\n", e.pressure, e.expected, e.relative, e.frames, e.floor_pressure,
                  e.floor_expected, e.floor_relative);
      return bw::kExitOk;
    }
    const auto report = bw::study::check_stability(run, limits);
    const bool passed = report.failures.empty() && (expect == "leaks" || report.leaks.empty());
    print_common(report.run);
    std::printf(",%d,%ld,%ld,%ld,%s\n", report.frames, report.nonfinite, report.outside_domain, report.inside_solids,
                !passed ? "FAILED" : report.stable() ? "stable" : "leaks");
    for (const auto* lines : {&report.failures, &report.leaks})
      for (const std::string& line : *lines) std::fprintf(stderr, "study-record: %s: %s\n", run.c_str(), line.c_str());
    return passed ? bw::kExitOk : bw::kExitCheckFailed;
  });
}

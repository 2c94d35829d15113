// bw-measure: measurements on simulated frames, for validation and for users who
// compare with experiments: dam-break front and residual height, pressure and
// velocity probes, wave gauges.
#include <cmath>
#include <cstdio>

#include "analysis/dambreak.h"
#include "analysis/measure.h"
#include "cli/tool.h"
#include "common/report.h"

namespace {

using bw::analysis::list_frames;

struct Options {
  std::string frames;
  bool json = false;
  // dambreak
  bw::analysis::DamBreakSetup dambreak;
  std::string reference;
  // probe and gauge
  std::vector<double> point;
  std::string field = "p";
  double radius = 0;
};

void print_rows(const Options& o, const std::vector<std::string>& columns, const std::vector<std::vector<double>>& rows,
                bw::Report* extra) {
  if (o.json) {
    bw::Report report;
    report.set("frames", o.frames);
    report.set("series", bw::Report::Table{columns, rows});
    if (extra) report.child("comparison") = *extra;
    std::fputs(report.to_json().c_str(), stdout);
    return;
  }
  for (std::size_t c = 0; c < columns.size(); ++c) std::printf("%s%s", c ? "," : "", columns[c].c_str());
  std::printf("\n");
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) std::printf("%s%.9g", c ? "," : "", row[c]);
    std::printf("\n");
  }
}

int run_dambreak(const Options& o) {
  std::vector<bw::analysis::DamBreakSample> samples;
  std::vector<std::vector<double>> rows;
  const double a = o.dambreak.column_width, g = o.dambreak.gravity;
  for (const std::string& path : list_frames(o.frames)) {
    const auto s = bw::analysis::measure_dambreak(bw::read_frame(path), o.dambreak);
    samples.push_back(s);
    rows.push_back({s.time, s.front, s.residual, s.time * std::sqrt(2 * g / a), s.front / a, s.time * std::sqrt(g / a),
                    s.residual / (2 * a)});
  }
  const std::vector<std::string> columns = {"time", "front", "residual", "T_front", "Z", "T_residual", "H"};
  if (o.reference.empty()) {
    print_rows(o, columns, rows, nullptr);
    return bw::kExitOk;
  }
  const auto reference = bw::analysis::read_dambreak_reference(o.reference);
  const auto cmp = bw::analysis::compare_dambreak(samples, o.dambreak, reference);
  bw::Report comparison;
  comparison.set("reference", o.reference);
  for (auto [name, e] : {std::pair{"front", cmp.front}, std::pair{"residual", cmp.residual}}) {
    bw::Report& r = comparison.child(name);
    r.set("rms", e.rms);
    r.set("max", e.max);
    r.set("points", e.points);
    r.set("skipped", e.skipped);
  }
  print_rows(o, columns, rows, &comparison);
  if (!o.json) {
    std::fprintf(stderr,
                 "bw-measure: against %s: front RMS %.4f a (max %.4f, %d points, %d beyond the run), "
                 "residual RMS %.4f (2a) (max %.4f, %d points, %d beyond)\n",
                 o.reference.c_str(), cmp.front.rms, cmp.front.max, cmp.front.points, cmp.front.skipped,
                 cmp.residual.rms, cmp.residual.max, cmp.residual.points, cmp.residual.skipped);
  }
  return bw::kExitOk;
}

int run_probe(const Options& o, bool gauge) {
  std::vector<std::vector<double>> rows;
  const bw::analysis::Field field = bw::analysis::parse_field(o.field);
  for (const std::string& path : list_frames(o.frames)) {
    const bw::FrameData frame = bw::read_frame(path);
    const double value = gauge ? bw::analysis::surface_elevation(frame, o.point[0], o.point[1], o.radius)
                               : bw::analysis::probe(frame, field, {o.point[0], o.point[1], o.point[2]}, o.radius);
    rows.push_back({frame.time, value});
  }
  print_rows(o, {"time", gauge ? "elevation" : bw::analysis::field_name(field)}, rows, nullptr);
  return bw::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measure simulated frames: dam-break front and residual height against Martin & Moyce,\n"
               "field probes and wave gauges. Prints CSV (or JSON) on standard output.",
               "bw-measure"};
  bw::cli::setup(app,
                 "  bw-measure dambreak out/frames --width 0.1 --band 0.01 --reference examples/data/martin-moyce-1952.csv\n"
                 "  bw-measure probe out/frames --point 0.3,0.05,0.01 --field p --radius 0.02\n"
                 "  bw-measure gauge out/frames --at 0.5,0.05 --radius 0.01 --json\n");
  app.require_subcommand(1);
  Options o;
  auto frames_option = [&](CLI::App* sub) {
    sub->add_option("frames", o.frames, "Folder of frame files (OUTDIR/frames of bw-sim)")->required();
    sub->add_flag("--json", o.json, "Print JSON instead of CSV");
  };

  CLI::App* dambreak = app.add_subcommand("dambreak", "Surge front and residual column height of a dam break");
  frames_option(dambreak);
  dambreak->add_option("--width", o.dambreak.column_width, "Width a of the released column (m)")
      ->required()
      ->check(bw::cli::kPositive);
  dambreak->add_option("--wall", o.dambreak.wall, "x of the back wall the column stands against (m)");
  dambreak->add_option("--floor", o.dambreak.floor, "z of the floor (m)");
  dambreak->add_option("--band", o.dambreak.band, "Particles this close to the floor or wall count (m); ~2 spacings")
      ->required()
      ->check(bw::cli::kPositive);
  dambreak->add_option("--gravity", o.dambreak.gravity, "Gravity (m/s^2)")->check(bw::cli::kPositive);
  dambreak->add_option("--reference", o.reference, "CSV of the experiment (series,T,value) to compare with")
      ->check(CLI::ExistingFile);

  CLI::App* probe = app.add_subcommand("probe", "A field at a point, kernel-averaged over the fluid particles");
  frames_option(probe);
  probe->add_option("--point", o.point, "x,y,z of the probe (m)")->required()->delimiter(',')->expected(3);
  probe->add_option("--field", o.field, "p, rho, speed, vx, vy or vz");
  probe->add_option("--radius", o.radius, "Kernel support (m), e.g. the smoothing length h")
      ->required()
      ->check(bw::cli::kPositive);

  CLI::App* gauge = app.add_subcommand("gauge", "Free-surface elevation on a vertical line");
  frames_option(gauge);
  gauge->add_option("--at", o.point, "x,y of the gauge (m)")->required()->delimiter(',')->expected(2);
  gauge->add_option("--radius", o.radius, "Particles within this distance of the line count (m)")
      ->required()
      ->check(bw::cli::kPositive);

  return bw::cli::run(app, argc, argv, [&] {
    if (dambreak->parsed()) return run_dambreak(o);
    if (probe->parsed()) return run_probe(o, false);
    return run_probe(o, true);
  });
}

// bw-measure: measurements on simulated frames, for validation and for users who
// compare with experiments: dam-break front and residual height, pressure and
// velocity probes, pressure sensors on solids' faces, loads on solids, the pressure
// on a solid's surface, wave gauges.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include <fmt/ranges.h>

#include "analysis/dambreak.h"
#include "analysis/measure.h"
#include "cli/tool.h"
#include "common/error.h"
#include "common/report.h"
#include "io/run_file.h"

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
  // gauge
  std::vector<std::string> gauges;  // NAME=x,y or x,y
  double gap = 0;                   // 0: 2 radius
  double bottom = -std::numeric_limits<double>::infinity();
  // sensor
  std::vector<std::string> sensors;  // NAME=x,y,z or x,y,z
  std::vector<double> normal{1, 0, 0};
  double h = 0, offset = -1, rho0 = 998;
  std::vector<double> gravity{0, 0, -9.81};
  // loads and wall
  std::string solid;
  std::string run;  // wall: the run file (default FRAMES/../run.h5)
  // sensors
  std::vector<std::string> names;
  double window = 0;
};

// "NAME=coords" or "coords": the name (`unnamed` without one) and the coordinates.
std::pair<std::string, std::string> split_named(const std::string& text, std::string unnamed) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) return {std::move(unnamed), text};
  return {text.substr(0, eq), text.substr(eq + 1)};
}

// "NAME=x,y,z" or "x,y,z" (named S1, S2, ... by position).
bw::analysis::Sensor parse_sensor(const std::string& text, std::size_t index) {
  bw::analysis::Sensor s;
  const auto [name, coords] = split_named(text, "S" + std::to_string(index + 1));
  s.name = name;
  double v[3];
  char tail = 0;
  if (s.name.empty() || std::sscanf(coords.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) != 3 ||
      !std::isfinite(v[0] + v[1] + v[2]))
    bw::fail_input("--at '{}': expected NAME=x,y,z or x,y,z (m), finite numbers", text);
  s.point = {v[0], v[1], v[2]};
  return s;
}

// "NAME=x,y" or "x,y": a gauge's line. One unnamed gauge is the column "elevation";
// among several, unnamed ones are G1, G2, ... by position.
struct GaugeLine {
  std::string name;
  double x = 0, y = 0;
};
std::vector<GaugeLine> parse_gauges(const std::vector<std::string>& texts) {
  std::vector<GaugeLine> lines;
  for (std::size_t k = 0; k < texts.size(); ++k) {
    GaugeLine g;
    const auto [name, coords] = split_named(texts[k], texts.size() == 1 ? "elevation" : "G" + std::to_string(k + 1));
    g.name = name;
    char tail = 0;
    if (g.name.empty() || std::sscanf(coords.c_str(), "%lf,%lf%c", &g.x, &g.y, &tail) != 2 ||
        !std::isfinite(g.x + g.y))
      bw::fail_input("--at '{}': expected NAME=x,y or x,y (m), finite numbers", texts[k]);
    for (const GaugeLine& other : lines)
      if (other.name == g.name)
        bw::fail_input("--at '{}': a second gauge named {}; the columns need names of their own", texts[k], g.name);
    lines.push_back(g);
  }
  return lines;
}

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

int run_probe(const Options& o) {
  std::vector<std::vector<double>> rows;
  const bw::analysis::Field field = bw::analysis::parse_field(o.field);
  for (const std::string& path : list_frames(o.frames)) {
    const bw::FrameData frame = bw::read_frame(path);
    rows.push_back({frame.time, bw::analysis::probe(frame, field, {o.point[0], o.point[1], o.point[2]}, o.radius)});
  }
  print_rows(o, {"time", bw::analysis::field_name(field)}, rows, nullptr);
  return bw::kExitOk;
}

// Every gauge of one pass over the frames: a frame is read once.
int run_gauge(const Options& o) {
  const std::vector<GaugeLine> lines = parse_gauges(o.gauges);
  const double gap = o.gap > 0 ? o.gap : 2 * o.radius;
  std::vector<std::string> columns{"time"};
  for (const GaugeLine& g : lines) columns.push_back(g.name);
  std::vector<std::vector<double>> rows;
  for (const std::string& path : list_frames(o.frames)) {
    const bw::FrameData frame = bw::read_frame(path);
    std::vector<double> row{frame.time};
    for (const GaugeLine& g : lines)
      row.push_back(bw::analysis::surface_elevation(frame, g.x, g.y, o.radius, gap, o.bottom));
    rows.push_back(std::move(row));
  }
  print_rows(o, columns, rows, nullptr);
  return bw::kExitOk;
}

// The load history of one solid from the run file's /loads: per frame the impulse
// since t = 0 and the mean force since the previous frame.
int run_loads(const Options& o) {
  const bw::RunRecord run = bw::read_run(o.frames);
  if (run.loads.empty())
    bw::fail_input("{}: holds no loads; set `loads = true` in the scene's [output] and run it again", o.frames);
  std::size_t solid = run.solids.size();
  std::string names;
  for (std::size_t k = 0; k < run.solids.size(); ++k) {
    if (run.solids[k].name == o.solid) solid = k;
    names += (k ? ", " : "") + run.solids[k].name;
  }
  if (solid == run.solids.size()) bw::fail_input("--solid '{}': {} has no such solid ({})", o.solid, o.frames, names);
  std::vector<std::vector<double>> rows;
  for (std::size_t f = 0; f < run.loads.size(); ++f) {
    const Eigen::Vector3d impulse = run.loads[f][solid];
    Eigen::Vector3d force = Eigen::Vector3d::Constant(std::nan(""));
    if (f > 0 && run.frames[f].time > run.frames[f - 1].time)
      force = (impulse - run.loads[f - 1][solid]) / (run.frames[f].time - run.frames[f - 1].time);
    rows.push_back({run.frames[f].time, force.x(), force.y(), force.z(), impulse.x(), impulse.y(), impulse.z()});
  }
  print_rows(o, {"time", "fx", "fy", "fz", "ix", "iy", "iz"}, rows, nullptr);
  return bw::kExitOk;
}

// The pressure histories of the scene's [[sensor]]s from the run file's /sensors:
// per sample, or averaged over windows of whole samples.
int run_sensors(const Options& o) {
  const bw::RunRecord run = bw::read_run(o.frames);
  const bw::SensorRecord& r = run.sensors;
  if (r.names.empty())
    bw::fail_input("{}: holds no sensors; add [[sensor]] tables to the scene (docs/scene.md, \"Sensors\") and run it "
                   "again",
                   o.frames);
  std::vector<std::size_t> chosen;
  std::vector<std::string> columns{"time"};
  const std::vector<std::string> wanted = o.names.empty() ? r.names : o.names;
  for (const std::string& name : wanted) {
    const auto it = std::find(r.names.begin(), r.names.end(), name);
    if (it == r.names.end())
      bw::fail_input("--sensor '{}': {} has no such sensor ({})", name, o.frames, fmt::join(r.names, ", "));
    chosen.push_back(static_cast<std::size_t>(it - r.names.begin()));
    columns.push_back(name);
  }
  std::size_t per = 1;
  if (o.window > 0) {
    const double ratio = o.window / r.interval;
    per = static_cast<std::size_t>(std::llround(ratio));
    if (per < 1 || std::abs(ratio - static_cast<double>(per)) > 1e-6 * ratio)
      bw::fail_input("--window {}: not a whole number of the run's samples of {} s", o.window, r.interval);
    if (per > r.samples())
      bw::fail_input("--window {}: longer than the {} s that {} recorded", o.window,
                     static_cast<double>(r.samples()) * r.interval, o.frames);
  }
  const std::size_t ns = r.names.size();
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k + per <= r.samples(); k += per) {
    std::vector<double> row{(static_cast<double>(k) + 0.5 * static_cast<double>(per)) * r.interval};
    for (std::size_t c : chosen) {
      double sum = 0;
      for (std::size_t j = k; j < k + per; ++j) sum += r.pressure[j * ns + c];
      row.push_back(sum / static_cast<double>(per));
    }
    rows.push_back(std::move(row));
  }
  print_rows(o, columns, rows, nullptr);
  return bw::kExitOk;
}

// The wall pressure on one solid, frame by frame: its peak and where, the mean over the
// loaded patches and how many there are.
int run_wall(const Options& o) {
  const std::string run_path = o.run.empty() ? o.frames + "/../run.h5" : o.run;
  const bw::RunRecord run = bw::read_run(run_path);
  int solid = -1;
  std::string names;
  for (std::size_t k = 0; k < run.solids.size(); ++k) {
    if (run.solids[k].name == o.solid) solid = static_cast<int>(k);
    names += (k ? ", " : "") + run.solids[k].name;
  }
  if (solid < 0) bw::fail_input("--solid '{}': {} has no such solid ({})", o.solid, run_path, names);
  std::vector<std::vector<double>> rows;
  for (const std::string& path : list_frames(o.frames)) {
    const bw::FrameData frame = bw::read_frame_boundary(path);
    const bw::analysis::WallLoad w = bw::analysis::wall_load(frame, solid, path);
    rows.push_back({frame.time, w.peak, w.at.x(), w.at.y(), w.at.z(), w.mean, static_cast<double>(w.loaded)});
  }
  print_rows(o, {"time", "peak", "x", "y", "z", "mean", "loaded"}, rows, nullptr);
  return bw::kExitOk;
}

int run_sensor(const Options& o) {
  const Eigen::Vector3d normal(o.normal[0], o.normal[1], o.normal[2]);
  if (!(normal.norm() > 0)) bw::fail_input("--normal: must not be zero");
  std::vector<bw::analysis::Sensor> sensors;
  std::vector<std::string> columns{"time"};
  for (std::size_t k = 0; k < o.sensors.size(); ++k) {
    bw::analysis::Sensor s = parse_sensor(o.sensors[k], k);
    if (std::find(columns.begin() + 1, columns.end(), s.name) != columns.end())
      bw::fail_input("--at '{}': a second sensor named {}; the columns need names of their own", o.sensors[k], s.name);
    s.normal = normal.normalized();
    s.radius = o.radius;
    s.h = o.h;
    s.offset = o.offset;
    s.rho0 = o.rho0;
    s.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
    columns.push_back(s.name);
    sensors.push_back(s);
  }
  std::vector<std::vector<double>> rows;
  for (const std::string& path : list_frames(o.frames)) {
    const bw::FrameData frame = bw::read_frame(path);
    if (frame.p.empty())
      bw::fail_input("{}: holds no pressure; add \"pressure\" to the scene's [output] fields", path);
    std::vector<double> row{frame.time};
    for (const auto& s : sensors) row.push_back(bw::analysis::sensor_pressure(frame, s));
    rows.push_back(std::move(row));
  }
  print_rows(o, columns, rows, nullptr);
  return bw::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measure simulated frames: dam-break front and residual height against Martin & Moyce,\n"
               "field probes, pressure sensors on faces and wave gauges. Prints CSV (or JSON) on standard output.",
               "bw-measure"};
  bw::cli::setup(app,
                 "  bw-measure dambreak out/frames --width 0.1 --band 0.01 --reference examples/data/martin-moyce-1952.csv\n"
                 "  bw-measure probe out/frames --point 0.3,0.05,0.01 --field p --radius 0.02\n"
                 "  bw-measure gauge out/frames --at H2=0.992,0.5 --at H4=2.638,0.5 --radius 0.02 --bottom 0\n"
                 "  bw-measure sensor out/frames --at P1=0.8245,0.471,0.021 --at P2=0.8245,0.471,0.061 \\\n"
                 "      --normal 1,0,0 --radius 0.01 --h 0.04\n"
                 "  bw-measure loads out/run.h5 --solid box\n"
                 "  bw-measure sensors out/run.h5 --sensor P1 --window 0.005\n"
                 "  bw-measure wall out/frames --solid house\n");
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
  dambreak->add_option("--wall", o.dambreak.wall, "x of the back wall the column stands against (m)")
      ->check(bw::cli::kFinite);
  dambreak->add_option("--floor", o.dambreak.floor, "z of the floor (m)")->check(bw::cli::kFinite);
  dambreak->add_option("--band", o.dambreak.band, "Particles this close to the floor or wall count (m); ~2 spacings")
      ->required()
      ->check(bw::cli::kPositive);
  dambreak->add_option("--gravity", o.dambreak.gravity, "Gravity (m/s^2)")->check(bw::cli::kPositive);
  dambreak->add_option("--reference", o.reference, "CSV of the experiment (series,T,value) to compare with");

  CLI::App* probe = app.add_subcommand("probe", "A field at a point, kernel-averaged over the fluid particles");
  frames_option(probe);
  probe->add_option("--point", o.point, "x,y,z of the probe (m)")
      ->required()
      ->delimiter(',')
      ->expected(3)
      ->check(bw::cli::kFinite);
  probe->add_option("--field", o.field, "p, rho, speed, vx, vy or vz");
  probe->add_option("--radius", o.radius, "Kernel support (m), e.g. the smoothing length h")
      ->required()
      ->check(bw::cli::kPositive);

  CLI::App* sensor = app.add_subcommand(
      "sensor", "Pressure on a solid's face as a sensor of a given radius reads it (Pa, one column per sensor)");
  frames_option(sensor);
  sensor->add_option("--at", o.sensors, "NAME=x,y,z: a sensor's centre on the face (m); repeat for more sensors")
      ->required();
  sensor->add_option("--normal", o.normal, "nx,ny,nz: the face's normal, into the fluid")
      ->delimiter(',')
      ->expected(3)
      ->check(bw::cli::kFinite);
  sensor->add_option("--radius", o.radius, "Radius of the sensor's disc (m); 0: a point")->check(bw::cli::kNonNegative);
  sensor->add_option("--h", o.h, "Kernel support (m): the run's smoothing length")->required()->check(bw::cli::kPositive);
  sensor->add_option("--offset", o.offset, "Distance into the fluid the pressure is read at (m); default h/2")
      ->check(bw::cli::kNonNegative);
  sensor->add_option("--rho0", o.rho0, "Density for the hydrostatic correction over the offset (kg/m^3)")
      ->check(bw::cli::kPositive);
  sensor->add_option("--gravity", o.gravity, "gx,gy,gz (m/s^2)")->delimiter(',')->expected(3)->check(bw::cli::kFinite);

  CLI::App* loads = app.add_subcommand(
      "loads", "Force (mean since the previous frame, N) and impulse (since t = 0, N s) of the fluid on a solid");
  loads->add_option("run", o.frames, "Run file (OUTDIR/run.h5 of bw-sim, with [output] loads = true)")->required();
  loads->add_option("--solid", o.solid, "The solid's name (its [[solid]] name)")->required();
  loads->add_flag("--json", o.json, "Print JSON instead of CSV");

  CLI::App* wall = app.add_subcommand(
      "wall", "The pressure on a solid's surface from the frames' wall pressure: its peak (Pa) and where, the mean over "
              "the loaded patches");
  frames_option(wall);
  wall->add_option("--solid", o.solid, "The solid's name (its [[solid]] name; its bodies and fragments count)")
      ->required();
  wall->add_option("--run", o.run, "Run file, for the solids' names (default: FRAMES/../run.h5)");

  CLI::App* sensors = app.add_subcommand(
      "sensors", "Pressure histories of the scene's [[sensor]]s, from the forces on the faces (Pa, from the run file)");
  sensors->add_option("run", o.frames, "Run file (OUTDIR/run.h5 of bw-sim, of a scene with [[sensor]] tables)")
      ->required();
  sensors->add_option("--sensor", o.names, "A sensor's name; repeat for more (default: all)");
  sensors->add_option("--window", o.window, "Average over windows of this many seconds, whole samples (default: each sample)")
      ->check(bw::cli::kPositive);
  sensors->add_flag("--json", o.json, "Print JSON instead of CSV");

  CLI::App* gauge = app.add_subcommand(
      "gauge", "Wave gauges: the free-surface elevation on vertical lines (m, one column per gauge)");
  frames_option(gauge);
  gauge->add_option("--at", o.gauges, "NAME=x,y (or x,y) of a gauge's vertical line (m); repeat for more")->required();
  gauge->add_option("--radius", o.radius, "Particles within this distance of the line count (m)")
      ->required()
      ->check(bw::cli::kPositive);
  gauge->add_option("--gap", o.gap,
                    "The water column ends at the first vertical gap between the line's particles wider than "
                    "this: spray over the water does not count (m; default 2 x radius)")
      ->check(bw::cli::kPositive);
  gauge->add_option("--bottom", o.bottom,
                    "The floor under the gauge (m): the line is dry (NaN) until a particle lies within --gap of it "
                    "(default: the column starts at its lowest particle)")
      ->check(bw::cli::kFinite);

  return bw::cli::run(app, argc, argv, [&] {
    if (dambreak->parsed()) return run_dambreak(o);
    if (probe->parsed()) return run_probe(o);
    if (sensor->parsed()) return run_sensor(o);
    if (loads->parsed()) return run_loads(o);
    if (sensors->parsed()) return run_sensors(o);
    if (wall->parsed()) return run_wall(o);
    return run_gauge(o);
  });
}

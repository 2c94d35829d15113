#include "analysis/dambreak.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/text.h"

namespace bw::analysis {

DamBreakSample measure_dambreak(const FrameData& frame, const DamBreakSetup& setup) {
  DamBreakSample s;
  s.time = frame.time;
  double front = -std::numeric_limits<double>::infinity();
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < frame.x.size(); ++i) {
    const double x = frame.x[i] - setup.wall;
    const double z = frame.z[i] - setup.floor;
    if (z <= setup.band) front = std::max(front, x);
    if (x <= setup.band) top = std::max(top, z);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.front = std::isfinite(front) ? front : nan;
  s.residual = std::isfinite(top) ? top : nan;
  return s;
}

DamBreakReference read_dambreak_reference(const std::string& csv_path) {
  std::istringstream in(read_text_file(csv_path, "a reference CSV"));
  DamBreakReference ref;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("series,T,value", 0) != 0) fail_input("{}:{}: expected the header 'series,T,value'", csv_path, number);
      header = true;
      continue;
    }
    std::stringstream row(line);
    std::string series, t_text, v_text;
    std::getline(row, series, ',');
    std::getline(row, t_text, ',');
    std::getline(row, v_text, ',');
    char* end_t = nullptr;
    char* end_v = nullptr;
    const double t = std::strtod(t_text.c_str(), &end_t);
    const double v = std::strtod(v_text.c_str(), &end_v);
    if (t_text.empty() || v_text.empty() || *end_t || (*end_v && *end_v != '\r')) {
      fail_input("{}:{}: expected 'series,T,value', found '{}'", csv_path, number, line);
    }
    if (series == "front") ref.front.push_back({t, v});
    else if (series == "residual") ref.residual.push_back({t, v});
    else fail_input("{}:{}: unknown series '{}' (front or residual)", csv_path, number, series);
  }
  if (ref.front.empty() || ref.residual.empty()) fail_input("{}: needs both a front and a residual series", csv_path);
  return ref;
}

namespace {

// Linear interpolation of (time, value) at t; NaN outside the sampled range.
double interpolate(const std::vector<std::pair<double, double>>& series, double t) {
  if (series.empty() || t < series.front().first || t > series.back().first) return std::numeric_limits<double>::quiet_NaN();
  auto it = std::lower_bound(series.begin(), series.end(), t, [](const auto& p, double v) { return p.first < v; });
  if (it == series.begin()) return it->second;
  const auto& [t1, v1] = *it;
  const auto& [t0, v0] = *(it - 1);
  return t1 > t0 ? v0 + (v1 - v0) * (t - t0) / (t1 - t0) : v1;
}

SeriesError compare(const std::vector<std::pair<double, double>>& simulated, const std::vector<ReferencePoint>& measured) {
  SeriesError e;
  double sum2 = 0;
  for (const ReferencePoint& m : measured) {
    const double s = interpolate(simulated, m.T);
    if (!std::isfinite(s)) {
      ++e.skipped;
      continue;
    }
    const double d = s - m.value;
    sum2 += d * d;
    e.max = std::max(e.max, std::fabs(d));
    ++e.points;
  }
  e.rms = e.points ? std::sqrt(sum2 / e.points) : std::numeric_limits<double>::quiet_NaN();
  return e;
}

}  // namespace

DamBreakComparison compare_dambreak(const std::vector<DamBreakSample>& samples, const DamBreakSetup& setup,
                                    const DamBreakReference& reference) {
  if (!(setup.column_width > 0)) fail_input("dam break: column width {} must be positive", setup.column_width);
  const double a = setup.column_width, g = setup.gravity;
  std::vector<std::pair<double, double>> front, residual;
  for (const DamBreakSample& s : samples) {
    if (std::isfinite(s.front)) front.emplace_back(s.time * std::sqrt(2 * g / a), s.front / a);
    if (std::isfinite(s.residual)) residual.emplace_back(s.time * std::sqrt(g / a), s.residual / (2 * a));
  }
  auto by_time = [](const auto& p, const auto& q) { return p.first < q.first; };
  std::sort(front.begin(), front.end(), by_time);
  std::sort(residual.begin(), residual.end(), by_time);
  return {compare(front, reference.front), compare(residual, reference.residual)};
}

}  // namespace bw::analysis

// The dam-break validation (Martin & Moyce 1952): a water column of width a and
// height 2a against a wall at x = wall, on a floor at z = floor, released at t = 0,
// spreads along +x. Compared by its surge front and its residual height at the wall,
// in the experiment's dimensionless form:
//   front:    T = t sqrt(2 g / a),  Z = x_front / a
//   residual: T = t sqrt(g / a),    H = h / (2 a)
#pragma once

#include <string>
#include <vector>

#include "io/frame_file.h"

namespace bw::analysis {

struct DamBreakSetup {
  double column_width = 0;   // a (m)
  double wall = 0;           // x of the back wall (m)
  double floor = 0;          // z of the floor (m)
  double band = 0;           // particles within this distance of the floor (front) or
                             // the wall (residual) count; about two particle spacings (m)
  double gravity = 9.81;     // m/s^2
};

struct DamBreakSample {
  double time = 0;
  double front = 0;      // furthest fluid particle along the floor, from the wall (m)
  double residual = 0;   // highest fluid particle at the wall, above the floor (m)
};

DamBreakSample measure_dambreak(const FrameData& frame, const DamBreakSetup& setup);

struct ReferencePoint {
  double T = 0;
  double value = 0;
};

struct DamBreakReference {
  std::vector<ReferencePoint> front;      // (T, Z)
  std::vector<ReferencePoint> residual;   // (T, H)
};

// Reads the CSV of ../shared/data (series,T,value; '#' comments). Throws InputError
// naming the file and line on malformed input.
DamBreakReference read_dambreak_reference(const std::string& csv_path);

struct SeriesError {
  double rms = 0;        // root mean square of (simulated - measured), dimensionless
  double max = 0;        // largest |simulated - measured|
  int points = 0;        // experimental points within the simulated time range
  int skipped = 0;       // experimental points beyond it
};

struct DamBreakComparison {
  SeriesError front;     // in units of a
  SeriesError residual;  // in units of 2a
};

// Interpolates the simulated series (linear in time) at each experimental time.
DamBreakComparison compare_dambreak(const std::vector<DamBreakSample>& samples, const DamBreakSetup& setup,
                                    const DamBreakReference& reference);

}  // namespace bw::analysis

// What the accuracy study and the stability suite measure on a finished run
// (docs/validation.md): a run's cost and error indicators from its run file, its
// error against Martin & Moyce's dam break or against hydrostatics, and the checks
// every stability case must pass (no non-finite value, every particle in the domain
// and out of every solid, density error bounded, energy not growing).
//
// A run folder is what bw-sim writes: RUN/run.h5 and RUN/frames/NNNNNN.h5.
#pragma once

#include <limits>
#include <algorithm>
#include <string>
#include <vector>

#include "analysis/dambreak.h"
#include "common/geometry.h"

namespace bw::study {

// From the run file alone.
struct RunIndicators {
  std::string status;            // "complete", or the error that stopped the run
  double wall_time = 0;          // s, at the last frame written
  double simulated_time = 0;     // s
  double steps = 0;
  double fluid = 0;              // particles at the first frame
  double removed = 0;            // lost at the domain by the last frame
  double density_error_worst = 0;  // max over frames of density_error_max
  double speed_worst = 0;        // m/s, max over frames of speed_max
  double energy_drift = 0;       // (E_last - E_0) / E_0, E = kinetic + potential + elastic
  double energy_growth = 0;      // (max_f E_f - E_0) / E_0: 0 when it never rose
  double spacing = 0, h = 0, c0 = 0;
  bool complete() const { return status == "complete"; }
};
RunIndicators read_indicators(const std::string& run_dir);

// Front and residual of the run's frames against the experiment (analysis/dambreak.h),
// and how much of the front's error a shift of the time origin explains: the delay
// dT (in the experiment's T = t sqrt(2 g / a); positive: the experiment lags the run)
// for which the front's RMS is least, and that RMS. Martin & Moyce released their
// column by pulling a diaphragm away, which takes time that their origin of time
// does not account for.
struct DamBreakError {
  analysis::DamBreakComparison comparison;
  double front_shift = 0;        // dT
  double front_rms_shifted = 0;  // front RMS with the run's T + dT against the experiment
};
DamBreakError dambreak_error(const std::string& run_dir, const analysis::DamBreakSetup& setup,
                             const std::string& reference_csv);

// RMS difference of two runs' fronts (Z = x / a, each measured with its own setup)
// at the experiment's times: a run's discretisation error when `other` is the same
// scene at a finer spacing (the study compares every run with its finest).
double front_difference(const std::string& run_dir, const analysis::DamBreakSetup& setup, const std::string& other_dir,
                        const analysis::DamBreakSetup& other_setup, const std::string& reference_csv);

struct HydrostaticError {
  double pressure = 0;     // Pa: the probe's pressure, averaged over the frames at or after `from`
  double expected = 0;     // Pa: rho0 |g| (surface - point z)
  double relative = 0;     // pressure / expected - 1
  int frames = 0;          // frames averaged
  // The scene's [[sensor]] named "floor" (the force on the floor's patches), averaged
  // over the samples at or after `from`, against rho0 |g| (surface - its z); NaN
  // when the scene has none.
  double floor_pressure = std::numeric_limits<double>::quiet_NaN();
  double floor_expected = std::numeric_limits<double>::quiet_NaN();
  double floor_relative = std::numeric_limits<double>::quiet_NaN();
};
// The pressure at `point` (Shepard kernel average of radius `radius`, the same as
// bw-measure probe) against rho0 g d, d the depth below the resting surface at
// height `surface`; rho0 and g from the run file.
HydrostaticError hydrostatic_error(const std::string& run_dir, const Vec3d& point, double surface, double radius,
                                   double from);

// Winding number of a closed, outward-oriented mesh around a point: 1 inside, 0
// outside (the sum of the triangles' signed solid angles over 4 pi).
double winding_number(const TriMesh& mesh, const Vec3d& point);
// Distance from a point to the nearest point of a mesh's triangles.
double distance_to_surface(const TriMesh& mesh, const Vec3d& point);

struct StabilityLimits {
  // Largest worst-frame density error a stable run may show, at least. An impact at
  // speed v compresses water by v / c0 (the water-hammer relation), 0.1 at the default
  // c0 of 10 x the scene's largest speed; twice that allows for corners where the
  // compression of two walls adds up. The run's fastest fluid can be faster than the
  // scene's largest speed (the suite's 30 m/s jet flings spray at 85-90 m/s from its
  // impact, and with the continuity equation a droplet keeps the density an impact gave
  // it), so the limit is 2 v / c0 with v the fastest fluid of any frame when that is
  // more (density_error_limit). A blow-up shows in the energy's rise first.
  double density_error = 0.2;
  double density_error_limit(const RunIndicators& run) const {
    return run.c0 > 0 ? std::max(density_error, 2 * run.speed_worst / run.c0) : density_error;
  }
  // Largest rise of the total energy above its initial value, relative to it, at any
  // frame. A closed scene only loses energy (viscosity, wall friction, contact), but
  // symplectic Euler conserves a shadow energy, not the energy itself: while an impact
  // stores energy in compression, the total it reports rises by up to about CFL / 2
  // of the elastic energy then held (the 30 m/s jet of the suite: 1.2% of its initial
  // total, 25% of the elastic energy at the impact), and falls back once the
  // compression is released. A blow-up grows it by orders of magnitude.
  double energy_growth = 0.02;
  // Rise of the total energy at the last frame above its initial value: growth that
  // stays is not the integrator's transient.
  double energy_final_growth = 1e-3;
  // Depth below a solid's surface, in spacings, from which a particle counts as inside
  // it. A solid's boundary particles lie half a spacing behind its faces (bw-sample):
  // they are the wall the fluid sees. A fluid particle pressed against them at an
  // impact comes closer than the spacing of its lattice and its centre passes the
  // face, which is contact, not a leak; a particle behind the boundary particles has
  // gone through the wall.
  double penetration = 0.5;
};

struct StabilityReport {
  RunIndicators run;
  int frames = 0;
  long nonfinite = 0;        // particle positions that are not numbers, over all frames
  long outside_domain = 0;   // particles outside the domain box, over all frames
  long inside_solids = 0;    // particles inside a solid deeper than `penetration`, over all frames
  double deepest = 0;        // deepest position of a particle inside a solid (spacings), any depth
  int first_bad_frame = -1;  // first frame with any of the three
  // One line per broken check: `leaks` for particles that left the domain or entered a
  // solid, `failures` for the others (did not finish, non-finite values, density
  // error, energy rise).
  std::vector<std::string> leaks, failures;
  bool stable() const { return failures.empty() && leaks.empty(); }
};
// Reads every frame and the scene the run file records (its solids' meshes, placed as
// the scene places them, and its domain) and checks them against `limits`.
StabilityReport check_stability(const std::string& run_dir, const StabilityLimits& limits);

}  // namespace bw::study

#include "rigid/contact.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bw::rigid {

double damping_ratio(double restitution) {
  const double e = std::clamp(restitution, 0.0, 1.0);
  if (e <= 0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double restitution_of(double zeta) {
  if (zeta >= 1) return 0;
  if (zeta <= 0) return 1;
  return std::exp(-zeta * std::numbers::pi / std::sqrt(1 - zeta * zeta));
}

double stepped_restitution(double zeta, double omega_dt) {
  // In units of 1 / omega: the gap x (< 0 in contact), the normal speed v, one
  // approach at speed 1 started at kPhases offsets within a step.
  constexpr int kPhases = 16;
  const double h = omega_dt;
  double sum = 0;
  for (int p = 0; p < kPhases; ++p) {
    double x = -h * (p + 0.5) / kPhases, v = -1;
    for (int step = 0; step < 100000; ++step) {
      const double a = x < 0 ? std::max(0.0, -x - 2 * zeta * v) : 0.0;
      v += a * h;
      x += v * h;
      if (x >= 0 && v > 0) break;
      if (x >= 0 && v <= 0 && a == 0 && step > 0) {  // came to rest on the surface
        v = 0;
        break;
      }
    }
    sum += std::max(0.0, v);
  }
  return sum / kPhases;
}

double damping_ratio_for_step(double restitution, double omega_dt) {
  const double e = std::clamp(restitution, 0.0, 1.0);
  // Restitution falls as zeta rises, until the explicit dashpot overshoots (c dt near
  // 2 m): find the least restitution on a grid of zeta up to there, then bisect below
  // it. A restitution below that least one gets the zeta of the least.
  constexpr int kGrid = 64;
  const double top = 1.0 / std::max(omega_dt, 1e-6);
  double hi = 0, least = 2;
  for (int k = 0; k <= kGrid; ++k) {
    const double z = top * k / kGrid;
    const double r = stepped_restitution(z, omega_dt);
    if (r < least) least = r, hi = z;
  }
  double lo = 0;
  if (stepped_restitution(lo, omega_dt) <= e) return lo;
  if (least >= e) return hi;
  for (int k = 0; k < 48; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stepped_restitution(mid, omega_dt) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double pair_friction(double a, double b) { return std::sqrt(std::max(0.0, a) * std::max(0.0, b)); }

double pair_restitution(double a, double b) { return std::max(a, b); }

}  // namespace bw::rigid

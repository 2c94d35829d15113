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

double pair_friction(double a, double b) { return std::sqrt(std::max(0.0, a) * std::max(0.0, b)); }

double pair_restitution(double a, double b) { return std::max(a, b); }

}  // namespace bw::rigid

// buoyancy-study [SPACING [DENSITY [END]]]: the floating box of coupled_test at any
// spacing (`make -f Makefile.scenes buoyancy` runs it at 0.01 and 0.005 m; docs/scene.md
// "Buoyancy"). Prints figures and asserts nothing. After END seconds (2 by default)
// it reports the draft against half the box's height scaled by its density, and
// where the box's weight goes, from the particles of the last frame: the boundary
// pressure forces on the box's bottom and sides (the fluid_forces term, recomputed on
// the host in double), the weight per column the floor carries under the box and
// beside it, and how many particles a volume of spacing^3 of the settled water holds.
// The water is 6 cm deep and the box 6 cm tall: at 0.02 m, three particles of water
// cannot float it (it sits nearly on the floor); 0.01 m is the coarsest that can.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "rigid_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

using test::kPoolHeight, test::kPoolTank, test::kPoolWidth;

// Where a boundary particle is, for the sums below.
enum class Place { floor, tank_wall, box_bottom, box_side, box_top };

struct Columns {
  double under = 0, beside = 0;  // per column
};

// What one frame shows.
struct Sample {
  double bottom = 0, sides = 0, top = 0;  // upward force on the box's faces (N)
  Columns load;                           // floor load per column (N)
  double packing = 0;                     // particles per spacing^3 beside the box
  double level_beside = 0;                // the level over the columns beside the box (m)
};

Sample measure(sim::Solver& solver, double s, double level) {
  const sim::Parameters& P = solver.parameters();
  const rigid::BodyState& st = solver.body(0).state();
  FrameFields fields;
  fields.density = fields.pressure = fields.boundary = true;
  const FrameData d = solver.frame(fields, 0);
  const std::size_t nb = d.bx.size(), nf = d.fluid_count();
  std::vector<Place> place(nb);
  std::vector<int> owner(nb);  // 1 for the box
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3d w(d.bx[b], d.by[b], d.bz[b]);
    const Vec3d l = st.orientation.conjugate() * (w - st.position);
    const bool box = std::abs(l.x()) < 0.5 * kPoolWidth && std::abs(l.y()) < 0.5 * kPoolWidth &&
                     std::abs(l.z()) < 0.5 * kPoolHeight;
    owner[b] = box ? 1 : 0;
    if (box)
      place[b] = l.z() < -0.5 * kPoolHeight + s ? Place::box_bottom
                 : l.z() > 0.5 * kPoolHeight - s ? Place::box_top
                                                 : Place::box_side;
    else
      place[b] = w.z() < 0 ? Place::floor : Place::tank_wall;
  }
  // Psi_b = rho0 / sum_k W_spiky(x_bk) over the particles k of b's owner (fluid.cl).
  const double h = P.h, spiky = 15.0 / (std::numbers::pi * std::pow(h, 6));
  const double grad = 3 * spiky;  // -dW_spiky/dr = grad (h - r)^2
  auto distance = [&](float ax, float ay, float az, float bx, float by, float bz) {
    return std::sqrt(double(ax - bx) * (ax - bx) + double(ay - by) * (ay - by) + double(az - bz) * (az - bz));
  };
  std::vector<double> psi(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    double sum = 0;
    for (std::size_t k = 0; k < nb; ++k) {
      if (owner[k] != owner[b]) continue;
      const double r = distance(d.bx[b], d.by[b], d.bz[b], d.bx[k], d.by[k], d.bz[k]);
      if (r < h) sum += spiky * std::pow(h - r, 3);
    }
    psi[b] = P.rho0 / sum;
  }
  // The pressure each boundary particle holds: the fluid particle's own with the
  // mirrored wall; with the hydrostatic wall the fluid's pressure extrapolated to it,
  // sum_f (p_f + rho_f g.(x_b - x_f)) W_bf / sum_f W_bf, not below 0, and per pair no
  // more than p_f + rho_f |g| (r + h) (fluid.cl boundary_pressure, sph_boundary.h).
  const double g = P.gravity.norm();
  std::vector<double> pb(nb, 0.0);
  if (P.wall_hydrostatic) {
    for (std::size_t b = 0; b < nb; ++b) {
      double sw = 0, sp = 0;
      for (std::size_t i = 0; i < nf; ++i) {
        const double r = distance(d.x[i], d.y[i], d.z[i], d.bx[b], d.by[b], d.bz[b]);
        if (r >= h) continue;
        const Vec3d from_f(double(d.bx[b]) - d.x[i], double(d.by[b]) - d.y[i], double(d.bz[b]) - d.z[i]);
        const double w = std::pow(h - r, 3);
        sw += w, sp += w * (d.p[i] + d.rho[i] * P.gravity.dot(from_f));
      }
      pb[b] = sw > 0 ? std::max(sp / sw, 0.0) : 0.0;
    }
  }
  // The vertical force each boundary particle takes from the fluid: the exact negative
  // of its pressure term in the fluid's forces, times the particle mass.
  Sample out;
  const int n = static_cast<int>(std::lround(kPoolTank / s));
  std::vector<double> floor_load(static_cast<std::size_t>(n * n), 0.0);
  for (std::size_t i = 0; i < nf; ++i) {
    const double p = d.p[i], rho = d.rho[i];
    for (std::size_t b = 0; b < nb; ++b) {
      const double r = distance(d.x[i], d.y[i], d.z[i], d.bx[b], d.by[b], d.bz[b]);
      if (r >= h || r <= 0) continue;
      const double wall = P.wall_hydrostatic ? std::min(pb[b], p + rho * g * (r + h)) : p;
      const double k = P.mass * P.gamma2 * (p / (rho * rho) + wall / (P.rho0 * P.rho0)) / P.gradient_moment;
      const double up = -k * psi[b] * grad * (h - r) * (h - r) / r * (double(d.z[i]) - d.bz[b]);
      switch (place[b]) {
        case Place::box_bottom: out.bottom += up; break;
        case Place::box_side: out.sides += up; break;
        case Place::box_top: out.top += up; break;
        case Place::floor: {
          const int cx = std::clamp(static_cast<int>(d.bx[b] / s), 0, n - 1);
          const int cy = std::clamp(static_cast<int>(d.by[b] / s), 0, n - 1);
          floor_load[static_cast<std::size_t>(cy * n + cx)] -= up;
          break;
        }
        case Place::tank_wall: break;
      }
    }
  }
  // Columns well under the box (at least 2 cm inside its edges) and well beside it
  // (at least 1 cm from the box and from the tank's walls).
  std::vector<int> count(static_cast<std::size_t>(n * n), 0);
  std::vector<double> top(static_cast<std::size_t>(n * n), 0.0);
  for (std::size_t i = 0; i < nf; ++i) {
    const int cx = std::clamp(static_cast<int>(d.x[i] / s), 0, n - 1);
    const int cy = std::clamp(static_cast<int>(d.y[i] / s), 0, n - 1);
    ++count[static_cast<std::size_t>(cy * n + cx)];
    top[static_cast<std::size_t>(cy * n + cx)] = std::max(top[static_cast<std::size_t>(cy * n + cx)], double(d.z[i]));
  }
  double particles = 0;
  int under = 0, beside = 0;
  for (int cy = 0; cy < n; ++cy)
    for (int cx = 0; cx < n; ++cx) {
      const std::size_t c = static_cast<std::size_t>(cy * n + cx);
      const double from_box = std::max(std::abs((cx + 0.5) * s - st.position.x()),
                                       std::abs((cy + 0.5) * s - st.position.y())) - 0.5 * kPoolWidth;
      const double from_wall = s * std::min({cx, cy, n - 1 - cx, n - 1 - cy});
      if (from_box < -0.02) {
        out.load.under += floor_load[c], ++under;
      } else if (from_box > 0.01 && from_wall >= 0.01) {
        out.load.beside += floor_load[c], particles += count[c], ++beside;
        out.level_beside += top[c] + 0.5 * s;
      }
    }
  out.load.under /= under;
  out.load.beside /= beside;
  out.packing = particles / beside / (level / s);
  out.level_beside /= beside;
  return out;
}

// Frames sampled over the last half second.
constexpr int kSamples = 10;

int run(double spacing, double density, double end) {
  const double s = spacing;
  test::TempDir dir;
  test::write_pool(dir.path(), s, density, end);
  sim::Solver solver(test::prepare_file(dir.file("pool.toml")), test::shared_context());
  const sim::Parameters& P = solver.parameters();
  double z_sum = 0, level_sum = 0;
  Sample mean;
  int late = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double t = end - 0.5 + 0.5 * (k + 1) / kSamples;
    while (solver.time() < t) {
      solver.step(t);
      if (solver.time() > end - 0.5) z_sum += solver.body(0).state().position.z(), ++late;
    }
    const double level = test::pool_level(solver, s);
    const Sample one = measure(solver, s, level);
    level_sum += level;
    mean.bottom += one.bottom / kSamples;
    mean.sides += one.sides / kSamples;
    mean.top += one.top / kSamples;
    mean.load.under += one.load.under / kSamples;
    mean.load.beside += one.load.beside / kSamples;
    mean.packing += one.packing / kSamples;
    mean.level_beside += one.level_beside / kSamples;
  }
  const double level = level_sum / kSamples;
  const double draft = level - (z_sum / late - 0.5 * kPoolHeight);
  const double ideal = kPoolHeight * density / P.rho0;
  const double weight = solver.body(0).mass().mass * -P.gravity.z();
  const double particle_weight = P.mass * -P.gravity.z();
  std::printf("means over the last 0.5 s (%d frames for the forces):\n", kSamples);
  test::figure("spacing", s, "m");
  test::figure("water level", level, "m");
  test::figure("draft", draft, "m");
  test::figure("draft the box's density gives", ideal, "m");
  test::figure("draft error", (draft - ideal) / ideal);
  test::figure("draft error", (draft - ideal) / s, "spacings");
  test::figure("box weight", weight, "N");
  test::figure("carried by its bottom", mean.bottom / weight);
  test::figure("carried by its sides", mean.sides / weight);
  test::figure("carried by its top", mean.top / weight);
  test::figure("floor load per column under the box", mean.load.under / particle_weight, "particle weights");
  test::figure("floor load per column beside it", mean.load.beside / particle_weight, "particle weights");
  test::figure("particles per spacing^3 of the water beside the box", mean.packing);
  test::figure("water level beside the box (columns of the floor loads)", mean.level_beside, "m");
  test::figure("draft error against that level", (mean.level_beside - (z_sum / late - 0.5 * kPoolHeight) - ideal) / ideal);
  return 0;
}

}  // namespace
}  // namespace bw

int main(int argc, char** argv) {
  const double spacing = argc > 1 ? std::atof(argv[1]) : 0.01;
  const double density = argc > 2 ? std::atof(argv[2]) : 499;
  const double end = argc > 3 ? std::atof(argv[3]) : 2.0;
  if (argc > 4 || !(spacing > 0) || !(density > 0) || !(end > 0.5)) {
    std::fprintf(stderr, "usage: buoyancy-study [SPACING (m, > 0) [DENSITY (kg/m^3, > 0) [END (s, > 0.5)]]]\n");
    return 2;
  }
  return bw::run(spacing, density, end);
}

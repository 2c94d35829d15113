#include "sim/setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "io/particles_file.h"
#include "mesh/triangle_box.h"
#include "rigid/contact.h"
#include "sample/sampler.h"

namespace bw::sim {
namespace {

// c0 = this factor times the largest speed the scene can produce when neither k nor
// c0 is given: the usual WCSPH rule, which keeps the density error near 1%.
constexpr double kSoundSpeedFactor = 10.0;
// The guard stops a run whose fastest particle exceeds this factor times the largest
// speed the scene can produce (or c0, if larger): a splash does not go there, a
// numerical blow-up does.
constexpr double kGuardSpeedFactor = 5.0;
// A solid sampled coarser than this many fluid spacings lets fluid leak through.
constexpr double kMaxSolidSpacingRatio = 1.5;
// Largest neighbour grid: cell indices are 32-bit keys, start[] holds one per cell.
constexpr std::int64_t kMaxGridCells = std::int64_t{1} << 30;
// A surface cell covers a part thinner than itself (faces facing away from each
// other) when the area-weighted mean of its triangles' normals keeps less than this
// fraction of their total area (a cube's corner keeps 0.58, opposite faces 0).
constexpr double kThinCell = 0.25;
// Lattice counts are floor(length / spacing + this), so that a length of exactly n
// spacings (up to rounding) gives n points.
constexpr double kLatticeSlack = 1e-9;
// Contacts between bodies reach a contact distance of up to the widest solid
// spacing plus a lateral reach (shaders/rigid.cl); the neighbour grid (cells of edge
// h) must hold both, which h >= this many spacings allows.
constexpr double kMinContactSupport = 1.25;
// Contact stiffness (docs/scene.md, "Physics"): a boundary particle hitting another
// solid head-on at the scene's largest speed (at least kMinContactSpeed) goes
// kContactPenetration spacings deep; a flat face landing at that speed goes about 2.5
// times as deep (its particles share the body's mass with the rest of the body).
constexpr double kMinContactSpeed = 1.0;     // m/s
constexpr double kContactPenetration = 0.1;  // spacings
// While bodies touch, dt <= kContactStepFactor / omega: about 12 steps per period of a
// particle's contact oscillation, so that the dashpot's damping is resolved and the
// explicit step stays far from its limit (omega dt < 2).
constexpr double kContactStepFactor = 0.5;
// An explicit dashpot c damps a contact point of effective mass m stably while
// c dt / m < 2. A pair's c is 2 zeta m_pair omega, and a corner touching alone has an
// effective mass down to a quarter of its body's (its lever adds rotation): zeta
// omega dt <= this keeps c dt / m_eff at 1.5. A scene whose most inelastic solid
// needs a larger zeta takes shorter contact steps.
constexpr double kMaxDampingStep = 0.1875;
// ... but no shorter than this (5 times the steps of kContactStepFactor), zeta then
// capped at kMaxDampingStep / it: a scene of restitution 0 bounces with about 0.05
// (docs/scene.md).
constexpr double kMinContactStep = 0.1;
// A dynamic solid starts overlapping fluid closer than this fraction of a spacing to
// one of its boundary particles (fluid rests one spacing from them), and another
// solid whose particles come closer than this fraction of the contact distance
// (particle layers of touching solids rest one contact distance apart); or whatever
// lies in one of its voxels that no surface crosses (the solid's inside).
constexpr double kOverlapFraction = 0.5;

double spiky(double r2, double h) {
  const double r = std::sqrt(r2);
  if (r >= h) return 0;
  return 15.0 / (std::numbers::pi * std::pow(h, 6)) * (h - r) * (h - r) * (h - r);
}

std::int64_t lattice_count(double length, double spacing) {
  return static_cast<std::int64_t>(std::floor(length / spacing + kLatticeSlack));
}

// Two unit vectors spanning the plane perpendicular to n; u x w = n. `up` (may be
// zero) fixes w; otherwise w is the world axis least parallel to n, projected
// (z first: scenes are z-up).
void plane_basis(const Vec3d& n, const Vec3d& up, Vec3d& u, Vec3d& w) {
  Vec3d a = up;
  if (a.norm() < 1e-12) a = std::abs(n.z()) < 0.9 ? Vec3d::UnitZ() : Vec3d::UnitY();
  w = (a - a.dot(n) * n).normalized();
  u = w.cross(n);
}

// Area of the part of triangle abc inside the box centre +- half (the triangle
// clipped by the box's six planes, Sutherland-Hodgman).
double area_in_box(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& centre, const Vec3d& half) {
  std::vector<Vec3d> poly{a, b, c}, next;
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      const double limit = centre[axis] + side * half[axis];
      auto inside = [&](const Vec3d& p) { return side * (p[axis] - limit) <= 0; };
      next.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3d& p = poly[i];
        const Vec3d& q = poly[(i + 1) % poly.size()];
        if (inside(p)) next.push_back(p);
        if (inside(p) != inside(q)) {
          const double t = (limit - p[axis]) / (q[axis] - p[axis]);
          next.push_back(p + t * (q - p));
        }
      }
      poly.swap(next);
      if (poly.size() < 3) return 0;
    }
  Vec3d twice = Vec3d::Zero();
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) twice += (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]);
  return 0.5 * twice.norm();
}

// Points hashed into cubic cells, to find those near a query point.
class PointHash {
 public:
  PointHash(const std::vector<Vec3d>& points, double cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[key(coords(points[i]))].push_back(i);
  }
  // True when a point lies closer than `radius` (at most the cell edge) to q.
  bool near(const Vec3d& q, double radius) const {
    const Eigen::Array3i c = coords(q);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(key(c + Eigen::Array3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::size_t i : it->second)
            if ((points_[i] - q).squaredNorm() < radius * radius) return true;
        }
    return false;
  }

 private:
  Eigen::Array3i coords(const Vec3d& p) const { return (p.array() / cell_).floor().cast<int>(); }
  static std::int64_t key(const Eigen::Array3i& c) {
    constexpr std::int64_t kOffset = 1 << 20;  // cells within +-2^20 of the origin
    return ((c.z() + kOffset) << 42) | ((c.y() + kOffset) << 21) | (c.x() + kOffset);
  }
  const std::vector<Vec3d>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

// A solid's boundary particles in the world at t = 0 and, for a dynamic solid, the
// voxels of its inside (voxels that no surface crosses), for the overlap checks.
struct BodyGeometry {
  std::vector<Vec3d> particles;
  double spacing = 0;
  bool has_inside = false;
  SampleGrid grid;
  Eigen::Quaterniond to_file = Eigen::Quaterniond::Identity();
  Vec3d translation = Vec3d::Zero();
  double scale = 1;
  std::vector<std::int64_t> inside;  // cell keys (k ny + j) nx + i, sorted

  std::int64_t key(const CellIndex& c) const {
    return (std::int64_t(c[2]) * grid.dims[1] + c[1]) * grid.dims[0] + c[0];
  }
  void set_interior(const SampledSolid& solid, const scene::Solid& placement) {
    has_inside = true;
    grid = solid.grid;
    to_file = placement.rotation().conjugate();
    translation = placement.translation;
    scale = placement.scale;
    std::vector<std::int64_t> surface;
    for (const CellIndex& c : solid.surface) surface.push_back(key(c));
    std::sort(surface.begin(), surface.end());
    for (const CellIndex& c : solid.voxels) {
      const std::int64_t k = key(c);
      if (!std::binary_search(surface.begin(), surface.end(), k)) inside.push_back(k);
    }
    std::sort(inside.begin(), inside.end());
  }
  bool contains(const Vec3d& world) const {
    if (!has_inside) return false;
    const Vec3d f = (to_file * (world - translation) / scale - grid.origin) / grid.spacing;
    CellIndex c;
    for (int a = 0; a < 3; ++a) {
      if (!(f[a] >= 0 && f[a] < grid.dims[a])) return false;
      c[a] = static_cast<std::int32_t>(std::floor(f[a]));
    }
    return std::binary_search(inside.begin(), inside.end(), key(c));
  }
};

// The anchor of an anchored breakable solid: its voxels within kAnchorReach of the
// mean of the two spacings from another solid's boundary particles at t = 0 (what it
// stands on: a wall's bottom layer on a floor is one spacing from the floor's
// particles).
constexpr double kAnchorReach = 1.5;
void mark_anchors(Setup& out, const std::vector<BodyGeometry>& geometry) {
  for (BodySetup& body : out.bodies) {
    if (!body.breakable || !body.anchored) continue;
    body.voxel_anchor.assign(body.voxel_centers.size(), 0);
    for (std::size_t j = 0; j < geometry.size(); ++j) {
      if (j == body.solid || geometry[j].particles.empty()) continue;
      const double reach = kAnchorReach * 0.5 * (body.voxel_size + geometry[j].spacing);
      const PointHash grid(geometry[j].particles, reach);
      for (std::size_t v = 0; v < body.voxel_centers.size(); ++v)
        if (!body.voxel_anchor[v] && grid.near(body.voxel_centers[v], reach)) body.voxel_anchor[v] = 1;
    }
  }
}

std::string point_text(const Vec3d& q) { return fmt::format("({:.4g}, {:.4g}, {:.4g}) m", q.x(), q.y(), q.z()); }

const char* kind(const BodySetup& body) { return body.motion.empty() ? "dynamic" : "moving"; }

// A dynamic or moving solid may not start inside the fluid or another solid
// (kOverlapFraction).
void check_overlaps(const scene::Scene& s, const Setup& out, const std::vector<BodyGeometry>& geometry) {
  const double fluid_gap = kOverlapFraction * s.spacing;
  for (const BodySetup& body : out.bodies) {
    const std::size_t i = body.solid;
    const BodyGeometry& g = geometry[i];
    double widest = 0;
    for (const BodyGeometry& other : geometry) widest = std::max(widest, other.spacing);
    const double cell = std::max(fluid_gap, kOverlapFraction * widest);
    const PointHash hash(g.particles, cell);
    Aabb box;
    for (const Vec3d& x : g.particles) box.add(x);
    box.min -= Vec3d::Constant(cell);
    box.max += Vec3d::Constant(cell);
    auto in_box = [&](const Vec3d& q) { return (q.array() >= box.min.array()).all() && (q.array() <= box.max.array()).all(); };
    const ParticleArrays& fluid = out.fluid;
    std::size_t block = 0, block_end = out.block_particles.empty() ? 0 : out.block_particles[0];
    for (std::size_t k = 0; k < fluid.size(); ++k) {
      while (k >= block_end && block + 1 < out.block_particles.size()) block_end += out.block_particles[++block];
      const Vec3d q(fluid.x[k], fluid.y[k], fluid.z[k]);
      if (in_box(q) && (g.contains(q) || hash.near(q, fluid_gap)))
        fail_input("{}: solid[{}]: the {} solid '{}' starts overlapping the fluid of fluid.block[{}] at {} (fluid "
                   "rests one spacing from a solid's boundary particles)",
                   s.path, i, kind(body), body.name, block, point_text(q));
    }
    for (std::size_t j = 0; j < geometry.size(); ++j) {
      if (j == i) continue;
      const double gap = kOverlapFraction * 0.5 * (g.spacing + geometry[j].spacing);
      for (const Vec3d& q : geometry[j].particles)
        if (in_box(q) && (g.contains(q) || hash.near(q, gap)))
          fail_input("{}: solid[{}]: the {} solid '{}' starts overlapping solid[{}] ('{}') at {}", s.path, i,
                     kind(body), body.name, j, s.solids[j].name, point_text(q));
    }
  }
}

// Fluid may not start inside a static solid sampled with its volume (whose voxels
// say it is solid there; without voxels either side of the surface may hold water, as
// a tank sampled from a box's faces). A block or an emitter deep inside is never near
// the solid's boundary particles, so no compression shows it: the fluid would sit or
// fall inside the wall. A block is tested at its centre (one that reaches out of the
// solid crosses its surface, which the initial compression refuses), an emitter at
// each point of its layer; the cells the surface crosses do not count.
void check_fluid_outside(const scene::Scene& s, const Setup& out, std::size_t solid, const BodyGeometry& g) {
  const scene::Solid& placement = s.solids[solid];
  for (std::size_t b = 0; b < s.blocks.size(); ++b) {
    const Vec3d centre = 0.5 * (s.blocks[b].min + s.blocks[b].max);
    if (g.contains(centre))
      fail_input("{}: fluid.block[{}]: lies inside solid[{}] ('{}'): its centre {} is among the solid's voxels",
                 s.path, b, solid, placement.name, point_text(centre));
  }
  for (std::size_t e = 0; e < out.emitters.size(); ++e) {
    const std::vector<Vec3d>& points = out.emitters[e].points;
    const auto inside = std::count_if(points.begin(), points.end(), [&](const Vec3d& x) { return g.contains(x); });
    if (inside > 0)
      fail_input("{}: fluid.emitter[{}]: {} of its {} points lie inside solid[{}] ('{}'), the first at {}: an "
                 "emitter's water must start in open space",
                 s.path, e, inside, points.size(), solid, placement.name,
                 point_text(*std::find_if(points.begin(), points.end(), [&](const Vec3d& x) { return g.contains(x); })));
  }
}

// A particles file from before bw-sample recorded its surface rule (docs/formats.md,
// "particles") may lack the rows behind concave edges: its cells are compared with
// those bw-sample marks now from the same mesh and grid, and a difference is said,
// not refused (the run goes on as it ran before, with a corner's load on the rows
// beside it). A file that has them all passes in silence.
void warn_if_sampled_before_the_rule(const SampledSolid& sampled, const std::string& scene, std::size_t index,
                                     const std::string& file) {
  if (sampled.surface_rule >= kSurfaceRule) return;
  std::vector<CellIndex> stored = sampled.surface;
  std::vector<CellIndex> now = sample::surface_cells(sampled.mesh, sampled.grid);
  std::sort(stored.begin(), stored.end());
  std::sort(now.begin(), now.end());
  std::vector<CellIndex> missing, extra;
  std::set_difference(now.begin(), now.end(), stored.begin(), stored.end(), std::back_inserter(missing));
  std::set_difference(stored.begin(), stored.end(), now.begin(), now.end(), std::back_inserter(extra));
  if (missing.empty() && extra.empty()) return;
  fmt::print(stderr,
             "bw-sim: warning: {}: solid[{}].particles: {} lacks {} of the {} surface cells bw-sample marks now{} "
             "(an older bw-sample left out the rows behind concave edges, docs/formats.md): sample it again\n",
             scene, index, file, missing.size(), now.size(),
             extra.empty() ? std::string() : fmt::format(" and has {} it does not", extra.size()));
}

}  // namespace

double lattice_kernel_sum(double spacing, double h) {
  const int reach = static_cast<int>(std::ceil(h / spacing));
  double sum = 0;
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) sum += spiky(spacing * spacing * (i * i + j * j + k * k), h);
  return sum;
}

namespace {

// Sum of f(r) over the simple cubic lattice's points at distances 0 < r < h from a
// lattice point.
template <typename F>
double sum_over_lattice_neighbours(double spacing, double h, F f) {
  const int reach = static_cast<int>(std::ceil(h / spacing));
  double sum = 0;
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double r = spacing * std::sqrt(double(i * i + j * j + k * k));
        if (r <= 0 || r >= h) continue;
        sum += f(r);
      }
  return sum;
}

}  // namespace

double lattice_gradient_moment(double spacing, double h) {
  const double spiky_grad = 45.0 / (std::numbers::pi * std::pow(h, 6));  // -dW/dr = spiky_grad (h - r)^2
  // x_ij (x) grad W: its trace is r dW/dr.
  const double moment =
      sum_over_lattice_neighbours(spacing, h, [&](double r) { return r * spiky_grad * (h - r) * (h - r); });
  return moment / (3 * lattice_kernel_sum(spacing, h));
}

double lattice_diffusion_rate(double spacing, double h, double delta, double c0) {
  const double eta2 = 0.01 * h * h;  // fluid.cl's BW_DIFFUSION_ETA2
  const double spiky_norm = 15.0 / (std::numbers::pi * std::pow(h, 6));
  const double sum =
      sum_over_lattice_neighbours(spacing, h, [&](double r) { return (h - r) * (h - r) * r / (r * r + eta2); });
  // 2 delta h c0 (the diffusion's coefficient) x 3 spiky m / rho0 x the sum, m / rho0 the kernel's volume.
  return 2 * delta * h * c0 * 3 * spiky_norm * sum / lattice_kernel_sum(spacing, h);
}

double signal_speed(const Parameters& p, double rho) {
  const double sound = rho > p.rho0 ? p.c0 * std::pow(rho / p.rho0, 0.5 * (p.gamma - 1)) : p.c0;
  // With gamma1 = 0 the walls add nothing to the density: no stiffness of theirs to compare.
  const double wall = p.gamma1 > 0 ? std::max(1.0, 2 * p.gamma2 / p.gamma1) : 1.0;
  return sound * std::sqrt(wall);
}

double calibrated_gamma1(double spacing, double h) {
  // Kernel sums over the lattice layer k spacings away (k = 0: the particle's own).
  const int reach = static_cast<int>(std::ceil(h / spacing));
  auto layer = [&](auto kernel, int k) {
    double sum = 0;
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) sum += kernel(spacing * spacing * (i * i + j * j + k * k), h);
    return sum;
  };
  // A particle one spacing from the wall misses the fluid layers 1, 2, ... (mass
  // m = rho0 / full lattice sum each); the wall, layer 1, gives gamma1 Psi_b per
  // particle with Psi_b = rho0 / (its own layer's sum).
  double missing = 0;
  for (int k = 1; k <= reach; ++k) missing += layer(spiky, k);
  missing /= lattice_kernel_sum(spacing, h);
  const double wall = layer(spiky, 1) / layer(spiky, 0);
  return missing / wall;
}

void ParticleArrays::push(const Vec3d& p, const Vec3d& v) {
  x.push_back(static_cast<float>(p.x()));
  y.push_back(static_cast<float>(p.y()));
  z.push_back(static_cast<float>(p.z()));
  vx.push_back(static_cast<float>(v.x()));
  vy.push_back(static_cast<float>(v.y()));
  vz.push_back(static_cast<float>(v.z()));
}

double EmitterLattice::distance_by(double t) const {
  if (t <= start) return 0;
  return speed * (std::min(t, stop) - start);
}

std::int64_t EmitterLattice::layers_by(double t, double spacing) const {
  return lattice_count(distance_by(t), spacing);
}

std::vector<Vec3d> surface_normals(const SampledSolid& solid, std::vector<double>* flatness) {
  const SampleGrid& g = solid.grid;
  const std::int64_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
  auto key = [&](std::int64_t i, std::int64_t j, std::int64_t k) { return (k * ny + j) * nx + i; };
  // Surface cells are sorted by (k, j, i): their keys ascend, so a cell is found by
  // binary search.
  std::vector<std::int64_t> keys(solid.surface.size());
  for (std::size_t c = 0; c < keys.size(); ++c)
    keys[c] = key(solid.surface[c][0], solid.surface[c][1], solid.surface[c][2]);
  std::vector<Vec3d> sum(keys.size(), Vec3d::Zero());
  std::vector<double> area(keys.size(), 0.0);
  const Vec3d half = Vec3d::Constant(0.5 * g.spacing);
  const TriMesh& m = solid.mesh;
  for (const Triangle& t : m.triangles) {
    const Vec3d& a = m.vertices[t[0]];
    const Vec3d& b = m.vertices[t[1]];
    const Vec3d& c = m.vertices[t[2]];
    const Vec3d area_normal = (b - a).cross(c - a);
    std::int64_t from[3], to[3];
    const std::int64_t dims[3] = {nx, ny, nz};
    for (int k = 0; k < 3; ++k) {
      const double lo = (std::min({a[k], b[k], c[k]}) - g.origin[k]) / g.spacing;
      const double hi = (std::max({a[k], b[k], c[k]}) - g.origin[k]) / g.spacing;
      from[k] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(lo)) - 1);
      to[k] = std::min<std::int64_t>(dims[k] - 1, static_cast<std::int64_t>(std::floor(hi)) + 1);
    }
    for (std::int64_t k = from[2]; k <= to[2]; ++k)
      for (std::int64_t j = from[1]; j <= to[1]; ++j)
        for (std::int64_t i = from[0]; i <= to[0]; ++i) {
          const auto it = std::lower_bound(keys.begin(), keys.end(), key(i, j, k));
          if (it == keys.end() || *it != key(i, j, k)) continue;
          const Vec3d centre = g.cell_center({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j),
                                              static_cast<std::int32_t>(k)});
          // Faces on the cell's planes count (the cell is the surface cell the sampler
          // marked on their inner side), whatever the rounding of the planes.
          Vec3d reach = half;
          for (int d = 0; d < 3; ++d) reach[d] += g.spacing * g.plane_tolerance(centre[d] + half[d], d);
          const double inside = area_in_box(a, b, c, centre, reach);
          const double whole = area_normal.norm();
          if (whole > 0 && inside > 0) {
            const std::size_t cell = static_cast<std::size_t>(it - keys.begin());
            sum[cell] += area_normal * (inside / whole);
            area[cell] += inside;
          }
        }
  }
  // On an edge or a corner the mean normal bisects the faces. On both faces of a part
  // thinner than a cell the normals cancel: zero (the particle's contact is then a
  // sphere, fluid_integrate).
  if (flatness) flatness->assign(sum.size(), 0.0);
  for (std::size_t c = 0; c < sum.size(); ++c) {
    const double len = sum[c].norm();
    const bool thick = len > kThinCell * area[c];
    if (flatness && thick) (*flatness)[c] = len / area[c];
    sum[c] = thick ? Vec3d(sum[c] / len) : Vec3d::Zero();
  }
  return sum;
}

std::vector<Vec3d> emitter_points(const scene::Emitter& e, double spacing) {
  Vec3d u, w;
  plane_basis(e.normal, e.shape == scene::Emitter::Shape::rectangle ? e.up : Vec3d::Zero(), u, w);
  std::vector<Vec3d> points;
  if (e.shape == scene::Emitter::Shape::disc) {
    const int reach = static_cast<int>(std::floor(e.radius / spacing + kLatticeSlack));
    const double r2 = e.radius * e.radius * (1 + kLatticeSlack);
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double a = i * spacing, b = j * spacing;
        if (a * a + b * b <= r2) points.push_back(e.center + a * u + b * w);
      }
  } else {
    const std::int64_t na = lattice_count(e.size[0], spacing), nb = lattice_count(e.size[1], spacing);
    for (std::int64_t j = 0; j < nb; ++j)
      for (std::int64_t i = 0; i < na; ++i) {
        const double a = (static_cast<double>(i) - 0.5 * static_cast<double>(na - 1)) * spacing;
        const double b = (static_cast<double>(j) - 0.5 * static_cast<double>(nb - 1)) * spacing;
        points.push_back(e.center + a * u + b * w);
      }
  }
  return points;
}

fracture::Piece breakable_piece(const BodySetup& body) {
  fracture::Piece piece;
  piece.cells = body.voxel_cells;
  piece.centers = body.voxel_centers;
  piece.anchor = body.voxel_anchor;
  piece.particles = body.particles;
  piece.normals = body.normals;
  piece.flatness = body.flatness;
  piece.particle_cells = body.particle_cells;
  return piece;
}

// A uniform number in [-1, 1) for (seed, particle, axis): a counter-based hash (the
// finaliser of splitmix64), so that a draw is the same whatever order particles are
// made in and on whatever device the run goes on.
double seeded_offset(std::uint64_t seed, std::uint64_t particle, int axis) {
  auto mix = [](std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  const std::uint64_t bits = mix(mix(seed) ^ (3 * particle + static_cast<std::uint64_t>(axis)));
  return static_cast<double>(bits >> 11) * 0x1.0p-52 - 1.0;
}

// The density the continuity equation starts from: each block at rest under gravity,
// rho0 (1 + rho0 |g| d / k)^(1 / gamma) at depth d below its top (half a spacing above
// its highest particles), the Tait law's inverse at the hydrostatic pressure, so a
// pool starts in balance instead of ringing at the speed of sound.
std::vector<float> hydrostatic_density(const scene::Scene& s, const Setup& out, const Parameters& p) {
  std::vector<float> rho(out.fluid.size(), static_cast<float>(p.rho0));
  const double g = p.gravity.norm();
  if (!(g > 0)) return rho;
  const Vec3d up = -p.gravity / g;
  std::size_t first = 0;
  for (std::size_t b = 0; b < s.blocks.size() && b < out.block_particles.size(); ++b) {
    const std::size_t end = first + out.block_particles[b];
    auto height = [&](std::size_t i) {
      return up.dot(Vec3d(out.fluid.x[i], out.fluid.y[i], out.fluid.z[i]));
    };
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = first; i < end; ++i) top = std::max(top, height(i));
    top += 0.5 * p.spacing;
    for (std::size_t i = first; i < end; ++i) {
      const double depth = std::max(0.0, top - height(i));
      rho[i] = static_cast<float>(p.rho0 * std::pow(1 + p.rho0 * g * depth / p.k, 1 / p.gamma));
    }
    first = end;
  }
  return rho;
}

Setup prepare(const scene::Scene& s, double end_time) {
  Setup out;
  Parameters& p = out.params;
  const scene::FluidSettings& f = s.fluid;
  p.spacing = s.spacing;
  p.h = s.smoothing_length;
  p.rho0 = f.rho0;
  p.gamma = f.gamma;
  p.mu = f.mu;
  p.mu_b = f.mu_b;
  p.gamma1 = f.gamma1 >= 0 ? f.gamma1 : calibrated_gamma1(p.spacing, p.h);
  // A hydrostatic wall pushes as the missing fluid would (gamma1); a mirrored one with
  // half of it, and the layer against it carries a density step (docs/scene.md, "Density").
  p.wall_hydrostatic = f.wall_pressure != scene::WallPressure::mirrored;
  p.wall_images = f.wall_pressure == scene::WallPressure::images;
  p.gamma2 = f.gamma2 >= 0 ? f.gamma2 : (p.wall_hydrostatic ? 1.0 : 0.5) * p.gamma1;
  p.gravity = s.gravity;
  p.end_time = end_time;
  p.frame_rate = s.time.frame_rate;
  p.dt_min = s.time.dt_min;
  p.dt_max = s.time.dt_max;
  p.cfl = s.time.cfl;
  p.force_factor = s.time.force_factor;
  p.mass = p.rho0 * p.spacing * p.spacing * p.spacing;
  p.kernel_mass = p.rho0 / lattice_kernel_sum(p.spacing, p.h);
  p.gradient_moment = lattice_gradient_moment(p.spacing, p.h);
  p.domain = s.domain;
  std::int64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    p.grid[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((s.domain.max[a] - s.domain.min[a]) / p.h)));
    cells = cells > kMaxGridCells ? cells : cells * p.grid[a];
  }
  if (cells >= kMaxGridCells)
    fail_input("{}: domain: {} x {} x {} grid cells of {} m (the smoothing length) are too many, at most {}; shrink "
               "the domain",
               s.path, p.grid[0], p.grid[1], p.grid[2], p.h, kMaxGridCells);
  const double nu = std::max(p.mu, p.mu_b) / p.rho0;
  p.dt_viscous = nu > 0 ? s.time.viscous_factor * p.h * p.h / nu : std::numeric_limits<double>::infinity();

  // Fluid blocks on the lattice min + (i + 1/2) spacing; in a draw (fluid.seed >= 1)
  // each particle off its point by up to fluid.jitter spacings per axis.
  const double jitter = f.seed > 0 ? f.jitter * p.spacing : 0.0;
  for (const scene::Block& b : s.blocks) {
    const std::size_t before = out.fluid.size();
    const Vec3d extent = b.max - b.min;
    const std::int64_t nx = lattice_count(extent.x(), p.spacing), ny = lattice_count(extent.y(), p.spacing),
                       nz = lattice_count(extent.z(), p.spacing);
    for (std::int64_t k = 0; k < nz; ++k)
      for (std::int64_t j = 0; j < ny; ++j)
        for (std::int64_t i = 0; i < nx; ++i) {
          const Vec3d q = b.min + p.spacing * Vec3d(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5,
                                                    static_cast<double>(k) + 0.5);
          Vec3d offset = Vec3d::Zero();
          if (jitter > 0)
            for (int a = 0; a < 3; ++a)
              offset[a] = jitter * seeded_offset(static_cast<std::uint64_t>(f.seed), out.fluid.size(), a);
          out.fluid.push(q + offset, b.velocity);
        }
    out.block_particles.push_back(out.fluid.size() - before);
  }

  // Emitters: one layer of lattice points, and how many particles they inject.
  for (std::size_t i = 0; i < s.emitters.size(); ++i) {
    const scene::Emitter& e = s.emitters[i];
    EmitterLattice lattice;
    lattice.points = emitter_points(e, p.spacing);
    if (lattice.points.empty())
      fail_input("{}: fluid.emitter[{}]: holds no particle at spacing {}", s.path, i, p.spacing);
    lattice.center = e.center;
    lattice.normal = e.normal;
    lattice.speed = e.speed;
    lattice.start = e.start;
    lattice.stop = std::min(e.stop, end_time);
    out.emitter_particles += lattice.layers_by(end_time, p.spacing) * static_cast<std::int64_t>(lattice.points.size());
    out.emitters.push_back(std::move(lattice));
  }

  // MFP: the scene's, or what the blocks and emitters need.
  const auto block_particles = static_cast<std::int64_t>(out.fluid.size());
  if (f.max_particles > 0) {
    p.max_particles = f.max_particles;
    if (p.max_particles < block_particles)
      fail_input("{}: fluid.max_particles: {} is fewer than the {} particles of the fluid blocks", s.path,
                 p.max_particles, block_particles);
  } else {
    p.max_particles = std::max<std::int64_t>(1, block_particles + out.emitter_particles);
  }
  if (p.max_particles > std::int64_t{1'000'000'000})
    fail_input("{}: fluid: the blocks and emitters need {} particles, more than the solver's limit of 10^9 (set "
               "fluid.max_particles)",
               s.path, p.max_particles);

  // Solids: static ones as boundary particles in the world, keeping those within h of
  // the domain; dynamic ones as rigid bodies (all their particles: they move).
  Aabb reach = s.domain;
  reach.min -= Vec3d::Constant(p.h);
  reach.max += Vec3d::Constant(p.h);
  BoundarySet& bset = out.boundary;
  std::vector<BodyGeometry> geometry(s.solids.size());
  for (std::size_t i = 0; i < s.solids.size(); ++i) {
    const scene::Solid& solid = s.solids[i];
    SampledSolid sampled;
    try {
      sampled = read_particles(solid.particles);
    } catch (const InputError& e) {
      fail_input("{}: solid[{}].particles: {}", s.path, i, e.what());
    }
    warn_if_sampled_before_the_rule(sampled, s.path, i, solid.particles_given);
    const double effective = sampled.grid.spacing * solid.scale;
    if (effective > kMaxSolidSpacingRatio * p.spacing * (1 + kLatticeSlack))
      fail_input("{}: solid[{}].particles: sampled at spacing {} (x scale {} = {}), coarser than {} x the scene's "
                 "spacing {}; fluid would leak through (sample it with bw-sample --spacing {})",
                 s.path, i, sampled.grid.spacing, solid.scale, effective, kMaxSolidSpacingRatio, p.spacing,
                 p.spacing / solid.scale);
    bset.solid_spacing.push_back(effective);
    bset.one_sided.push_back(sampled.has_voxels && !sampled.voxels.empty() ? 1 : 0);
    out.materials.push_back({solid.friction, solid.restitution, effective});
    const Eigen::Quaterniond q = solid.rotation();
    const std::vector<Vec3d> positions = sampled.surface_positions();
    std::vector<double> flatness;
    const std::vector<Vec3d> normals = surface_normals(sampled, &flatness);
    BodyGeometry& g = geometry[i];
    g.spacing = effective;
    for (std::size_t k = 0; k < positions.size(); ++k) g.particles.push_back(q * (solid.scale * positions[k]) + solid.translation);
    if (solid.body() || solid.moving()) {  // a body: all its particles (they move)
      BodySetup body;
      body.solid = i;
      body.name = solid.name;
      body.particles = g.particles;
      for (const Vec3d& n : normals) body.normals.push_back(q * n);
      body.flatness = flatness;
      if (solid.moving()) {  // moved as told: its mass is nominal, nothing reads it
        body.mass.mass = 1;
        for (const Vec3d& x : g.particles) body.mass.center += x / static_cast<double>(g.particles.size());
        body.mass.inertia = Mat3d::Identity();
        body.motion.translation = rigid::Motion(solid.motion_times, solid.motion_velocities);
        std::vector<Vec3d> turn;
        for (double rate : solid.angular_rates) turn.push_back(rate * solid.axis);
        body.motion.turn = rigid::Motion(solid.angular_times, std::move(turn));
        body.motion.pivot = solid.pivot;
        body.velocity = body.motion.velocity(body.mass.center, 0);
        body.angular_velocity = body.motion.angular_velocity(0);
      } else {
        if (!sampled.has_voxels || sampled.voxels.empty())
          fail_input("{}: solid[{}].particles: {} has no voxels; a {} solid needs its volume (sample it with "
                     "bw-sample --volume)",
                     s.path, i, solid.particles_given, solid.breakable ? "breakable" : "dynamic");
        std::vector<Vec3d> centers;
        centers.reserve(sampled.voxels.size());
        for (const Vec3d& c : sampled.voxel_positions()) centers.push_back(q * (solid.scale * c) + solid.translation);
        body.mass = rigid::voxel_mass_properties(centers, effective, solid.density);
        body.voxels = static_cast<std::int32_t>(sampled.voxels.size());
        body.velocity = solid.velocity;
        body.angular_velocity = solid.angular_velocity;
        if (solid.breakable) {
          body.breakable = true;
          body.anchored = solid.anchored;
          body.frc = solid.frc;
          body.density = solid.density;
          body.voxel_size = effective;
          body.voxel_cells = sampled.voxels;
          body.particle_cells = sampled.surface;
          body.voxel_centers = centers;
        }
        g.set_interior(sampled, solid);
      }
      out.bodies.push_back(std::move(body));
      bset.per_solid.push_back(0);
      continue;
    }
    if (sampled.has_voxels && !sampled.voxels.empty()) {
      g.set_interior(sampled, solid);
      check_fluid_outside(s, out, i, g);
    }
    std::size_t kept = 0;
    for (std::size_t k = 0; k < positions.size(); ++k) {
      const Vec3d& world = g.particles[k];
      if ((world.array() < reach.min.array()).any() || (world.array() > reach.max.array()).any()) {
        ++bset.dropped;
        continue;
      }
      const Vec3d n = q * normals[k];
      bset.particles.push(world, Vec3d::Zero());
      bset.nx.push_back(static_cast<float>(n.x()));
      bset.ny.push_back(static_cast<float>(n.y()));
      bset.nz.push_back(static_cast<float>(n.z()));
      bset.flatness.push_back(static_cast<float>(flatness[k]));
      bset.solid.push_back(static_cast<std::uint32_t>(i));
      ++kept;
    }
    bset.per_solid.push_back(kept);
  }
  if (!out.bodies.empty()) {
    // Contacts search the neighbour grid (cells of edge h) for particles within the
    // contact distance plus the lateral reach (shaders/rigid.cl).
    double widest = 0;
    for (const SolidMaterial& m : out.materials) widest = std::max(widest, m.spacing);
    if (p.h < kMinContactSupport * widest)
      fail_input("{}: smoothing_length: {} m is too short for contacts between solids sampled at {} m; dynamic "
                 "solids need at least {} x their spacing",
                 s.path, p.h, widest, kMinContactSupport);
  }

  // The largest speed the scene gives the fluid: its initial and emitter speeds plus
  // a fall through the domain from the highest fluid source (energy conservation).
  double v_init = 0;
  for (const scene::Block& b : s.blocks) v_init = std::max(v_init, b.velocity.norm());
  for (const scene::Emitter& e : s.emitters) v_init = std::max(v_init, e.speed);
  for (const BodySetup& b : out.bodies) {
    double radius = 0;
    for (const Vec3d& x : b.particles) radius = std::max(radius, (x - b.mass.center).norm());
    v_init = std::max(v_init, b.velocity.norm() + b.angular_velocity.norm() * radius);
    v_init = std::max(v_init, b.motion.top_speed(b.particles));
  }
  double fall = 0;
  const double g = p.gravity.norm();
  if (g > 0) {
    const Vec3d down = p.gravity / g;
    double lowest = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) {
      const Vec3d corner((c & 1) ? s.domain.max.x() : s.domain.min.x(), (c & 2) ? s.domain.max.y() : s.domain.min.y(),
                         (c & 4) ? s.domain.max.z() : s.domain.min.z());
      lowest = std::max(lowest, down.dot(corner));
    }
    double highest = std::numeric_limits<double>::infinity();
    for (const scene::Block& b : s.blocks)
      for (int c = 0; c < 8; ++c) {
        const Vec3d corner((c & 1) ? b.max.x() : b.min.x(), (c & 2) ? b.max.y() : b.min.y(),
                           (c & 4) ? b.max.z() : b.min.z());
        highest = std::min(highest, down.dot(corner));
      }
    for (const scene::Emitter& e : s.emitters) highest = std::min(highest, down.dot(e.center));
    for (const BodySetup& b : out.bodies)
      if (b.motion.empty())  // a moving solid goes where it is told, not down
        for (const Vec3d& x : b.particles) highest = std::min(highest, down.dot(x));
    fall = std::max(0.0, lowest - highest);
  }
  p.scene_speed = std::sqrt(v_init * v_init + 2 * g * fall);
  if (f.k > 0) {
    p.k = f.k;
    p.c0 = std::sqrt(p.k * p.gamma / p.rho0);
  } else if (f.c0 > 0) {
    p.c0 = f.c0;
    p.k = p.rho0 * p.c0 * p.c0 / p.gamma;
  } else {
    if (!(p.scene_speed > 0))
      fail_input("{}: fluid.c0: cannot be derived, neither the fluid nor a body moves or falls in this scene; give "
                 "fluid.c0 or fluid.k",
                 s.path);
    p.c0 = kSoundSpeedFactor * p.scene_speed;
    p.k = p.rho0 * p.c0 * p.c0 / p.gamma;
  }
  // Slower than the water can move, the flow outruns its own sound and the fluid
  // compresses far beyond the 1% weak compressibility assumes. Said, not refused: the
  // scene's speed is a bound (a fall through the whole domain).
  if (p.c0 < p.scene_speed)
    fmt::print(stderr,
               "bw-sim: warning: {}: fluid.{} gives a speed of sound of {:.3g} m/s, below the {:.3g} m/s the scene's "
               "water can reach (its speeds and a fall through the domain): the fluid will compress far beyond the 1% "
               "weak compressibility assumes (the default c0 is 10 x that speed)\n",
               s.path, f.k > 0 ? "k" : "c0", p.c0, p.scene_speed);
  p.speed_limit = std::max(kGuardSpeedFactor * p.scene_speed, p.c0);
  p.continuity = f.density == scene::DensityScheme::continuity;
  p.diffusion = f.diffusion;
  // The diffusion is integrated explicitly: each particle's density relaxes toward its
  // neighbours' at its own rate (about 13 delta c0 / h on the lattice), and a step
  // longer than about 2 / (the largest eigenvalue, up to twice that rate) amplifies the
  // particle-scale mode instead of damping it (docs/scene.md, "[time]"). The solver
  // limits each step by its largest rate; this is the same limit at rest.
  p.diffusion_factor = s.time.diffusion_factor;
  p.dt_diffusion = p.continuity && p.diffusion > 0
                       ? p.diffusion_factor / lattice_diffusion_rate(p.spacing, p.h, p.diffusion, p.c0)
                       : std::numeric_limits<double>::infinity();
  if (p.continuity) out.fluid_rho = hydrostatic_density(s, out, p);
  p.contact_dt = std::numeric_limits<double>::infinity();
  if (!out.bodies.empty()) {
    // A particle that hits another solid head-on at the scene's largest speed goes
    // kContactPenetration spacings deep: omega = v / (that depth).
    p.contact_frequency = std::max(p.scene_speed, kMinContactSpeed) / (kContactPenetration * p.spacing);
    // The damping ratio that bounces with the lowest restitution of the scene's solids
    // as the solver steps it (rigid::damping_ratio_for_step), and the step it allows.
    double least = 1;
    for (const SolidMaterial& m : out.materials) least = std::min(least, m.restitution);
    p.contact_step = kContactStepFactor;
    for (int k = 0; k < 4; ++k) {
      const double zeta = rigid::damping_ratio_for_step(least, p.contact_step);
      if (zeta * p.contact_step <= kMaxDampingStep) break;
      p.contact_step = std::max(kMinContactStep, kMaxDampingStep / zeta);
    }
    p.contact_dt = p.contact_step / p.contact_frequency;
    p.contact_zeta_max = kMaxDampingStep / p.contact_step;
    check_overlaps(s, out, geometry);
    mark_anchors(out, geometry);
  }
  out.fracture = s.fracture;

  return out;
}

}  // namespace bw::sim

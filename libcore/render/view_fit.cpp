#include "render/view_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "render/camera.h"

namespace bw::render {
namespace {

// Triangles per leaf of the hierarchy.
constexpr std::uint32_t kLeafTriangles = 4;
// Points that fraction_seen tests at most (an even stride over the particles), and
// the grid of probes over the framed box that candidate views are scored on.
constexpr std::size_t kMaxSamples = 1024;
constexpr int kProbeGrid = 24;
// The framed box is the water's surroundings, not the whole scene, when the scene's
// diagonal exceeds kFrameRatio times the water's; the surroundings reach one water
// diagonal beyond the water on every side.
constexpr double kFrameRatio = 4.0;
// A view that sees this much of the water's surface and this much of the floor it
// can reach is good: the first good one in order of preference is taken.
constexpr double kGoodView = 0.8;
constexpr double kElevations[] = {40.0, 55.0, 70.0, 85.0};
constexpr int kAzimuths = 12;  // every 30 degrees

double diagonal(const Aabb& b) { return b.empty() ? 0.0 : (b.max - b.min).norm(); }

// Entry and exit of the ray in the box, clipped to [t0, t1]; false when it misses.
bool slab(const Aabb& box, const Vec3d& origin, const Vec3d& inverse, double t0, double t1) {
  for (int k = 0; k < 3; ++k) {
    double a = (box.min[k] - origin[k]) * inverse[k], b = (box.max[k] - origin[k]) * inverse[k];
    if (a > b) std::swap(a, b);
    // NaN (0 * inf: the ray runs in the slab's plane) keeps the interval as it is.
    if (a > t0) t0 = a;
    if (b < t1) t1 = b;
    if (t0 > t1) return false;
  }
  return true;
}

// Möller-Trumbore: the ray parameter where it meets the triangle, or -1.
double intersect(const std::array<Vec3d, 3>& t, const Vec3d& origin, const Vec3d& direction) {
  const Vec3d e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return -1;
  const double inv = 1.0 / det;
  const Vec3d s = origin - t[0];
  const double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return -1;
  const Vec3d q = s.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0 || u + v > 1) return -1;
  return e2.dot(q) * inv;
}

bool in_image(const Camera& c, double aspect, const Vec3d& p) {
  const Vec3d f = (c.target - c.position).normalized();
  const Vec3d s = f.cross(c.up).normalized();
  const Vec3d u = s.cross(f);
  const Vec3d o = p - c.position;
  const double depth = o.dot(f);
  if (!(depth > 0)) return false;
  const double tan_v = std::tan(c.fov_degrees * 3.14159265358979323846 / 360.0);
  return std::abs(o.dot(u)) <= tan_v * depth && std::abs(o.dot(s)) <= tan_v * aspect * depth;
}

std::vector<Vec3d> strided(const std::vector<Vec3d>& points) {
  if (points.size() <= kMaxSamples) return points;
  std::vector<Vec3d> out;
  out.reserve(kMaxSamples);
  for (std::size_t k = 0; k < kMaxSamples; ++k) out.push_back(points[k * points.size() / kMaxSamples]);
  return out;
}

double seen(const Camera& camera, double aspect, const std::vector<Vec3d>& sample, const Occluders* occluders) {
  if (sample.empty()) return 0;
  std::size_t n = 0;
  for (const Vec3d& p : sample)
    if (in_image(camera, aspect, p) && !(occluders && occluders->blocks(p, camera.position))) ++n;
  return static_cast<double>(n) / static_cast<double>(sample.size());
}

}  // namespace

Occluders::Occluders(const TriangleSoup& soup) {
  const std::vector<float>& v = soup.vertices;
  for (std::size_t t = 0; t + 27 <= v.size(); t += 27) {
    std::array<Vec3d, 3> tri;
    for (int k = 0; k < 3; ++k) tri[k] = Vec3d(v[t + 9 * k], v[t + 9 * k + 1], v[t + 9 * k + 2]);
    triangles_.push_back(tri);
  }
  if (triangles_.empty()) return;
  std::vector<Vec3d> centroids;
  centroids.reserve(triangles_.size());
  for (const auto& t : triangles_) centroids.push_back((t[0] + t[1] + t[2]) / 3.0);
  nodes_.reserve(2 * triangles_.size() / kLeafTriangles + 1);
  build(0, static_cast<std::uint32_t>(triangles_.size()), centroids);
}

std::uint32_t Occluders::build(std::uint32_t first, std::uint32_t count, std::vector<Vec3d>& centroids) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, centers;
  for (std::uint32_t i = first; i < first + count; ++i) {
    for (const Vec3d& p : triangles_[i]) box.add(p);
    centers.add(centroids[i]);
  }
  nodes_[index].box = box;
  if (count <= kLeafTriangles) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Median split along the longest axis of the centroids.
  int axis = 0;
  centers.extent().maxCoeff(&axis);
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), first);
  const std::uint32_t half = count / 2;
  std::nth_element(order.begin(), order.begin() + half, order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return centroids[a][axis] < centroids[b][axis] || (centroids[a][axis] == centroids[b][axis] && a < b);
  });
  std::vector<std::array<Vec3d, 3>> tris(count);
  std::vector<Vec3d> cents(count);
  for (std::uint32_t k = 0; k < count; ++k) tris[k] = triangles_[order[k]], cents[k] = centroids[order[k]];
  std::copy(tris.begin(), tris.end(), triangles_.begin() + first);
  std::copy(cents.begin(), cents.end(), centroids.begin() + first);
  build(first, half, centroids);
  const std::uint32_t right = build(first + half, count - half, centroids);
  nodes_[index].right = right;
  return index;
}

double Occluders::cast(const Vec3d& origin, const Vec3d& direction, double t_min, double t_max, bool any) const {
  if (nodes_.empty()) return t_max;
  const Vec3d inverse = direction.cwiseInverse();
  double best = t_max;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!slab(node.box, origin, inverse, t_min, best)) continue;
    if (node.count == 0) {
      const auto self = static_cast<std::uint32_t>(&node - nodes_.data());
      stack[top++] = node.right;
      stack[top++] = self + 1;
      continue;
    }
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
      const double t = intersect(triangles_[i], origin, direction);
      if (t > t_min && t < best) {
        best = t;
        if (any) return best;
      }
    }
  }
  return best;
}

bool Occluders::blocks(const Vec3d& a, const Vec3d& b) const {
  // The ends are left out by a relative margin: a point on a surface does not hide itself.
  constexpr double kEnd = 1e-7;
  return cast(a, b - a, kEnd, 1 - kEnd, true) < 1 - kEnd;
}

double Occluders::first_hit(const Vec3d& origin, const Vec3d& direction, double t_max) const {
  return cast(origin, direction, 0, t_max, false);
}

double fraction_seen(const Camera& camera, double aspect, const std::vector<Vec3d>& points,
                     const Occluders* occluders) {
  return seen(camera, aspect, strided(points), occluders);
}

FittedView fit_view(const ViewFitInput& in, double fov_degrees, double aspect) {
  FittedView view;
  std::vector<Vec3d> water;
  water.reserve(in.water.size());
  Aabb water_box;
  for (const Vec3d& p : in.water)
    if (p.allFinite()) water.push_back(p), water_box.add(p);
  Aabb scene = in.solids;
  if (!water_box.empty()) {
    water_box.min.array() -= in.particle_radius;
    water_box.max.array() += in.particle_radius;
    scene.add(water_box.min), scene.add(water_box.max);
  }
  view.framed = scene;
  if (water_box.empty()) {
    view.camera = fit_camera(scene, fov_degrees, aspect);
    return view;
  }
  const double water_size = diagonal(water_box);
  if (diagonal(scene) > kFrameRatio * water_size) {
    view.framed.min = (water_box.min.array() - water_size).max(scene.min.array());
    view.framed.max = (water_box.max.array() + water_size).min(scene.max.array());
  }
  const Aabb& framed = view.framed;

  // Probes on a grid over the framed box: in a cell with water, the top of its
  // highest particle (the surface); in a dry one, the first solid below, or the
  // ground, where that lies no higher than the water's top (where water can go).
  const Vec3d cell_size = framed.extent() / kProbeGrid;
  auto cell_of = [&](double v, int axis) {
    return std::clamp(static_cast<int>(std::floor((v - framed.min[axis]) / cell_size[axis])), 0, kProbeGrid - 1);
  };
  std::vector<Vec3d> highest(kProbeGrid * kProbeGrid, Vec3d::Constant(-std::numeric_limits<double>::infinity()));
  for (const Vec3d& p : water) {
    if (p.x() < framed.min.x() || p.x() > framed.max.x() || p.y() < framed.min.y() || p.y() > framed.max.y())
      continue;
    Vec3d& h = highest[cell_of(p.y(), 1) * kProbeGrid + cell_of(p.x(), 0)];
    if (p.z() > h.z()) h = p;
  }
  std::vector<Vec3d> surface, floor;
  const double top = framed.max.z() + 0.01 * diagonal(framed) + in.particle_radius;
  const double bottom = in.ground_height ? std::min(*in.ground_height, scene.min.z()) : scene.min.z();
  const double reach = top - bottom;
  for (int j = 0; j < kProbeGrid; ++j)
    for (int i = 0; i < kProbeGrid; ++i) {
      const Vec3d& h = highest[j * kProbeGrid + i];
      if (std::isfinite(h.z())) {
        surface.push_back(h + Vec3d(0, 0, in.particle_radius));
        continue;
      }
      const double x = framed.min.x() + (i + 0.5) * cell_size.x(), y = framed.min.y() + (j + 0.5) * cell_size.y();
      const double t = in.occluders ? in.occluders->first_hit(Vec3d(x, y, top), Vec3d(0, 0, -1), reach) : reach;
      if (t >= reach && !in.ground_height) continue;  // nothing below: no floor
      const double z = top - t;
      if (z > water_box.max.z()) continue;  // higher than the water: it will not go there
      floor.emplace_back(x, y, z + in.particle_radius);
    }

  struct Candidate {
    double azimuth, elevation, surface, floor, score;
  };
  std::vector<Candidate> candidates;  // in order of preference
  for (double elevation : kElevations)
    for (int k = 0; k < kAzimuths; ++k) {
      // kFitAzimuth first, then alternately either side of it.
      const int step = (k + 1) / 2 * (k % 2 ? 1 : -1);
      const double azimuth = kFitAzimuth + 30.0 * step;
      const Camera c = fit_camera(framed, fov_degrees, aspect, azimuth, elevation);
      Candidate candidate{azimuth, elevation, seen(c, aspect, surface, in.occluders), -1, 0};
      candidate.score = candidate.surface;
      if (!floor.empty()) {
        candidate.floor = seen(c, aspect, floor, in.occluders);
        candidate.score = std::min(candidate.surface, candidate.floor);
      }
      candidates.push_back(candidate);
    }
  // The first good view, or failing that the best.
  const Candidate* chosen = &candidates.front();
  for (const Candidate& c : candidates)
    if (c.score > chosen->score) chosen = &c;
  for (const Candidate& c : candidates)
    if (c.score >= kGoodView) {
      chosen = &c;
      break;
    }
  view.azimuth = chosen->azimuth;
  view.elevation = chosen->elevation;
  view.surface_seen = chosen->surface;
  view.floor_seen = chosen->floor;
  view.camera = fit_camera(framed, fov_degrees, aspect, chosen->azimuth, chosen->elevation);
  view.water_seen = fraction_seen(view.camera, aspect, water, in.occluders);
  return view;
}

}  // namespace bw::render

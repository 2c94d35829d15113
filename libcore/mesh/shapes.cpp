#include "mesh/shapes.h"

#include <cmath>
#include <map>
#include <numbers>

#include "common/error.h"
#include "mesh/weld.h"

namespace bw::mesh {
namespace {

std::int32_t add_vertex(TriMesh& mesh, const Vec3d& p) {
  mesh.vertices.push_back(p);
  return static_cast<std::int32_t>(mesh.vertices.size() - 1);
}

void add_quad(TriMesh& mesh, std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Ear clipping of a simple counter-clockwise polygon; triangles as polygon indices.
std::vector<Triangle> triangulate_polygon(const std::vector<Eigen::Vector2d>& poly) {
  std::vector<std::int32_t> open(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) open[i] = static_cast<std::int32_t>(i);
  std::vector<Triangle> result;
  while (open.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const std::int32_t ia = open[(i + open.size() - 1) % open.size()];
      const std::int32_t ib = open[i];
      const std::int32_t ic = open[(i + 1) % open.size()];
      const auto &a = poly[ia], &b = poly[ib], &c = poly[ic];
      if (cross2(b - a, c - b) <= 0) continue;  // reflex corner
      bool contains = false;
      for (std::int32_t k : open) {
        if (k == ia || k == ib || k == ic) continue;
        const auto& p = poly[k];
        if (cross2(b - a, p - a) >= 0 && cross2(c - b, p - b) >= 0 && cross2(a - c, p - c) >= 0) {
          contains = true;
          break;
        }
      }
      if (contains) continue;
      result.push_back({ia, ib, ic});
      open.erase(open.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
      break;
    }
    if (!clipped) fail_input("extrude: polygon is not simple and counter-clockwise");
  }
  result.push_back({open[0], open[1], open[2]});
  return result;
}

}  // namespace

TriMesh box(const Vec3d& min, const Vec3d& max, int n) {
  TriMesh mesh;
  // Lattice points are computed by one formula, so shared corners weld exactly.
  auto coord = [&](int axis, int i) {
    return i == n ? max[axis] : min[axis] + (max[axis] - min[axis]) * static_cast<double>(i) / n;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      std::vector<std::int32_t> idx((n + 1) * (n + 1));
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          Vec3d p;
          p[axis] = side ? max[axis] : min[axis];
          p[u] = coord(u, i);
          p[v] = coord(v, j);
          idx[j * (n + 1) + i] = add_vertex(mesh, p);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const std::int32_t a = idx[j * (n + 1) + i], b = idx[j * (n + 1) + i + 1];
          const std::int32_t c = idx[(j + 1) * (n + 1) + i + 1], d = idx[(j + 1) * (n + 1) + i];
          // e_u x e_v = e_axis: counter-clockwise seen from +axis.
          if (side) add_quad(mesh, a, b, c, d);
          else add_quad(mesh, a, d, c, b);
        }
    }
  }
  weld_vertices(mesh);
  return mesh;
}

TriMesh icosphere(const Vec3d& center, double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3d& p : v) p.normalize();
  std::vector<Triangle> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> midpoint;
    auto mid = [&](std::int32_t a, std::int32_t b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const auto index = static_cast<std::int32_t>(v.size() - 1);
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<Triangle> next;
    next.reserve(f.size() * 4);
    for (const Triangle& tri : f) {
      const std::int32_t ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  TriMesh mesh;
  mesh.vertices.reserve(v.size());
  for (const Vec3d& p : v) mesh.vertices.push_back(center + radius * p);
  mesh.triangles = std::move(f);
  return mesh;
}

TriMesh torus(const Vec3d& center, double major_radius, double minor_radius, int nu, int nv) {
  TriMesh mesh;
  const double two_pi = 2 * std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = two_pi * i / nu, w = two_pi * j / nv;
      const double ring = major_radius + minor_radius * std::cos(w);
      add_vertex(mesh, center + Vec3d(ring * std::cos(u), ring * std::sin(u), minor_radius * std::sin(w)));
    }
  auto at = [&](int i, int j) { return static_cast<std::int32_t>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return mesh;
}

TriMesh cylinder(const Vec3d& base_center, double radius, double height, int segments) {
  std::vector<Eigen::Vector2d> polygon;
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * std::numbers::pi * i / segments;
    polygon.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  TriMesh mesh = extrude(polygon, 0.0, height);
  transform(mesh, Mat3d::Identity(), base_center);
  return mesh;
}

TriMesh extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  if (polygon.size() < 3) fail_input("extrude: a polygon needs at least 3 points");
  double area2 = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) area2 += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  if (area2 <= 0) fail_input("extrude: polygon must be counter-clockwise");
  TriMesh mesh;
  const auto n = static_cast<std::int32_t>(polygon.size());
  for (const auto& p : polygon) add_vertex(mesh, Vec3d(p.x(), p.y(), z0));
  for (const auto& p : polygon) add_vertex(mesh, Vec3d(p.x(), p.y(), z1));
  for (std::int32_t i = 0; i < n; ++i) {
    const std::int32_t j = (i + 1) % n;
    add_quad(mesh, i, j, n + j, n + i);
  }
  for (const Triangle& t : triangulate_polygon(polygon)) {
    mesh.triangles.push_back({t[0], t[2], t[1]});           // bottom, facing -z
    mesh.triangles.push_back({n + t[0], n + t[1], n + t[2]});  // top, facing +z
  }
  return mesh;
}

TriMesh open_box(const Vec3d& inner_min, const Vec3d& inner_max, double wall) {
  if (!(wall > 0) || (inner_max.array() <= inner_min.array()).any()) {
    fail_input("open_box: needs inner_min < inner_max and a positive wall thickness");
  }
  const Vec3d outer_min = inner_min - Vec3d(wall, wall, wall);
  const Vec3d outer_max(inner_max.x() + wall, inner_max.y() + wall, inner_max.z());
  TriMesh mesh;
  // Corners 0..3 at the bottom, 4..7 at the top, counter-clockwise seen from above.
  auto corners = [&](const Vec3d& lo, const Vec3d& hi) {
    const auto base = static_cast<std::int32_t>(mesh.vertices.size());
    for (double z : {lo.z(), hi.z()}) {
      mesh.vertices.emplace_back(lo.x(), lo.y(), z);
      mesh.vertices.emplace_back(hi.x(), lo.y(), z);
      mesh.vertices.emplace_back(hi.x(), hi.y(), z);
      mesh.vertices.emplace_back(lo.x(), hi.y(), z);
    }
    return base;
  };
  const std::int32_t o = corners(outer_min, outer_max);
  const std::int32_t i = corners(inner_min, inner_max);
  // Outer shell: bottom facing down, sides facing out.
  add_quad(mesh, o + 0, o + 3, o + 2, o + 1);
  for (int k = 0; k < 4; ++k) add_quad(mesh, o + k, o + (k + 1) % 4, o + 4 + (k + 1) % 4, o + 4 + k);
  // Rim between the outer and inner top edges, facing up.
  for (int k = 0; k < 4; ++k) add_quad(mesh, o + 4 + k, o + 4 + (k + 1) % 4, i + 4 + (k + 1) % 4, i + 4 + k);
  // Inner shell: faces point into the cavity (away from the solid).
  add_quad(mesh, i + 0, i + 1, i + 2, i + 3);
  for (int k = 0; k < 4; ++k) add_quad(mesh, i + k, i + 4 + k, i + 4 + (k + 1) % 4, i + (k + 1) % 4);
  return mesh;
}

TriMesh sealed_box(const Vec3d& inner_min, const Vec3d& inner_max, double wall) {
  if (!(wall > 0) || (inner_max.array() <= inner_min.array()).any()) {
    fail_input("sealed_box: needs inner_min < inner_max and a positive wall thickness");
  }
  TriMesh mesh = box(inner_min - Vec3d::Constant(wall), inner_max + Vec3d::Constant(wall));
  const TriMesh cavity = box(inner_min, inner_max);
  const auto base = static_cast<std::int32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), cavity.vertices.begin(), cavity.vertices.end());
  for (const Triangle& t : cavity.triangles) mesh.triangles.push_back({base + t[0], base + t[2], base + t[1]});
  return mesh;
}

TriMesh heightfield(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, int nx, int ny, double z_bottom,
                    const std::function<double(double, double)>& height) {
  if (nx < 1 || ny < 1) fail_input("heightfield: needs at least one quad along x and y");
  TriMesh mesh;
  auto x_at = [&](int i) { return i == nx ? max_xy.x() : min_xy.x() + (max_xy.x() - min_xy.x()) * i / nx; };
  auto y_at = [&](int j) { return j == ny ? max_xy.y() : min_xy.y() + (max_xy.y() - min_xy.y()) * j / ny; };
  auto top = [&](int i, int j) { return static_cast<std::int32_t>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double z = height(x_at(i), y_at(j));
      if (!(z > z_bottom)) fail_input("heightfield: height {} at ({}, {}) is not above the bottom {}", z, x_at(i), y_at(j), z_bottom);
      mesh.vertices.emplace_back(x_at(i), y_at(j), z);
    }
  const auto bottom_base = static_cast<std::int32_t>(mesh.vertices.size());
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.vertices.emplace_back(x_at(i), y_at(j), z_bottom);
  auto bottom = [&](int i, int j) { return bottom_base + top(i, j); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      add_quad(mesh, top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1));
      add_quad(mesh, bottom(i, j), bottom(i, j + 1), bottom(i + 1, j + 1), bottom(i + 1, j));
    }
  // Sides: each boundary edge of the top joined to the bottom, facing out.
  for (int i = 0; i < nx; ++i) {
    add_quad(mesh, bottom(i, 0), bottom(i + 1, 0), top(i + 1, 0), top(i, 0));
    add_quad(mesh, bottom(i + 1, ny), bottom(i, ny), top(i, ny), top(i + 1, ny));
  }
  for (int j = 0; j < ny; ++j) {
    add_quad(mesh, bottom(nx, j), bottom(nx, j + 1), top(nx, j + 1), top(nx, j));
    add_quad(mesh, bottom(0, j + 1), bottom(0, j), top(0, j), top(0, j + 1));
  }
  return mesh;
}

void transform(TriMesh& mesh, const Mat3d& rotation, const Vec3d& translation) {
  for (Vec3d& v : mesh.vertices) v = rotation * v + translation;
}

void append(TriMesh& mesh, const TriMesh& other) {
  const auto base = static_cast<std::int32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const Triangle& t : other.triangles) mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

}  // namespace bw::mesh

#include "render/wall_paint.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "common/error.h"

namespace bw::render {
namespace {

struct Cell {
  std::int32_t x, y, z;
};

Cell cell_of(float x, float y, float z, float reach) {
  // In float, as mesh.frag computes a pixel's cell.
  return {static_cast<std::int32_t>(std::floor(x / reach)), static_cast<std::int32_t>(std::floor(y / reach)),
          static_cast<std::int32_t>(std::floor(z / reach))};
}

std::uint64_t cell_key(std::int32_t x, std::int32_t y, std::int32_t z) {
  const auto u = [](std::int32_t v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1fffff); };
  return u(x) | u(y) << 21 | u(z) << 42;
}

// Matt Zucker's polynomial fit of matplotlib's viridis (sRGB), within 0.01 of it.
Vec3d viridis(double t) {
  static const Vec3d c[7] = {{0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
                             {0.1050930431085774, 1.404613529898575, 1.384590162594685},
                             {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
                             {-4.634230498983486, -5.799100973351585, -19.33244095627987},
                             {6.228269936347081, 14.17993336680509, 56.69055260068105},
                             {4.776384997670288, -13.74514537774601, -65.35303263337234},
                             {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  t = std::clamp(t, 0.0, 1.0);
  Vec3d v = c[6];
  for (int k = 5; k >= 0; --k) v = c[k] + t * v;
  return v.cwiseMax(0.0).cwiseMin(1.0);
}

// The scale starts below 0 when the 1st percentile is below -this x the 99th.
constexpr double kSuction = 0.05;

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double percentile(std::vector<float>& v, double q) {
  const std::size_t k = static_cast<std::size_t>(std::floor(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

std::uint32_t paint_bucket(std::int32_t cx, std::int32_t cy, std::int32_t cz, std::uint32_t mask) {
  return ((static_cast<std::uint32_t>(cx) * 73856093u) ^ (static_cast<std::uint32_t>(cy) * 19349663u) ^
          (static_cast<std::uint32_t>(cz) * 83492791u)) &
         mask;
}

PaintTable paint_table(const FrameData& frame, double spacing, const std::string& where) {
  require_wall_pressure(frame.fields(), where);
  if (!(spacing > 0)) fail_input("{}: particle spacing {} is not positive", where, spacing);
  PaintTable t;
  t.reach = static_cast<float>(spacing);
  const std::size_t n = frame.bp.size();

  // Cells of edge 2R that hold a loaded particle: a particle within R of a point within
  // R of a loaded one is in such a cell or a neighbour.
  const float wide = 2 * t.reach;
  std::unordered_set<std::uint64_t> loaded;
  for (std::size_t k = 0; k < n; ++k)
    if (frame.bp[k] != 0.0f && std::isfinite(frame.bp[k])) {
      const Cell c = cell_of(frame.bx[k], frame.by[k], frame.bz[k], wide);
      loaded.insert(cell_key(c.x, c.y, c.z));
    }
  std::vector<std::size_t> kept;
  if (!loaded.empty())
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(frame.bp[k])) continue;
      const Cell c = cell_of(frame.bx[k], frame.by[k], frame.bz[k], wide);
      bool near = false;
      for (int dz = -1; dz <= 1 && !near; ++dz)
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx) near = loaded.count(cell_key(c.x + dx, c.y + dy, c.z + dz)) > 0;
      if (near) kept.push_back(k);
    }

  std::uint32_t buckets = 1;
  while (buckets < 2 * kept.size()) buckets *= 2;
  t.mask = buckets - 1;
  // Counting sort by bucket, in the particles' order within a bucket.
  std::vector<Cell> cell(kept.size());
  std::vector<std::uint32_t> bucket(kept.size());
  t.start.assign(buckets + 1, 0);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::size_t k = kept[i];
    cell[i] = cell_of(frame.bx[k], frame.by[k], frame.bz[k], t.reach);
    bucket[i] = paint_bucket(cell[i].x, cell[i].y, cell[i].z, t.mask);
    ++t.start[bucket[i] + 1];
  }
  for (std::uint32_t b = 0; b < buckets; ++b) t.start[b + 1] += t.start[b];
  std::vector<std::uint32_t> next(t.start.begin(), t.start.end() - 1);
  t.points.resize(4 * kept.size());
  t.cells.resize(4 * kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::size_t k = kept[i];
    const std::uint32_t at = next[bucket[i]]++;
    const float p[4] = {frame.bx[k], frame.by[k], frame.bz[k], frame.bp[k]};
    const std::int32_t q[4] = {cell[i].x, cell[i].y, cell[i].z, frame.bsolid[k]};
    std::copy(p, p + 4, t.points.begin() + 4 * at);
    std::copy(q, q + 4, t.cells.begin() + 4 * at);
  }
  return t;
}

double PaintTable::value(const Vec3d& x, std::int32_t solid) const {
  if (cells.empty()) return 0;
  const Cell c = cell_of(static_cast<float>(x.x()), static_cast<float>(x.y()), static_cast<float>(x.z()), reach);
  const double r2 = static_cast<double>(reach) * reach;
  double sum = 0, weight = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const std::int32_t cx = c.x + dx, cy = c.y + dy, cz = c.z + dz;
        const std::uint32_t b = paint_bucket(cx, cy, cz, mask);
        for (std::uint32_t j = start[b]; j < start[b + 1]; ++j) {
          const std::int32_t* q = &cells[4 * j];
          if (q[0] != cx || q[1] != cy || q[2] != cz || q[3] != solid) continue;
          const float* p = &points[4 * j];
          const double d2 = (Vec3d(p[0], p[1], p[2]) - x).squaredNorm();
          if (d2 >= r2) continue;
          const double s = 1 - d2 / r2, w = s * s * s;
          sum += w * p[3];
          weight += w;
        }
      }
  return weight > 0 ? sum / weight : 0;
}

Vec3d ColorScale::srgb(double value) const {
  const double span = max - min;
  return viridis(span > 0 ? (value - min) / span : 0.0);
}

Vec3d ColorScale::linear(double value) const {
  const Vec3d c = srgb(value);
  return Vec3d(srgb_to_linear(c.x()), srgb_to_linear(c.y()), srgb_to_linear(c.z()));
}

std::vector<float> paint_colors_linear(int samples) {
  const ColorScale unit;
  std::vector<float> out;
  for (int i = 0; i < samples; ++i) {
    const Vec3d c = unit.linear(samples > 1 ? static_cast<double>(i) / (samples - 1) : 0.0);
    out.insert(out.end(), {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z()), 1.0f});
  }
  return out;
}

PaintRange wall_pressure_range(const std::vector<std::string>& frame_paths, std::size_t max_samples) {
  PaintRange r;
  std::vector<float> loaded;
  std::size_t stride = 1;  // every stride-th loaded patch is kept
  r.peak = -std::numeric_limits<double>::infinity();
  for (const std::string& path : frame_paths) {
    const FrameData frame = read_frame_boundary(path);
    require_wall_pressure(frame.fields(), path);
    for (float p : frame.bp) {
      if (p == 0.0f || !std::isfinite(p)) continue;
      r.peak = std::max(r.peak, static_cast<double>(p));
      if (r.samples++ % stride != 0) continue;
      loaded.push_back(p);
      if (loaded.size() > std::max<std::size_t>(max_samples, 2)) {
        // Keep every second: the share stays even over everything seen.
        std::size_t kept = 0;
        for (std::size_t k = 0; k < loaded.size(); k += 2) loaded[kept++] = loaded[k];
        loaded.resize(kept);
        stride *= 2;
      }
    }
    ++r.frames;
  }
  if (loaded.empty()) {  // nothing loaded anywhere: [0, 1] Pa, every face at the bottom colour
    r.peak = 0;
    return r;
  }
  const double high = percentile(loaded, 0.99);
  // Suction shows only where it is more than a trace of the loads (a few patches'
  // fractions of a pascal would otherwise start the scale just below 0).
  const double first = percentile(loaded, 0.01);
  const double low = first < -kSuction * std::max(high, 0.0) ? first : 0.0;
  r.scale.min = low;
  r.scale.max = high > low ? high : low + 1;
  return r;
}

}  // namespace bw::render

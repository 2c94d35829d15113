// The solids coloured by the pressure on their faces: the frames' wall_pressure field
// (docs/formats.md, "Wall pressure"), each boundary particle's pressure on its patch,
// spread over the solid's mesh. At a point x of a solid's surface
//   p(x) = sum_j w_j p_j / sum_j w_j,   w_j = (1 - |x - x_j|^2 / R^2)^3,
// over that solid's particles j within R = one particle spacing, and 0 where there is
// none. R reaches the surface layer (half a spacing behind a face on the sampling
// grid's planes, bw-sample) and not the layer behind it; the weight falls to 0 at R, so
// the colour has no seams where particles enter or leave the reach. mesh.frag
// evaluates p(x) at every pixel from a PaintTable; PaintTable::value is the same on the
// host, for tests and for what a pixel is expected to show.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "io/frame_file.h"

namespace bw::render {

// The particles that can colour a pixel (those within two reaches of a loaded one: the
// rest would add only zeros far from any load), in buckets by a hash of their cell of
// edge R, as std430 arrays for the shader.
struct PaintTable {
  float reach = 0;                     // R, also the cells' edge (m)
  std::uint32_t mask = 0;              // buckets - 1 (buckets a power of two)
  std::vector<float> points;           // x, y, z, p per particle, bucket by bucket
  std::vector<std::int32_t> cells;     // cell x, y, z and solid per particle
  std::vector<std::uint32_t> start;    // bucket b holds particles [start[b], start[b + 1])

  std::size_t size() const { return cells.size() / 4; }
  // p(x) on a face of solid `solid` (the run file's solid row).
  double value(const Vec3d& x, std::int32_t solid) const;
};

// The bucket of cell (cx, cy, cz); mesh.frag computes the same.
std::uint32_t paint_bucket(std::int32_t cx, std::int32_t cy, std::int32_t cz, std::uint32_t mask);

// The table of one frame's boundary particles. Throws InputError naming `where` when
// the frame holds no wall_pressure or no boundary/solid.
PaintTable paint_table(const FrameData& frame, double spacing, const std::string& where);

// Values to colours: [min, max] onto the colour map (viridis: dark blue, green,
// yellow; it reads the same to colour-blind eyes and in grey), clamped at both ends.
struct ColorScale {
  double min = 0, max = 1;
  // sRGB in [0, 1] and linear RGB of a value.
  Vec3d srgb(double value) const;
  Vec3d linear(double value) const;
};

// The colour map at `samples` evenly spaced points of [0, 1], linear RGB: what the
// shader interpolates.
std::vector<float> paint_colors_linear(int samples);

// The range that colours a sequence when none is given: from 0 (or the 1st
// percentile, where that is a suction of more than 5% of the top) to the 99th
// percentile of the loaded patches' pressures (non-zero),
// pooled over the given frames, so that a few single patches' spikes do not darken
// everything else, and every part of a sequence rendered in pieces has the same scale.
// The percentiles come from every loaded patch while there are at most `max_samples`
// of them, else from an even, deterministic share of them (every 2nd, 4th, ... in the
// frames' order), so that a long run's scale costs bounded memory.
struct PaintRange {
  ColorScale scale;
  std::size_t frames = 0, samples = 0;  // frames read, loaded patches seen
  double peak = 0;                      // the highest patch pressure of all
};
PaintRange wall_pressure_range(const std::vector<std::string>& frame_paths, std::size_t max_samples = 1 << 23);

}  // namespace bw::render

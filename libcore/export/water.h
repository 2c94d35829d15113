// The water as a surface: a narrow-band level set of the fluid particles (OpenVDB),
// written as .vdb, and optionally turned into a triangle mesh.
//
// Each particle is rasterized as a sphere of `radius`, the union is smoothed by
// mean-curvature flow, and, when asked, moved inwards by `erode`. With the default
// radius (one spacing) a flat surface of water lies 0.87 spacing beyond its
// outermost particles' centres, 0.37 spacing beyond where their volumes (spacing^3
// each) end: a little more water than there is (a 0.4 x 0.3 x 0.2 m block at 2 cm
// holds 13% more), and no holes in sheets and jets one particle thick. `erode` =
// 0.4 spacing gives the volume back (within 5%), at about twice the cost: each step
// of the offset renormalizes the band, which the union of spheres needs before it
// can shrink (inside overlapping spheres it is no distance). This header keeps
// OpenVDB out of its users.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "common/geometry.h"

namespace bw::exporter {

// breakwater's scenes are z-up; Houdini and glTF are y-up. kY maps (x, y, z) to
// (x, z, -y): a rotation, so shapes and orientation are kept.
enum class Up { kZ, kY };
Vec3d to_up(const Vec3d& p, Up up);

struct WaterOptions {
  double spacing = 0;      // particle spacing (m); required
  double radius = 0;       // sphere radius (m); 0: kRadiusFactor * spacing
  double voxel = 0;        // voxel edge (m); 0: radius / kVoxelsPerRadius
  int smooth = 1;          // mean-curvature iterations
  double erode = 0;        // inward offset after smoothing (m)
  double half_width = 3;   // narrow band, voxels on each side of the surface
  Up up = Up::kZ;

  // Fills in the defaults and checks the values; `where`, when not empty, prefixes
  // messages. Throws InputError.
  void resolve(const std::string& where);
};

// Spheres of one spacing close the gaps between neighbours, also in thin sheets and
// jets a particle thick; two voxels per radius keep the spheres round (OpenVDB drops
// spheres below 1.5 voxels) at a grid eight times finer than the particles.
inline constexpr double kRadiusFactor = 1.0;
inline constexpr double kVoxelsPerRadius = 2.0;
// The smallest voxel edge OpenVDB takes (m): its transforms refuse a voxel volume
// under 3e-15.
inline constexpr double kMinVoxel = 1.5e-5;
// The most voxels a sphere's radius may span: drawing a sphere visits about
// (2 x that)^3 voxels, and at 40 a frame of 2000 particles takes 8 s and 0.9 GB.
inline constexpr double kMaxVoxelsPerRadius = 64;

struct WaterStats {
  std::size_t particles = 0;      // rasterized (finite positions)
  std::size_t active_voxels = 0;  // in the narrow band
  double seconds = 0;             // building the level set
};

class WaterSurface {
 public:
  // Builds the level set of `count` particles (float positions as in frame files).
  static WaterSurface build(const float* x, const float* y, const float* z, std::size_t count,
                            const WaterOptions& options);
  ~WaterSurface();
  WaterSurface(WaterSurface&&) noexcept;
  WaterSurface& operator=(WaterSurface&&) noexcept;

  const WaterStats& stats() const { return stats_; }
  bool empty() const;

  // Writes the grid "surface" (a level set, in metres), and with `density` also a
  // fog volume "density" (1 inside, 0 outside, across the band), through a
  // temporary file. Throws RunError when writing fails.
  void write_vdb(const std::string& path, bool density) const;

  // The zero isosurface as triangles, counter-clockwise seen from outside.
  // `adaptivity` in [0, 1]: 0 keeps every voxel's polygon, more merges flat parts.
  TriMesh mesh(double adaptivity = 0) const;

  // Volume inside the surface (m^3).
  double volume() const;

 private:
  struct Grid;
  WaterSurface();
  std::unique_ptr<Grid> grid_;
  WaterStats stats_;
};

}  // namespace bw::exporter

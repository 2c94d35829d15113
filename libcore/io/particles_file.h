// Files of kind "particles": a solid sampled on a grid of cubic cells, written by
// bw-sample and read by bw-sim, bw-voronoi and bw-render. Layout in docs/formats.md.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace bw {

using CellIndex = std::array<std::int32_t, 3>;

// The sampling grid: cubic cells of edge `spacing`; cell (i, j, k) spans
// origin + [i, i+1] x [j, j+1] x [k, k+1] * spacing.
struct SampleGrid {
  Vec3d origin = Vec3d::Zero();
  double spacing = 0;
  CellIndex dims{0, 0, 0};

  Vec3d cell_center(const CellIndex& c) const {
    return origin + spacing * Vec3d(c[0] + 0.5, c[1] + 0.5, c[2] + 0.5);
  }
  std::uint64_t cell_count() const {
    return static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(dims[1]) *
           static_cast<std::uint64_t>(dims[2]);
  }
  // How far, in cells, a coordinate meant to lie on a cell plane (a face 0.2 m from the
  // origin at a spacing of 0.01 m) may be off it: kPlaneSnap cells, plus what storing
  // it and the origin in single precision can move them. Mesh readers (assimp among
  // them) hand over float vertices: 0.8245 m as a float is 0.82450002, 1.3e-6 of a
  // 0.02 m cell off the plane it was meant to lie on.
  static constexpr double kPlaneSnap = 1e-6;
  static constexpr double kFloatRounding = 0x1p-22;  // four times a float's half-ulp, relative
  double plane_tolerance(double coordinate, int axis) const {
    return kPlaneSnap + kFloatRounding * (std::abs(coordinate) + std::abs(origin[axis])) / spacing;
  }
};

// Which surface cells bw-sample marks (the file's `surface_rule`, docs/formats.md):
// 2 since the cells behind concave edges on cell planes (a tank's floor-wall edge) are
// surface cells; 1 for files written before, which lack those rows.
inline constexpr std::int32_t kSurfaceRule = 2;

struct SampledSolid {
  SampleGrid grid;
  std::int32_t surface_rule = kSurfaceRule;
  // Cells that a triangle of the mesh overlaps: one boundary particle at each centre.
  std::vector<CellIndex> surface;
  // Cells whose centre lies inside the mesh ("voxels"); empty unless has_voxels.
  std::vector<CellIndex> voxels;
  bool has_voxels = false;
  // The sampled mesh, after scaling and welding (bw-voronoi and bw-render use it).
  TriMesh mesh;
  // Provenance, stored as attributes.
  std::string source;       // the mesh file as given to bw-sample
  double scale = 1.0;
  double mesh_volume = 0;   // volume the mesh bounds (0 when it is open)

  std::vector<Vec3d> surface_positions() const;
  std::vector<Vec3d> voxel_positions() const;
  double voxel_volume() const { return static_cast<double>(voxels.size()) * grid.spacing * grid.spacing * grid.spacing; }
};

// Writes `solid` to `path` ("-" for standard output) through a temporary file.
void write_particles(const SampledSolid& solid, const std::string& path, const std::string& tool);

// Reads a particles file ("-" for standard input). Throws InputError naming the file
// and what is wrong with it.
SampledSolid read_particles(const std::string& path);

}  // namespace bw

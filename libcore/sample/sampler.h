// Turning a triangle mesh into particles (method.md 2.1).
//
// The mesh's bounding box is divided into cubic cells of edge `spacing`. Surface
// sampling marks every cell that a triangle overlaps (exact triangle-box test), and
// the cells behind concave edges whose faces lie on cell planes, and puts one
// boundary particle at each centre. Volume sampling also marks the cells
// whose centre lies inside the closed mesh ("voxels"), by exact ray parity with a
// symbolic perturbation, so that rays through vertices and along edges, and faces
// lying on cell planes, are all counted right. Cost: proportional to the cells the
// triangles cover, never cells x triangles.
#pragma once

#include <string>
#include <vector>

#include "io/particles_file.h"
#include "mesh/check.h"

namespace bw::sample {

struct SampleOptions {
  double spacing = 0;       // cell edge r0 (m); > 0
  bool volume = false;      // also sample interior voxels (needs a closed, oriented mesh)
  std::string source;       // the mesh file, for messages and provenance
  double scale = 1.0;       // recorded in the output
};

// The grid of the paper: its origin is the minimum corner of the mesh's bounding
// box, with enough cells to cover the box (at least one per axis).
SampleGrid grid_for(const Aabb& bounds, double spacing);

// Grid coordinates of a point: cell (i, j, k) spans [i, i+1] x [j, j+1] x [k, k+1].
// A coordinate within SampleGrid::plane_tolerance of an integer is set to it, so that
// a face meant to lie on a cell plane does so exactly instead of falling on either
// side by rounding.
Vec3d to_grid_coordinates(const Vec3d& p, const SampleGrid& grid);

struct SampleEstimate {
  double surface_particles = 0;
  double voxels = 0;
  double bytes = 0;          // peak memory of sampling and writing
};
SampleEstimate estimate(const TriMesh& mesh, const SampleGrid& grid, bool volume);

// Cells that a triangle overlaps, sorted by (k, j, i), without duplicates. A face
// lying exactly on a cell plane (axis-aligned) marks only the cells on its inner
// side (against its normal), so boundary particles stay inside the solid, half a cell
// from such faces, as they do at the faces of the bounding box. A cell that faces
// touch without entering it is marked too when the faces nearest its centre lie on
// two different planes and all have it behind them (the solid's cell at a tank's
// floor-wall edge).
std::vector<CellIndex> surface_cells(const TriMesh& mesh, const SampleGrid& grid);

// Cells whose centre has a non-zero winding number with respect to the mesh, sorted
// by (k, j, i). Right for closed, consistently oriented meshes of either
// orientation.
std::vector<CellIndex> interior_cells(const TriMesh& mesh, const SampleGrid& grid);

struct SampleReport {
  mesh::MeshReport mesh;
  bool flipped = false;   // the closed mesh faced inwards and was turned right
};

// Checks the input (finite coordinates, spacing, memory, closedness when volume is
// asked for) and samples. An inside-out closed mesh is flipped so that the stored
// mesh faces outwards. Throws InputError naming options.source.
SampledSolid sample_mesh(TriMesh mesh, const SampleOptions& options, SampleReport* report = nullptr);

}  // namespace bw::sample

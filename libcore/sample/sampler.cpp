#include "sample/sampler.h"

#include <cmath>

#include "common/error.h"
#include "common/memory.h"
#include "common/text.h"
#include "mesh/properties.h"

namespace bw::sample {
namespace {

// Largest grid extent per axis: cell indices are stored as int32.
constexpr double kMaxCellsPerAxis = 2147483647.0;

}  // namespace

Vec3d to_grid_coordinates(const Vec3d& p, const SampleGrid& grid) {
  Vec3d t = (p - grid.origin) / grid.spacing;
  for (int k = 0; k < 3; ++k) {
    const double nearest = std::round(t[k]);
    if (std::fabs(t[k] - nearest) <= grid.plane_tolerance(p[k], k)) t[k] = nearest;
  }
  return t;
}

SampleGrid grid_for(const Aabb& bounds, double spacing) {
  SampleGrid grid;
  grid.origin = bounds.min;
  grid.spacing = spacing;
  // The far faces in grid coordinates, snapped as every vertex is: a box of exactly n
  // cells gets n, whichever way its corners rounded.
  const Vec3d far = to_grid_coordinates(bounds.max, grid);
  for (int k = 0; k < 3; ++k) {
    const double cells = std::ceil(far[k]);
    grid.dims[k] = static_cast<std::int32_t>(std::max(1.0, std::min(cells, kMaxCellsPerAxis)));
  }
  return grid;
}

SampleEstimate estimate(const TriMesh& mesh, const SampleGrid& grid, bool volume) {
  const mesh::MassProperties props = mesh::mass_properties(mesh);
  const double r = grid.spacing;
  double perimeter = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3d& a = mesh.vertices[t[0]];
    const Vec3d& b = mesh.vertices[t[1]];
    const Vec3d& c = mesh.vertices[t[2]];
    perimeter += (b - a).norm() + (c - b).norm() + (a - c).norm();
  }
  const double triangles = static_cast<double>(mesh.triangles.size());
  SampleEstimate e;
  // A plane crosses up to sqrt(3) cells per r^2 of its area.
  e.surface_particles = std::min(1.8 * props.area / (r * r) + triangles, static_cast<double>(grid.cell_count()));
  // Cells found before duplicates are removed: each triangle also finds the cells
  // along its edges and corners.
  const double found = 1.8 * props.area / (r * r) + perimeter / r + 8 * triangles;
  e.voxels = volume ? std::min(std::fabs(props.volume) / (r * r * r), static_cast<double>(grid.cell_count())) : 0;
  const double crossings = volume ? 2.0 * props.area / (r * r) + triangles : 0;
  const double mesh_bytes = 24.0 * static_cast<double>(mesh.vertices.size()) + 12.0 * triangles;
  // Cells touched without being entered (48 B each, sorted), at most the layer in
  // front of each face on a cell plane and the cells along the triangles' edges.
  const double touched = props.area / (r * r) + perimeter / r + 8 * triangles;
  // Candidates (8 B) sorted; cells (12 B) and positions (24 B) while writing;
  // crossings (24 B) sorted; the in-memory copy HDF5 keeps when writing to stdout.
  e.bytes = 2 * 8 * found + 2 * 48 * touched + 36 * e.surface_particles + 12 * e.voxels + 2 * 24 * crossings +
            2 * mesh_bytes;
  return e;
}

SampledSolid sample_mesh(TriMesh mesh, const SampleOptions& options, SampleReport* report_out) {
  const std::string& name = options.source;
  if (!(options.spacing > 0) || !std::isfinite(options.spacing)) {
    fail_input("{}: spacing {} must be a positive number", name, options.spacing);
  }
  const mesh::MeshReport report = mesh::check_mesh(mesh);
  if (report_out) report_out->mesh = report;
  if (report.triangles == 0) fail_input("{}: the mesh has no triangles", name);
  if (report.nonfinite_vertices) fail_input("{}: {} vertices have a non-finite coordinate", name, report.nonfinite_vertices);
  if (report.bad_indices) fail_input("{}: {} faces refer to vertices that do not exist", name, report.bad_indices);
  if (options.volume && !report.bounds_volume()) {
    fail_input("{}: --volume needs a closed, consistently oriented mesh; this one has {}", name, report.summary());
  }

  const Aabb bounds = mesh.bounds();
  const Vec3d extent = bounds.extent();
  for (int k = 0; k < 3; ++k) {
    if (extent[k] / options.spacing >= kMaxCellsPerAxis) {
      fail_input("{}: spacing {} gives {:.3g} cells along axis {}; at most {:.0f} are possible", name, options.spacing,
                 extent[k] / options.spacing, "xyz"[k], kMaxCellsPerAxis);
    }
  }
  const SampleGrid grid = grid_for(bounds, options.spacing);
  const SampleEstimate need = estimate(mesh, grid, options.volume);
  check_fits_in_memory(static_cast<std::uint64_t>(need.bytes),
                       fmt::format("{}: spacing {} gives about {} surface particles{}; sampling", name, options.spacing,
                                   human_count(need.surface_particles),
                                   options.volume ? fmt::format(" and {} voxels", human_count(need.voxels)) : ""));

  SampledSolid solid;
  solid.grid = grid;
  solid.source = options.source;
  solid.scale = options.scale;
  if (report.bounds_volume()) {
    const double volume = mesh::mass_properties(mesh).volume;
    if (volume < 0) {
      mesh::flip_faces(mesh);
      if (report_out) report_out->flipped = true;
    }
    solid.mesh_volume = std::fabs(volume);
  }
  solid.surface = surface_cells(mesh, grid);
  // No particle is no solid: a spacing beyond the mesh's size, most likely in other units.
  if (solid.surface.empty())
    fail_input("{}: spacing {} gives no surface particle; the mesh spans {:.4g} m at most", name, options.spacing,
               extent.maxCoeff());
  if (options.volume) {
    solid.voxels = interior_cells(mesh, grid);
    solid.has_voxels = true;
  }
  solid.mesh = std::move(mesh);
  return solid;
}

}  // namespace bw::sample

#include "io/particles_file.h"

#include <cmath>

#include "common/error.h"
#include "io/arrays.h"
#include "io/h5.h"

namespace bw {
namespace {

constexpr const char* kKind = "particles";

std::vector<CellIndex> read_cells(const h5::Group& group, const char* name, const SampleGrid& grid) {
  std::size_t rows = 0;
  const std::vector<std::int32_t> flat = group.read_rows<std::int32_t>(name, 3, &rows);
  std::vector<CellIndex> cells(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    for (int k = 0; k < 3; ++k) {
      cells[i][k] = flat[3 * i + k];
      if (cells[i][k] < 0 || cells[i][k] >= grid.dims[k]) {
        fail_input("{}: row {} holds cell index {} outside the grid of {} cells along axis {}", group.where(name), i,
                   cells[i][k], grid.dims[k], k);
      }
    }
  }
  return cells;
}

}  // namespace

std::vector<Vec3d> SampledSolid::surface_positions() const {
  std::vector<Vec3d> p(surface.size());
  for (std::size_t i = 0; i < surface.size(); ++i) p[i] = grid.cell_center(surface[i]);
  return p;
}

std::vector<Vec3d> SampledSolid::voxel_positions() const {
  std::vector<Vec3d> p(voxels.size());
  for (std::size_t i = 0; i < voxels.size(); ++i) p[i] = grid.cell_center(voxels[i]);
  return p;
}

void write_particles(const SampledSolid& solid, const std::string& path, const std::string& tool) {
  h5::File file = h5::File::create(path, kKind);
  h5::Group& root = file.root();
  root.set_attr("tool", tool);
  root.set_attr("source", solid.source);
  root.set_attr("scale", solid.scale);
  root.set_attr("spacing", solid.grid.spacing);
  const double origin[3] = {solid.grid.origin.x(), solid.grid.origin.y(), solid.grid.origin.z()};
  root.set_attr("origin", std::span<const double>(origin));
  root.set_attr("dims", std::span<const std::int32_t>(solid.grid.dims));
  root.set_attr("mesh_volume", solid.mesh_volume);
  root.set_attr<std::int32_t>("surface_rule", solid.surface_rule);

  h5::Group surface = root.create_group("surface");
  const std::uint64_t n = solid.surface.size();
  surface.write<std::int32_t>("cell", io::flatten(solid.surface), {n, 3});
  surface.write<double>("position", io::flatten(solid.surface_positions()), {n, 3});

  if (solid.has_voxels) {
    h5::Group voxels = root.create_group("voxels");
    voxels.write<std::int32_t>("cell", io::flatten(solid.voxels), {solid.voxels.size(), 3});
    voxels.set_attr("volume", solid.voxel_volume());
  }

  h5::Group mesh = root.create_group("mesh");
  mesh.write<double>("vertices", io::flatten(solid.mesh.vertices), {solid.mesh.vertices.size(), 3});
  mesh.write<std::int32_t>("triangles", io::flatten(solid.mesh.triangles), {solid.mesh.triangles.size(), 3});
  file.commit();
}

SampledSolid read_particles(const std::string& path) {
  h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  SampledSolid solid;
  solid.source = root.has_attr("source") ? root.attr_string("source") : "";
  solid.scale = root.has_attr("scale") ? root.attr<double>("scale") : 1.0;
  solid.mesh_volume = root.has_attr("mesh_volume") ? root.attr<double>("mesh_volume") : 0.0;
  solid.surface_rule = root.has_attr("surface_rule") ? root.attr<std::int32_t>("surface_rule") : 1;
  solid.grid.spacing = root.attr<double>("spacing");
  if (!(solid.grid.spacing > 0) || !std::isfinite(solid.grid.spacing)) {
    fail_input("{}: spacing {} is not a positive number", file.name(), solid.grid.spacing);
  }
  const std::vector<double> origin = root.attr_array<double>("origin");
  const std::vector<std::int32_t> dims = root.attr_array<std::int32_t>("dims");
  if (origin.size() != 3 || dims.size() != 3) fail_input("{}: 'origin' and 'dims' must hold 3 values", file.name());
  solid.grid.origin = Vec3d(origin[0], origin[1], origin[2]);
  for (int k = 0; k < 3; ++k) solid.grid.dims[k] = dims[k];

  solid.surface = read_cells(root.open_group("surface"), "cell", solid.grid);
  solid.has_voxels = root.is_group("voxels");
  if (solid.has_voxels) solid.voxels = read_cells(root.open_group("voxels"), "cell", solid.grid);

  const h5::Group mesh = root.open_group("mesh");
  std::size_t nv = 0, nf = 0;
  const std::vector<double> vertices = mesh.read_rows<double>("vertices", 3, &nv);
  const std::vector<std::int32_t> triangles = mesh.read_rows<std::int32_t>("triangles", 3, &nf);
  solid.mesh.vertices = io::unflatten_points(vertices);
  solid.mesh.triangles.resize(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = triangles[3 * i + k];
      if (v < 0 || static_cast<std::size_t>(v) >= nv) {
        fail_input("{}: triangle {} refers to vertex {}, the mesh has {}", mesh.where("triangles"), i, v, nv);
      }
      solid.mesh.triangles[i][k] = v;
    }
  }
  return solid;
}

}  // namespace bw

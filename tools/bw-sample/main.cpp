// bw-sample: turn a triangle mesh into boundary particles (and interior voxels).
#include <cstdio>

#include "cli/tool.h"
#include "common/atomic_file.h"
#include "common/terminal.h"
#include "io/particles_file.h"
#include "mesh/import.h"
#include "mesh/properties.h"
#include "sample/sampler.h"

namespace {

struct Options {
  std::string mesh;
  std::string output;
  double spacing = 0;
  bool volume = false;
  double scale = 1.0;
  double weld = 0.0;
  bool verbose = false;
};

void print_summary(const Options& o, const bw::SampledSolid& s, const bw::sample::SampleReport& report,
                   const bw::mesh::ImportStats& import, double seconds) {
  const auto& m = report.mesh;
  std::fprintf(stderr, "bw-sample: %s -> %s in %.2f s\n", o.mesh.c_str(), o.output.c_str(), seconds);
  std::fprintf(stderr, "  options      spacing %g, scale %g, weld %g, volume %s\n", o.spacing, o.scale, o.weld,
               o.volume ? "yes" : "no");
  std::fprintf(stderr, "  mesh         %zu meshes merged, %zu vertices (%zu read), %zu triangles, %zu components\n",
               import.meshes, m.vertices, import.vertices_read, m.triangles, m.components);
  std::fprintf(stderr, "  topology     %s%s\n", m.summary().c_str(), report.flipped ? " (faced inwards: flipped)" : "");
  if (m.degenerate_faces) std::fprintf(stderr, "  warning      %zu degenerate faces\n", m.degenerate_faces);
  const bw::Aabb box = s.mesh.bounds();
  std::fprintf(stderr, "  bounds       [%g, %g, %g] .. [%g, %g, %g]\n", box.min.x(), box.min.y(), box.min.z(),
               box.max.x(), box.max.y(), box.max.z());
  std::fprintf(stderr, "  grid         %d x %d x %d cells, origin [%g, %g, %g]\n", s.grid.dims[0], s.grid.dims[1],
               s.grid.dims[2], s.grid.origin.x(), s.grid.origin.y(), s.grid.origin.z());
  std::fprintf(stderr, "  surface      %zu particles\n", s.surface.size());
  if (m.bounds_volume()) std::fprintf(stderr, "  mesh volume  %.6g\n", s.mesh_volume);
  if (s.has_voxels) {
    const double err = s.mesh_volume > 0 ? (s.voxel_volume() - s.mesh_volume) / s.mesh_volume : 0.0;
    std::fprintf(stderr, "  voxels       %zu, volume %.6g (%+.2f%% of the mesh volume)\n", s.voxels.size(),
                 s.voxel_volume(), 100 * err);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Sample a triangle mesh into boundary particles, one per grid cell that the surface\n"
               "overlaps, and with --volume the interior cells (voxels) too.",
               "bw-sample"};
  bw::cli::setup(app,
                 "  bw-sample wall.obj -o wall.h5 --spacing 0.02\n"
                 "  bw-sample house.ply -o house.h5 --spacing 0.05 --volume -v\n"
                 "  bw-sample model.fbx --scale 0.01 --spacing 0.02 -o - | bw-info -\n");
  Options o;
  app.add_option("mesh", o.mesh, "Mesh file: any format assimp reads (OBJ, PLY, STL, OFF, glTF, FBX, ...)")
      ->required();
  app.add_option("-o,--output", o.output, "Particle file to write (HDF5; '-' for standard output)")->required();
  app.add_option("--spacing", o.spacing, "Cell edge and particle spacing r0, in scene units (m)")
      ->required()
      ->check(bw::cli::kPositive);
  app.add_flag("--volume", o.volume, "Also sample the interior cells (needs a closed, consistently oriented mesh)");
  app.add_option("--scale", o.scale, "Multiply every coordinate by this factor")->check(bw::cli::kPositive);
  app.add_option("--weld", o.weld, "Merge vertices closer than this distance (default: only identical ones)")
      ->check(bw::cli::kNonNegative);
  app.add_flag("-v,--verbose", o.verbose, "Print counts, bounds, volumes and the options used");

  return bw::cli::run(app, argc, argv, [&] {
    bw::check_output_file(o.output, {o.mesh});  // before the work, not after it
    bw::Stopwatch clock;
    bw::mesh::ImportStats import;
    bw::TriMesh mesh = bw::mesh::import_mesh(o.mesh, {o.scale, o.weld}, &import);
    bw::sample::SampleReport report;
    const bw::SampledSolid solid =
        bw::sample::sample_mesh(std::move(mesh), {o.spacing, o.volume, o.mesh, o.scale}, &report);
    bw::write_particles(solid, o.output, "bw-sample " BW_VERSION);
    if (o.verbose) print_summary(o, solid, report, import, clock.seconds());
    return bw::kExitOk;
  });
}

// Surface and volume sampling of a mesh of about 1 M triangles at a spacing that
// gives about 1 M particles (issue target: under 5 s each on 2 cores).
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/terminal.h"
#include "io/particles_file.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"

int main() {
  // A torus of 1000 x 500 quads: 1 M triangles.
  const double R = 1.0, r = 0.35;
  bw::Stopwatch make;
  const bw::TriMesh mesh = bw::mesh::torus(bw::Vec3d::Zero(), R, r, 1000, 500);
  const double area = 4 * std::numbers::pi * std::numbers::pi * R * r;
  const double volume = 2 * std::numbers::pi * std::numbers::pi * R * r * r;
  std::printf("mesh: torus, %zu triangles, %zu vertices (made in %.2f s); threads: %d\n", mesh.triangles.size(),
              mesh.vertices.size(), make.seconds(), omp_get_max_threads());

  // About 1 M surface particles: a surface crosses ~1.5 cells per spacing^2 of area.
  const double surface_spacing = std::sqrt(1.5 * area / 1.0e6);
  // About 1 M voxels.
  const double volume_spacing = std::cbrt(volume / 1.0e6);

  for (int rep = 0; rep < 2; ++rep) {
    bw::Stopwatch clock;
    const auto grid = bw::sample::grid_for(mesh.bounds(), surface_spacing);
    const auto surface = bw::sample::surface_cells(mesh, grid);
    const double t = clock.seconds();
    std::printf("surface sampling: spacing %.5f, grid %d x %d x %d, %zu particles, %.3f s, %.2f M triangles/s\n",
                surface_spacing, grid.dims[0], grid.dims[1], grid.dims[2], surface.size(), t,
                mesh.triangles.size() / t / 1e6);
  }
  for (int rep = 0; rep < 2; ++rep) {
    bw::Stopwatch clock;
    const auto grid = bw::sample::grid_for(mesh.bounds(), volume_spacing);
    const auto voxels = bw::sample::interior_cells(mesh, grid);
    const double t = clock.seconds();
    const double vv = voxels.size() * std::pow(volume_spacing, 3);
    std::printf("volume sampling:  spacing %.5f, grid %d x %d x %d, %zu voxels, %.3f s, volume error %+.3f%%\n",
                volume_spacing, grid.dims[0], grid.dims[1], grid.dims[2], voxels.size(), t,
                100 * (vv - volume) / volume);
  }
  {
    // The whole of bw-sample --volume minus import: checks, both samplings, writing.
    bw::Stopwatch clock;
    bw::sample::SampleOptions options;
    options.spacing = volume_spacing;
    options.volume = true;
    options.source = "torus";
    const bw::SampledSolid solid = bw::sample::sample_mesh(mesh, options);
    const double t_sample = clock.seconds();
    bw::write_particles(solid, "/tmp/bench-sample.h5", "bench-sample");
    std::printf("sample_mesh --volume (checks + surface + volume): %.3f s; writing %zu + %zu cells: %.3f s\n", t_sample,
                solid.surface.size(), solid.voxels.size(), clock.seconds() - t_sample);
    std::remove("/tmp/bench-sample.h5");
  }
  return 0;
}

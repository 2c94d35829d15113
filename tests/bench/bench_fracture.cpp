// Fracture benchmark: the host side of one fracture event (docs/performance.md) for
// a solid of 100 k voxels (a 100 x 100 x 10 slab at 1 cm) and 100 seeds: the seed
// choice among the particles over their binding energy, the particles' voxels, the
// Voronoi cells restricted to the voxels and their components, the fragments' mass
// properties and particles, and their binding energies. Prints figures, asserts
// nothing.
//   bench-fracture [SEEDS [THREADS]]
#include <cstdio>
#include <cstdlib>
#include <random>

#include "common/terminal.h"
#include "fracture/fracture.h"
#include "test_support.h"

int main(int argc, char** argv) {
  const std::size_t seeds = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  constexpr double s = 0.01;
  constexpr int nx = 100, ny = 100, nz = 10;
  bw::fracture::Piece piece;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bw::Vec3d c = s * bw::Vec3d(i + 0.5, j + 0.5, k + 0.5);
        piece.cells.push_back({i, j, k});
        piece.centers.push_back(c);
        piece.anchor.push_back(k == 0 ? 1 : 0);
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) {
          piece.particles.push_back(c);
          piece.normals.push_back(bw::Vec3d::Zero());
          piece.flatness.push_back(1.0);
          piece.particle_cells.push_back({i, j, k});
        }
      }
  // Every particle of the top face over its binding energy, the strongest near one
  // corner (an impact there).
  std::mt19937 rng(7);
  std::vector<bw::fracture::Candidate> candidates;
  for (std::size_t p = 0; p < piece.particles.size(); ++p)
    if (piece.particle_cells[p][2] == nz - 1)
      candidates.push_back({static_cast<std::int32_t>(p), 1.0 + 10.0 / (1.0 + piece.particles[p].head<2>().norm() * 10) +
                                                               std::uniform_real_distribution<double>(0, 0.1)(rng)});
  bw::Stopwatch clock;
  const auto chosen = bw::fracture::select_seeds(candidates, piece.particles, 2 * s, seeds);
  const double t_seeds = clock.seconds();
  clock = bw::Stopwatch();
  const auto voxel_of = bw::fracture::particle_voxels(piece);
  std::vector<bw::Vec3d> points;
  for (const std::int32_t p : chosen) points.push_back(piece.centers[static_cast<std::size_t>(voxel_of[static_cast<std::size_t>(p)])]);
  const double t_voxels = clock.seconds();
  clock = bw::Stopwatch();
  const auto fragments = bw::fracture::split(piece, points, s, 2400, threads);
  const double t_split = clock.seconds();
  clock = bw::Stopwatch();
  std::size_t particles = 0;
  for (const auto& b : bw::fracture::fragment_bond_counts(fragments, s, 2 * s, threads)) particles += b.size();
  const double t_bonds = clock.seconds();
  const double total = t_seeds + t_voxels + t_split + t_bonds;
  std::printf("fracture: %zu voxels, %zu particles, %zu seeds, %d threads\n", piece.size(), piece.particles.size(),
              points.size(), threads);
  bw::test::figure("fragments", static_cast<double>(fragments.size()));
  bw::test::figure("fragment particles", static_cast<double>(particles));
  bw::test::figure("seed choice", t_seeds, "s");
  bw::test::figure("particle voxels", t_voxels, "s");
  bw::test::figure("split (cells, components, mass, particles)", t_split, "s");
  bw::test::figure("binding energies", t_bonds, "s");
  bw::test::figure("total", total, "s");
  return 0;
}

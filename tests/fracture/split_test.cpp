// Fracture on the host (libcore/fracture): the voxels nearest each seed, split into
// face-connected components, with exact voxel counts and masses, crack particles, the
// seed choice and the bond counts.
#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "fracture/fracture.h"

namespace bw::fracture {
namespace {

constexpr double kS = 0.01;

// A block of nx x ny x nz voxels of edge kS from the origin, with particles on its
// surface voxels (normals along the faces, zero elsewhere).
Piece block(int nx, int ny, int nz) {
  Piece p;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Vec3d c = kS * Vec3d(i + 0.5, j + 0.5, k + 0.5);
        p.cells.push_back({i, j, k});
        p.centers.push_back(c);
        p.anchor.push_back(k == 0 ? 1 : 0);
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) {
          p.particles.push_back(c);
          p.normals.push_back(Vec3d::Zero());
          p.flatness.push_back(1.0);
          p.particle_cells.push_back({i, j, k});
        }
      }
  return p;
}

std::size_t voxels_of(const std::vector<Fragment>& fragments) {
  std::size_t n = 0;
  for (const Fragment& f : fragments) n += f.piece.size();
  return n;
}

TEST(Split, VoxelsAndMassAreConservedExactly) {
  const Piece p = block(20, 10, 8);
  const std::vector<Vec3d> seeds = {{0.03, 0.02, 0.01}, {0.15, 0.05, 0.05}, {0.12, 0.08, 0.02}, {0.05, 0.07, 0.06}};
  const auto fragments = split(p, seeds, kS, 2400);
  ASSERT_GE(fragments.size(), 4u);
  EXPECT_EQ(voxels_of(fragments), p.size());
  std::int64_t counted = 0;
  for (const Fragment& f : fragments) counted += static_cast<std::int64_t>(f.piece.size());
  EXPECT_EQ(counted, 1600);
  // Mass is voxels x voxel mass, exactly as the voxel count.
  for (const Fragment& f : fragments)
    EXPECT_DOUBLE_EQ(f.mass.mass, rigid::voxel_mass_properties(f.piece.centers, kS, 2400).mass);
  // Every voxel is in the cell of its nearest seed.
  for (const Fragment& f : fragments)
    for (const Vec3d& c : f.piece.centers)
      for (std::size_t s = 0; s < seeds.size(); ++s)
        EXPECT_LE((c - seeds[static_cast<std::size_t>(f.seed)]).norm(), (c - seeds[s]).norm() + 1e-12);
  // The parent's particles are all kept, and crack faces got new ones.
  std::size_t particles = 0;
  for (const Fragment& f : fragments) particles += f.piece.particles.size();
  EXPECT_GT(particles, p.particles.size());
}

TEST(Split, CellsFallApartIntoFaceConnectedComponents) {
  // A U of voxels: the seed in the middle of the bottom gets the bottom, the seeds
  // over the arms' tops ... one cell holds both arm tips only through other cells.
  Piece p;
  auto add = [&](int i, int j, int k) {
    p.cells.push_back({i, j, k});
    p.centers.push_back(kS * Vec3d(i + 0.5, j + 0.5, k + 0.5));
  };
  for (int i = 0; i < 9; ++i) add(i, 0, 0);
  for (int k = 1; k < 6; ++k) add(0, 0, k), add(8, 0, k);
  // Seed 0 in the middle of the bottom, seed 1 high between the arms: its cell is
  // the top of both arms, two components.
  const auto fragments = split(p, {kS * Vec3d(4.5, 0.5, 0.5), kS * Vec3d(4.5, 0.5, 5.5)}, kS, 1000);
  ASSERT_EQ(fragments.size(), 3u);
  EXPECT_EQ(fragments[0].seed, 0);
  EXPECT_EQ(fragments[1].seed, 1);
  EXPECT_EQ(fragments[2].seed, 1);
  EXPECT_EQ(fragments[1].component, 0);
  EXPECT_EQ(fragments[2].component, 1);
  EXPECT_GE(fragments[1].piece.size(), fragments[2].piece.size());
  EXPECT_EQ(voxels_of(fragments), p.size());
}

TEST(Split, DeterministicWhateverTheThreads) {
  const Piece p = block(30, 12, 10);
  std::vector<Vec3d> seeds;
  for (int s = 0; s < 17; ++s) seeds.push_back(kS * Vec3d((s * 7) % 30 + 0.5, (s * 5) % 12 + 0.5, (s * 3) % 10 + 0.5));
  const auto a = split(p, seeds, kS, 2400, 1);
  const auto b = split(p, seeds, kS, 2400, 2);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t f = 0; f < a.size(); ++f) {
    EXPECT_EQ(a[f].seed, b[f].seed);
    EXPECT_EQ(a[f].component, b[f].component);
    EXPECT_EQ(a[f].piece.cells, b[f].piece.cells);
    EXPECT_EQ(a[f].piece.particles, b[f].piece.particles);
    EXPECT_EQ(a[f].mass.center, b[f].mass.center);
  }
}

TEST(Split, AnchorGoesWithItsVoxels) {
  const Piece p = block(4, 4, 10);  // anchor: the bottom layer
  const auto fragments = split(p, {kS * Vec3d(2, 2, 1), kS * Vec3d(2, 2, 9)}, kS, 2400);
  ASSERT_EQ(fragments.size(), 2u);
  EXPECT_TRUE(fragments[0].anchored);
  EXPECT_FALSE(fragments[1].anchored);
}

TEST(Seeds, StrongestFirstAtLeastTheMinimumDistanceApartUpToTheCap) {
  const std::vector<Vec3d> x = {{0, 0, 0}, {0.005, 0, 0}, {0.05, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}};
  const std::vector<Candidate> c = {{0, 2.0}, {1, 3.0}, {2, 1.5}, {3, 1.2}, {4, 1.1}};
  EXPECT_EQ(select_seeds(c, x, 0.02, 10), (std::vector<std::int32_t>{1, 2, 3, 4}));
  EXPECT_EQ(select_seeds(c, x, 0.02, 2), (std::vector<std::int32_t>{1, 2}));
}

TEST(Bonds, KernelWeightedNeighbourCount) {
  // Alone: W_spiky(0, h) s^3 = 15 / (pi 8) = 0.597 at h = 2 s.
  EXPECT_NEAR(bond_counts({Vec3d::Zero()}, kS, 2 * kS)[0], 15.0 / (3.14159265358979 * 8), 1e-9);
  // Inside a lattice it has more bonds than on its face.
  const Piece p = block(7, 7, 7);
  std::vector<Vec3d> all = p.centers;
  const auto b = bond_counts(all, kS, 2 * kS);
  const std::size_t centre = (3 * 7 + 3) * 7 + 3, face = (3 * 7 + 3) * 7 + 0;
  EXPECT_NEAR(b[centre], 1.24, 0.02);
  EXPECT_LT(b[face], b[centre]);
}

TEST(Bonds, FragmentsByCellOffsetsAsByDistance) {
  // fragment_bond_counts finds bonds at cell offsets; bond_counts by distance. They
  // agree on split's fragments (parent particles and crack faces), at h = 2 s and at
  // a support that is not a whole number of spacings.
  const Piece p = block(16, 12, 9);
  const std::vector<Vec3d> seeds = {{0.03, 0.02, 0.01}, {0.13, 0.05, 0.05}, {0.1, 0.09, 0.02}, {0.05, 0.08, 0.07}};
  const auto fragments = split(p, seeds, kS, 2400);
  ASSERT_GE(fragments.size(), 4u);
  for (const double h : {2 * kS, 1.7 * kS, 2.6 * kS}) {
    const auto by_cells = fragment_bond_counts(fragments, kS, h, 2);
    ASSERT_EQ(by_cells.size(), fragments.size());
    for (std::size_t f = 0; f < fragments.size(); ++f) {
      const auto by_distance = bond_counts(fragments[f].piece.particles, kS, h);
      ASSERT_EQ(by_cells[f].size(), by_distance.size());
      for (std::size_t i = 0; i < by_distance.size(); ++i)
        EXPECT_NEAR(by_cells[f][i], by_distance[i], 1e-12) << "h " << h << ", fragment " << f << ", particle " << i;
    }
  }
}

TEST(Split, PartsGiveTheSameFragmentsAsTheWhole) {
  // face_neighbours, components and fragments, as the simulator calls them with its
  // own partition, give what split gives.
  const Piece p = block(14, 9, 6);
  const std::vector<Vec3d> seeds = {{0.02, 0.02, 0.01}, {0.11, 0.05, 0.04}, {0.07, 0.08, 0.02}};
  const auto whole = split(p, seeds, kS, 2400);
  const FaceNeighbours n = face_neighbours(p);
  const auto parts = fragments(p, n, components(n, nearest_seeds(p.centers, seeds)), kS, 2400, 2);
  ASSERT_EQ(parts.size(), whole.size());
  for (std::size_t f = 0; f < whole.size(); ++f) {
    EXPECT_EQ(parts[f].seed, whole[f].seed);
    EXPECT_EQ(parts[f].component, whole[f].component);
    EXPECT_EQ(parts[f].piece.cells, whole[f].piece.cells);
    EXPECT_EQ(parts[f].piece.particles, whole[f].piece.particles);
    EXPECT_EQ(parts[f].source, whole[f].source);
    EXPECT_EQ(parts[f].mass.center, whole[f].mass.center);
  }
  // Neighbours: the +x neighbour of voxel 0 is voxel 1, it has no -x neighbour.
  EXPECT_EQ(n[0][0], 1);
  EXPECT_EQ(n[0][1], -1);
  EXPECT_EQ(n[0][2], 14);
  EXPECT_EQ(n[0][4], 14 * 9);
}

}  // namespace
}  // namespace bw::fracture

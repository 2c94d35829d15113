// Fracture on the host (method.md 3 and 4, "Ours"): what a breakable body is made
// of, how seeds split it, and the bond counts of the energy criterion.
//
// A piece is a set of voxels of its root solid's sampling grid, in the reference
// configuration (docs/formats.md, "Body poses"), with its boundary particles. Seeds
// split it into the voxels nearest to each seed (the Voronoi cells restricted to the
// piece; a voxel equally near two seeds goes to the lower seed), and each cell into
// its face-connected components (6-connectivity): the fragments. Every voxel lands in
// exactly one fragment, so voxel counts and masses add up exactly. A fragment keeps
// the parent's particles that lie in or next to its voxels and gets new ones at the
// centres of its voxels that face another fragment (the crack faces, half a voxel
// inside them, like bw-sample's particles). Deterministic: the result depends only on
// the input, not on the number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "io/particles_file.h"
#include "rigid/body.h"

namespace bw::fracture {

struct Piece {
  std::vector<CellIndex> cells;         // voxels: cells of the root solid's grid
  std::vector<Vec3d> centers;           // their centres, reference configuration
  std::vector<std::uint8_t> anchor;     // per voxel: touches the anchor (empty: none does)
  std::vector<Vec3d> particles;         // boundary particles, reference configuration
  std::vector<Vec3d> normals;           // unit normals (zero where unknown)
  std::vector<double> flatness;         // sim::surface_normals' flatness (1 on faces)
  std::vector<CellIndex> particle_cells;  // the grid cell each particle sits in
  std::size_t size() const { return cells.size(); }
};

struct Fragment {
  std::int32_t seed = -1;               // index into the seeds
  std::int32_t component = -1;          // within the seed's cell, from 0 by decreasing size
  Piece piece;
  rigid::MassProperties mass;
  bool anchored = false;                // holds an anchor voxel
  std::vector<std::int32_t> source;     // per particle: the parent's particle it was, -1 on a crack face
};

// Per voxel centre, the index of the nearest seed (ties: the lower index).
std::vector<std::int32_t> nearest_seeds(const std::vector<Vec3d>& centers, const std::vector<Vec3d>& seeds,
                                        int threads = 0);
// The same for one point, by a plain search in double: the rule every partition of
// the simulator follows (its device decides in float only where that cannot differ).
std::int32_t nearest_seed(const Vec3d& point, const std::vector<Vec3d>& seeds);

// Splits `piece` by `seeds` into fragments, ordered by seed, then component.
// `voxel_size` is the voxel edge in the reference configuration (m), `density` in
// kg/m^3. Seeds whose cell holds no voxel give no fragment.
std::vector<Fragment> split(const Piece& piece, const std::vector<Vec3d>& seeds, double voxel_size, double density,
                            int threads = 0);

// The parts of split, for a caller that partitions on its own (the simulator's
// device) or tries several seed sets on one piece:

// Per voxel, its face neighbours in the piece (+x, -x, +y, -y, +z, -z; -1 where the
// cell is not a voxel of the piece).
using FaceNeighbours = std::vector<std::array<std::int32_t, 6>>;
FaceNeighbours face_neighbours(const Piece& piece);

// The fragments of a partition: per voxel its fragment, and per fragment its seed,
// component and voxel count, ordered by seed, then by decreasing size (ties: the
// smaller first voxel), components numbered from 0 within their seed.
struct Components {
  std::vector<std::int32_t> fragment;   // per voxel
  std::vector<std::int32_t> seed, component, size;  // per fragment
};
// `labels`: the nearest seed of each voxel (nearest_seeds' result).
Components components(const FaceNeighbours& neighbours, const std::vector<std::int32_t>& labels);

// The fragments themselves: voxels, particles (the parent's, and new ones on the
// crack faces), mass properties.
std::vector<Fragment> fragments(const Piece& piece, const FaceNeighbours& neighbours, const Components& parts,
                                double voxel_size, double density, int threads = 0);

// Per particle: spacing^3 sum_j W_spiky(|x_i - x_j|, h) over the particles (itself
// included): the kernel-weighted number of its bonds (0.60 alone at h = 2 spacings,
// 1.24 inside a full cubic lattice).
std::vector<double> bond_counts(const std::vector<Vec3d>& particles, double spacing, double h);

// bond_counts of each fragment's particles, fragments shared out over `threads`.
// Found by cell offsets: each fragment's particles must sit one per cell at the
// centres of their particle_cells, as split's do (bw-sample's particles and the crack
// faces' at their voxels); a fragment without particle_cells is searched by distance.
std::vector<std::vector<double>> fragment_bond_counts(const std::vector<Fragment>& fragments, double spacing, double h,
                                                      int threads = 0);

// Per particle, the voxel it belongs to: the voxel of its own cell, else the nearest
// voxel among the 26 cells around it (ties: the lower index), else the nearest voxel.
std::vector<std::int32_t> particle_voxels(const Piece& piece);

// Candidates for seeds: particles with their strength (received over binding
// energy, >= 1). Takes them by decreasing strength (ties: lower index), skipping any
// closer than `min_distance` to one taken, up to `max_count`; returns their indices.
struct Candidate {
  std::int32_t particle = -1;
  double strength = 0;
};
std::vector<std::int32_t> select_seeds(std::vector<Candidate> candidates, const std::vector<Vec3d>& particles,
                                       double min_distance, std::size_t max_count);

}  // namespace bw::fracture

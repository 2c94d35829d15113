// Fracture seeds: reading them from a file, drawing them at random inside a solid,
// and sorting out the ones that cannot take part (outside the solid, on its surface,
// repeated). File formats in docs/voronoi.md.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "voronoi/solid.h"

namespace bw::voronoi {

// Reads seeds from `path`:
//  - an HDF5 breakwater file of any kind with a dataset /seeds (S x 3, float64), such
//    as a fragments file written by bw-voronoi;
//  - otherwise text: one seed per line as three numbers "x y z" separated by spaces,
//    tabs or commas; '#' starts a comment; blank lines are skipped.
// Throws InputError naming the file (and line) for anything else, a non-finite
// coordinate or a file without seeds.
std::vector<Vec3d> read_seeds(const std::string& path);

// Writes seeds as text, one "x y z" line each with every digit a double needs to
// read back the same (through a temporary file).
void write_seeds_text(std::span<const Vec3d> seeds, const std::string& path);

// A double uniformly distributed in [0, 1), made from the top 53 bits of one draw:
// the same on every platform and standard library (std::uniform_real_distribution
// is not specified bit for bit).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// `count` points uniformly distributed in the interior of the solid: points drawn
// uniformly in its bounding box with std::mt19937_64 seeded with `random_seed`, kept
// when strictly inside (exact test), in the order drawn. The same arguments give the
// same points everywhere. Throws InputError when the solid fills so little of its box
// that the draws run out (kMaxDrawsPerSeed per seed).
std::vector<Vec3d> random_seeds(const Solid& solid, std::size_t count, std::uint64_t random_seed);
inline constexpr std::size_t kMaxDrawsPerSeed = 100000;

enum class SeedFate { used, outside, on_surface, duplicate };
const char* to_string(SeedFate fate);

struct SeedSorting {
  std::vector<std::int32_t> active;     // indices of the seeds that take part, increasing
  std::vector<SeedFate> fate;           // one per seed
  std::vector<std::int32_t> same_as;    // duplicate: the earlier seed it repeats; -1 otherwise
};

// Decides for every seed whether it takes part: strictly inside the solid and not
// equal to an earlier seed.
SeedSorting sort_seeds(const Solid& solid, std::span<const Vec3d> seeds);

}  // namespace bw::voronoi

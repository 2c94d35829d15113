// The spacing of fluid particles, estimated from their positions: frame files do not
// carry it, and the renderer sizes its spheres and filters by it.
#pragma once

#include <cstddef>

namespace bw::render {

// Median distance from a particle to its nearest neighbour, over an evenly strided
// subset of at most `max_queries` particles (deterministic). Positions are the
// arrays x, y, z of `count` particles. Returns 0 when there are fewer than two
// distinct particles.
double estimate_particle_spacing(const float* x, const float* y, const float* z, std::size_t count,
                                 std::size_t max_queries = 4096);

}  // namespace bw::render

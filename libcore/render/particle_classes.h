// Spray, foam and water: what each particle of a frame is drawn as, from how many
// neighbours it has (the way FLIP whitewater tools tell spray from the body). A
// particle with few neighbours is a drop flung out of the water: drawn as a small,
// white, diffuse sprite and left out of the water's surface. One with a moderate
// count lies on an edge or a thin sheet: still water, tinted as foam. The rest is
// water.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bw::render {

enum class ParticleClass : std::uint8_t { kWater = 0, kFoam = 1, kSpray = 2 };

struct ClassifyParams {
  double spacing = 0;          // particle spacing (m), > 0
  double radius_spacings = 2;  // neighbours are counted within this many spacings
  int spray_neighbours = 3;    // at most this many: spray
  int foam_neighbours = 8;     // at most this many (and more than spray): foam
};

// Neighbours of each particle within radius_spacings * spacing (itself not counted),
// from a uniform grid; particles with a non-finite coordinate count for no one and
// get 0. Integer counts, so the result does not depend on the order of the sums.
std::vector<int> count_neighbours(const float* x, const float* y, const float* z, std::size_t count,
                                  double radius);

// The class of each particle (a non-finite one is spray; the renderer drops it).
std::vector<ParticleClass> classify_particles(const float* x, const float* y, const float* z, std::size_t count,
                                              const ClassifyParams& params);

}  // namespace bw::render

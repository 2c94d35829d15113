// Scenes for the fracture tests: a breakable wall (0.06 x 0.3 x 0.3 m, 675 voxels
// at 0.02 m) standing on a static floor, hit by a block of water (0.12 m cube) at a
// given speed. Small enough that a run of 40 ms takes a few seconds on 2 cores.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "compute/context.h"
#include "rigid/body.h"
#include "sim/setup.h"
#include "sim/solver.h"

namespace bw::test {

// Writes floor.h5 and wall.h5 (the wall with its voxels, or without) into `folder`.
void write_fracture_solids(const std::string& folder, bool wall_voxels = true);

// The scene text: the wall (solid[1]) breakable with `frc`, the block at `speed`
// (m/s, along +x) starting `gap` m before the wall, `extra` appended (e.g. a
// [fracture] table).
std::string fracture_scene(double speed, double frc, double end, const std::string& extra = "", double gap = 0.08);

// The centre of the wall's face where the block hits it (world = reference).
Vec3d impact_point();
inline constexpr int kWallVoxels = 675;
inline constexpr double kWallSpacing = 0.02;
inline constexpr double kWallDensity = 2400;

sim::Setup prepare_text(const std::string& folder, const std::string& text);

// One context on the default device for the whole executable.
compute::Context& shared_context();

// What a fracture scene's run ended with.
struct FractureOutcome {
  std::vector<FractureEvent> events;
  std::vector<sim::BodyInfo> infos;
  std::vector<rigid::MassProperties> masses;
  BodyStates states;
  std::int64_t most_active = 0;  // largest number of active bodies after any step
  double first = -1;             // time of the first fracture; < 0: none
};

// Runs the scene `text` (fracture_scene) with the fracture solids to `end` seconds.
FractureOutcome run_fracture_scene(const std::string& text, double end);

// Fragments active at the end (bodies split off a parent).
std::size_t fragments(const FractureOutcome& o);

}  // namespace bw::test

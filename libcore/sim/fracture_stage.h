// The solver's fracture stage (method.md 3 and 4; docs/scene.md "Fracture"): only
// created when the scene has a breakable solid. Internal to libcore/sim.
//
// Device: per boundary particle of a breakable body (a "slot"), the velocity change
// it has caused in the fluid over the window, the energy that stands for, and its
// strength (energy over binding energy), shaders/fracture.cl. Host: the binding
// energies (precomputed per body, again only for fragments), the seed choice, the
// split into fragments (libcore/fracture) and the new bodies, and the events the run
// file records.
#pragma once

#include <cstdint>
#include <vector>

#include "compute/context.h"
#include "fracture/fracture.h"
#include "io/run_file.h"
#include "scene/scene.h"

namespace bw::sim {

struct BreakableBody {
  int body = -1;                  // solver body index
  fracture::Piece piece;          // voxels and particles, reference configuration
  std::vector<float> binding;     // per particle: E_r (J)
  double frc = 0, density = 0, voxel_size = 0;
  std::uint32_t slot = 0;         // first slot of its particles
};

struct FractureStage {
  compute::Program program;
  compute::Kernel load;
  scene::FractureSettings settings;
  std::vector<BreakableBody> bodies;   // the active breakable bodies, in body order
  std::uint32_t slots = 0, capacity = 0;
  compute::Buffer map, binding, dvx, dvy, dvz, energy, strength;
  std::vector<std::uint32_t> map_host;  // master index per slot, as uploaded
  bool layout_dirty = true;             // slots changed: upload binding energies
  std::vector<FractureEvent> events;
};

}  // namespace bw::sim

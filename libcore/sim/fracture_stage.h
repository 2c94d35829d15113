// The solver's fracture stage (method.md 3 and 4; docs/scene.md "Fracture"): only
// created when the scene has a breakable solid. Internal to libcore/sim.
//
// Device: per boundary particle of a breakable body (a "slot"), the velocity change
// it has caused in the fluid over the window, the energy that stands for, and its
// strength (energy over binding energy), and, when a body breaks, the nearest seed of
// each of its voxels (shaders/fracture.cl). Host: the binding
// energies (precomputed per body, again only for fragments), the seed choice, the
// cells' components and fragments (libcore/fracture) and the new bodies, and the
// events the run file records.
#pragma once

#include <cstdint>
#include <vector>

#include "compute/context.h"
#include "fracture/fracture.h"
#include "io/run_file.h"
#include "scene/scene.h"
#include "sim/solver.h"

namespace bw::sim {

struct BreakableBody {
  int body = -1;                  // solver body index
  fracture::Piece piece;          // voxels and particles, reference configuration
  std::vector<float> binding;     // per particle: E_r (J)
  double frc = 0, density = 0, voxel_size = 0;
  std::uint32_t slot = 0;         // first slot of its particles
};

// What the fluid delivered to each slot, read from the device when a body breaks.
struct FractureLoads {
  std::vector<float> energy, dx, dy, dz;
};

struct FractureStage {
  compute::Program program;
  compute::Kernel load, voxel_seeds;
  scene::FractureSettings settings;
  std::vector<BreakableBody> bodies;   // the active breakable bodies, in body order
  std::uint32_t slots = 0, capacity = 0;
  compute::Buffer map, binding, dvx, dvy, dvz, energy, strength;
  std::vector<std::uint32_t> map_host;  // master index per slot, as uploaded
  bool layout_dirty = true;             // slots changed: upload binding energies
  std::vector<FractureEvent> events;
  // The partition (voxel_seeds): the voxels of the body being split in voxel units,
  // sorted by brick (uploaded once per body and event; uploaded_perm[i] is the voxel
  // at sorted place i), the bricks' starts and boxes, the seeds, the labels; grown as
  // needed.
  compute::Buffer vox_x, vox_y, vox_z, vox_label, brick_start, brick_lo, brick_hi, seed_points;
  std::size_t voxel_capacity = 0, brick_capacity = 0, seed_capacity = 0;
  int uploaded_body = -1;
  std::size_t uploaded_voxels = 0, uploaded_bricks = 0;
  std::vector<std::uint32_t> uploaded_perm;
  std::int64_t partition_close = 0;     // voxels decided on the host (two seeds too close for float)
  Solver::FractureTimes times;
};

}  // namespace bw::sim

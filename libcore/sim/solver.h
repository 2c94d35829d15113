// The WCSPH fluid on the device (method.md 1, 2 and 6): one kernel per stage, data
// on the device from start to end, only what a frame needs coming back.
//
// Device layout (shaders/fluid.cl, shaders/grid.cl):
//   fluid     x, y, z, vx, vy, vz (float) and id (uint), one array each, sorted by
//             grid cell every step; two copies of each, swapped by the reorder;
//             rho, p, p/rho^2, 1/rho and ax, ay, az in the current order;
//   boundary  bx, by, bz, Psi_b, bvx, bvy, bvz (float) and the solid index (uint),
//             sorted by cell once (static solids);
//   grid      start[c] = first particle of cell c, for fluid and boundary.
// One step: keys -> radix sort -> reorder -> cell starts -> density -> forces ->
// reduction (max |v|, max |a|, non-finite values; the one small read per step) ->
// dt on the host -> symplectic Euler with wall contact -> emitters.
//
// Moving solids fit this layout as follows. Boundary particles carry the solid's
// index (bsolid) and a velocity (bvx, bvy, bvz, zero for static solids) that the
// friction term and the contact rule already use. To move a body, recompute its
// particles' positions, velocities and normals from reference arrays and the body's
// pose, then sort the boundary again (boundary_keys, the radix sort, the gathers and
// cell_starts, as at construction) before the density of the next step; Psi_b only
// changes when a body's own particles change (fracture). The force of the fluid on a
// boundary particle b is the negative of what b does to its fluid neighbours in
// fluid_forces (boundary pressure and friction, and the contact impulse of
// fluid_integrate): a kernel over boundary particles can gather it from the fluid
// grid (start, x, ...) without atomics, and a per-body sum over blocks of boundary
// particles in body order gives force and torque deterministically.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "compute/context.h"
#include "io/frame_file.h"
#include "sim/setup.h"

namespace bw::sim {

struct StepInfo {
  double dt = 0;
  double max_speed = 0;       // at the start of the step
  double max_acceleration = 0;
  std::int64_t emitted = 0;   // particles the emitters added after the step
};

// Sums over the fluid at one instant (frame statistics).
struct FluidStats {
  double kinetic = 0, potential = 0, elastic = 0;  // J
  double density_error_max = 0, density_error_mean = 0;  // of max(0, rho/rho0 - 1)
  double speed_max = 0;
  std::int64_t fluid = 0;
};

class Solver {
 public:
  // Uploads the setup and builds the kernels. Throws RunError on device failures,
  // InputError when the scene does not fit the device.
  Solver(const Setup& setup, compute::Context& context);
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  // One adaptive step that never passes `t_target` and lands on it exactly when it
  // is within reach. Throws RunError naming the step, time and particle when the
  // fluid blew up (non-finite values, or a speed above Parameters::speed_limit).
  StepInfo step(double t_target);

  double time() const;
  std::int64_t steps() const;
  std::int64_t fluid_count();             // live fluid particles (reads the device)
  std::int64_t boundary_count() const;
  std::int64_t removed_count();           // left the domain since the start
  bool emitters_capped() const;           // an emitter was held back by MFP

  FluidStats stats();
  // The fluid particles now, with the optional fields asked for (positions always).
  FrameData frame(const FrameFields& fields, int frame_index);

  const Parameters& parameters() const;
  compute::Context& context();
  std::uint64_t device_bytes() const;     // held by the solver's buffers
  std::int64_t capacity() const;          // MFP

  // For tests: the sorted fluid positions and, per particle, the sorted indices of
  // its neighbours within h (including itself).
  struct Neighbours {
    std::vector<float> x, y, z;
    std::vector<std::vector<std::uint32_t>> lists;
  };
  Neighbours neighbour_lists(std::uint32_t max_per_particle);

  // For tests: the current state with densities, pressures and accelerations (fluid
  // in sorted order) and the boundary particles with their Psi_b.
  struct Snapshot {
    std::vector<float> x, y, z, vx, vy, vz, rho, p, ax, ay, az;
    std::vector<float> bx, by, bz, bpsi;
    std::vector<std::uint32_t> bsolid;
  };
  Snapshot snapshot();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::sim

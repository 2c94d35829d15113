// The WCSPH fluid on the device (method.md 1, 2 and 6): one kernel per stage, data
// on the device from start to end, only what a frame needs coming back.
//
// Device layout (shaders/fluid.cl, shaders/grid.cl):
//   fluid     x, y, z, vx, vy, vz (float) and id (uint), one array each, sorted by
//             grid cell every step; two copies of each, swapped by the reorder;
//             rho (with the continuity equation a state, carried by the reorder
//             into rho_state), p, p/rho^2, 1/rho and ax, ay, az in the current order;
//   boundary  bx, by, bz, Psi_b, bvx, bvy, bvz (float) and the solid index (uint),
//             sorted by cell once (static solids);
//   grid      start[c] = first particle of cell c, for fluid and boundary.
// One step: keys -> radix sort -> reorder -> cell starts -> density -> forces ->
// reduction (max |v|, max |a|, non-finite values; the one small read per step) ->
// dt on the host -> symplectic Euler with wall contact -> emitters.
//
// Rigid bodies (shaders/rigid.cl; only when the scene has dynamic solids or a body
// is added: a scene without bodies runs no rigid kernel and allocates nothing for
// them). Boundary particles then also live in a master order: the static solids'
// particles first (in scene order), then each body's particles in a contiguous range,
// body after body. Master arrays hold the world positions, velocities and normals
// (bodies' recomputed every step from reference arrays and the pose), Psi_b and the
// owner (a static solid's index, or body_owner0 + the body's index); every step the
// boundary is sorted again from them (boundary_keys, the radix sort, a gather,
// cell_starts) before the fluid's density. Psi_b is computed for an owner when its
// particles are new (boundary_psi_owners) and kept, since a rigid motion leaves it
// unchanged. After the fluid's forces and the time step, boundary_forces gathers, per
// boundary particle of a body, the fluid's reaction (the exact negative of the
// boundary pressure and friction terms of fluid_forces and of the momentum its
// patch takes in fluid_integrate's wall contact) and the contacts with other
// owners' particles; body_reduce sums fixed blocks of one body's particles, and the
// host adds the blocks of each body in order (double), adds gravity and steps the
// bodies (rigid::Body::step) in step with the fluid's symplectic Euler.
#pragma once

#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "compute/context.h"
#include "io/frame_file.h"
#include "io/run_file.h"
#include "rigid/body.h"
#include "rigid/motion.h"
#include "sim/sensors.h"
#include "sim/setup.h"

namespace bw::h5 {
class Group;
}

namespace bw::sim {

struct StepInfo {
  double dt = 0;
  double max_speed = 0;       // at the start of the step
  double max_acceleration = 0;
  std::int64_t emitted = 0;   // particles the emitters added after the step
};

// Sums over the fluid at one instant (frame statistics), and the bodies' energies.
struct FluidStats {
  double kinetic = 0, potential = 0, elastic = 0;  // J
  double density_error_max = 0, density_error_mean = 0;  // of max(0, rho/rho0 - 1)
  double speed_max = 0;
  std::int64_t fluid = 0;
  double body_kinetic = 0, body_potential = 0;  // J, of the active bodies (potential as the fluid's)
  // J the emitters have put in since the start: the kinetic and potential energy of
  // the particles they made, and the work of holding them at their speed; and the
  // work of the solids moved as told against the forces on them.
  double emitted = 0;
  // J carried out of the domain by the particles that left it since the start (their
  // kinetic and potential energy when they left).
  double outflow = 0;
};

// A rigid body to add to a running solver (a dynamic solid at the start, a fragment
// of a broken one later). Geometry is in the reference configuration of its root
// solid (docs/formats.md, "Body poses"); the state's position is where mass.center is
// now.
struct BodySpec {
  std::string name;
  std::int32_t solid = -1;          // root solid (scene index)
  std::int32_t parent = -1;         // body it broke from, -1 for a solid's own body
  rigid::MassProperties mass;       // reference configuration; mass > 0
  std::int32_t voxels = 0;          // voxels it was made of (run file)
  std::vector<Vec3d> particles;     // boundary particles, reference configuration
  std::vector<Vec3d> normals;       // their unit surface normals (zero where unknown)
  std::vector<double> flatness;     // of the surface there, in [0, 1] (sim::surface_normals): 1 on
                                    // faces, 0.71 on a box's edges; empty: all faces
  double spacing = 0;               // sampling spacing of the particles (m)
  double friction = 0.5, restitution = 0.3;
  bool fixed = false;               // does not move (an anchored fragment)
  rigid::PrescribedMotion motion;  // non-empty: moves as told, whatever its forces (mass nominal)
  rigid::BodyState state;           // pose and velocities now
};

// What the run file records of a body (docs/formats.md, /bodies).
struct BodyInfo {
  std::string name;
  std::int32_t solid = -1, parent = -1;
  std::int32_t voxels = 0;
  double created_time = 0;
  bool fixed = false;
  bool active = true;               // false once retired (its row stays)
  std::size_t particles = 0;        // boundary particles now
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
  // With fields.wall_pressure (and record_wall_pressure), each boundary particle's mean
  // patch pressure since the last such frame, which starts the next mean.
  FrameData frame(const FrameFields& fields, int frame_index);
  // [output] fields "wall_pressure", before the first step: integrate every boundary
  // particle's patch pressure, -F . n / spacing^2 (F the fluid's and contacts' force on
  // it, n its normal), over time for frame() (docs/formats.md). Measures the static
  // reactions.
  void record_wall_pressure();

  const Parameters& parameters() const;
  compute::Context& context();
  std::uint64_t device_bytes() const;     // held by the solver's buffers
  std::int64_t capacity() const;          // MFP

  // Rigid bodies. Body indices are rows of the run file's /bodies and never reused.
  // Changes take effect at the next step (the boundary is sorted again, Psi_b
  // computed for the new particles only).
  int add_body(const BodySpec& spec);
  // New boundary particles of a body (reference configuration), e.g. with crack
  // faces; its Psi_b is recomputed, its mass properties stay. `flatness` as in
  // BodySpec (empty: all faces).
  void replace_body_particles(int body, const std::vector<Vec3d>& particles, const std::vector<Vec3d>& normals,
                              const std::vector<double>& flatness = {});
  // A fixed body keeps its pose and acts on others like a static solid.
  void set_body_fixed(int body, bool fixed);
  // Takes a body out of the simulation (its particles go; its index stays).
  void retire_body(int body);
  int body_count() const;
  const BodyInfo& body_info(int body) const;
  const rigid::Body& body(int body) const;
  rigid::BodyState& body_state(int body);   // e.g. to give a fragment its velocity
  // Force and torque (about the centre of mass, world) of the last step, gravity
  // included (N, N m).
  Vec3d body_force(int body) const;
  Vec3d body_torque(int body) const;
  // States of the active bodies (frame files).
  BodyStates body_states() const;
  // Master index of a body's first boundary particle, valid until bodies change.
  std::uint32_t body_first_particle(int body) const;
  // The fractures so far (docs/formats.md, /fracture), in order; empty without
  // breakable solids.
  const std::vector<FractureEvent>& fracture_events() const;
  // Breaks the breakable body `body` now at `seeds` (reference configuration) as the
  // energy criterion does at its seeds: the same partition, fragments, new bodies and
  // event, without the kick of leftover energy. Returns the number of fragments, 0
  // when fewer than two seeds are left once every fragment has its least size (8
  // voxels) and the scene's max_chunks holds. Throws RunError when the body is not breakable.
  int break_body(int body, const std::vector<Vec3d>& seeds);
  // Voxels of the partitions so far that the device left to the host (their two
  // nearest seeds closer than float can tell).
  std::int64_t fracture_host_decided_voxels() const;
  // Wall time the fracture stage spent breaking bodies so far, by part (s).
  struct FractureTimes {
    double partition = 0;   // nearest seed of every voxel (device, and the host's ties)
    double fragments = 0;   // components, the fragments' voxels, particles and mass
    double bonds = 0;       // the fragments' binding energies
    double bodies = 0;      // new bodies, retired parents, events, the slots' layout
    int events = 0;
  };
  FractureTimes fracture_times() const;

  // For tests and diagnostics: also sum the forces on the static solids' particles
  // (fluid reaction and contacts with bodies) and accumulate their impulse over the
  // steps since this was turned on (N s). Runs the rigid stage even without bodies.
  void measure_static_reactions(bool on);
  Vec3d static_impulse() const;
  // While reactions are measured: per scene solid, the impulse of the fluid and of
  // contacts on it since they were turned on (N s): on a static solid's particles, or
  // on the bodies it became (itself, or its fragments, fixed ones included), without
  // gravity. Empty when not measured.
  std::vector<Vec3d> solid_impulses() const;

  // Pressure sensors (sim/sensors.h) from the next step on: each step's reading, from
  // the forces of that step, is averaged over samples of `interval` s, the k-th over
  // [k, k + 1] x interval from t = 0; before the first step only (a resumed run's
  // samples come from its checkpoint). Measures the static reactions.
  void set_sensors(std::vector<SensorWeights> sensors, double interval);
  // The sensors, and their completed samples (Pa), sample after sample, one value
  // per sensor each. Empty without sensors.
  const std::vector<SensorWeights>& sensors() const;
  const std::vector<double>& sensor_samples() const;

  // The density of every fluid particle as the kernel sum gives it now (the sum the
  // continuity equation starts from), in the order of frame(); for the check that
  // no fluid starts on top of a solid or of other fluid, whatever the density scheme.
  std::vector<float> summed_density();

  // fluid.wall_pressure = "images": of the fluid particles within h of a solid's
  // particles now, how many have mirror planes; the others are held by the particles
  // (convex edges and rims, bodies the water moves, faces that look away from the
  // water: docs/scene.md, "Walls as mirror images"). Both -1 with another wall.
  struct ImageCoverage {
    std::int64_t near = -1, imaged = -1;
  };
  ImageCoverage image_coverage();

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

  // Checkpoints (sim/checkpoint.cpp, docs/formats.md "checkpoint"): the whole state
  // at a frame (just after Simulation wrote it) into `group`, and back into a solver
  // made from the same setup on the same device, which then steps on exactly as the
  // saved one would have.
  void save_state(h5::Group& group);
  void load_state(const h5::Group& group);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::sim

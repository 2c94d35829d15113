// The solver's state and the pieces of a step, shared by solver.cpp (the fluid) and
// rigid_stage.cpp (rigid bodies). Internal to libcore/sim: the public interface is
// sim/solver.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "compute/context.h"
#include "compute/radix_sort.h"
#include "sim/fracture_stage.h"
#include "sim/solver.h"
#include "sim/sensors.h"
#include "sim/setup.h"
#include "sph_common.h"

namespace bw::sim {


using compute::Buffer;
using compute::Kernel;

// Elements past the end of every array the neighbour loops read: they load up to
// 16 (float16, the widest BW_VW) candidates at once.
inline constexpr std::size_t kPad = 16;
// Particles per block of the reduction kernels: long enough for a serial loop to pay,
// short enough that float partial sums stay accurate.
inline constexpr std::uint32_t kReduceChunk = 512;
// Blocks per compute unit for the reductions.
inline constexpr std::uint32_t kReduceBlocksPerUnit = 64;
// Largest grid (cells): the cell index is a 32-bit key and start[] has one entry each.
inline constexpr std::uint64_t kMaxCells = std::uint64_t{1} << 30;
// Wall contact (fluid_integrate): a fluid particle closer than kContactDistance
// spacings to a solid's surface, over the patch of radius kPatchRadius spacings a
// boundary particle stands for, cannot move further into the surface. Fluid at rest
// is one spacing from the surface's particles; a CFL step moves a particle at most
// 0.4 spacings at speeds up to c0, less than 0.6. Patches of 0.71 spacings around
// particles one spacing apart would cover a flat surface; in a concave corner the
// edge's particle has a patch tilted halfway between the faces, whose plane passes
// in front of the faces' particles, and a particle sliding up it reaches 0.76
// spacings from the nearest face particle: one spacing closes that gap (a convex
// edge's nearest face particles are 1.5 spacings from the fluid beside it).
inline constexpr double kContactDistance = 0.6;
inline constexpr double kPatchRadius = 1.0;
// The density step of the fluid layer against a mirrored wall, in hydrostatic
// excesses per unit of boundary fraction (fluid.cl, BW_WALL_STEP): what its boundary
// force, half the missing fluid's at the same pressure, needs to hold the column up.
inline constexpr double kMirroredWallStep = 3.0;
// A step shorter than this fraction of the proposed dt before a frame time would be
// a sliver: the last two steps share the remaining time instead.
inline constexpr double kSplitBeforeFrame = 2.0;

inline std::uint32_t u32(std::int64_t v) { return static_cast<std::uint32_t>(v); }

// A rigid body as the solver holds it.
struct BodyEntry {
  BodyInfo info;
  rigid::Body body;
  std::vector<Vec3d> reference;          // boundary particles minus mass.center, reference configuration
  std::vector<Vec3d> reference_normals;
  std::vector<float> flatness;           // of the surface at each particle (1 on faces)
  std::vector<float> psi;                // Psi_b of its particles, master order (valid unless psi_dirty)
  bool psi_dirty = true;
  double spacing = 0, friction = 0.5, restitution = 0.3;
  double radius = 0;                     // farthest particle from the centre of mass (m)
  std::uint32_t first = 0;               // master index of its first particle
  double contact_weight = 0;             // weight of its contact pairs at the last step
  rigid::PrescribedMotion motion;        // non-empty: a solid moved as told (BodySpec::motion)
  bool moving() const { return !motion.empty(); }
  Vec3d force = Vec3d::Zero(), torque = Vec3d::Zero();  // of the last step, gravity included
};

// The device side of the rigid bodies (rigid_stage.cpp, shaders/rigid.cl).
struct RigidStage {
  compute::Program program;
  Kernel pose, gather, psi, forces, reduce;
  std::vector<BodyEntry> bodies;
  std::uint32_t body_owner0 = 0;         // owner of body 0: the number of scene solids
  std::vector<SolidMaterial> materials;  // of the scene solids
  // Static particles (master indices 0 .. ns - 1), kept on the host for reallocations.
  std::uint32_t ns = 0;
  std::vector<float> sx, sy, sz, snx, sny, snz, sflat, spsi;
  std::vector<std::uint32_t> sowner;
  bool static_psi_dirty = true;
  std::uint32_t nb = 0, capacity = 0;    // boundary particles in use, allocated
  // master order (capacity)
  Buffer mx, my, mz, mvx, mvy, mvz, mnx, mny, mnz, mflat, mpsi, mowner;
  // bodies' particles (capacity, index = master index - ns): reference arrays, body
  Buffer rx, ry, rz, rnx, rny, rnz, pbody;
  // the boundary sort: keys, order (sorted -> master), scratch, rank (master -> sorted)
  Buffer keys, order, keys_tmp, order_tmp, rank;
  // per particle, master order: force, own torque, contact pairs
  Buffer fx, fy, fz, tx, ty, tz, touching;
  // per particle, master order: fluid near it at the last step (read) and now (written)
  std::array<Buffer, 2> wet;
  int wet_read = 0;
  // tables: poses (per body), owners, blocks, block sums, Psi_b requests (per owner)
  Buffer poses, owners, blocks, block_sums, dirty;
  std::vector<BodyBlock> block_table;
  bool layout_dirty = true;              // bodies or their particles changed
  bool touching_now = true;              // contact pairs at the last step (the contact time step)
  bool measure_static = false;
  std::map<double, double> damping_of;   // damping ratio by restitution (rigid::damping_ratio_for_step)
  Vec3d static_impulse = Vec3d::Zero();  // N s
  std::vector<Vec3d> solid_impulse;      // N s, per scene solid: static, or its bodies and fragments
  // [output] fields "wall_pressure" (Solver::record_wall_pressure): per particle, master
  // order, its patch pressure integrated over time (Pa s) since the last frame for the
  // static particles, and for the bodies' since then or since their layout last changed
  // (a fracture re-lays their master order), over these times (s).
  Kernel wall_integrate;
  Buffer wall_integral;
  bool wall_pressure = false;
  double wall_static_time = 0, wall_body_time = 0;
};

// Pressure sensors (sim/sensors.h, rigid_stage.cpp): their particles and weights on
// the device, and the samples so far.
struct SensorStage {
  Kernel kernel;
  Buffer first, particle, weight, normal, out;
  std::vector<SensorWeights> sensors;
  double interval = 0;        // s per sample
  std::int64_t sample = 0;    // the sample being accumulated: [sample, sample + 1] x interval
  std::vector<double> partial;  // its pressure integrated over time so far (Pa s), per sensor
  std::vector<double> samples;  // the completed samples (Pa), sample after sample
};

struct Solver::Impl {
  compute::Context& ctx;
  Parameters params;
  SimParams P{};
  std::uint32_t ncells = 0;
  std::uint32_t capacity = 0;

  compute::Program grid_program, fluid_program;
  Kernel fluid_keys, boundary_keys, cell_starts, reorder, gather_float, gather_uint, neighbour_lists;
  Kernel psi, wall_fraction, boundary_pressure, wall_step, density, forces, integrate, step_reduce, frame_reduce, emit;
  Kernel density_rate;  // the density pass that also finds the diffusion's rate (fluid.cl)
  Kernel wall_planes;   // each particle's mirror planes (fluid.wall_pressure = "images", sph_images.h)
  std::unique_ptr<compute::RadixSort> sort;

  // fluid
  std::array<Buffer, 2> x, y, z, vx, vy, vz, id, hold;
  int front = 0;
  Buffer keys, values, keys_tmp, values_tmp;
  // rho: the density now, in the current order (with P.continuity the state the
  // continuity equation integrates; the reorder carries it into rho_state, its value
  // at the start of the step, from which fluid_density integrates the step).
  Buffer rho, rho_state, pres, pterm, vol, phi, ax, ay, az, start;
  Buffer diffusion_rate;  // per particle, the density diffusion's rate on its own density (1/s)
  // per particle, with the images: its mirror planes (uint4, the boundary particles they
  // were found at; with bodies also their solids), and per plane the images' push along
  // the normal per unit of the weight of the boundary particles they replace (float4)
  Buffer wplane, wowner, image_share;
  Buffer no_owners, no_poses;  // the images' tables without bodies: never read (all static)
  static constexpr int kRateEvery = 4;         // steps between the rate's computations at most
  static constexpr double kRateGrowth = 1.25;  // how much the largest rate may grow meanwhile
  bool rate_wanted = true;  // the density pass in flight computes the rate
  double rate_last = 0;     // the largest rate when it was last computed (1/s)
  int rate_age = 0;         // steps since then
  double limit_last = 0;    // the last step's dt from the other limits and dt_max (s)
  // Whether the diffusion's limit could bind at limit_last: the rate is needed.
  bool rate_may_bind() const { return limit_last * rate_last * kRateGrowth >= params.diffusion_factor; }
  double pending_dt = 0;   // the step taken since the density was last integrated
  double density_dt = 0;   // the step the last density launch integrated
  // boundary
  Buffer bx, by, bz, bpsi, bpt, bvx, bvy, bvz, bnx, bny, bnz, bsolid, bstart;
  Buffer one_sided;  // per scene solid (BoundarySet::one_sided); bodies' owners are all one-sided
  std::uint32_t nb = 0;
  ParticleArrays boundary_host;
  // reductions
  Buffer step_out, frame_out;
  // emitters
  std::vector<EmitterLattice> emitters;
  std::vector<std::uint32_t> emitter_first_point;
  std::vector<std::int64_t> emitter_layers;
  Buffer ex, ey, ez, emitter_table;
  bool capped = false;

  // state
  double t = 0;
  std::int64_t steps = 0;
  std::uint32_t n = 0;          // particles in the arrays (live, plus any to be removed)
  std::int64_t removed = 0;
  double emitted_energy = 0;  // FluidStats::emitted
  double outflow_energy = 0;  // FluidStats::outflow
  std::uint32_t next_id = 0;
  bool grid_valid = false;

  // rigid bodies: null until the scene has one (or static reactions are measured)
  std::unique_ptr<RigidStage> rigid;
  BoundarySet static_boundary;  // the static solids' particles as set up (unsorted)
  Buffer bflat;                 // sorted flatness of the boundary particles (with bodies only)
  std::vector<SolidMaterial> materials;
  // The continuity equation's start: the wall layer's step goes into the densities
  // before the first density pass (fluid_wall_step); a resumed run has it already.
  bool wall_step_pending = false;
  bool boundary_dirty = false;  // bodies moved: sort the boundary again before the density
  // sensors: null unless the scene has some
  std::unique_ptr<SensorStage> sensors;
  // fracture: null unless the scene has a breakable solid (no kernel, no buffer)
  std::unique_ptr<FractureStage> fracture;

  explicit Impl(compute::Context& c) : ctx(c) {}

  // rigid_stage.cpp
  void enable_bodies();
  int add_body(const BodySpec& spec);
  void replace_body_particles(int body, const std::vector<Vec3d>& particles, const std::vector<Vec3d>& normals,
                              const std::vector<double>& flatness);
  void upload_layout();
  void update_boundary();
  double body_speed_max() const;
  void rigid_forces(double dt);
  void sum_blocks(double dt);
  void upload_owners();
  void step_bodies(double dt);
  void body_energies(double& kinetic, double& potential) const;
  BodyEntry& body_entry(int body);
  const BodyEntry& body_entry(int body) const;
  std::uint64_t rigid_bytes() const;
  void sample_sensors(double t0, double t1);
  void integrate_wall_pressure(double dt);
  void reset_wall_pressure(const std::vector<float>& static_part);
  std::vector<float> take_wall_pressure();

  // fracture_stage.cpp
  void enable_fracture(const Setup& setup, const std::vector<int>& body_of_setup);
  std::vector<float> binding_energies(double frc, const std::vector<double>& bonds) const;
  void fracture_layout(const std::vector<float>& dx, const std::vector<float>& dy, const std::vector<float>& dz);
  void fracture_load(double dt);
  void fracture_test();
  void reserve_partition(std::size_t voxels, std::size_t bricks);
  std::vector<std::int32_t> partition(const BreakableBody& tb, const std::vector<Vec3d>& seeds);
  std::vector<fracture::Fragment> fragments_of(const BreakableBody& tb, std::vector<Vec3d>& seeds,
                                               std::vector<std::int32_t>* seed_particles, std::int64_t budget);
  void break_into(BreakableBody& tb, std::vector<fracture::Fragment>& fragments, const std::vector<Vec3d>& seeds,
                  const std::vector<std::int32_t>& seed_particles, const FractureLoads* loads,
                  std::vector<BreakableBody>& next);
  int fracture_pass(const std::function<std::vector<fracture::Fragment>(BreakableBody&, std::int64_t, std::vector<Vec3d>&,
                                                                        std::vector<std::int32_t>&)>& choose);
  int break_body(int body, const std::vector<Vec3d>& seeds);
  void retire_body(int body);
  std::uint64_t fracture_bytes() const;

  int back() const { return 1 - front; }

  // ---- checkpoints (sim/checkpoint.cpp)
  // The per-particle state of the fluid, in the current (front) order: what a
  // checkpoint saves and loads, n elements each: rho is state with the continuity
  // equation (the summation recomputes it). Everything else per particle (p, the
  // accelerations, the grid) is recomputed from it. A new per-particle state buffer
  // is one more line here.
  enum class StateType { f32, u32 };
  struct StateBuffer {
    const char* name;
    Buffer* buffer;
    StateType type;
  };
  std::vector<StateBuffer> state_buffers() {
    const int f = front;
    return {{"x", &x[f], StateType::f32},   {"y", &y[f], StateType::f32},   {"z", &z[f], StateType::f32},
            {"vx", &vx[f], StateType::f32}, {"vy", &vy[f], StateType::f32}, {"vz", &vz[f], StateType::f32},
            {"id", &id[f], StateType::u32}, {"hold", &hold[f], StateType::u32}, {"rho", &rho, StateType::f32}};
  }
  // ---- end of checkpoints

  std::uint32_t reduce_blocks(std::uint32_t count, std::uint32_t& chunk) const {
    const std::uint32_t units = static_cast<std::uint32_t>(std::max(1, ctx.device().compute_units));
    std::uint32_t blocks = std::max<std::uint32_t>(1, (count + kReduceChunk - 1) / kReduceChunk);
    blocks = std::min(blocks, units * kReduceBlocksPerUnit);
    chunk = std::max<std::uint32_t>(1, (count + blocks - 1) / blocks);
    return (count + chunk - 1) / chunk;
  }

  Buffer floats(std::size_t count, const std::string& name) { return ctx.buffer((count + kPad) * sizeof(float), name); }
  Buffer uints(std::size_t count, const std::string& name) {
    return ctx.buffer((count + kPad) * sizeof(std::uint32_t), name);
  }

  // Sorts the fluid by cell, finds the cell starts and computes density and pressure
  // for the current positions (once per state).
  void ensure_grid() {
    if (boundary_dirty) update_boundary();
    if (grid_valid) return;
    const int f = front, b = back();
    if (n > 0) {
      fluid_keys.args(P, n, x[f], y[f], z[f], keys, values);
      ctx.launch(fluid_keys, n);
      sort->sort(keys, values, keys_tmp, values_tmp, n, ncells);
      reorder.args(n, values, x[f], y[f], z[f], vx[f], vy[f], vz[f], id[f], hold[f], rho, x[b], y[b], z[b], vx[b],
                   vy[b], vz[b], id[b], hold[b], rho_state);
      ctx.launch(reorder, n);
      front = b;
    }
    cell_starts.args(n, ncells, keys, start);
    ctx.launch(cell_starts, std::size_t(n) + 1);
    density_dt = pending_dt;  // integrated once, whatever else sorts the particles again
    pending_dt = 0;
    if (wall_step_pending && n > 0) {
      wall_fraction.args(P, start, x[front], y[front], z[front], bstart, bx, by, bz, bpsi, phi);
      ctx.launch(wall_fraction, n);
      wall_step.args(P, start, phi, rho_state);
      ctx.launch(wall_step, n);
    }
    wall_step_pending = false;
    // The diffusion's rate, for its step limit, on the steps where that limit could
    // bind: every step while the last step's other limits times the last rate come
    // within kRateGrowth of diffusion_factor, at least every kRateEvery steps otherwise
    // (the largest rate grows by less than 2% in four steps, measured in a stiff
    // fluid's impact: docs/performance.md). Where it is skipped the limit cannot
    // bind, so every step's dt is what the rate of every step would give.
    rate_wanted = params.continuity && params.diffusion > 0 &&
                  !(rate_last > 0 && rate_age < kRateEvery && !rate_may_bind());
    launch_density(P);
    grid_valid = true;
  }

  // The density kernel with parameters Q (P, or P with the summation for a check).
  void launch_density(const SimParams& Q) {
    const int f = front;
    // The diffusion reads every neighbour's phi where the wall has a density step;
    // otherwise the density pass finds phi itself.
    if (Q.continuity && Q.wall_layer_step != 0) {
      wall_fraction.args(Q, start, x[f], y[f], z[f], bstart, bx, by, bz, bpsi, phi);
      ctx.launch(wall_fraction, n);
    }
    if (params.wall_images && n > 0) {
      wall_planes.args(Q, start, x[f], y[f], z[f], bstart, bx, by, bz, bnx, bny, bnz, bflat, bsolid,
                       rigid ? rigid->owners : no_owners, wplane, wowner);
      ctx.launch(wall_planes, n);
    }
    Kernel& pass = Q.continuity && rate_wanted ? density_rate : density;
    pass.args(Q, static_cast<float>(density_dt), start, x[f], y[f], z[f], vx[f], vy[f], vz[f], rho_state, bstart, bx,
              by, bz, bpsi, bvx, bvy, bvz, rho, pres, pterm, vol, phi, diffusion_rate, bnx, bny, bnz, wplane, wowner,
              rigid ? rigid->poses : no_poses);
    ctx.launch(pass, n);
    if (Q.wall_hydrostatic && nb > 0) {  // the walls' pressures, from the fluid's just found
      boundary_pressure.args(Q, nb, start, x[f], y[f], z[f], rho, pres, bx, by, bz, bpt);
      ctx.launch(boundary_pressure, nb);
    }
  }

  void launch_forces() {
    const int f = front;
    forces.args(P, start, x[f], y[f], z[f], vx[f], vy[f], vz[f], rho, pterm, vol, bstart, bx, by, bz, bpsi, bpt, bvx,
                bvy, bvz, ax, ay, az, wplane, image_share, bnx, bny, bnz, bflat);
    ctx.launch(forces, n);
  }

  std::uint32_t read_live() {
    std::uint32_t live = 0;
    ctx.read(start, &live, sizeof(live), std::size_t(ncells) * sizeof(std::uint32_t));
    return live;
  }

  // A fluid particle's kinetic and potential energy, as fluid_frame_reduce counts them
  // (potential relative to the domain's minimum corner).
  double particle_energy(const Vec3d& position, const Vec3d& velocity) const {
    return params.mass * (0.5 * velocity.squaredNorm() - params.gravity.dot(position - params.domain.min));
  }

  // After a sort: drop the particles that left the domain from the count, adding
  // the energy they carried out to outflow_energy. They sort after the live ones.
  void settle_count() {
    const std::uint32_t live = read_live();
    if (live < n) {
      const int f = front;
      const std::size_t count = n - live;
      auto read = [&](const Buffer& b) { return ctx.read_vector<float>(b, count, live); };
      const std::vector<float> px = read(x[f]), py = read(y[f]), pz = read(z[f]);
      const std::vector<float> ux = read(vx[f]), uy = read(vy[f]), uz = read(vz[f]);
      for (std::size_t k = 0; k < count; ++k) {
        const double e = particle_energy(Vec3d(px[k], py[k], pz[k]), Vec3d(ux[k], uy[k], uz[k]));
        if (std::isfinite(e)) outflow_energy += e;  // a broken particle is the guard's (step_reduce)
      }
    }
    removed += n - live;
    n = live;
  }

  float read_float(const Buffer& buffer, std::uint32_t i) {
    float v = 0;
    ctx.read(buffer, &v, sizeof(v), std::size_t(i) * sizeof(float));
    return v;
  }

  std::string describe_particle(std::uint32_t i) {
    const int f = front;
    std::uint32_t pid = 0;
    ctx.read(id[f], &pid, sizeof(pid), std::size_t(i) * sizeof(std::uint32_t));
    const float px = read_float(x[f], i), py = read_float(y[f], i), pz = read_float(z[f], i);
    const float ux = read_float(vx[f], i), uy = read_float(vy[f], i), uz = read_float(vz[f], i);
    return fmt::format("particle {} at ({:.4g}, {:.4g}, {:.4g}) m with velocity ({:.4g}, {:.4g}, {:.4g}) m/s", pid, px,
                       py, pz, ux, uy, uz);
  }

  [[noreturn]] void blow_up(const std::string& what) const {
    fail_run("step {} (t = {:.6f} s): {}; the fluid blew up (lower time.dt_max or time.cfl, or raise fluid.mu)",
             steps + 1, t, what);
  }

  std::int64_t emit_after_step() {
    std::int64_t emitted = 0;
    for (std::size_t e = 0; e < emitters.size(); ++e) {
      const EmitterLattice& em = emitters[e];
      const std::int64_t target = em.layers_by(t, params.spacing);
      const double travelled = em.distance_by(t);
      const std::uint32_t per_layer = static_cast<std::uint32_t>(em.points.size());
      for (std::int64_t layer = emitter_layers[e]; layer < target; ++layer) {
        const std::int64_t room = std::int64_t(capacity) - std::int64_t(n);
        const std::uint32_t count = static_cast<std::uint32_t>(std::clamp<std::int64_t>(room, 0, per_layer));
        if (count < per_layer) capped = true;
        if (count > 0) {
          // Layer k crossed the emitter when the fluid had moved (k + 1) spacings.
          const double offset = travelled - static_cast<double>(layer + 1) * params.spacing;
          const Vec3d o = em.normal * offset;
          const Vec3d v = em.normal * em.speed;
          // Their energy (elastic: none, on the lattice).
          for (std::uint32_t k = 0; k < count; ++k) emitted_energy += particle_energy(em.points[k] + o, v);
          const int f = front;
          emit.args(count, n, next_id, emitter_first_point[e], static_cast<std::uint32_t>(e), ex, ey, ez,
                    static_cast<float>(o.x()), static_cast<float>(o.y()), static_cast<float>(o.z()),
                    static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()), x[f], y[f], z[f],
                    vx[f], vy[f], vz[f], id[f], hold[f], P.rho0, rho);
          ctx.launch(emit, count);
          n += count;
          next_id += count;
          emitted += count;
        }
      }
      emitter_layers[e] = target;
    }
    if (emitted) grid_valid = false;
    return emitted;
  }
};

}  // namespace bw::sim

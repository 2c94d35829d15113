#include "sim/solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "compute/kernels.h"
#include "compute/radix_sort.h"
#include "sim/solver_impl.h"
#include "sph_common.h"

namespace bw::sim {

Solver::Solver(const Setup& setup, compute::Context& context)
    : impl_(std::make_unique<Impl>(context)) {
  Impl& s = *impl_;
  s.params = setup.params;
  const Parameters& p = s.params;

  // Grid over the domain, cells of edge h (sized and checked by prepare()).
  const Aabb& domain = p.domain;
  const std::array<std::uint64_t, 3> dims{std::uint64_t(p.grid[0]), std::uint64_t(p.grid[1]), std::uint64_t(p.grid[2])};
  const std::uint64_t cells = dims[0] * dims[1] * dims[2];
  if (cells >= kMaxCells) fail_run("grid of {} cells is too large", cells);
  s.ncells = static_cast<std::uint32_t>(cells);
  s.capacity = u32(p.max_particles);

  SimParams& P = s.P;
  const double pi = std::numbers::pi;
  P.h = static_cast<float>(p.h);
  P.h2 = static_cast<float>(p.h * p.h);
  P.spiky = static_cast<float>(15.0 / (pi * std::pow(p.h, 6)));
  P.grad_scale = static_cast<float>(1.0 / p.gradient_moment);
  P.pressure_scale = static_cast<float>(3.0 * 15.0 / (pi * std::pow(p.h, 6)) * p.kernel_mass / p.gradient_moment);
  P.viscosity_scale = static_cast<float>(p.mu * p.kernel_mass * 45.0 / (pi * std::pow(p.h, 6)));
  P.visc = static_cast<float>(45.0 / (pi * std::pow(p.h, 6)));
  P.mass = static_cast<float>(p.mass);
  P.kernel_mass = static_cast<float>(p.kernel_mass);
  P.rho0 = static_cast<float>(p.rho0);
  P.stiffness = static_cast<float>(p.k);
  P.gamma = static_cast<float>(p.gamma);
  P.gamma_int = (p.gamma == std::floor(p.gamma) && p.gamma <= 64) ? static_cast<int>(p.gamma) : 0;
  P.mu = static_cast<float>(p.mu);
  P.mu_b = static_cast<float>(p.mu_b);
  P.gamma1 = static_cast<float>(p.gamma1);
  P.gamma2 = static_cast<float>(p.gamma2);
  P.wall_hydrostatic = p.wall_hydrostatic ? 1 : 0;
  P.wall_layer_step = static_cast<float>(p.wall_hydrostatic ? 0.0 : kMirroredWallStep);
  P.continuity = p.continuity ? 1 : 0;
  P.diffusion = static_cast<float>(p.continuity ? 2.0 * p.diffusion * p.h * p.c0 : 0.0);
  const Vec3d hydrostatic = p.rho0 * p.rho0 / (p.gamma * p.k) * p.gravity;
  P.hx = static_cast<float>(hydrostatic.x());
  P.hy = static_cast<float>(hydrostatic.y());
  P.hz = static_cast<float>(hydrostatic.z());
  P.contact = static_cast<float>(kContactDistance * p.spacing);
  P.patch = static_cast<float>(kPatchRadius * p.spacing);
  P.layer = static_cast<float>(0.5 * p.spacing);
  P.gx = static_cast<float>(p.gravity.x());
  P.gy = static_cast<float>(p.gravity.y());
  P.gz = static_cast<float>(p.gravity.z());
  P.ox = static_cast<float>(domain.min.x());
  P.oy = static_cast<float>(domain.min.y());
  P.oz = static_cast<float>(domain.min.z());
  P.cell = static_cast<float>(p.h);
  P.inv_cell = static_cast<float>(1.0 / p.h);
  P.max_x = static_cast<float>(domain.max.x());
  P.max_y = static_cast<float>(domain.max.y());
  P.max_z = static_cast<float>(domain.max.z());
  P.nx = static_cast<int>(dims[0]);
  P.ny = static_cast<int>(dims[1]);
  P.nz = static_cast<int>(dims[2]);
  P.ncells = static_cast<int>(s.ncells);

  // Refuse what cannot fit before allocating anything (the images' planes and push
  // are two 16-byte vectors per particle, and with bodies the planes' solids a third).
  const std::uint64_t per_particle =
      (29 + (p.wall_images ? (setup.bodies.empty() ? 8 : 12) : 0)) * sizeof(float);
  const std::uint64_t nb_all = setup.boundary.particles.size();
  const std::uint64_t estimate = (s.capacity + kPad) * per_particle + 2 * (cells + 1) * sizeof(std::uint32_t) +
                                 (nb_all + kPad) * 16 * sizeof(float);
  const compute::DeviceInfo& dev = context.device();
  if (dev.global_memory && estimate > dev.global_memory)
    fail_input("the scene needs about {} of device memory ({} fluid particles, {} boundary particles, {} grid cells); "
               "{} has {}",
               human_bytes(estimate), s.capacity, nb_all, cells, dev.label(), human_bytes(dev.global_memory));

  const std::string options = compute::kernel_build_options(dev);
  s.grid_program = context.build("grid.cl", compute::embedded_kernels(), options);
  // Without density diffusion its terms are compiled out of the density pass (bench-sim
  // measures what they cost against that build), without the wall layer's density
  // step (the hydrostatic wall) the step's terms, and with gravity along z the
  // hydrostatic part's other two products.
  const bool diffusion = p.continuity && p.diffusion > 0;
  const std::string fluid_options = options + (diffusion ? "" : " -DBW_DIFFUSION=0") +
                                    (P.wall_layer_step != 0 ? "" : " -DBW_WALL_STEP_ON=0") +
                                    (P.hx == 0 && P.hy == 0 ? " -DBW_GRAVITY_ALONG_Z=1" : "") +
                                    (p.wall_images ? " -DBW_GHOST_WALLS=1" : "") +
                                    (p.wall_images && !setup.bodies.empty() ? " -DBW_GHOST_BODIES=1" : "");
  s.fluid_program = context.build("fluid.cl", compute::embedded_kernels(), fluid_options);
  s.fluid_keys = s.grid_program.kernel("fluid_keys");
  s.boundary_keys = s.grid_program.kernel("boundary_keys");
  s.cell_starts = s.grid_program.kernel("cell_starts");
  s.reorder = s.grid_program.kernel("fluid_reorder");
  s.gather_float = s.grid_program.kernel("gather_float");
  s.gather_uint = s.grid_program.kernel("gather_uint");
  s.neighbour_lists = s.grid_program.kernel("neighbour_lists");
  s.psi = s.fluid_program.kernel("boundary_psi");
  s.density = s.fluid_program.kernel("fluid_density");
  s.density_rate = s.fluid_program.kernel("fluid_density_rate");
  s.wall_fraction = s.fluid_program.kernel("fluid_wall_fraction");
  s.boundary_pressure = s.fluid_program.kernel("boundary_pressure");
  s.wall_step = s.fluid_program.kernel("fluid_wall_step");
  s.wall_planes = s.fluid_program.kernel("fluid_wall_planes");
  s.forces = s.fluid_program.kernel("fluid_forces");
  s.integrate = s.fluid_program.kernel("fluid_integrate");
  s.step_reduce = s.fluid_program.kernel("fluid_step_reduce");
  s.frame_reduce = s.fluid_program.kernel("fluid_frame_reduce");
  s.emit = s.fluid_program.kernel("fluid_emit");
  s.sort = std::make_unique<compute::RadixSort>(context);

  const std::size_t cap = s.capacity;
  const char* names[2] = {"a", "b"};
  for (int k = 0; k < 2; ++k) {
    s.x[k] = s.floats(cap, fmt::format("fluid x ({})", names[k]));
    s.y[k] = s.floats(cap, fmt::format("fluid y ({})", names[k]));
    s.z[k] = s.floats(cap, fmt::format("fluid z ({})", names[k]));
    s.vx[k] = s.floats(cap, fmt::format("fluid vx ({})", names[k]));
    s.vy[k] = s.floats(cap, fmt::format("fluid vy ({})", names[k]));
    s.vz[k] = s.floats(cap, fmt::format("fluid vz ({})", names[k]));
    s.id[k] = s.uints(cap, fmt::format("fluid id ({})", names[k]));
    s.hold[k] = s.uints(cap, fmt::format("fluid emitter hold ({})", names[k]));
  }
  s.keys = s.uints(cap, "fluid keys");
  s.values = s.uints(cap, "fluid order");
  s.keys_tmp = s.uints(cap, "fluid keys (sort scratch)");
  s.values_tmp = s.uints(cap, "fluid order (sort scratch)");
  s.rho = s.floats(cap, "fluid rho");
  s.pres = s.floats(cap, "fluid p");
  s.pterm = s.floats(cap, "fluid p/rho^2");
  s.vol = s.floats(cap, "fluid 1/rho");
  s.phi = s.floats(cap, "fluid boundary fraction");
  s.diffusion_rate = s.floats(cap, "fluid diffusion rate");
  {
    // Without the images one element each: the kernels take them, never read them.
    const std::size_t images = p.wall_images ? cap + kPad : 1;
    s.wplane = context.buffer(images * 4 * sizeof(std::uint32_t), "fluid mirror planes");
    const std::size_t moving_images = p.wall_images && !setup.bodies.empty() ? cap + kPad : 1;
    s.wowner = context.buffer(moving_images * 4 * sizeof(std::uint32_t), "fluid mirror planes' solids");
    s.no_owners = context.buffer(sizeof(OwnerParams), "no owners");
    s.no_poses = context.buffer(sizeof(BodyPose), "no poses");
    s.image_share = context.buffer(images * 4 * sizeof(float), "fluid images' push per replaced weight");
  }
  s.ax = s.floats(cap, "fluid ax");
  s.ay = s.floats(cap, "fluid ay");
  s.az = s.floats(cap, "fluid az");
  s.rho_state = s.floats(cap, "fluid rho at the step's start");
  s.start = context.buffer((std::size_t(s.ncells) + 1) * sizeof(std::uint32_t), "fluid cell starts");
  s.bstart = context.buffer((std::size_t(s.ncells) + 1) * sizeof(std::uint32_t), "boundary cell starts");
  std::uint32_t chunk = 0;
  const std::uint32_t max_blocks = s.reduce_blocks(s.capacity, chunk);
  s.step_out = context.buffer(std::size_t(max_blocks + 1) * sizeof(StepReduce), "step reduction");
  s.frame_out = context.buffer(std::size_t(max_blocks + 1) * sizeof(FrameReduce), "frame reduction");

  // Initial fluid.
  const ParticleArrays& fluid = setup.fluid;
  s.n = static_cast<std::uint32_t>(fluid.size());
  context.write_vector(s.x[0], fluid.x);
  context.write_vector(s.y[0], fluid.y);
  context.write_vector(s.z[0], fluid.z);
  context.write_vector(s.vx[0], fluid.vx);
  context.write_vector(s.vy[0], fluid.vy);
  context.write_vector(s.vz[0], fluid.vz);
  context.write_vector(s.rho,
                       setup.fluid_rho.size() == fluid.size() ? setup.fluid_rho
                                                              : std::vector<float>(fluid.size(), P.rho0));
  s.wall_step_pending = P.continuity != 0;
  std::vector<std::uint32_t> ids(fluid.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
  context.write_vector(s.id[0], ids);
  s.next_id = s.n;

  // Boundary: upload, sort by cell once (static), then Psi_b.
  const BoundarySet& bset = setup.boundary;
  s.boundary_host = bset.particles;
  s.nb = static_cast<std::uint32_t>(bset.particles.size());
  const std::size_t nb = s.nb;
  s.bx = s.floats(nb, "boundary x");
  s.by = s.floats(nb, "boundary y");
  s.bz = s.floats(nb, "boundary z");
  s.bpsi = s.floats(nb, "boundary psi");
  s.bpt = s.floats(nb, "boundary pressure term");
  s.bvx = s.floats(nb, "boundary vx");
  s.bvy = s.floats(nb, "boundary vy");
  s.bvz = s.floats(nb, "boundary vz");
  s.bnx = s.floats(nb, "boundary normal x");
  s.bny = s.floats(nb, "boundary normal y");
  s.bnz = s.floats(nb, "boundary normal z");
  s.bsolid = s.uints(nb, "boundary solid");
  s.bflat = s.floats(nb, "boundary flatness");
  P.static_owners = static_cast<std::uint32_t>(bset.one_sided.size());
  s.one_sided = s.uints(std::max<std::size_t>(1, bset.one_sided.size()), "one-sided solids");
  if (!bset.one_sided.empty()) context.write_vector(s.one_sided, bset.one_sided);
  {
    Buffer ux = s.floats(nb, "boundary x (unsorted)"), uy = s.floats(nb, "boundary y (unsorted)"),
           uz = s.floats(nb, "boundary z (unsorted)"), us = s.uints(nb, "boundary solid (unsorted)");
    Buffer unx = s.floats(nb, "boundary normal x (unsorted)"), uny = s.floats(nb, "boundary normal y (unsorted)"),
           unz = s.floats(nb, "boundary normal z (unsorted)"), uflat = s.floats(nb, "boundary flatness (unsorted)");
    context.write_vector(uflat, bset.flatness);
    context.write_vector(unx, bset.nx);
    context.write_vector(uny, bset.ny);
    context.write_vector(unz, bset.nz);
    context.write_vector(ux, bset.particles.x);
    context.write_vector(uy, bset.particles.y);
    context.write_vector(uz, bset.particles.z);
    context.write_vector(us, bset.solid);
    Buffer bkeys = s.uints(nb, "boundary keys"), bvalues = s.uints(nb, "boundary order");
    Buffer bkeys_tmp = s.uints(nb, "boundary keys (sort scratch)"), bvalues_tmp = s.uints(nb, "boundary order (sort scratch)");
    if (s.nb > 0) {
      s.boundary_keys.args(P, s.nb, ux, uy, uz, bkeys, bvalues);
      context.launch(s.boundary_keys, s.nb);
      s.sort->sort(bkeys, bvalues, bkeys_tmp, bvalues_tmp, s.nb, s.ncells);
      s.gather_float.args(s.nb, bvalues, ux, s.bx);
      context.launch(s.gather_float, s.nb);
      s.gather_float.args(s.nb, bvalues, uy, s.by);
      context.launch(s.gather_float, s.nb);
      s.gather_float.args(s.nb, bvalues, uz, s.bz);
      context.launch(s.gather_float, s.nb);
      for (auto [from, to] : {std::pair{&unx, &s.bnx}, std::pair{&uny, &s.bny}, std::pair{&unz, &s.bnz},
                              std::pair{&uflat, &s.bflat}}) {
        s.gather_float.args(s.nb, bvalues, *from, *to);
        context.launch(s.gather_float, s.nb);
      }
      s.gather_uint.args(s.nb, bvalues, us, s.bsolid);
      context.launch(s.gather_uint, s.nb);
    }
    s.cell_starts.args(s.nb, s.ncells, bkeys, s.bstart);
    context.launch(s.cell_starts, nb + 1);
    s.psi.args(P, s.nb, s.bstart, s.bx, s.by, s.bz, s.bnx, s.bny, s.bnz, s.bsolid, s.bpsi);
    context.launch(s.psi, s.nb);
    context.finish();
  }

  // Emitters: every layer's points in one set of arrays.
  s.emitters = setup.emitters;
  std::vector<float> px, py, pz;
  for (const EmitterLattice& e : s.emitters) {
    s.emitter_first_point.push_back(static_cast<std::uint32_t>(px.size()));
    s.emitter_layers.push_back(0);
    for (const Vec3d& q : e.points) {
      px.push_back(static_cast<float>(q.x()));
      py.push_back(static_cast<float>(q.y()));
      pz.push_back(static_cast<float>(q.z()));
    }
  }
  // What the integration needs of each emitter: particles are held for h.
  std::vector<EmitterParams> table;
  for (const EmitterLattice& e : s.emitters) {
    EmitterParams q{};
    const Vec3d c = e.points.empty() ? Vec3d::Zero() : e.center;
    q.cx = static_cast<float>(c.x());
    q.cy = static_cast<float>(c.y());
    q.cz = static_cast<float>(c.z());
    q.nx = static_cast<float>(e.normal.x());
    q.ny = static_cast<float>(e.normal.y());
    q.nz = static_cast<float>(e.normal.z());
    q.speed = static_cast<float>(e.speed);
    q.hold = static_cast<float>(p.h);
    table.push_back(q);
  }
  s.emitter_table = context.buffer(std::max<std::size_t>(1, table.size()) * sizeof(EmitterParams), "emitters");
  context.write_vector(s.emitter_table, table);
  s.ex = s.floats(px.size(), "emitter points x");
  s.ey = s.floats(py.size(), "emitter points y");
  s.ez = s.floats(pz.size(), "emitter points z");
  context.write_vector(s.ex, px);
  context.write_vector(s.ey, py);
  context.write_vector(s.ez, pz);

  // Rigid bodies: the dynamic solids, in their reference configuration with their
  // initial velocities.
  s.static_boundary = setup.boundary;
  s.materials = setup.materials;
  std::vector<int> body_of_setup;
  for (const BodySetup& b : setup.bodies) {
    BodySpec spec;
    spec.name = b.name;
    spec.solid = static_cast<std::int32_t>(b.solid);
    spec.mass = b.mass;
    spec.voxels = b.voxels;
    spec.particles = b.particles;
    spec.normals = b.normals;
    spec.flatness = b.flatness;
    const SolidMaterial& m = setup.materials.at(b.solid);
    spec.spacing = m.spacing;
    spec.friction = m.friction;
    spec.restitution = m.restitution;
    spec.state.position = b.mass.center;
    spec.state.linear_velocity = b.velocity;
    spec.state.angular_velocity = b.angular_velocity;
    spec.fixed = b.breakable && b.anchored;
    spec.motion = b.motion;
    body_of_setup.push_back(s.add_body(spec));
  }
  if (std::any_of(setup.bodies.begin(), setup.bodies.end(), [](const BodySetup& b) { return b.breakable; }))
    s.enable_fracture(setup, body_of_setup);
}

Solver::~Solver() = default;

StepInfo Solver::step(double t_target) {
  Impl& s = *impl_;
  const Parameters& p = s.params;
  if (!(t_target > s.t)) fail_run("step to t = {} requested at t = {}", t_target, s.t);
  s.ensure_grid();
  const int f = s.front;
  s.launch_forces();

  std::uint32_t chunk = 0;
  const std::uint32_t blocks = s.reduce_blocks(s.n, chunk);
  s.step_reduce.args(s.n, chunk, blocks, s.ncells, s.P.mass, s.start, s.x[f], s.y[f], s.z[f], s.vx[f], s.vy[f],
                     s.vz[f], s.ax, s.ay, s.az, s.rho, s.diffusion_rate, s.hold[f], s.step_out);
  s.ctx.launch(s.step_reduce, blocks);
  const std::vector<StepReduce> parts = s.ctx.read_vector<StepReduce>(s.step_out, blocks);
  double max_v2 = 0, max_a2 = 0, max_rho = 0, max_rate = 0, held_power = 0;
  int fastest = -1, bad = -1;
  for (const StepReduce& r : parts) {
    held_power += r.held_power;
    if (r.bad >= 0 && bad < 0) bad = r.bad;
    if (r.fastest >= 0 && (fastest < 0 || r.max_v2 > max_v2)) {
      max_v2 = r.max_v2;
      fastest = r.fastest;
    }
    max_a2 = std::max(max_a2, double(r.max_a2));
    max_rho = std::max(max_rho, double(r.max_rho));
    max_rate = std::max(max_rate, double(r.max_diffusion_rate));
  }
  // Guard: stop before a broken state is integrated or written.
  if (bad >= 0) s.blow_up(s.describe_particle(static_cast<std::uint32_t>(bad)) + " has a non-finite value");
  const double vmax = std::sqrt(max_v2), amax = std::sqrt(max_a2);
  if (vmax > p.speed_limit)
    s.blow_up(fmt::format("{} moves at {:.4g} m/s, far faster than this scene can produce (limit {:.4g} m/s)",
                          s.describe_particle(static_cast<std::uint32_t>(fastest)), vmax, p.speed_limit));
  s.settle_count();

  // Adaptive step: CFL (over the fluid and the bodies' particles), force, viscous and
  // diffusion limits, the contact limit while bodies touch, at most dt_max, landing on t_target.
  // The CFL limit takes the sound speed of the most compressed particle (signal_speed):
  // a block that hits a wall near c0 doubles its density, where the Tait law's sound
  // speed is 8 times c0, and steps sized for c0 pumped energy into it.
  const double vbody = s.rigid ? s.body_speed_max() : 0.0;
  double dt = p.cfl * p.h / (signal_speed(p, max_rho) + std::max(vmax, vbody));
  const char* limit = "CFL";
  if (amax > 0 && p.force_factor * std::sqrt(p.h / amax) < dt) {
    dt = p.force_factor * std::sqrt(p.h / amax);
    limit = "force";
  }
  if (p.dt_viscous < dt) {
    dt = p.dt_viscous;
    limit = "viscous";
  }
  // The density diffusion is explicit: a step of at most 1 / (the largest rate at which
  // it pulls a particle's density toward its neighbours') cannot amplify any mode
  // (Gershgorin: the update's eigenvalues lie within twice the diagonal). Where
  // particles crowd together in an impact the rate rises above the lattice's, and a
  // bound fixed at the lattice's rate let such impacts gain energy. The density pass
  // skips the rate where the limit cannot bind (ensure_grid); where this step's other
  // limits come within the margin of the last rate after all, it runs again with the
  // rate (the same densities), so every dt is what the rate of every step would give.
  const bool diffusion = p.continuity && p.diffusion > 0;
  s.limit_last = std::min(dt, p.dt_max);
  if (diffusion && !s.rate_wanted && s.rate_may_bind()) {
    s.rate_wanted = true;
    s.launch_density(s.P);
    s.ctx.launch(s.step_reduce, blocks);
    max_rate = 0;
    for (const StepReduce& r : s.ctx.read_vector<StepReduce>(s.step_out, blocks))
      max_rate = std::max(max_rate, double(r.max_diffusion_rate));
  }
  if (s.rate_wanted) {
    s.rate_last = max_rate;
    s.rate_age = 0;
    if (diffusion && max_rate > 0 && p.diffusion_factor / max_rate < dt) {
      dt = p.diffusion_factor / max_rate;
      limit = "diffusion";
    }
  } else {
    ++s.rate_age;
  }
  if (s.rigid && s.rigid->touching_now && p.contact_dt < dt) {
    dt = p.contact_dt;
    limit = "contact";
  }
  // A step below dt_min would be needed: stop rather than take an unstable one (a
  // dt_min above the limits at the start is refused before the run, sim/run.cpp).
  if (dt < p.dt_min)
    fail_run("step {} (t = {:.6f} s): the {} limit asks for a step of {:.3g} s, below time.dt_min = {:.3g} s; the "
             "run stops rather than take unstable steps (lower time.dt_min)",
             s.steps, s.t, limit, dt, p.dt_min);
  dt = std::min(dt, p.dt_max);
  const double remaining = t_target - s.t;
  bool lands = false;
  if (remaining <= dt) {
    dt = remaining;
    lands = true;
  } else if (remaining < kSplitBeforeFrame * dt) {
    dt = 0.5 * remaining;
  }

  if (s.rigid) s.rigid_forces(dt);
  if (s.rigid && s.rigid->wall_pressure) s.integrate_wall_pressure(dt);
  if (s.sensors) s.sample_sensors(s.t, lands ? t_target : s.t + dt);
  if (s.fracture) s.fracture_load(dt);
  s.integrate.args(s.P, s.n, static_cast<float>(dt), s.x[f], s.y[f], s.z[f], s.vx[f], s.vy[f], s.vz[f], s.ax, s.ay,
                   s.az, s.phi, s.bstart, s.bx, s.by, s.bz, s.bnx, s.bny, s.bnz, s.bvx, s.bvy, s.bvz, s.bsolid,
                   s.one_sided, s.hold[f], s.emitter_table);
  s.ctx.launch(s.integrate, s.n);
  s.emitted_energy += held_power * dt;
  s.pending_dt += dt;
  if (s.rigid) s.step_bodies(dt);
  s.grid_valid = false;
  s.t = lands ? t_target : s.t + dt;
  ++s.steps;
  if (s.fracture) s.fracture_test();

  StepInfo info;
  info.dt = dt;
  info.max_speed = vmax;
  info.max_acceleration = amax;
  info.emitted = s.emit_after_step();
  return info;
}

double Solver::time() const { return impl_->t; }
std::int64_t Solver::steps() const { return impl_->steps; }
std::int64_t Solver::boundary_count() const { return impl_->nb; }
bool Solver::emitters_capped() const { return impl_->capped; }
const Parameters& Solver::parameters() const { return impl_->params; }
compute::Context& Solver::context() { return impl_->ctx; }
std::int64_t Solver::capacity() const { return impl_->capacity; }

std::uint64_t Solver::device_bytes() const {
  const Impl& s = *impl_;
  std::uint64_t total = 0;
  for (int k = 0; k < 2; ++k)
    total += s.x[k].bytes() + s.y[k].bytes() + s.z[k].bytes() + s.vx[k].bytes() + s.vy[k].bytes() + s.vz[k].bytes() +
             s.id[k].bytes() + s.hold[k].bytes();
  for (const Buffer* b : {&s.keys, &s.values, &s.keys_tmp, &s.values_tmp, &s.rho, &s.pres, &s.pterm, &s.vol, &s.phi, &s.diffusion_rate, &s.ax,
                          &s.ay, &s.az, &s.rho_state, &s.start, &s.bx, &s.by, &s.bz, &s.bpsi, &s.bpt, &s.bvx, &s.bvy, &s.bvz, &s.bnx, &s.bny, &s.bnz, &s.bsolid, &s.wplane, &s.wowner, &s.image_share,
                          &s.bstart, &s.step_out, &s.frame_out, &s.ex, &s.ey, &s.ez, &s.emitter_table})
    total += b->bytes();
  return total + s.sort->scratch_bytes() + s.rigid_bytes() + s.bflat.bytes() + s.fracture_bytes();
}

std::int64_t Solver::fluid_count() {
  impl_->ensure_grid();
  impl_->settle_count();
  return impl_->n;
}

std::int64_t Solver::removed_count() {
  fluid_count();
  return impl_->removed;
}

FluidStats Solver::stats() {
  Impl& s = *impl_;
  s.ensure_grid();
  s.settle_count();
  FluidStats out;
  out.fluid = s.n;
  out.emitted = s.emitted_energy;
  out.outflow = s.outflow_energy;
  s.body_energies(out.body_kinetic, out.body_potential);
  if (s.n == 0) return out;
  std::uint32_t chunk = 0;
  const std::uint32_t blocks = s.reduce_blocks(s.n, chunk);
  const int f = s.front;
  s.frame_reduce.args(s.P, s.n, chunk, blocks, s.x[f], s.y[f], s.z[f], s.vx[f], s.vy[f], s.vz[f], s.rho, s.frame_out);
  s.ctx.launch(s.frame_reduce, blocks);
  const std::vector<FrameReduce> parts = s.ctx.read_vector<FrameReduce>(s.frame_out, blocks);
  double error_sum = 0;
  for (const FrameReduce& r : parts) {
    out.kinetic += r.kinetic;
    out.potential += r.potential;
    out.elastic += r.elastic;
    error_sum += r.error_sum;
    out.density_error_max = std::max(out.density_error_max, double(r.error_max));
    out.speed_max = std::max(out.speed_max, double(r.speed_max));
  }
  out.density_error_mean = error_sum / s.n;
  return out;
}

FrameData Solver::frame(const FrameFields& fields, int frame_index) {
  Impl& s = *impl_;
  s.ensure_grid();
  s.settle_count();
  FrameData d;
  d.frame = frame_index;
  d.time = s.t;
  const int f = s.front;
  const std::size_t n = s.n;
  d.x = s.ctx.read_vector<float>(s.x[f], n);
  d.y = s.ctx.read_vector<float>(s.y[f], n);
  d.z = s.ctx.read_vector<float>(s.z[f], n);
  if (fields.velocity) {
    d.vx = s.ctx.read_vector<float>(s.vx[f], n);
    d.vy = s.ctx.read_vector<float>(s.vy[f], n);
    d.vz = s.ctx.read_vector<float>(s.vz[f], n);
  }
  if (fields.density) d.rho = s.ctx.read_vector<float>(s.rho, n);
  if (fields.pressure) d.p = s.ctx.read_vector<float>(s.pres, n);
  if (fields.id) {
    const auto ids = s.ctx.read_vector<std::uint32_t>(s.id[f], n);
    d.id.assign(ids.begin(), ids.end());
  }
  if (fields.boundary && s.rigid) {  // master order: the static solids', then each body's
    const RigidStage& r = *s.rigid;
    d.bx = s.ctx.read_vector<float>(r.mx, s.nb);
    d.by = s.ctx.read_vector<float>(r.my, s.nb);
    d.bz = s.ctx.read_vector<float>(r.mz, s.nb);
    d.bsolid.assign(r.sowner.begin(), r.sowner.end());
    for (const BodyEntry& e : r.bodies)
      if (e.info.active) d.bsolid.insert(d.bsolid.end(), e.reference.size(), static_cast<std::int32_t>(e.info.solid));
  } else if (fields.boundary) {
    d.bx = s.boundary_host.x;
    d.by = s.boundary_host.y;
    d.bz = s.boundary_host.z;
    d.bsolid.assign(s.static_boundary.solid.begin(), s.static_boundary.solid.end());
  }
  if (fields.wall_pressure && s.rigid && s.rigid->wall_pressure) d.bp = s.take_wall_pressure();
  d.bodies = body_states();
  return d;
}

std::vector<float> Solver::summed_density() {
  Impl& s = *impl_;
  s.ensure_grid();
  s.settle_count();
  SimParams summation = s.P;
  summation.continuity = 0;
  s.launch_density(summation);
  std::vector<float> out = s.ctx.read_vector<float>(s.rho, s.n);
  s.launch_density(s.P);  // the solver's own densities again
  return out;
}

Solver::ImageCoverage Solver::image_coverage() {
  Impl& s = *impl_;
  ImageCoverage out;
  if (!s.params.wall_images) return out;
  s.ensure_grid();
  s.settle_count();
  out.near = out.imaged = 0;
  if (s.n == 0) return out;
  constexpr std::uint32_t kNoPlane = 0xffffffffu;  // BW_NO_PLANE, sph_images.h
  const std::vector<float> phi = s.ctx.read_vector<float>(s.phi, s.n);
  const std::vector<std::uint32_t> planes = s.ctx.read_vector<std::uint32_t>(s.wplane, 4 * std::size_t(s.n));
  for (std::size_t i = 0; i < s.n; ++i) {
    if (!(phi[i] > 0)) continue;  // no solid's particle within h
    ++out.near;
    if (planes[4 * i] != kNoPlane) ++out.imaged;
  }
  return out;
}

Solver::Neighbours Solver::neighbour_lists(std::uint32_t max_per_particle) {
  Impl& s = *impl_;
  s.ensure_grid();
  s.settle_count();
  Neighbours out;
  const std::size_t n = s.n;
  Buffer count = s.uints(n, "neighbour counts");
  Buffer list = s.ctx.buffer(std::max<std::size_t>(1, n * max_per_particle) * sizeof(std::uint32_t), "neighbour lists");
  const int f = s.front;
  s.neighbour_lists.args(s.P, s.start, s.x[f], s.y[f], s.z[f], max_per_particle, count, list);
  s.ctx.launch(s.neighbour_lists, n);
  const auto counts = s.ctx.read_vector<std::uint32_t>(count, n);
  const auto flat = s.ctx.read_vector<std::uint32_t>(list, n * max_per_particle);
  out.x = s.ctx.read_vector<float>(s.x[f], n);
  out.y = s.ctx.read_vector<float>(s.y[f], n);
  out.z = s.ctx.read_vector<float>(s.z[f], n);
  out.lists.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (counts[i] > max_per_particle)
      fail_run("particle {} has {} neighbours, more than the {} asked for", i, counts[i], max_per_particle);
    out.lists[i].assign(flat.begin() + static_cast<std::ptrdiff_t>(i * max_per_particle),
                        flat.begin() + static_cast<std::ptrdiff_t>(i * max_per_particle + counts[i]));
  }
  return out;
}

Solver::Snapshot Solver::snapshot() {
  Impl& s = *impl_;
  s.ensure_grid();
  const int f = s.front;
  s.launch_forces();
  s.settle_count();
  const std::size_t n = s.n, nb = s.nb;
  Snapshot out;
  out.x = s.ctx.read_vector<float>(s.x[f], n);
  out.y = s.ctx.read_vector<float>(s.y[f], n);
  out.z = s.ctx.read_vector<float>(s.z[f], n);
  out.vx = s.ctx.read_vector<float>(s.vx[f], n);
  out.vy = s.ctx.read_vector<float>(s.vy[f], n);
  out.vz = s.ctx.read_vector<float>(s.vz[f], n);
  out.rho = s.ctx.read_vector<float>(s.rho, n);
  out.p = s.ctx.read_vector<float>(s.pres, n);
  out.ax = s.ctx.read_vector<float>(s.ax, n);
  out.ay = s.ctx.read_vector<float>(s.ay, n);
  out.az = s.ctx.read_vector<float>(s.az, n);
  out.bx = s.ctx.read_vector<float>(s.bx, nb);
  out.by = s.ctx.read_vector<float>(s.by, nb);
  out.bz = s.ctx.read_vector<float>(s.bz, nb);
  out.bpsi = s.ctx.read_vector<float>(s.bpsi, nb);
  out.bsolid = s.ctx.read_vector<std::uint32_t>(s.bsolid, nb);
  return out;
}

}  // namespace bw::sim

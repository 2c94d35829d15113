// The rigid bodies of the solver (sim/solver.h, "Rigid bodies"): the master order of
// the boundary, its sort every step, Psi_b of new particles, the forces on the
// bodies' particles and their per-body sums, and the bodies' steps on the host.
#include <cmath>
#include <limits>

#include "compute/kernels.h"
#include "rigid/contact.h"
#include "sim/solver_impl.h"

namespace bw::sim {
namespace {

// Particles per block of the per-body sums: a block never holds two bodies, and a
// float sum over this many forces stays accurate to about 1e-5 (the host adds the
// blocks in double).
constexpr std::uint32_t kBodyBlock = 256;
// Room for more boundary particles when the arrays grow (fragments, new crack faces),
// so that they are not reallocated at every change.
constexpr double kBoundaryGrowth = 1.25;
// Lateral reach of a boundary particle's contact, in the pair's widest spacing: the
// weight (1 - l^2/R^2)^2 summed over a square lattice of spacing s varies by 2% with
// where the particle lies over it at R = 1.5 s (by 20% at R = s).
constexpr float kContactReach = 1.5f;
// Pairs within the contact distance plus this fraction of the scene's spacing count
// as touching: the next step then takes the contact time step. A CFL step moves a
// particle less than 0.4 h, and bodies move far less (c0 >= 10 x their speed).
constexpr double kTouchMargin = 0.5;
// A gap between two solids narrower than the margin with fluid at either side (a
// boundary particle is wet with a fluid particle within kWetReach spacings, one
// spacing being where fluid rests against it) is damped along its normal with this
// damping ratio (docs/scene.md, "Resting in water"). An explicit dashpot is stable
// while c dt / m_eff < 2: with the contact time step (omega dt <= 0.5) and a contact
// point's effective mass down to M / 4 (a box turning about its edge), 0.25 keeps it
// at 1.
constexpr double kSqueezeDamping = 0.25;
constexpr double kWetReach = 1.5;

BodyPose pose_of(const rigid::Body& body) {
  const rigid::BodyState& st = body.state();
  const Mat3d r = body.rotation();
  BodyPose p{};
  p.cx = static_cast<float>(st.position.x());
  p.cy = static_cast<float>(st.position.y());
  p.cz = static_cast<float>(st.position.z());
  p.r00 = static_cast<float>(r(0, 0)), p.r01 = static_cast<float>(r(0, 1)), p.r02 = static_cast<float>(r(0, 2));
  p.r10 = static_cast<float>(r(1, 0)), p.r11 = static_cast<float>(r(1, 1)), p.r12 = static_cast<float>(r(1, 2));
  p.r20 = static_cast<float>(r(2, 0)), p.r21 = static_cast<float>(r(2, 1)), p.r22 = static_cast<float>(r(2, 2));
  p.vx = static_cast<float>(st.linear_velocity.x());
  p.vy = static_cast<float>(st.linear_velocity.y());
  p.vz = static_cast<float>(st.linear_velocity.z());
  p.wx = static_cast<float>(st.angular_velocity.x());
  p.wy = static_cast<float>(st.angular_velocity.y());
  p.wz = static_cast<float>(st.angular_velocity.z());
  return p;
}

OwnerParams owner_params(double mass_per_particle, double friction, double damping, double spacing) {
  OwnerParams o{};
  o.inv_mass = mass_per_particle > 0 ? static_cast<float>(1.0 / mass_per_particle) : 0.0f;
  o.friction = static_cast<float>(friction);
  o.damping = static_cast<float>(damping);
  o.spacing = static_cast<float>(spacing);
  return o;
}

bool finite(const Vec3d& v) { return v.allFinite(); }

}  // namespace

BodyEntry& Solver::Impl::body_entry(int body) {
  if (!rigid || body < 0 || body >= static_cast<int>(rigid->bodies.size()))
    fail_run("no body {} (the solver has {})", body, rigid ? rigid->bodies.size() : 0);
  return rigid->bodies[static_cast<std::size_t>(body)];
}

const BodyEntry& Solver::Impl::body_entry(int body) const {
  return const_cast<Impl*>(this)->body_entry(body);
}

void Solver::Impl::enable_bodies() {
  if (rigid) return;
  rigid = std::make_unique<RigidStage>();
  RigidStage& r = *rigid;
  const std::string images = params.wall_images ? " -DBW_GHOST_WALLS=1" : "";
  r.program = ctx.build("rigid.cl", compute::embedded_kernels(), compute::kernel_build_options(ctx.device()) + images);
  r.pose = r.program.kernel("body_pose");
  r.gather = r.program.kernel("boundary_gather");
  r.psi = r.program.kernel("boundary_psi_owners");
  r.forces = r.program.kernel("boundary_forces");
  r.reduce = r.program.kernel("body_reduce");
  r.materials = materials;
  r.body_owner0 = static_cast<std::uint32_t>(materials.size());
  const BoundarySet& b = static_boundary;
  r.ns = static_cast<std::uint32_t>(b.particles.size());
  r.sx = b.particles.x, r.sy = b.particles.y, r.sz = b.particles.z;
  r.snx = b.nx, r.sny = b.ny, r.snz = b.nz;
  r.sflat = b.flatness;
  r.sowner = b.solid;
  r.spsi.assign(r.ns, 0.0f);
  r.static_psi_dirty = true;
  r.layout_dirty = true;
  boundary_dirty = true;
}

int Solver::Impl::add_body(const BodySpec& spec) {
  if (spec.particles.size() != spec.normals.size())
    fail_run("body '{}': {} particles but {} normals", spec.name, spec.particles.size(), spec.normals.size());
  if (!(spec.spacing > 0)) fail_run("body '{}': spacing {} must be positive", spec.name, spec.spacing);
  enable_bodies();
  BodyEntry e;
  e.body = rigid::Body(spec.mass);  // checks the mass
  e.body.state() = spec.state;
  e.info.name = spec.name;
  e.info.solid = spec.solid;
  e.info.parent = spec.parent;
  e.info.voxels = spec.voxels;
  e.info.created_time = t;
  e.info.fixed = spec.fixed;
  e.motion = spec.motion;
  e.spacing = spec.spacing;
  e.friction = spec.friction;
  e.restitution = spec.restitution;
  rigid->bodies.push_back(std::move(e));
  const int index = static_cast<int>(rigid->bodies.size()) - 1;
  replace_body_particles(index, spec.particles, spec.normals, spec.flatness);
  return index;
}

void Solver::Impl::replace_body_particles(int body, const std::vector<Vec3d>& particles,
                                          const std::vector<Vec3d>& normals, const std::vector<double>& flatness) {
  BodyEntry& e = body_entry(body);
  if (particles.size() != normals.size() || (!flatness.empty() && flatness.size() != particles.size()))
    fail_run("body '{}': {} particles, {} normals and {} flatness values", e.info.name, particles.size(),
             normals.size(), flatness.size());
  e.flatness.assign(particles.size(), 1.0f);
  for (std::size_t i = 0; i < flatness.size(); ++i) e.flatness[i] = static_cast<float>(flatness[i]);
  const Vec3d c = e.body.mass().center;
  e.reference.clear();
  e.reference_normals = normals;
  e.radius = 0;
  for (const Vec3d& q : particles) {
    e.reference.push_back(q - c);
    e.radius = std::max(e.radius, (q - c).norm());
  }
  e.info.particles = particles.size();
  e.psi.assign(particles.size(), 0.0f);
  e.psi_dirty = true;
  rigid->layout_dirty = true;
  boundary_dirty = true;
}

void Solver::Impl::upload_layout() {
  RigidStage& r = *rigid;
  // The static particles' wall pressure so far stays; the bodies' starts again.
  const std::vector<float> static_wall =
      r.wall_integral.valid() ? ctx.read_vector<float>(r.wall_integral, r.ns) : std::vector<float>(r.ns, 0.0f);
  // Master order: static particles, then each body's in index order.
  std::uint32_t total = r.ns;
  for (BodyEntry& e : r.bodies) {
    e.first = total;
    total += static_cast<std::uint32_t>(e.info.active ? e.reference.size() : 0);
  }
  if (total > r.capacity) {
    // (Re)allocate every per-particle array, the solver's sorted ones included, and
    // put the static particles back.
    const std::size_t cap = static_cast<std::size_t>(std::ceil(kBoundaryGrowth * total));
    r.capacity = static_cast<std::uint32_t>(cap);
    for (auto [buffer, name] : {std::pair{&r.mx, "x"}, {&r.my, "y"}, {&r.mz, "z"}, {&r.mvx, "vx"}, {&r.mvy, "vy"},
                                {&r.mvz, "vz"}, {&r.mnx, "normal x"}, {&r.mny, "normal y"}, {&r.mnz, "normal z"}, {&r.mflat, "flatness"},
                                {&r.mpsi, "psi"}, {&r.fx, "force x"}, {&r.fy, "force y"}, {&r.fz, "force z"},
                                {&r.tx, "torque x"}, {&r.ty, "torque y"}, {&r.tz, "torque z"},
                                {&r.touching, "contact pairs"}})
      *buffer = floats(cap, fmt::format("boundary {} (master order)", name));
    for (auto [buffer, name] : {std::pair{&r.rx, "x"}, {&r.ry, "y"}, {&r.rz, "z"}, {&r.rnx, "normal x"},
                                {&r.rny, "normal y"}, {&r.rnz, "normal z"}})
      *buffer = floats(cap, fmt::format("body particles reference {}", name));
    r.pbody = uints(cap, "body particles body");
    r.wet = {uints(cap, "boundary wet (last step)"), uints(cap, "boundary wet (this step)")};
    r.mowner = uints(cap, "boundary owner (master order)");
    r.keys = uints(cap, "boundary keys");
    r.order = uints(cap, "boundary order");
    r.keys_tmp = uints(cap, "boundary keys (sort scratch)");
    r.order_tmp = uints(cap, "boundary order (sort scratch)");
    r.rank = uints(cap, "boundary rank");
    r.wall_integral = Buffer{};  // reallocated by reset_wall_pressure
    bx = floats(cap, "boundary x");
    by = floats(cap, "boundary y");
    bz = floats(cap, "boundary z");
    bpsi = floats(cap, "boundary psi");
    bpt = floats(cap, "boundary pressure term");
    bvx = floats(cap, "boundary vx");
    bvy = floats(cap, "boundary vy");
    bvz = floats(cap, "boundary vz");
    bnx = floats(cap, "boundary normal x");
    bny = floats(cap, "boundary normal y");
    bnz = floats(cap, "boundary normal z");
    bsolid = uints(cap, "boundary owner");
    bflat = floats(cap, "boundary flatness");
    ctx.write_vector(r.mx, r.sx);
    ctx.write_vector(r.my, r.sy);
    ctx.write_vector(r.mz, r.sz);
    ctx.write_vector(r.mnx, r.snx);
    ctx.write_vector(r.mny, r.sny);
    ctx.write_vector(r.mnz, r.snz);
    ctx.write_vector(r.mflat, r.sflat);
    ctx.write_vector(r.mowner, r.sowner);
    ctx.write_vector(r.mpsi, r.spsi);
  }
  // The bodies' part: reference arrays, body and owner of each particle, and the Psi_b
  // known so far (new particles get theirs after the sort).
  std::vector<float> rx, ry, rz, rnx, rny, rnz, flat, known_psi;
  std::vector<std::uint32_t> pbody, owner;
  for (std::size_t k = 0; k < r.bodies.size(); ++k) {
    const BodyEntry& e = r.bodies[k];
    if (!e.info.active) continue;
    for (std::size_t i = 0; i < e.reference.size(); ++i) {
      rx.push_back(static_cast<float>(e.reference[i].x()));
      ry.push_back(static_cast<float>(e.reference[i].y()));
      rz.push_back(static_cast<float>(e.reference[i].z()));
      rnx.push_back(static_cast<float>(e.reference_normals[i].x()));
      rny.push_back(static_cast<float>(e.reference_normals[i].y()));
      rnz.push_back(static_cast<float>(e.reference_normals[i].z()));
      pbody.push_back(static_cast<std::uint32_t>(k));
      owner.push_back(r.body_owner0 + static_cast<std::uint32_t>(k));
    }
    known_psi.insert(known_psi.end(), e.psi.begin(), e.psi.end());
    flat.insert(flat.end(), e.flatness.begin(), e.flatness.end());
  }
  ctx.write_vector(r.rx, rx);
  ctx.write_vector(r.ry, ry);
  ctx.write_vector(r.rz, rz);
  ctx.write_vector(r.rnx, rnx);
  ctx.write_vector(r.rny, rny);
  ctx.write_vector(r.rnz, rnz);
  ctx.write_vector(r.pbody, pbody);
  ctx.write_vector(r.mowner, owner, r.ns);
  ctx.write_vector(r.mpsi, known_psi, r.ns);
  ctx.write_vector(r.mflat, flat, r.ns);

  r.owners = ctx.buffer((r.body_owner0 + std::max<std::size_t>(1, r.bodies.size())) * sizeof(OwnerParams), "owners");
  r.poses = ctx.buffer(std::max<std::size_t>(1, r.bodies.size()) * sizeof(BodyPose), "body poses");

  // Blocks of the per-body sums: the moving bodies' particles (and the static ones
  // when their reactions are measured), never two owners' in one block.
  r.block_table.clear();
  // A static block's pad holds its solid's index (the loads of each solid).
  auto add_blocks = [&](std::uint32_t body, std::uint32_t first, std::uint32_t count, std::uint32_t solid) {
    for (std::uint32_t k = 0; k < count; k += kBodyBlock)
      r.block_table.push_back(BodyBlock{body, first + k, std::min(kBodyBlock, count - k), solid});
  };
  if (r.measure_static)  // one solid's particles at a time: they are in scene order
    for (std::uint32_t a = 0; a < r.ns;) {
      std::uint32_t b = a;
      while (b < r.ns && r.sowner[b] == r.sowner[a]) ++b;
      add_blocks(BW_NO_BODY, a, b - a, r.sowner[a]);
      a = b;
    }
  // Fixed bodies only for their loads: they do not move.
  for (std::size_t k = 0; k < r.bodies.size(); ++k) {
    const BodyEntry& e = r.bodies[k];
    if (e.info.active && (!e.info.fixed || r.measure_static))
      add_blocks(static_cast<std::uint32_t>(k), e.first, static_cast<std::uint32_t>(e.reference.size()), 0);
  }
  r.blocks = ctx.buffer(std::max<std::size_t>(1, r.block_table.size()) * sizeof(BodyBlock), "body blocks");
  ctx.write_vector(r.blocks, r.block_table);
  r.block_sums = ctx.buffer(std::max<std::size_t>(1, r.block_table.size()) * sizeof(BodyReduce), "body block sums");
  r.dirty = uints(r.body_owner0 + r.bodies.size(), "Psi_b requests");
  // Master indices changed: no particle is known to be wet until the next step.
  const std::vector<std::uint32_t> dry(total, 0u);
  for (Buffer& w : r.wet) ctx.write_vector(w, dry);
  r.nb = total;
  nb = total;
  r.layout_dirty = false;
  if (r.wall_pressure) reset_wall_pressure(static_wall);
}

// What contacts need of every owner: static solids have no mass (inv_mass 0), as do
// fixed and retired bodies, and solids moved as told (they do not give way); a body
// moved by its forces has as contact mass its mass over the weight of its contact
// pairs at the last step (at least 1).
void Solver::Impl::upload_owners() {
  RigidStage& r = *rigid;
  // The damping ratio of a restitution as the solver steps contacts (the solid's own
  // zeta; a pair takes the lesser of its two, so the larger restitution).
  auto damping = [&](double restitution) {
    auto it = r.damping_of.find(restitution);
    if (it == r.damping_of.end())
      it = r.damping_of
               .emplace(restitution, std::min(params.contact_zeta_max,
                                              rigid::damping_ratio_for_step(restitution, params.contact_step)))
               .first;
    return it->second;
  };
  std::vector<OwnerParams> owners;
  for (const SolidMaterial& m : r.materials)
    owners.push_back(owner_params(0, m.friction, damping(m.restitution), m.spacing));
  for (const BodyEntry& e : r.bodies) {
    const bool moves = e.info.active && !e.info.fixed && !e.moving() && !e.reference.empty();
    const double contact_mass = moves ? e.body.mass().mass / std::max(1.0, e.contact_weight) : 0.0;
    owners.push_back(owner_params(contact_mass, e.friction, damping(e.restitution), e.spacing));
  }
  ctx.write_vector(r.owners, owners);
}

void Solver::Impl::update_boundary() {
  RigidStage& r = *rigid;
  if (r.layout_dirty) upload_layout();
  const std::uint32_t total = r.nb, nd = r.nb - r.ns;
  std::vector<BodyPose> poses;
  for (const BodyEntry& e : r.bodies) poses.push_back(pose_of(e.body));
  ctx.write_vector(r.poses, poses);
  upload_owners();
  if (nd > 0) {
    r.pose.args(r.ns, nd, r.poses, r.pbody, r.rx, r.ry, r.rz, r.rnx, r.rny, r.rnz, r.mx, r.my, r.mz, r.mvx, r.mvy,
                r.mvz, r.mnx, r.mny, r.mnz);
    ctx.launch(r.pose, nd);
  }
  boundary_keys.args(P, total, r.mx, r.my, r.mz, r.keys, r.order);
  ctx.launch(boundary_keys, total);
  sort->sort(r.keys, r.order, r.keys_tmp, r.order_tmp, total, ncells);
  r.gather.args(total, r.order, r.mx, r.my, r.mz, r.mvx, r.mvy, r.mvz, r.mnx, r.mny, r.mnz, r.mflat, r.mpsi, r.mowner,
                bx, by, bz, bvx, bvy, bvz, bnx, bny, bnz, bflat, bpsi, bsolid, r.rank);
  ctx.launch(r.gather, total);
  cell_starts.args(total, ncells, r.keys, bstart);
  ctx.launch(cell_starts, std::size_t(total) + 1);

  // Psi_b of the owners whose particles are new, read back so that a later change of
  // the layout keeps it.
  std::vector<std::uint32_t> dirty(r.body_owner0 + r.bodies.size(), 0);
  bool any = false;
  if (r.static_psi_dirty)
    for (std::uint32_t o = 0; o < r.body_owner0; ++o) dirty[o] = 1, any = true;
  for (std::size_t k = 0; k < r.bodies.size(); ++k)
    if (r.bodies[k].psi_dirty && r.bodies[k].info.active && !r.bodies[k].reference.empty())
      dirty[r.body_owner0 + k] = 1, any = true;
  if (any) {
    ctx.write_vector(r.dirty, dirty);
    r.psi.args(P, total, bstart, bx, by, bz, bnx, bny, bnz, bsolid, r.order, static_cast<std::uint32_t>(dirty.size()),
               r.dirty, bpsi, r.mpsi);
    ctx.launch(r.psi, total);
    if (r.static_psi_dirty) r.spsi = ctx.read_vector<float>(r.mpsi, r.ns);
    r.static_psi_dirty = false;
    for (BodyEntry& e : r.bodies) {
      if (!e.psi_dirty || !e.info.active) continue;
      e.psi = ctx.read_vector<float>(r.mpsi, e.reference.size(), e.first);
      e.psi_dirty = false;
    }
  }
  boundary_dirty = false;
  grid_valid = false;
  // The contact weights of where the bodies are now, before the step's forces and
  // time step: a body's contact mass then shares its mass over the pairs it has now,
  // not those of the last step (a face arriving at a floor brings all its pairs at
  // once), and a step that starts touching takes the contact time step.
  rigid_forces(-1.0);
  upload_owners();
}

double Solver::Impl::body_speed_max() const {
  double v = 0;
  for (const BodyEntry& e : rigid->bodies) {
    if (!e.info.active || e.info.fixed) continue;
    const rigid::BodyState& st = e.body.state();
    v = std::max(v, st.linear_velocity.norm() + st.angular_velocity.norm() * e.radius);
  }
  return v;
}

// dt < 0: only count the contact weights (boundary_forces' count mode).
void Solver::Impl::rigid_forces(double dt) {
  RigidStage& r = *rigid;
  const std::uint32_t first = r.measure_static ? 0 : r.ns;
  const std::uint32_t count = r.nb - first;
  if (dt >= 0)
    for (BodyEntry& e : r.bodies) e.force = e.torque = Vec3d::Zero();
  if (count == 0 || r.block_table.empty()) {
    r.touching_now = false;
    return;
  }
  ContactParams C{};
  C.omega = static_cast<float>(params.contact_frequency);
  C.reach = kContactReach;
  C.margin = static_cast<float>(kTouchMargin * params.spacing);
  C.squeeze = static_cast<float>(kSqueezeDamping);
  C.wet2 = static_cast<float>(kWetReach * kWetReach * params.spacing * params.spacing);
  C.body_owner0 = r.body_owner0;
  const int f = front;
  const int w = r.wet_read;
  r.forces.args(P, C, first, count, static_cast<float>(dt), start, x[f], y[f], z[f], vx[f], vy[f], vz[f], ax, ay, az,
                rho, pterm, phi, hold[f], bstart, bx, by, bz, bvx, bvy, bvz, bnx, bny, bnz, bflat, bpsi, bpt, bsolid,
                one_sided, r.rank, r.order, r.owners, r.wet[static_cast<std::size_t>(w)], r.fx, r.fy, r.fz, r.tx, r.ty, r.tz,
                r.touching, r.wet[static_cast<std::size_t>(1 - w)], wplane, image_share);
  ctx.launch(r.forces, count);
  if (dt >= 0) r.wet_read = 1 - w;
  sum_blocks(dt);
}

// The per-body sums: blocks on the device, added on the host in their fixed order,
// in double.
void Solver::Impl::sum_blocks(double dt) {
  RigidStage& r = *rigid;
  const std::uint32_t nblocks = static_cast<std::uint32_t>(r.block_table.size());
  r.reduce.args(nblocks, r.blocks, r.poses, r.mx, r.my, r.mz, r.fx, r.fy, r.fz, r.tx, r.ty, r.tz, r.touching,
                r.block_sums);
  ctx.launch(r.reduce, nblocks);
  const std::vector<BodyReduce> sums = ctx.read_vector<BodyReduce>(r.block_sums, nblocks);
  double pairs = 0;
  Vec3d static_force = Vec3d::Zero();
  for (BodyEntry& e : r.bodies) e.contact_weight = 0;
  for (std::size_t b = 0; b < nblocks; ++b) {
    const BodyReduce& s = sums[b];
    const Vec3d force(s.fx, s.fy, s.fz), torque(s.tx, s.ty, s.tz);
    const std::uint32_t body = r.block_table[b].body;
    const bool measured_only = body != BW_NO_BODY && r.bodies[body].info.fixed;
    if (!measured_only) pairs += s.touching;
    if (body == BW_NO_BODY) {
      static_force += force;
      if (dt > 0) r.solid_impulse[r.block_table[b].pad] += dt * force;
      continue;
    }
    BodyEntry& e = r.bodies[body];
    if (measured_only) {  // a fixed body's load (its contact weight is not a moving owner's)
      if (dt > 0) r.solid_impulse[static_cast<std::size_t>(e.info.solid)] += dt * force;
      continue;
    }
    e.contact_weight += s.touching;
    if (dt >= 0) {
      e.force += force;
      e.torque += torque;
    }
  }
  r.touching_now = pairs > 0;
  if (dt > 0) {
    r.static_impulse += dt * static_force;
    if (r.measure_static)  // the moving bodies' loads: fluid and contacts, without gravity
      for (const BodyEntry& e : r.bodies)
        if (e.info.active && !e.info.fixed) r.solid_impulse[static_cast<std::size_t>(e.info.solid)] += dt * e.force;
  }
}

void Solver::Impl::step_bodies(double dt) {
  RigidStage& r = *rigid;
  bool moved = false;
  for (BodyEntry& e : r.bodies) {
    if (!e.info.active || e.info.fixed) continue;
    if (e.moving()) {
      // Along its path, whatever its forces; what it does against them (the fluid's
      // and its contacts' force on it) is energy put into the scene.
      rigid::BodyState& st = e.body.state();
      const Vec3d before = st.position;
      const Vec3d turned = e.motion.advance(t, dt, st.position, st.orientation);
      emitted_energy -= e.force.dot(st.position - before) + e.torque.dot(turned);
      st.linear_velocity = e.motion.velocity(st.position, t + dt);
      st.angular_velocity = e.motion.angular_velocity(t + dt);
      moved = moved || st.position != before || turned != Vec3d::Zero();
      continue;
    }
    e.force += e.body.mass().mass * params.gravity;
    e.body.step(e.force, e.torque, dt);
    const rigid::BodyState& st = e.body.state();
    if (!finite(st.position) || !finite(st.linear_velocity) || !finite(st.angular_velocity))
      blow_up(fmt::format("body '{}' has a non-finite state (force ({:.4g}, {:.4g}, {:.4g}) N)", e.info.name,
                          e.force.x(), e.force.y(), e.force.z()));
    moved = true;
  }
  if (moved) boundary_dirty = true;
}

void Solver::Impl::body_energies(double& kinetic, double& potential) const {
  kinetic = potential = 0;
  if (!rigid) return;
  for (const BodyEntry& e : rigid->bodies) {
    if (!e.info.active || e.moving()) continue;  // a moving solid's energy is not the scene's
    kinetic += e.body.kinetic_energy();
    potential -= e.body.mass().mass * params.gravity.dot(e.body.state().position - params.domain.min);
  }
}

std::uint64_t Solver::Impl::rigid_bytes() const {
  if (!rigid) return 0;
  const RigidStage& r = *rigid;
  std::uint64_t total = 0;
  for (const Buffer* b : {&r.mx, &r.my, &r.mz, &r.mvx, &r.mvy, &r.mvz, &r.mnx, &r.mny, &r.mnz, &r.mflat, &r.mpsi, &r.mowner,
                          &r.rx, &r.ry, &r.rz, &r.rnx, &r.rny, &r.rnz, &r.pbody, &r.keys, &r.order, &r.keys_tmp,
                          &r.order_tmp, &r.rank, &r.fx, &r.fy, &r.fz, &r.tx, &r.ty, &r.tz, &r.touching, &r.wet[0], &r.wet[1], &r.poses,
                          &r.owners, &r.blocks, &r.block_sums, &r.dirty})
    total += b->bytes();
  return total;
}

// ---- the public interface

int Solver::add_body(const BodySpec& spec) { return impl_->add_body(spec); }

void Solver::replace_body_particles(int body, const std::vector<Vec3d>& particles, const std::vector<Vec3d>& normals,
                                    const std::vector<double>& flatness) {
  impl_->replace_body_particles(body, particles, normals, flatness);
}

void Solver::set_body_fixed(int body, bool fixed) {
  BodyEntry& e = impl_->body_entry(body);
  if (e.info.fixed == fixed) return;
  e.info.fixed = fixed;
  if (fixed) {
    e.body.state().linear_velocity = Vec3d::Zero();
    e.body.state().angular_velocity = Vec3d::Zero();
  }
  impl_->rigid->layout_dirty = true;
  impl_->boundary_dirty = true;
}

void Solver::retire_body(int body) { impl_->retire_body(body); }

int Solver::body_count() const { return impl_->rigid ? static_cast<int>(impl_->rigid->bodies.size()) : 0; }
const BodyInfo& Solver::body_info(int body) const { return impl_->body_entry(body).info; }
const rigid::Body& Solver::body(int body) const { return impl_->body_entry(body).body; }

rigid::BodyState& Solver::body_state(int body) {
  impl_->boundary_dirty = true;  // the caller may move it
  return impl_->body_entry(body).body.state();
}

Vec3d Solver::body_force(int body) const { return impl_->body_entry(body).force; }
Vec3d Solver::body_torque(int body) const { return impl_->body_entry(body).torque; }

std::uint32_t Solver::body_first_particle(int body) const {
  Impl& s = *impl_;
  if (s.rigid && s.rigid->layout_dirty) s.upload_layout();
  return s.body_entry(body).first;
}

BodyStates Solver::body_states() const {
  BodyStates out;
  if (!impl_->rigid) return out;
  const auto& bodies = impl_->rigid->bodies;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (!bodies[k].info.active) continue;
    const rigid::BodyState& st = bodies[k].body.state();
    out.id.push_back(static_cast<std::int32_t>(k));
    out.position.push_back(st.position);
    out.orientation.push_back(st.orientation);
    out.linear_velocity.push_back(st.linear_velocity);
    out.angular_velocity.push_back(st.angular_velocity);
  }
  return out;
}

void Solver::measure_static_reactions(bool on) {
  Impl& s = *impl_;
  if (on) s.enable_bodies();
  if (!s.rigid || s.rigid->measure_static == on) return;
  s.rigid->measure_static = on;
  s.rigid->static_impulse = Vec3d::Zero();
  s.rigid->solid_impulse.assign(s.rigid->body_owner0, Vec3d::Zero());
  s.rigid->layout_dirty = true;
  s.boundary_dirty = true;
}

void Solver::set_sensors(std::vector<SensorWeights> sensors, double interval) {
  Impl& s = *impl_;
  if (sensors.empty()) {
    s.sensors.reset();
    return;
  }
  if (!(interval > 0)) fail_run("sensor interval {} s must be positive", interval);
  if (s.steps > 0) fail_run("sensors are set before the first step (their samples count from t = 0)");
  measure_static_reactions(true);
  auto st = std::make_unique<SensorStage>();
  st->kernel = s.rigid->program.kernel("sensor_pressure");
  std::vector<std::uint32_t> first{0}, particle;
  std::vector<float> weight, normal;
  for (const SensorWeights& w : sensors) {
    for (std::size_t k = 0; k < w.particle.size(); ++k) {
      if (w.particle[k] >= s.rigid->ns)
        fail_run("sensor '{}': particle {} is not a static particle (the solver has {})", w.name, w.particle[k],
                 s.rigid->ns);
      particle.push_back(w.particle[k]);
      weight.push_back(static_cast<float>(w.weight[k]));
    }
    first.push_back(static_cast<std::uint32_t>(particle.size()));
    for (int c = 0; c < 3; ++c) normal.push_back(static_cast<float>(w.normal[c]));
  }
  st->first = s.uints(first.size(), "sensor first");
  st->particle = s.uints(particle.size(), "sensor particles");
  st->weight = s.floats(weight.size(), "sensor weights");
  st->normal = s.floats(normal.size(), "sensor normals");
  st->out = s.floats(sensors.size(), "sensor pressures");
  s.ctx.write_vector(st->first, first);
  if (!particle.empty()) {
    s.ctx.write_vector(st->particle, particle);
    s.ctx.write_vector(st->weight, weight);
  }
  s.ctx.write_vector(st->normal, normal);
  st->interval = interval;
  st->sample = 0;
  st->partial.assign(sensors.size(), 0.0);
  st->sensors = std::move(sensors);
  s.sensors = std::move(st);
}

const std::vector<SensorWeights>& Solver::sensors() const {
  static const std::vector<SensorWeights> none;
  return impl_->sensors ? impl_->sensors->sensors : none;
}

const std::vector<double>& Solver::sensor_samples() const {
  static const std::vector<double> none;
  return impl_->sensors ? impl_->sensors->samples : none;
}

// The readings of this step's forces, held from t0 to t1, into the samples they
// overlap (a sample closes when the step reaches its end, to a billionth of it).
void Solver::Impl::sample_sensors(double t0, double t1) {
  SensorStage& st = *sensors;
  const std::uint32_t count = static_cast<std::uint32_t>(st.sensors.size());
  st.kernel.args(count, st.first, st.particle, st.weight, st.normal, rigid->fx, rigid->fy, rigid->fz, st.out);
  ctx.launch(st.kernel, count);
  const std::vector<float> now = ctx.read_vector<float>(st.out, count);
  double from = t0;
  while (from < t1) {
    const double end = static_cast<double>(st.sample + 1) * st.interval;
    const bool closes = t1 >= end - 1e-9 * st.interval;
    const double until = std::min(t1, end);
    for (std::uint32_t k = 0; k < count; ++k) st.partial[k] += double(now[k]) * (until - from);
    if (!closes) break;
    for (std::uint32_t k = 0; k < count; ++k) {
      st.samples.push_back(st.partial[k] / st.interval);
      st.partial[k] = 0;
    }
    ++st.sample;
    from = end;
  }
}

void Solver::Impl::reset_wall_pressure(const std::vector<float>& static_part) {
  RigidStage& r = *rigid;
  if (!r.wall_integral.valid())
    r.wall_integral = floats(std::max(r.capacity, 1u), "boundary wall pressure (master order)");
  std::vector<float> integral(r.nb, 0.0f);
  std::copy(static_part.begin(), static_part.begin() + std::min<std::size_t>(static_part.size(), r.nb), integral.begin());
  if (!integral.empty()) ctx.write_vector(r.wall_integral, integral);
  r.wall_body_time = 0;
}

void Solver::Impl::integrate_wall_pressure(double dt) {
  RigidStage& r = *rigid;
  if (r.nb > 0 && !r.block_table.empty()) {
    r.wall_integrate.args(0u, r.nb, static_cast<float>(dt), r.fx, r.fy, r.fz, r.mnx, r.mny, r.mnz, r.mowner, r.owners,
                          r.wall_integral);
    ctx.launch(r.wall_integrate, r.nb);
  }
  r.wall_static_time += dt;
  r.wall_body_time += dt;
}

std::vector<float> Solver::Impl::take_wall_pressure() {
  RigidStage& r = *rigid;
  std::vector<float> p = r.nb > 0 ? ctx.read_vector<float>(r.wall_integral, r.nb) : std::vector<float>{};
  for (std::uint32_t k = 0; k < r.nb; ++k) {
    const double time = k < r.ns ? r.wall_static_time : r.wall_body_time;
    p[k] = time > 0 ? static_cast<float>(p[k] / time) : 0.0f;
  }
  r.wall_static_time = 0;
  reset_wall_pressure({});
  return p;
}

void Solver::record_wall_pressure() {
  Impl& s = *impl_;
  if (s.steps > 0) fail_run("the wall pressure is recorded from the first step on");
  measure_static_reactions(true);
  RigidStage& r = *s.rigid;
  if (r.wall_pressure) return;
  r.wall_pressure = true;
  r.wall_integrate = r.program.kernel("wall_pressure_integrate");
  r.layout_dirty = true;
  s.boundary_dirty = true;
}

Vec3d Solver::static_impulse() const { return impl_->rigid ? impl_->rigid->static_impulse : Vec3d::Zero(); }

std::vector<Vec3d> Solver::solid_impulses() const {
  if (!impl_->rigid || !impl_->rigid->measure_static) return {};
  return impl_->rigid->solid_impulse;
}

}  // namespace bw::sim

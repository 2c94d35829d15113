// Checkpoints (sim/checkpoint.h; the layout: docs/formats.md, kind "checkpoint").
#include "sim/checkpoint.h"

#include <algorithm>
#include <csignal>
#include <cstring>

#include <fmt/format.h>

#include "common/error.h"
#include "io/h5.h"
#include "sim/solver_impl.h"

namespace bw::sim {
namespace {

constexpr const char* kKind = "checkpoint";

// ---- host arrays as datasets

void write_vec3(h5::Group& g, const char* name, const std::vector<Vec3d>& v) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const Vec3d& p : v) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  g.write<double>(name, flat, {v.size(), 3});
}

std::vector<Vec3d> read_vec3(const h5::Group& g, const char* name) {
  std::size_t rows = 0;
  const std::vector<double> flat = g.read_rows<double>(name, 3, &rows);
  std::vector<Vec3d> v(rows);
  for (std::size_t i = 0; i < rows; ++i) v[i] = Vec3d(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return v;
}

void write_cells(h5::Group& g, const char* name, const std::vector<CellIndex>& v) {
  std::vector<std::int32_t> flat;
  flat.reserve(3 * v.size());
  for (const CellIndex& c : v) flat.insert(flat.end(), {c[0], c[1], c[2]});
  g.write<std::int32_t>(name, flat, {v.size(), 3});
}

std::vector<CellIndex> read_cells(const h5::Group& g, const char* name) {
  std::size_t rows = 0;
  const std::vector<std::int32_t> flat = g.read_rows<std::int32_t>(name, 3, &rows);
  std::vector<CellIndex> v(rows);
  for (std::size_t i = 0; i < rows; ++i) v[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return v;
}

void set_vec3(h5::Group& g, const char* name, const Vec3d& v) {
  const double a[3] = {v.x(), v.y(), v.z()};
  g.set_attr<double>(name, std::span<const double>(a, 3));
}

Vec3d get_vec3(const h5::Group& g, const char* name) {
  const std::vector<double> a = g.attr_array<double>(name);
  if (a.size() != 3) fail_input("{}: attribute {} has {} values, expected 3", g.where(), name, a.size());
  return Vec3d(a[0], a[1], a[2]);
}

template <class T>
std::vector<T> read_exact(const h5::Group& g, const char* name, std::size_t count) {
  std::size_t rows = 0;
  std::vector<T> v = g.read_rows<T>(name, 0, &rows);
  if (rows != count) fail_input("{}: {} values, expected {}", g.where(name), rows, count);
  return v;
}

// Raw bytes of device tables (packed host/device structs: sph_common.h).
void write_bytes(h5::Group& g, const char* name, compute::Context& ctx, const Buffer& b, std::size_t bytes) {
  g.write<std::uint8_t>(name, ctx.read_vector<std::uint8_t>(b, bytes));
}

// ---- FNV-1a over what the setup holds
struct Digest {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    const std::uint64_t n = v.size();
    bytes(&n, sizeof(n));
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
  void value(double d) { bytes(&d, sizeof(d)); }
  void points(const std::vector<Vec3d>& v) {
    for (const Vec3d& p : v) value(p.x()), value(p.y()), value(p.z());
  }
};

// The run file's /frames columns, as float64 (what the run file stores them as).
struct Column {
  const char* name;
  double (*get)(const FrameStats&);
  void (*set)(FrameStats&, double);
};
#define BW_COLUMN(field, type)                                                        \
  Column {                                                                            \
    #field, [](const FrameStats& r) { return static_cast<double>(r.field); },         \
        [](FrameStats& r, double v) { r.field = static_cast<type>(v); }               \
  }
const Column kColumns[] = {
    BW_COLUMN(frame, std::int32_t),          BW_COLUMN(time, double),
    BW_COLUMN(steps, std::int64_t),          BW_COLUMN(dt_min, double),
    BW_COLUMN(dt_max, double),               BW_COLUMN(fluid, std::int64_t),
    BW_COLUMN(boundary, std::int64_t),       BW_COLUMN(removed, std::int64_t),
    BW_COLUMN(density_error_max, double),    BW_COLUMN(density_error_mean, double),
    BW_COLUMN(kinetic_energy, double),       BW_COLUMN(potential_energy, double),
    BW_COLUMN(wall_time, double),            BW_COLUMN(elastic_energy, double),
    BW_COLUMN(speed_max, double),            BW_COLUMN(emitted_energy, double),
    BW_COLUMN(outflow_energy, double),
};
#undef BW_COLUMN

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

}  // namespace

double CheckpointHeader::value(const std::string& name) const {
  for (const auto& [k, v] : run_values)
    if (k == name) return v;
  fail_input("checkpoint: no run value '{}'", name);
}

double CheckpointHeader::value_or(const std::string& name, double fallback) const {
  for (const auto& [k, v] : run_values)
    if (k == name) return v;
  return fallback;
}

std::string device_identity(const compute::DeviceInfo& device) {
  return fmt::format("{}, {} compute units, driver {}", device.label(), device.compute_units, device.driver);
}

std::string setup_fingerprint(const Setup& setup) {
  Digest d;
  const Parameters& p = setup.params;
  for (double v : {p.spacing, p.h, p.mass, p.kernel_mass, p.rho0, p.k, p.c0, p.gamma, p.mu, p.mu_b, p.gamma1, p.gamma2,
                   p.end_time, p.frame_rate, p.dt_min, p.dt_max, p.cfl, p.dt_viscous, p.scene_speed,
                   static_cast<double>(p.max_particles)})
    d.value(v);
  // The density scheme and the wall: a run resumed under another one would not go on.
  // (Digested only where they differ from the first release's, whose checkpoints stay valid.)
  if (p.continuity) d.value(1.0), d.value(p.diffusion);
  if (p.continuity && p.diffusion > 0 && p.diffusion_factor != scene::TimeSettings{}.diffusion_factor)
    d.value(p.diffusion_factor);
  if (p.wall_hydrostatic) d.value(2.0);
  if (p.wall_images) d.value(3.0);
  for (const auto* a : {&setup.fluid, &setup.boundary.particles}) {
    d.vec(a->x), d.vec(a->y), d.vec(a->z), d.vec(a->vx), d.vec(a->vy), d.vec(a->vz);
  }
  d.vec(setup.boundary.nx), d.vec(setup.boundary.ny), d.vec(setup.boundary.nz), d.vec(setup.boundary.solid);
  for (const EmitterLattice& e : setup.emitters) d.points(e.points), d.value(e.speed), d.value(e.start), d.value(e.stop);
  for (const BodySetup& b : setup.bodies) {
    d.points(b.particles), d.points(b.normals), d.vec(b.flatness), d.points(b.voxel_centers), d.vec(b.voxel_anchor);
    d.value(b.mass.mass), d.value(b.frc), d.value(b.density), d.value(b.voxel_size);
  }
  return fmt::format("{:016x}", d.h);
}

// ---- the solver's state

void Solver::save_state(h5::Group& group) {
  Impl& s = *impl_;
  compute::Context& ctx = s.ctx;
  s.ensure_grid();
  s.settle_count();
  group.set_attr<double>("time", s.t);
  group.set_attr<std::int64_t>("steps", s.steps);
  group.set_attr<std::uint32_t>("n", s.n);
  group.set_attr<std::int64_t>("removed", s.removed);
  group.set_attr<double>("emitted_energy", s.emitted_energy);
  group.set_attr<double>("outflow_energy", s.outflow_energy);
  group.set_attr<std::uint32_t>("next_id", s.next_id);
  group.set_attr<std::int32_t>("capped", s.capped ? 1 : 0);
  group.set_attr<std::uint32_t>("boundary", s.nb);

  h5::Group fluid = group.create_group("fluid");
  for (const Impl::StateBuffer& b : s.state_buffers()) {
    if (b.type == Impl::StateType::f32) fluid.write<float>(b.name, ctx.read_vector<float>(*b.buffer, s.n));
    else fluid.write<std::uint32_t>(b.name, ctx.read_vector<std::uint32_t>(*b.buffer, s.n));
  }
  group.write<std::int64_t>("emitter_layers", s.emitter_layers);

  if (s.rigid) {
    RigidStage& r = *s.rigid;
    h5::Group rg = group.create_group("rigid");
    rg.set_attr<std::int32_t>("wet_read", r.wet_read);
    rg.set_attr<std::int32_t>("touching_now", r.touching_now ? 1 : 0);
    rg.set_attr<std::int32_t>("measure_static", r.measure_static ? 1 : 0);
    rg.set_attr<std::int32_t>("static_psi_dirty", r.static_psi_dirty ? 1 : 0);
    set_vec3(rg, "static_impulse", r.static_impulse);
    write_vec3(rg, "solid_impulse", r.solid_impulse);
    rg.write<float>("static_psi", r.spsi);
    // Contact memory: which boundary particles had fluid near them at the last step
    // (master order), and the owners' contact masses as the device has them.
    rg.write<std::uint32_t>("wet", ctx.read_vector<std::uint32_t>(r.wet[static_cast<std::size_t>(r.wet_read)], r.nb));
    write_bytes(rg, "owners", ctx, r.owners, (r.body_owner0 + r.bodies.size()) * sizeof(OwnerParams));
    h5::Group bodies = rg.create_group("bodies");
    for (std::size_t k = 0; k < r.bodies.size(); ++k) {
      const BodyEntry& e = r.bodies[k];
      h5::Group b = bodies.create_group(fmt::format("{:06d}", k));
      b.set_attr("name", e.info.name);
      b.set_attr<std::int32_t>("solid", e.info.solid);
      b.set_attr<std::int32_t>("parent", e.info.parent);
      b.set_attr<std::int32_t>("voxels", e.info.voxels);
      b.set_attr<double>("created_time", e.info.created_time);
      b.set_attr<std::int32_t>("fixed", e.info.fixed ? 1 : 0);
      b.set_attr<std::int32_t>("active", e.info.active ? 1 : 0);
      b.set_attr<std::int32_t>("psi_dirty", e.psi_dirty ? 1 : 0);
      b.set_attr<double>("spacing", e.spacing);
      b.set_attr<double>("friction", e.friction);
      b.set_attr<double>("restitution", e.restitution);
      b.set_attr<double>("radius", e.radius);
      b.set_attr<double>("contact_weight", e.contact_weight);
      set_vec3(b, "force", e.force);
      set_vec3(b, "torque", e.torque);
      const rigid::MassProperties& m = e.body.mass();
      b.set_attr<double>("mass", m.mass);
      set_vec3(b, "center", m.center);
      b.set_attr<double>("inertia", std::span<const double>(m.inertia.data(), 9));
      const rigid::BodyState& st = e.body.state();
      set_vec3(b, "position", st.position);
      const double q[4] = {st.orientation.w(), st.orientation.x(), st.orientation.y(), st.orientation.z()};
      b.set_attr<double>("orientation", std::span<const double>(q, 4));
      set_vec3(b, "linear_velocity", st.linear_velocity);
      set_vec3(b, "angular_velocity", st.angular_velocity);
      write_vec3(b, "reference", e.reference);
      write_vec3(b, "reference_normals", e.reference_normals);
      b.write<float>("flatness", e.flatness);
      b.write<float>("psi", e.psi);
      // A solid moved as told: its keys (each part it has) and where its pivot is.
      for (const auto& [part, keys] : {std::pair{"motion", &e.motion.translation}, std::pair{"turn", &e.motion.turn}})
        if (!keys->empty()) {
          b.set_attr<double>(fmt::format("{}_times", part), std::span<const double>(keys->times()));
          write_vec3(b, fmt::format("{}_velocities", part).c_str(), keys->velocities());
        }
      if (e.moving()) set_vec3(b, "pivot", e.motion.pivot);
    }
  }

  if (s.sensors) {
    // The sample in progress and those before it.
    const SensorStage& st = *s.sensors;
    h5::Group sg = group.create_group("sensors");
    sg.set_attr<std::int64_t>("sample", st.sample);
    sg.set_attr<double>("interval", st.interval);
    sg.write<double>("partial", st.partial);
    sg.write<double>("samples", st.samples);
  }

  if (s.fracture) {
    FractureStage& fs = *s.fracture;
    h5::Group fg = group.create_group("fracture");
    fg.set_attr<std::int64_t>("partition_close", fs.partition_close);
    // The load memory of every slot (and what it stood for at the last step).
    h5::Group load = fg.create_group("load");
    for (auto [name, buffer] : {std::pair{"dvx", &fs.dvx}, {"dvy", &fs.dvy}, {"dvz", &fs.dvz}, {"energy", &fs.energy},
                                {"strength", &fs.strength}})
      load.write<float>(name, fs.slots ? ctx.read_vector<float>(*buffer, fs.slots) : std::vector<float>{});
    h5::Group bodies = fg.create_group("bodies");
    for (std::size_t k = 0; k < fs.bodies.size(); ++k) {
      const BreakableBody& tb = fs.bodies[k];
      h5::Group b = bodies.create_group(fmt::format("{:06d}", k));
      b.set_attr<std::int32_t>("body", tb.body);
      b.set_attr<double>("frc", tb.frc);
      b.set_attr<double>("density", tb.density);
      b.set_attr<double>("voxel_size", tb.voxel_size);
      write_cells(b, "cells", tb.piece.cells);
      write_vec3(b, "centers", tb.piece.centers);
      b.write<std::uint8_t>("anchor", tb.piece.anchor);
      write_vec3(b, "particles", tb.piece.particles);
      write_vec3(b, "normals", tb.piece.normals);
      b.write<double>("flatness", tb.piece.flatness);
      write_cells(b, "particle_cells", tb.piece.particle_cells);
      b.write<float>("binding", tb.binding);
    }
    h5::Group events = fg.create_group("events");
    for (std::size_t k = 0; k < fs.events.size(); ++k) {
      const FractureEvent& ev = fs.events[k];
      h5::Group e = events.create_group(fmt::format("{:06d}", k));
      e.set_attr<double>("time", ev.time);
      e.set_attr<std::int32_t>("parent", ev.parent);
      write_vec3(e, "seeds", ev.seeds);
      e.write<std::int32_t>("child_body", ev.child_body);
      e.write<std::int32_t>("child_seed", ev.child_seed);
      e.write<std::int32_t>("child_component", ev.child_component);
    }
  }
}

void Solver::load_state(const h5::Group& group) {
  Impl& s = *impl_;
  compute::Context& ctx = s.ctx;
  const std::uint32_t n = group.attr<std::uint32_t>("n");
  if (n > s.capacity)
    fail_input("{}: {} fluid particles, more than this run's max_particles ({})", group.where(), n, s.capacity);
  s.t = group.attr<double>("time");
  s.steps = group.attr<std::int64_t>("steps");
  s.n = n;
  s.removed = group.attr<std::int64_t>("removed");
  s.emitted_energy = group.attr<double>("emitted_energy");
  s.outflow_energy = group.attr<double>("outflow_energy");
  s.next_id = group.attr<std::uint32_t>("next_id");
  s.capped = group.attr<std::int32_t>("capped") != 0;
  s.wall_step_pending = false;  // the densities it carries have the step
  const h5::Group fluid = group.open_group("fluid");
  for (const Impl::StateBuffer& b : s.state_buffers()) {
    if (b.type == Impl::StateType::f32) ctx.write_vector(*b.buffer, read_exact<float>(fluid, b.name, n));
    else ctx.write_vector(*b.buffer, read_exact<std::uint32_t>(fluid, b.name, n));
  }
  s.emitter_layers = read_exact<std::int64_t>(group, "emitter_layers", s.emitters.size());
  if (group.has("rigid") != static_cast<bool>(s.rigid) && !group.has("rigid"))
    fail_input("{}: has no rigid bodies, but this run's scene has", group.where());
  if (group.has("fracture") != static_cast<bool>(s.fracture))
    fail_input("{}: {} a fracture stage, this run's scene {}", group.where(), group.has("fracture") ? "has" : "has no",
               s.fracture ? "has one" : "has none");

  if (group.has("rigid")) {
    s.enable_bodies();
    RigidStage& r = *s.rigid;
    const h5::Group rg = group.open_group("rigid");
    r.measure_static = rg.attr<std::int32_t>("measure_static") != 0;
    r.static_impulse = get_vec3(rg, "static_impulse");
    r.solid_impulse = read_vec3(rg, "solid_impulse");
    r.spsi = read_exact<float>(rg, "static_psi", r.ns);
    r.static_psi_dirty = rg.attr<std::int32_t>("static_psi_dirty") != 0;
    const h5::Group bodies = rg.open_group("bodies");
    r.bodies.clear();
    for (const std::string& name : bodies.children()) {
      const h5::Group b = bodies.open_group(name);
      rigid::MassProperties m;
      m.mass = b.attr<double>("mass");
      m.center = get_vec3(b, "center");
      const std::vector<double> inertia = b.attr_array<double>("inertia");
      if (inertia.size() != 9) fail_input("{}: inertia has {} values, expected 9", b.where(), inertia.size());
      std::copy(inertia.begin(), inertia.end(), m.inertia.data());
      BodyEntry e;
      e.body = rigid::Body(m);
      rigid::BodyState& st = e.body.state();
      st.position = get_vec3(b, "position");
      const std::vector<double> q = b.attr_array<double>("orientation");
      if (q.size() != 4) fail_input("{}: orientation has {} values, expected 4", b.where(), q.size());
      st.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      st.linear_velocity = get_vec3(b, "linear_velocity");
      st.angular_velocity = get_vec3(b, "angular_velocity");
      e.info.name = b.attr_string("name");
      e.info.solid = b.attr<std::int32_t>("solid");
      e.info.parent = b.attr<std::int32_t>("parent");
      e.info.voxels = b.attr<std::int32_t>("voxels");
      e.info.created_time = b.attr<double>("created_time");
      e.info.fixed = b.attr<std::int32_t>("fixed") != 0;
      e.info.active = b.attr<std::int32_t>("active") != 0;
      e.psi_dirty = b.attr<std::int32_t>("psi_dirty") != 0;
      e.spacing = b.attr<double>("spacing");
      e.friction = b.attr<double>("friction");
      e.restitution = b.attr<double>("restitution");
      e.radius = b.attr<double>("radius");
      e.contact_weight = b.attr<double>("contact_weight");
      e.force = get_vec3(b, "force");
      e.torque = get_vec3(b, "torque");
      e.reference = read_vec3(b, "reference");
      e.reference_normals = read_vec3(b, "reference_normals");
      e.flatness = read_exact<float>(b, "flatness", e.reference.size());
      e.psi = read_exact<float>(b, "psi", e.reference.size());
      for (const auto& [part, keys] : {std::pair{"motion", &e.motion.translation}, std::pair{"turn", &e.motion.turn}}) {
        const std::string times_name = fmt::format("{}_times", part);
        if (!b.has_attr(times_name)) continue;
        std::vector<double> times = b.attr_array<double>(times_name);
        std::vector<Vec3d> velocities = read_vec3(b, fmt::format("{}_velocities", part).c_str());
        if (velocities.size() != times.size() || !std::is_sorted(times.begin(), times.end()))
          fail_input("{}: {}: {} times (in order: {}) and {} velocities", b.where(), part, times.size(),
                     std::is_sorted(times.begin(), times.end()) ? "yes" : "no", velocities.size());
        *keys = rigid::Motion(std::move(times), std::move(velocities));
      }
      if (e.moving()) e.motion.pivot = get_vec3(b, "pivot");
      if (e.reference_normals.size() != e.reference.size())
        fail_input("{}: {} particles but {} normals", b.where(), e.reference.size(), e.reference_normals.size());
      e.info.particles = e.reference.size();
      r.bodies.push_back(std::move(e));
    }
    // The master order, poses, sort and cell starts of the saved bodies, as the
    // saved run made them after its last step; then the memory of that step, which
    // a new layout would clear.
    r.layout_dirty = true;
    s.boundary_dirty = true;
    s.update_boundary();
    r.wet_read = rg.attr<std::int32_t>("wet_read") & 1;
    ctx.write_vector(r.wet[static_cast<std::size_t>(r.wet_read)], read_exact<std::uint32_t>(rg, "wet", r.nb));
    ctx.write_vector(r.owners, read_exact<std::uint8_t>(rg, "owners", (r.body_owner0 + r.bodies.size()) * sizeof(OwnerParams)));
    r.touching_now = rg.attr<std::int32_t>("touching_now") != 0;
    for (std::size_t k = 0; k < r.bodies.size(); ++k)
      r.bodies[k].contact_weight = bodies.open_group(fmt::format("{:06d}", k)).attr<double>("contact_weight");
  }
  if (group.attr<std::uint32_t>("boundary") != s.nb)
    fail_input("{}: {} boundary particles, this run has {}", group.where(), group.attr<std::uint32_t>("boundary"), s.nb);

  if (group.has("sensors") != static_cast<bool>(s.sensors))
    fail_input("{}: {} sensors, this run's scene {}", group.where(), group.has("sensors") ? "has" : "has no",
               s.sensors ? "has some" : "has none");
  if (s.sensors) {
    SensorStage& st = *s.sensors;
    const h5::Group sg = group.open_group("sensors");
    if (sg.attr<double>("interval") != st.interval)
      fail_input("{}: samples of {} s, this run's of {} s", sg.where(), sg.attr<double>("interval"), st.interval);
    st.sample = sg.attr<std::int64_t>("sample");
    st.partial = read_exact<double>(sg, "partial", st.sensors.size());
    st.samples = sg.read<double>("samples");
    if (st.samples.size() != static_cast<std::size_t>(st.sample) * st.sensors.size())
      fail_input("{}: {} values for {} samples of {} sensors", sg.where("samples"), st.samples.size(), st.sample,
                 st.sensors.size());
  }

  if (s.fracture) {
    FractureStage& fs = *s.fracture;
    const h5::Group fg = group.open_group("fracture");
    fs.partition_close = fg.attr<std::int64_t>("partition_close");
    fs.bodies.clear();
    const h5::Group bodies = fg.open_group("bodies");
    for (const std::string& name : bodies.children()) {
      const h5::Group b = bodies.open_group(name);
      BreakableBody tb;
      tb.body = b.attr<std::int32_t>("body");
      tb.frc = b.attr<double>("frc");
      tb.density = b.attr<double>("density");
      tb.voxel_size = b.attr<double>("voxel_size");
      tb.piece.cells = read_cells(b, "cells");
      tb.piece.centers = read_vec3(b, "centers");
      tb.piece.anchor = b.read<std::uint8_t>("anchor");
      tb.piece.particles = read_vec3(b, "particles");
      tb.piece.normals = read_vec3(b, "normals");
      tb.piece.flatness = b.read<double>("flatness");
      tb.piece.particle_cells = read_cells(b, "particle_cells");
      tb.binding = read_exact<float>(b, "binding", tb.piece.particles.size());
      if (tb.body < 0 || tb.body >= body_count()) fail_input("{}: no body {}", b.where(), tb.body);
      fs.bodies.push_back(std::move(tb));
    }
    fs.events.clear();
    const h5::Group events = fg.open_group("events");
    for (const std::string& name : events.children()) {
      const h5::Group e = events.open_group(name);
      FractureEvent ev;
      ev.time = e.attr<double>("time");
      ev.parent = e.attr<std::int32_t>("parent");
      ev.seeds = read_vec3(e, "seeds");
      ev.child_body = e.read<std::int32_t>("child_body");
      ev.child_seed = e.read<std::int32_t>("child_seed");
      ev.child_component = e.read<std::int32_t>("child_component");
      fs.events.push_back(std::move(ev));
    }
    fs.times = {};
    fs.times.events = static_cast<int>(fs.events.size());
    std::uint32_t slots = 0;
    for (const BreakableBody& tb : fs.bodies) slots += static_cast<std::uint32_t>(tb.piece.particles.size());
    const h5::Group load = fg.open_group("load");
    const std::vector<float> dvx = read_exact<float>(load, "dvx", slots), dvy = read_exact<float>(load, "dvy", slots),
                             dvz = read_exact<float>(load, "dvz", slots);
    s.fracture_layout(dvx, dvy, dvz);
    ctx.write_vector(fs.energy, read_exact<float>(load, "energy", slots));
    ctx.write_vector(fs.strength, read_exact<float>(load, "strength", slots));
    fs.map_host.clear();
    fs.uploaded_body = -1;
  }
  // The fluid is sorted again before the next step: the saved order is already the
  // grid's, so the stable sort keeps it, and the densities come out as saved.
  s.grid_valid = false;
  ctx.finish();
}

// ---- the file

void write_checkpoint(const std::string& path, const CheckpointHeader& header, Solver& solver) {
  h5::File file = h5::File::create(path, kKind);
  h5::Group& root = file.root();
  root.set_attr<std::int32_t>("checkpoint_version", header.version);
  root.set_attr("tool", header.tool);
  root.set_attr("device", header.device);
  root.set_attr("scene", header.scene_text);
  root.set_attr("scene_path", header.scene_path);
  root.set_attr("setup_fingerprint", header.fingerprint);
  root.set_attr<std::int32_t>("frame", header.frame);
  root.set_attr<double>("time", header.time);
  root.set_attr<double>("end_time", header.end_time);
  root.set_attr<std::int32_t>("checkpoint_every", header.checkpoint_every);
  h5::Group run = root.create_group("run");
  for (const auto& [name, value] : header.run_values) run.set_attr<double>(name, value);
  h5::Group rows = run.create_group("rows");
  for (const Column& c : kColumns) {
    std::vector<double> v;
    for (const FrameStats& r : header.rows) v.push_back(c.get(r));
    rows.write<double>(c.name, v);
  }
  std::vector<Vec3d> loads;  // the run file's /loads rows, frame after frame
  for (const auto& row : header.loads) loads.insert(loads.end(), row.begin(), row.end());
  write_vec3(run, "loads", loads);
  run.set_attr<std::int32_t>("load_solids", header.loads.empty() ? 0 : static_cast<std::int32_t>(header.loads[0].size()));
  h5::Group state = root.create_group("solver");
  solver.save_state(state);
  file.commit();
}

CheckpointHeader read_checkpoint_header(const std::string& path) {
  const h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  CheckpointHeader h;
  h.version = root.attr<std::int32_t>("checkpoint_version");
  if (h.version != kCheckpointVersion)
    fail_input("{}: checkpoint version {}, this bw-sim reads version {} only; start the run again", path, h.version,
               kCheckpointVersion);
  h.tool = root.attr_string("tool");
  h.device = root.attr_string("device");
  h.scene_text = root.attr_string("scene");
  h.scene_path = root.attr_string("scene_path");
  h.fingerprint = root.attr_string("setup_fingerprint");
  h.frame = root.attr<std::int32_t>("frame");
  h.time = root.attr<double>("time");
  h.end_time = root.attr<double>("end_time");
  h.checkpoint_every = root.attr<std::int32_t>("checkpoint_every");
  const h5::Group run = root.open_group("run");
  for (const std::string& name : run.attr_names()) h.run_values.emplace_back(name, run.attr<double>(name));
  const h5::Group rows = run.open_group("rows");
  h.rows.resize(static_cast<std::size_t>(h.frame) + 1);
  for (const Column& c : kColumns) {
    const std::vector<double> v = read_exact<double>(rows, c.name, h.rows.size());
    for (std::size_t i = 0; i < v.size(); ++i) c.set(h.rows[i], v[i]);
  }
  const std::size_t solids = static_cast<std::size_t>(run.attr<std::int32_t>("load_solids"));
  const std::vector<Vec3d> loads = read_vec3(run, "loads");
  if (solids > 0) {
    if (loads.size() != solids * h.rows.size())
      fail_input("{}: {} load rows, expected {} x {}", run.where("loads"), loads.size(), h.rows.size(), solids);
    for (std::size_t f = 0; f < h.rows.size(); ++f)
      h.loads.emplace_back(loads.begin() + static_cast<std::ptrdiff_t>(f * solids),
                           loads.begin() + static_cast<std::ptrdiff_t>((f + 1) * solids));
  }
  return h;
}

void read_checkpoint_state(const std::string& path, Solver& solver) {
  const h5::File file = h5::File::open(path, kKind);
  solver.load_state(file.root().open_group("solver"));
}

void install_stop_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second signal takes the default action: the process ends at once
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

int stop_signal() { return g_stop_signal; }

}  // namespace bw::sim

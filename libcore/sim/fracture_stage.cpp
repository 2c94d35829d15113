// The fracture stage of the solver (sim/fracture_stage.h, docs/scene.md "Fracture").
#include "sim/fracture_stage.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "compute/kernels.h"
#include "sim/solver_impl.h"

namespace bw::sim {
namespace {

// Seeds of one event are at least this many voxels apart (method.md 3, "Ours": thin
// the seeds by a minimum distance), so that a broad impact gives fragments of a few
// voxels, not single voxels.
constexpr double kMinSeedDistance = 2.0;
// No fragment has fewer voxels than this (a 2 x 2 x 2 block): a body of a handful of
// boundary particles weighs each of them as a whole wall (Akinci's Psi_b of a lone
// particle is the volume of all its missing neighbours) and blasts the fluid away.
constexpr std::size_t kMinFragmentVoxels = 8;

// A seed sits near the centre of its voxel, off it by a few hundredths of a voxel
// that differ from seed to seed (fixed fractions, no randomness): seeds on the voxel
// lattice would put Voronoi faces exactly through voxel centres (ties) and along the
// faces of earlier cuts, which the exact cut of bw-voronoi replay cannot take.
Vec3d seed_offset(std::size_t k) {
  const double phi[3] = {0.6180339887498949, 0.4142135623730950, 0.7320508075688772};
  Vec3d o;
  for (int a = 0; a < 3; ++a) {
    const double f = static_cast<double>(k + 1) * phi[a];
    o[a] = 0.02 + 0.05 * (f - std::floor(f));
  }
  return o;
}

}  // namespace

void Solver::Impl::enable_fracture(const Setup& setup, const std::vector<int>& body_of_setup) {
  fracture = std::make_unique<FractureStage>();
  FractureStage& fs = *fracture;
  fs.settings = setup.fracture;
  fs.program = ctx.build("fracture.cl", compute::embedded_kernels(), compute::kernel_build_options(ctx.device()));
  fs.load = fs.program.kernel("fracture_load");
  for (std::size_t k = 0; k < setup.bodies.size(); ++k) {
    const BodySetup& b = setup.bodies[k];
    if (!b.breakable) continue;
    BreakableBody tb;
    tb.body = body_of_setup[k];
    tb.frc = b.frc;
    tb.density = b.density;
    tb.voxel_size = b.voxel_size;
    tb.piece.cells = b.voxel_cells;
    tb.piece.centers = b.voxel_centers;
    tb.piece.anchor = b.voxel_anchor;
    tb.piece.particles = b.particles;
    tb.piece.normals = b.normals;
    tb.piece.flatness = b.flatness;
    tb.piece.particle_cells = b.particle_cells;
    fs.bodies.push_back(std::move(tb));
  }
  for (BreakableBody& tb : fs.bodies)
    tb.binding = binding_energies(tb.frc, fracture::bond_counts(tb.piece.particles, tb.voxel_size, params.h));
  fs.layout_dirty = true;
}

// E_r,i = E_sigma x (its kernel-weighted bond count), E_sigma = frc x energy_scale x
// spacing (J).
std::vector<float> Solver::Impl::binding_energies(double frc, const std::vector<double>& bonds) const {
  const double sigma = frc * fracture->settings.energy_scale * params.spacing;
  std::vector<float> out(bonds.size());
  for (std::size_t i = 0; i < bonds.size(); ++i) out[i] = static_cast<float>(sigma * bonds[i]);
  return out;
}

// The slots of the active breakable bodies: binding energies (when they changed) and
// the master index of each slot (every step: the master order moves when bodies change).
void Solver::Impl::fracture_layout(const std::vector<float>& dx, const std::vector<float>& dy,
                                   const std::vector<float>& dz) {
  FractureStage& fs = *fracture;
  std::uint32_t slots = 0;
  for (BreakableBody& tb : fs.bodies) {
    tb.slot = slots;
    slots += static_cast<std::uint32_t>(tb.piece.particles.size());
  }
  fs.slots = slots;
  if (slots > fs.capacity) {
    const std::size_t cap = std::max<std::size_t>(slots + slots / 4, 64);
    fs.capacity = static_cast<std::uint32_t>(cap);
    fs.map = uints(cap, "fracture slots");
    fs.binding = floats(cap, "fracture binding energy");
    fs.dvx = floats(cap, "fracture load x");
    fs.dvy = floats(cap, "fracture load y");
    fs.dvz = floats(cap, "fracture load z");
    fs.energy = floats(cap, "fracture energy");
    fs.strength = floats(cap, "fracture strength");
  }
  std::vector<float> binding;
  binding.reserve(slots);
  for (const BreakableBody& tb : fs.bodies) binding.insert(binding.end(), tb.binding.begin(), tb.binding.end());
  ctx.write_vector(fs.binding, binding);
  std::vector<float> zero(slots, 0.0f);
  ctx.write_vector(fs.dvx, dx.size() == slots ? dx : zero);
  ctx.write_vector(fs.dvy, dy.size() == slots ? dy : zero);
  ctx.write_vector(fs.dvz, dz.size() == slots ? dz : zero);
  fs.map_host.clear();
  fs.layout_dirty = false;
}

void Solver::Impl::fracture_load(double dt) {
  FractureStage& fs = *fracture;
  if (fs.layout_dirty) fracture_layout({}, {}, {});
  if (fs.slots == 0 || n == 0) return;
  std::vector<std::uint32_t> map;
  map.reserve(fs.slots);
  for (const BreakableBody& tb : fs.bodies) {
    const std::uint32_t first = body_entry(tb.body).first;
    for (std::uint32_t k = 0; k < tb.piece.particles.size(); ++k) map.push_back(first + k);
  }
  if (map != fs.map_host) {
    ctx.write_vector(fs.map, map);
    fs.map_host = std::move(map);
  }
  const float decay = static_cast<float>(std::exp(-dt / fs.settings.window));
  const int f = front;
  fs.load.args(P, fs.slots, static_cast<float>(dt), decay, fs.map, rigid->rank, start, x[f], y[f], z[f], rho, pterm,
               bx, by, bz, bpsi, fs.binding, fs.dvx, fs.dvy, fs.dvz, fs.energy, fs.strength);
  ctx.launch(fs.load, fs.slots);
}

// After a step: bodies with two or more particles at or above their binding energy
// break (within the scene's max_chunks).
void Solver::Impl::fracture_test() {
  FractureStage& fs = *fracture;
  if (fs.slots == 0 || n == 0 || fs.layout_dirty) return;
  const std::vector<float> strength = ctx.read_vector<float>(fs.strength, fs.slots);
  std::vector<float> energy, dx, dy, dz;
  bool changed = false;
  std::vector<BreakableBody> next;
  auto active = static_cast<std::int64_t>(fs.bodies.size());
  for (std::size_t b = 0; b < fs.bodies.size(); ++b) {
    BreakableBody& tb = fs.bodies[b];
    const std::size_t np = tb.piece.particles.size();
    std::vector<fracture::Candidate> candidates;
    for (std::size_t i = 0; i < np; ++i)
      if (strength[tb.slot + i] >= 1.0f)
        candidates.push_back({static_cast<std::int32_t>(i), static_cast<double>(strength[tb.slot + i])});
    const std::int64_t budget = fs.settings.max_chunks - active + 1;
    std::vector<fracture::Fragment> fragments;
    std::vector<std::int32_t> seed_particles;
    std::vector<Vec3d> seeds;
    if (candidates.size() >= 2 && budget >= 2 && tb.piece.size() >= 2 * kMinFragmentVoxels) {
      seed_particles = fracture::select_seeds(candidates, tb.piece.particles, kMinSeedDistance * tb.voxel_size,
                                              static_cast<std::size_t>(budget));
      // Seeds at the centres of the seed particles' voxels (inside the solid, where the
      // exact cut of bw-voronoi replay finds them too); one per voxel.
      const std::vector<std::int32_t> pv = fracture::particle_voxels(tb.piece);
      std::vector<std::int32_t> used, kept;
      for (const std::int32_t p : seed_particles) {
        const std::int32_t v = pv[static_cast<std::size_t>(p)];
        if (v < 0 || std::find(used.begin(), used.end(), v) != used.end()) continue;
        used.push_back(v);
        kept.push_back(p);
        seeds.push_back(tb.piece.centers[static_cast<std::size_t>(v)] + tb.voxel_size * seed_offset(seeds.size()));
      }
      seed_particles = kept;
      // Seeds go until the fragments fit the cap (the weakest seed) and none is
      // smaller than kMinFragmentVoxels (the seed of the smallest).
      while (seeds.size() >= 2) {
        fragments = fracture::split(tb.piece, seeds, tb.voxel_size, tb.density);
        std::size_t drop = seeds.size() - 1, smallest = kMinFragmentVoxels;
        for (const fracture::Fragment& fr : fragments)
          if (fr.piece.size() < smallest) smallest = fr.piece.size(), drop = static_cast<std::size_t>(fr.seed);
        if (static_cast<std::int64_t>(fragments.size()) <= budget && fragments.size() >= 2 &&
            smallest == kMinFragmentVoxels)
          break;
        fragments.clear();
        seeds.erase(seeds.begin() + static_cast<std::ptrdiff_t>(drop));
        seed_particles.erase(seed_particles.begin() + static_cast<std::ptrdiff_t>(drop));
      }
    }
    if (fragments.empty()) {
      next.push_back(std::move(tb));
      continue;
    }
    if (!changed) {
      energy = ctx.read_vector<float>(fs.energy, fs.slots);
      dx = ctx.read_vector<float>(fs.dvx, fs.slots);
      dy = ctx.read_vector<float>(fs.dvy, fs.slots);
      dz = ctx.read_vector<float>(fs.dvz, fs.slots);
      changed = true;
    }
    // The parent's state now (add_body may move the body table).
    const BodyEntry& pe = body_entry(tb.body);
    const rigid::Body parent = pe.body;
    const bool parent_fixed = pe.info.fixed;
    const std::string parent_name = pe.info.name;
    const std::vector<float> parent_psi = pe.psi_dirty ? std::vector<float>{} : pe.psi;
    const std::int32_t solid = pe.info.solid;
    const double spacing = pe.spacing, friction = pe.friction, restitution = pe.restitution;
    FractureEvent event;
    event.time = this->t;
    event.parent = tb.body;
    event.seeds = seeds;
    const std::vector<std::vector<double>> bonds_of = fracture::fragment_bond_counts(fragments, tb.voxel_size, params.h);
    std::vector<std::size_t> seed_voxels(seeds.size(), 0);
    for (const fracture::Fragment& fr : fragments) seed_voxels[static_cast<std::size_t>(fr.seed)] += fr.piece.size();
    for (std::size_t c = 0; c < fragments.size(); ++c) {
      fracture::Fragment& fr = fragments[c];
      BodySpec spec;
      spec.name = fmt::format("{}.{}", parent_name, c);
      spec.solid = solid;
      spec.parent = tb.body;
      spec.mass = fr.mass;
      spec.voxels = static_cast<std::int32_t>(fr.piece.size());
      spec.particles = fr.piece.particles;
      spec.normals = fr.piece.normals;
      spec.flatness = fr.piece.flatness;
      spec.spacing = spacing;
      spec.friction = friction;
      spec.restitution = restitution;
      spec.fixed = (parent_fixed && fr.anchored);
      rigid::BodyState st = parent.state();
      st.position = parent.to_world(fr.mass.center);
      // Fixed, or moving with the parent plus, along the load, the energy its seed
      // received beyond its binding energy (shared by the seed's fragments by voxels),
      // but never faster than the scene's largest flow speed: the load energy is
      // reckoned from the fluid's velocity changes and is not taken from the fluid, and
      // water cannot throw a piece faster than it flows itself.
      if (spec.fixed) {
        st.linear_velocity = st.angular_velocity = Vec3d::Zero();
      } else {
        st.linear_velocity = parent.velocity_at(st.position);
        const std::size_t sp = tb.slot + static_cast<std::size_t>(seed_particles[static_cast<std::size_t>(fr.seed)]);
        const double left = std::max(0.0, double(energy[sp]) - double(tb.binding[sp - tb.slot]));
        const Vec3d load = -Vec3d(dx[sp], dy[sp], dz[sp]);
        const double share = left * double(fr.piece.size()) / double(seed_voxels[static_cast<std::size_t>(fr.seed)]);
        if (load.norm() > 0 && share > 0)
          st.linear_velocity += std::min(std::sqrt(2 * share / fr.mass.mass), params.scene_speed) * load.normalized();
      }
      spec.state = st;
      const int child = add_body(spec);
      // Psi_b handed over (method.md 4): the parent's particles keep theirs, so that the
      // fluid at the surface feels the same wall as before the crack; only the crack
      // faces' particles get their own, from their fragment's neighbours.
      const std::vector<double>& bonds = bonds_of[c];
      BodyEntry& ce = body_entry(child);
      const double volume = tb.voxel_size * tb.voxel_size * tb.voxel_size;
      for (std::size_t k = 0; k < ce.psi.size(); ++k) {
        const std::int32_t src = fr.source[k];
        ce.psi[k] = src >= 0 && !parent_psi.empty() ? parent_psi[static_cast<std::size_t>(src)]
                                                   : static_cast<float>(params.rho0 * volume / bonds[k]);
      }
      ce.psi_dirty = false;
      event.child_body.push_back(child);
      event.child_seed.push_back(fr.seed);
      event.child_component.push_back(fr.component);
      BreakableBody ct;
      ct.body = child;
      ct.frc = tb.frc;
      ct.density = tb.density;
      ct.voxel_size = tb.voxel_size;
      ct.piece = std::move(fr.piece);
      ct.binding = binding_energies(ct.frc, bonds);
      next.push_back(std::move(ct));
    }
    retire_body(tb.body);
    active += static_cast<std::int64_t>(fragments.size()) - 1;
    fs.events.push_back(std::move(event));
  }
  if (!changed) {
    fs.bodies = std::move(next);  // the same bodies, in the same slots
    return;
  }
  // The load so far stays with the bodies that did not break; fragments start afresh.
  std::map<int, const BreakableBody*> old;
  for (const BreakableBody& tb : fs.bodies) old[tb.body] = &tb;
  std::vector<float> nx, ny, nz;
  for (const BreakableBody& tb : next) {
    const auto it = old.find(tb.body);
    for (std::size_t i = 0; i < tb.piece.particles.size(); ++i) {
      const bool kept = it != old.end();
      const std::size_t s = kept ? it->second->slot + i : 0;
      nx.push_back(kept ? dx[s] : 0.0f);
      ny.push_back(kept ? dy[s] : 0.0f);
      nz.push_back(kept ? dz[s] : 0.0f);
    }
  }
  fs.bodies = std::move(next);
  fracture_layout(nx, ny, nz);
}

// A body that fracture replaced by its fragments: its row stays, its particles go.
void Solver::Impl::retire_body(int body) {
  BodyEntry& e = body_entry(body);
  e.info.active = false;
  e.info.particles = 0;
  e.reference.clear();
  e.reference_normals.clear();
  e.flatness.clear();
  e.psi.clear();
  rigid->layout_dirty = true;
  boundary_dirty = true;
}

std::uint64_t Solver::Impl::fracture_bytes() const {
  if (!fracture) return 0;
  const FractureStage& fs = *fracture;
  std::uint64_t total = 0;
  for (const Buffer* b : {&fs.map, &fs.binding, &fs.dvx, &fs.dvy, &fs.dvz, &fs.energy, &fs.strength})
    if (b->valid()) total += b->bytes();
  return total;
}

const std::vector<FractureEvent>& Solver::fracture_events() const {
  static const std::vector<FractureEvent> none;
  return impl_->fracture ? impl_->fracture->events : none;
}

}  // namespace bw::sim

// The fracture stage of the solver (sim/fracture_stage.h, docs/scene.md "Fracture").
#include "sim/fracture_stage.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <functional>
#include <map>
#include <numeric>

#include "common/terminal.h"
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
// voxel_seeds' flag for a voxel whose two nearest seeds float cannot tell apart, and
// its bricks: cubes of kBrickEdge cells, one work-group of kBrickVoxels each.
constexpr std::uint32_t kSeedClose = 0x80000000u;
constexpr std::int32_t kBrickEdge = 4;
constexpr std::size_t kBrickVoxels = 64;

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
  fs.voxel_seeds = fs.program.kernel("voxel_seeds");
  for (std::size_t k = 0; k < setup.bodies.size(); ++k) {
    const BodySetup& b = setup.bodies[k];
    if (!b.breakable) continue;
    BreakableBody tb;
    tb.body = body_of_setup[k];
    tb.frc = b.frc;
    tb.density = b.density;
    tb.voxel_size = b.voxel_size;
    tb.piece = breakable_piece(b);
    fs.bodies.push_back(std::move(tb));
  }
  for (BreakableBody& tb : fs.bodies)
    tb.binding = binding_energies(tb.frc, fracture::bond_counts(tb.piece.particles, tb.voxel_size, params.h));
  fs.layout_dirty = true;
  // The partition's kernel once on 1728 voxels, one per brick, now: a device that
  // compiles a kernel at its first launches (PoCL: about 0.3 s, for small grids and
  // again for large ones) then does so before the run, not at the first fracture.
  if (!fs.bodies.empty()) {
    std::size_t largest = 0;
    for (const BreakableBody& tb : fs.bodies) largest = std::max(largest, tb.piece.size());
    reserve_partition(largest, largest);
    BreakableBody probe;
    probe.body = -2;
    probe.voxel_size = 1;
    for (std::int32_t k = 0; k < 12; ++k)
      for (std::int32_t j = 0; j < 12; ++j)
        for (std::int32_t i = 0; i < 12; ++i) {
          probe.piece.cells.push_back({kBrickEdge * i, kBrickEdge * j, kBrickEdge * k});
          probe.piece.centers.push_back(kBrickEdge * Vec3d(i, j, k));
        }
    partition(probe, {Vec3d::Zero(), Vec3d::Constant(44)});
    fs.uploaded_body = -1;
    fs.times = {};
    fs.partition_close = 0;
  }
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
               bx, by, bz, bpsi, bpt, fs.binding, fs.dvx, fs.dvy, fs.dvz, fs.energy, fs.strength);
  ctx.launch(fs.load, fs.slots);
}

// Room on the device for partitioning `voxels` voxels in `bricks` bricks; buffers are
// filled once when made, so that the memory is mapped before a fracture needs it.
void Solver::Impl::reserve_partition(std::size_t voxels, std::size_t bricks) {
  FractureStage& fs = *fracture;
  if (voxels <= fs.voxel_capacity && bricks <= fs.brick_capacity) return;
  fs.voxel_capacity = std::max(fs.voxel_capacity, voxels);
  fs.brick_capacity = std::max(fs.brick_capacity, bricks);
  const std::size_t nv = fs.voxel_capacity, nbricks = fs.brick_capacity;
  const std::vector<float> zeros(4 * std::max(nv, nbricks), 0.0f);
  const std::vector<std::uint32_t> none(std::max(nv, nbricks) + 1, 0u);
  for (auto [buffer, name] : {std::pair{&fs.vox_x, "x"}, {&fs.vox_y, "y"}, {&fs.vox_z, "z"}}) {
    *buffer = floats(nv, fmt::format("fracture voxels {}", name));
    ctx.write(*buffer, zeros.data(), nv * sizeof(float));
  }
  fs.vox_label = uints(nv, "fracture voxel seeds");
  ctx.write(fs.vox_label, none.data(), nv * sizeof(std::uint32_t));
  fs.brick_start = uints(nbricks + 1, "fracture bricks");
  ctx.write(fs.brick_start, none.data(), (nbricks + 1) * sizeof(std::uint32_t));
  fs.brick_lo = floats(4 * nbricks, "fracture brick boxes (low)");
  fs.brick_hi = floats(4 * nbricks, "fracture brick boxes (high)");
  ctx.write(fs.brick_lo, zeros.data(), 4 * nbricks * sizeof(float));
  ctx.write(fs.brick_hi, zeros.data(), 4 * nbricks * sizeof(float));
}

// The nearest seed of every voxel of `tb` (fracture::nearest_seeds' result), on the
// device (shaders/fracture.cl, voxel_seeds): voxels in voxel units about the centre
// of their box, sorted by the bricks of 4 x 4 x 4 cells they lie in (a counting sort
// on the host, once per body and event), seeds in the same units; the voxels float
// cannot decide (two seeds within `tol` of each other) decided on the host in double.
std::vector<std::int32_t> Solver::Impl::partition(const BreakableBody& tb, const std::vector<Vec3d>& seeds) {
  FractureStage& fs = *fracture;
  const fracture::Piece& piece = tb.piece;
  const std::size_t nv = piece.size();
  const Stopwatch clock;
  Vec3d lo = piece.centers.front(), hi = lo;
  for (const Vec3d& c : piece.centers) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const Vec3d mid = 0.5 * (lo + hi);
  const double unit = 1.0 / tb.voxel_size;
  if (fs.uploaded_body != tb.body || fs.uploaded_voxels != nv) {
    // Bricks: cells of kBrickEdge voxels' edge over the voxels' cells.
    CellIndex cmin = piece.cells.front(), cmax = cmin;
    for (const CellIndex& c : piece.cells)
      for (std::size_t a = 0; a < 3; ++a) cmin[a] = std::min(cmin[a], c[a]), cmax[a] = std::max(cmax[a], c[a]);
    std::array<std::uint32_t, 3> bd{};
    for (std::size_t a = 0; a < 3; ++a) bd[a] = static_cast<std::uint32_t>(cmax[a] - cmin[a]) / kBrickEdge + 1;
    std::vector<std::uint32_t> key(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      const CellIndex& c = piece.cells[v];
      const auto kx = static_cast<std::uint32_t>(c[0] - cmin[0]) / kBrickEdge;
      const auto ky = static_cast<std::uint32_t>(c[1] - cmin[1]) / kBrickEdge;
      const auto kz = static_cast<std::uint32_t>(c[2] - cmin[2]) / kBrickEdge;
      key[v] = (kz * bd[1] + ky) * bd[0] + kx;
    }
    // Voxels by brick (a counting sort), in voxel order within a brick.
    std::vector<std::uint32_t>& perm = fs.uploaded_perm;
    perm.resize(nv);
    const std::uint64_t bricks_in_box = std::uint64_t(bd[0]) * bd[1] * bd[2];
    if (bricks_in_box <= std::uint64_t{1} << 24) {
      std::vector<std::uint32_t> count(static_cast<std::size_t>(bricks_in_box) + 1, 0);
      for (std::size_t v = 0; v < nv; ++v) ++count[key[v] + 1];
      for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
      for (std::size_t v = 0; v < nv; ++v) perm[count[key[v]]++] = static_cast<std::uint32_t>(v);
    } else {
      std::iota(perm.begin(), perm.end(), 0u);
      std::stable_sort(perm.begin(), perm.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    }
    // Coordinates in voxel units, computed in voxel order and gathered by brick.
    std::vector<float> qx(nv), qy(nv), qz(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      const Vec3d q = (piece.centers[v] - mid) * unit;
      qx[v] = static_cast<float>(q.x()), qy[v] = static_cast<float>(q.y()), qz[v] = static_cast<float>(q.z());
    }
    std::vector<float> px(nv), py(nv), pz(nv);
    std::vector<std::uint32_t> firsts;
    std::vector<float> blo, bhi;
    for (std::size_t i = 0; i < nv; ++i) {
      const std::uint32_t v = perm[i];
      const float ux = qx[v], uy = qy[v], uz = qz[v];
      px[i] = ux, py[i] = uy, pz[i] = uz;
      if (i == 0 || key[v] != key[perm[i - 1]]) {
        firsts.push_back(static_cast<std::uint32_t>(i));
        blo.insert(blo.end(), {ux, uy, uz, 0.0f});
        bhi.insert(bhi.end(), {ux, uy, uz, 0.0f});
        continue;
      }
      float* l = blo.data() + blo.size() - 4;
      float* h = bhi.data() + bhi.size() - 4;
      l[0] = std::min(l[0], ux), l[1] = std::min(l[1], uy), l[2] = std::min(l[2], uz);
      h[0] = std::max(h[0], ux), h[1] = std::max(h[1], uy), h[2] = std::max(h[2], uz);
    }
    firsts.push_back(static_cast<std::uint32_t>(nv));
    const std::size_t bricks = firsts.size() - 1;
    reserve_partition(nv, bricks);
    ctx.write_vector(fs.vox_x, px);
    ctx.write_vector(fs.vox_y, py);
    ctx.write_vector(fs.vox_z, pz);
    ctx.write_vector(fs.brick_start, firsts);
    ctx.write_vector(fs.brick_lo, blo);
    ctx.write_vector(fs.brick_hi, bhi);
    fs.uploaded_body = tb.body;
    fs.uploaded_voxels = nv;
    fs.uploaded_bricks = bricks;
  }
  if (seeds.size() > fs.seed_capacity) {
    fs.seed_capacity = seeds.size() + 16;
    fs.seed_points = floats(4 * fs.seed_capacity, "fracture seeds");
  }
  std::vector<float> packed(4 * seeds.size(), 0.0f);
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const Vec3d q = (seeds[k] - mid) * unit;
    packed[4 * k] = static_cast<float>(q.x());
    packed[4 * k + 1] = static_cast<float>(q.y());
    packed[4 * k + 2] = static_cast<float>(q.z());
  }
  ctx.write_vector(fs.seed_points, packed);
  // float's error in a squared distance (voxel units): each coordinate is within
  // 2^-24 L of its exact value, L the box's size, so d^2 is within about 4 2^-24 L^2
  // of its own; twice that for two of them, and a factor 10 to spare.
  const double size = ((hi - lo) * unit + Vec3d::Ones()).norm();
  const float tol = static_cast<float>(80.0 * std::ldexp(1.0, -24) * size * size);
  fs.voxel_seeds.args(static_cast<std::uint32_t>(seeds.size()), fs.seed_points, fs.brick_start, fs.brick_lo, fs.brick_hi,
                      fs.vox_x, fs.vox_y, fs.vox_z, tol, fs.vox_label);
  ctx.launch_groups(fs.voxel_seeds, fs.uploaded_bricks, kBrickVoxels);
  const std::vector<std::uint32_t> raw = ctx.read_vector<std::uint32_t>(fs.vox_label, nv);
  std::vector<std::int32_t> labels(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const std::size_t v = fs.uploaded_perm[i];
    if (raw[i] & kSeedClose) {
      labels[v] = fracture::nearest_seed(piece.centers[v], seeds);
      ++fs.partition_close;
    } else {
      labels[v] = static_cast<std::int32_t>(raw[i]);
    }
  }
  fs.times.partition += clock.seconds();
  return labels;
}

// Splits `tb` by `seeds` (dropping seeds, and their entries of `seed_particles` when
// given, until the fragments fit `budget` and none is smaller than
// kMinFragmentVoxels: the seed of the smallest, else the last). Empty when no two
// seeds are left. The device partitions once; a dropped seed's voxels go to their
// nearest remaining seed, decided on the host (no other voxel's nearest changes).
std::vector<fracture::Fragment> Solver::Impl::fragments_of(const BreakableBody& tb, std::vector<Vec3d>& seeds,
                                                           std::vector<std::int32_t>* seed_particles,
                                                           std::int64_t budget) {
  if (seeds.size() < 2) return {};
  std::vector<std::int32_t> labels = partition(tb, seeds);
  Stopwatch clock;
  const fracture::FaceNeighbours neighbours = fracture::face_neighbours(tb.piece);
  while (seeds.size() >= 2) {
    const fracture::Components parts = fracture::components(neighbours, labels);
    std::size_t drop = seeds.size() - 1, smallest = kMinFragmentVoxels;
    for (std::size_t f = 0; f < parts.size.size(); ++f)
      if (static_cast<std::size_t>(parts.size[f]) < smallest)
        smallest = static_cast<std::size_t>(parts.size[f]), drop = static_cast<std::size_t>(parts.seed[f]);
    const std::size_t count = parts.size.size();
    if (static_cast<std::int64_t>(count) <= budget && count >= 2 && smallest == kMinFragmentVoxels) {
      std::vector<fracture::Fragment> out = fracture::fragments(tb.piece, neighbours, parts, tb.voxel_size, tb.density);
      fracture->times.fragments += clock.seconds();
      return out;
    }
    seeds.erase(seeds.begin() + static_cast<std::ptrdiff_t>(drop));
    if (seed_particles) seed_particles->erase(seed_particles->begin() + static_cast<std::ptrdiff_t>(drop));
    const auto dropped = static_cast<std::int32_t>(drop);
    for (std::size_t v = 0; v < labels.size(); ++v) {
      if (labels[v] == dropped) labels[v] = fracture::nearest_seed(tb.piece.centers[v], seeds);
      else if (labels[v] > dropped) --labels[v];
    }
  }
  fracture->times.fragments += clock.seconds();
  return {};
}

// Replaces `tb` by its fragments: new bodies (moving with the parent, plus the kick
// of the energy their seed received beyond its binding energy when `loads` are
// given), their breakable records appended to `next`, the parent retired, the event
// recorded.
void Solver::Impl::break_into(BreakableBody& tb, std::vector<fracture::Fragment>& fragments,
                              const std::vector<Vec3d>& seeds, const std::vector<std::int32_t>& seed_particles,
                              const FractureLoads* loads, std::vector<BreakableBody>& next) {
  FractureStage& fs = *fracture;
  Stopwatch clock;
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
  fs.times.bonds += clock.seconds();
  clock.restart();
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
      if (loads && !seed_particles.empty()) {
        const std::size_t sp = tb.slot + static_cast<std::size_t>(seed_particles[static_cast<std::size_t>(fr.seed)]);
        const double left = std::max(0.0, double(loads->energy[sp]) - double(tb.binding[sp - tb.slot]));
        const Vec3d load = -Vec3d(loads->dx[sp], loads->dy[sp], loads->dz[sp]);
        const double share = left * double(fr.piece.size()) / double(seed_voxels[static_cast<std::size_t>(fr.seed)]);
        if (load.norm() > 0 && share > 0)
          st.linear_velocity += std::min(std::sqrt(2 * share / fr.mass.mass), params.scene_speed) * load.normalized();
      }
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
  fs.events.push_back(std::move(event));
  fs.uploaded_body = -1;
  fs.times.bodies += clock.seconds();
  ++fs.times.events;
}

// One pass over the breakable bodies: `choose` gives a body's seeds (with the
// particles they came from, or none) and the fragments they make within the budget
// the scene's max_chunks leaves, or nothing; bodies that break are replaced by their
// fragments. Returns the number of bodies that broke.
int Solver::Impl::fracture_pass(const std::function<std::vector<fracture::Fragment>(
                                    BreakableBody&, std::int64_t, std::vector<Vec3d>&, std::vector<std::int32_t>&)>& choose) {
  FractureStage& fs = *fracture;
  if (fs.layout_dirty) fracture_layout({}, {}, {});
  FractureLoads loads;
  bool read = false;
  int broke = 0;
  std::vector<BreakableBody> next;
  auto active = static_cast<std::int64_t>(fs.bodies.size());
  for (BreakableBody& tb : fs.bodies) {
    std::vector<Vec3d> seeds;
    std::vector<std::int32_t> seed_particles;
    std::vector<fracture::Fragment> fragments = choose(tb, fs.settings.max_chunks - active + 1, seeds, seed_particles);
    if (fragments.empty()) {
      next.push_back(std::move(tb));
      continue;
    }
    if (!read && fs.slots > 0) {
      loads.energy = ctx.read_vector<float>(fs.energy, fs.slots);
      loads.dx = ctx.read_vector<float>(fs.dvx, fs.slots);
      loads.dy = ctx.read_vector<float>(fs.dvy, fs.slots);
      loads.dz = ctx.read_vector<float>(fs.dvz, fs.slots);
      read = true;
    }
    break_into(tb, fragments, seeds, seed_particles, read ? &loads : nullptr, next);
    active += static_cast<std::int64_t>(fragments.size()) - 1;
    ++broke;
  }
  if (broke == 0) {
    fs.bodies = std::move(next);  // the same bodies, in the same slots
    return 0;
  }
  // The load so far stays with the bodies that did not break; fragments start afresh.
  std::map<int, const BreakableBody*> old;
  for (const BreakableBody& tb : fs.bodies) old[tb.body] = &tb;
  std::vector<float> nx, ny, nz;
  for (const BreakableBody& tb : next) {
    const auto it = old.find(tb.body);
    for (std::size_t i = 0; i < tb.piece.particles.size(); ++i) {
      const bool kept = it != old.end() && read;
      const std::size_t s = kept ? it->second->slot + i : 0;
      nx.push_back(kept ? loads.dx[s] : 0.0f);
      ny.push_back(kept ? loads.dy[s] : 0.0f);
      nz.push_back(kept ? loads.dz[s] : 0.0f);
    }
  }
  fs.bodies = std::move(next);
  const Stopwatch clock;
  fracture_layout(nx, ny, nz);
  fs.times.bodies += clock.seconds();
  return broke;
}

// After a step: bodies with two or more particles at or above their binding energy
// break (within the scene's max_chunks).
void Solver::Impl::fracture_test() {
  FractureStage& fs = *fracture;
  if (fs.slots == 0 || n == 0 || fs.layout_dirty) return;
  const std::vector<float> strength = ctx.read_vector<float>(fs.strength, fs.slots);
  fracture_pass([&](BreakableBody& tb, std::int64_t budget, std::vector<Vec3d>& seeds,
                    std::vector<std::int32_t>& seed_particles) -> std::vector<fracture::Fragment> {
    const std::size_t np = tb.piece.particles.size();
    std::vector<fracture::Candidate> candidates;
    for (std::size_t i = 0; i < np; ++i)
      if (strength[tb.slot + i] >= 1.0f)
        candidates.push_back({static_cast<std::int32_t>(i), static_cast<double>(strength[tb.slot + i])});
    if (candidates.size() < 2 || budget < 2 || tb.piece.size() < 2 * kMinFragmentVoxels) return {};
    const std::vector<std::int32_t> chosen = fracture::select_seeds(
        candidates, tb.piece.particles, kMinSeedDistance * tb.voxel_size, static_cast<std::size_t>(budget));
    // Seeds at the centres of the seed particles' voxels (inside the solid, where the
    // exact cut of bw-voronoi replay finds them too); one per voxel.
    const std::vector<std::int32_t> pv = fracture::particle_voxels(tb.piece);
    std::vector<std::int32_t> used;
    for (const std::int32_t p : chosen) {
      const std::int32_t v = pv[static_cast<std::size_t>(p)];
      if (v < 0 || std::find(used.begin(), used.end(), v) != used.end()) continue;
      used.push_back(v);
      seed_particles.push_back(p);
      seeds.push_back(tb.piece.centers[static_cast<std::size_t>(v)] + tb.voxel_size * seed_offset(seeds.size()));
    }
    return fragments_of(tb, seeds, &seed_particles, budget);
  });
}

int Solver::Impl::break_body(int body, const std::vector<Vec3d>& given) {
  if (!fracture) fail_run("body {}: the scene has no breakable solid", body);
  bool found = false;
  for (const BreakableBody& tb : fracture->bodies) found = found || tb.body == body;
  if (!found) fail_run("body {} is not an unbroken breakable body", body);
  std::size_t made = 0;
  fracture_pass([&](BreakableBody& tb, std::int64_t budget, std::vector<Vec3d>& seeds,
                    std::vector<std::int32_t>&) -> std::vector<fracture::Fragment> {
    if (tb.body != body || budget < 2) return {};
    seeds = given;
    std::vector<fracture::Fragment> fragments = fragments_of(tb, seeds, nullptr, budget);
    made = fragments.size();
    return fragments;
  });
  return static_cast<int>(made);
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
  for (const Buffer* b : {&fs.map, &fs.binding, &fs.dvx, &fs.dvy, &fs.dvz, &fs.energy, &fs.strength, &fs.vox_x,
                          &fs.vox_y, &fs.vox_z, &fs.vox_label, &fs.seed_points, &fs.brick_start, &fs.brick_lo, &fs.brick_hi})
    if (b->valid()) total += b->bytes();
  return total;
}

const std::vector<FractureEvent>& Solver::fracture_events() const {
  static const std::vector<FractureEvent> none;
  return impl_->fracture ? impl_->fracture->events : none;
}

int Solver::break_body(int body, const std::vector<Vec3d>& seeds) { return impl_->break_body(body, seeds); }

Solver::FractureTimes Solver::fracture_times() const { return impl_->fracture ? impl_->fracture->times : FractureTimes{}; }

std::int64_t Solver::fracture_host_decided_voxels() const {
  return impl_->fracture ? impl_->fracture->partition_close : 0;
}

}  // namespace bw::sim

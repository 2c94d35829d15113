#include "sim/run.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <utility>
#include <vector>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/error.h"
#include "common/terminal.h"
#include "common/text.h"
#include "io/frame_file.h"
#include "io/h5.h"
#include "io/run_file.h"
#include "io/run_index.h"
#include "sim/checkpoint.h"

namespace bw::sim {
namespace fs = std::filesystem;

namespace {

// Largest compression (rho / rho0 - 1) the fluid may start with: a block placed one
// spacing from walls starts below 1e-5; overlapping a solid gives tens of percent.
constexpr double kMaxInitialCompression = 0.05;
// Blocks and solids leave one spacing between particles, a draw's jitter up to twice
// its offset less: a particle nearer than that, less this margin, overlaps another.
constexpr double kOverlapMargin = 0.05;

// The smallest distance from a fluid particle of a frame to another particle, the
// fluid's or a static solid's, among those nearer than `reach` (`reach` when none is).
// The particles are sorted by cells of edge `reach` (16 bytes each), and each fluid
// particle looks in the 27 cells around its own.
double nearest_pair(const FrameData& d, const ParticleArrays& boundary, double reach) {
  const std::size_t nf = d.x.size();
  const auto point = [&](std::size_t k) {
    return k < nf ? Vec3d(d.x[k], d.y[k], d.z[k]) : Vec3d(boundary.x[k - nf], boundary.y[k - nf], boundary.z[k - nf]);
  };
  const auto cell_of = [&](const Vec3d& x) { return (x / reach).array().floor().cast<std::int64_t>().eval(); };
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>(((i & 0x1fffff) << 42) | ((j & 0x1fffff) << 21) | (k & 0x1fffff));
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> sorted(nf + boundary.size());
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    const auto c = cell_of(point(k));
    sorted[k] = {key(c[0], c[1], c[2]), k};
  }
  std::sort(sorted.begin(), sorted.end());
  double nearest = reach;
  for (std::size_t i = 0; i < nf; ++i) {
    const Vec3d xi = point(i);
    const auto c = cell_of(xi);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::uint64_t cell = key(c[0] + dx, c[1] + dy, c[2] + dz);
          auto at = std::lower_bound(sorted.begin(), sorted.end(), std::pair<std::uint64_t, std::size_t>{cell, 0});
          for (; at != sorted.end() && at->first == cell; ++at)
            if (at->second != i) nearest = std::min(nearest, (point(at->second) - xi).norm());
        }
  }
  return nearest;
}

// Removes frame files of an earlier run in the same folder, so that the folder holds
// this run only. Only names this tool writes (six digits .h5) are touched, and only
// from frame `from` on (a resumed run keeps the frames before its checkpoint).
void remove_old_frames(const fs::path& folder, int from) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return;
  static const std::regex pattern("[0-9]{6}\\.h5");
  std::vector<fs::path> old;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && std::regex_match(name, pattern) && std::stoi(name.substr(0, 6)) >= from)
      old.push_back(entry.path());
  }
  for (const fs::path& p : old) fs::remove(p, ec);
}

}  // namespace

// Holds OUTDIR for one bw-sim at a time: a second run into the same folder (a repeated
// command, make -j, a job started twice) would interleave frames with the first. An
// flock on the folder itself leaves no file behind and goes with the process, however
// it ends.
namespace {
class FolderLock {
 public:
  FolderLock() = default;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  void lock(const std::string& folder) {
    fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) fail_run("{}: cannot open the folder: {}", folder, std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (errno == EWOULDBLOCK)
        fail_input("{}: another bw-sim is writing to this folder; wait for it, stop it, or give another -o", folder);
      // A file system without locks (some network ones) runs unguarded, as it always did.
    }
  }

 private:
  int fd_ = -1;
};
}  // namespace

struct Simulation::Impl {
  FolderLock lock;
  scene::Scene scene;
  RunOptions options;
  Setup setup;
  std::unique_ptr<compute::Context> context;
  std::unique_ptr<Solver> solver;
  double end_time = 0;
  int checkpoint_every = 0;
  std::string fingerprint;         // setup_fingerprint(setup)
  bool resuming = false;
  CheckpointHeader resume;         // the checkpoint it goes on from
};

std::string checkpoint_path(const std::string& output) { return (fs::path(output) / kCheckpointFile).string(); }

void require_checkpoint(const std::string& output) {
  const std::string path = checkpoint_path(output);
  std::error_code ec;
  if (fs::exists(path, ec)) return;
  // --resume takes the folder bw-sim wrote to: say so for a file or a folder that is not there.
  if (fs::is_regular_file(output, ec))
    fail_input("--resume {}: is a file; give the output folder of the run ({})", output,
               fs::path(output).parent_path().empty() ? "." : fs::path(output).parent_path().string());
  if (!fs::is_directory(output, ec)) fail_input("--resume {}: no such folder", output);
  const fs::path run = fs::path(output) / "run.h5";
  const bool complete = fs::exists(run, ec) && h5::is_hdf5_file(run.string()) && read_run(run.string()).status == "complete";
  fail_input("{}: no checkpoint to resume from{}", path,
             complete ? " (the run in that folder is complete)"
                      : " (bw-sim writes one every output.checkpoint_every frames and when SIGTERM or SIGINT stops it)");
}

namespace {

const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

// An emitter that starts at or after the last frame emits nothing: a preview run
// (--end-time) often ends before the water comes. Said, not refused.
void warn_of_emitters_after_the_end(const scene::Scene& scene, double end_time, bool end_from_option) {
  const double last = scene::last_frame(end_time, scene.time.frame_rate) / scene.time.frame_rate;
  for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
    if (scene.emitters[i].start < last) continue;
    fmt::print(stderr,
               "bw-sim: warning: {}: fluid.emitter[{}] starts at {} s, and the run ends at {} s{}: it emits nothing\n",
               scene.path, i, scene.emitters[i].start, last, end_from_option ? " (--end-time)" : "");
  }
}

}  // namespace

Simulation::Simulation(const scene::Scene& scene, const compute::DeviceInfo& device, RunOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.scene = scene;
  s.options = std::move(options);
  const bool end_from_option = s.options.end_time > 0;
  s.end_time = end_from_option ? s.options.end_time : scene.time.end;
  scene::check_end_time(scene, s.end_time, end_from_option ? std::string("--end-time") : scene.path + ": time.end");
  if (s.options.output.empty()) fail_input("no output folder given (-o OUTDIR)");
  const fs::path out(s.options.output);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    fail_input("{}: exists and is not a folder", s.options.output);
  // The output folder, or the closest folder above it that exists, must be writable.
  fs::path existing = fs::absolute(out, ec);
  while (!existing.empty() && !fs::exists(existing, ec) && existing != existing.parent_path())
    existing = existing.parent_path();
  if (::access(existing.c_str(), W_OK) != 0)
    fail_input("{}: cannot write there ({} is not writable)", s.options.output, existing.string());
  s.checkpoint_every = s.options.checkpoint_every >= 0 ? s.options.checkpoint_every : scene.checkpoint_every;
  // A resumed run must be the one the checkpoint was made of: refused before any work
  // when it is not (another scene, version, end time or device).
  if (s.options.resume) {
    const std::string path = checkpoint_path(s.options.output);
    require_checkpoint(s.options.output);
    s.resume = read_checkpoint_header(path);
    const CheckpointHeader& h = s.resume;
    const std::string tool = s.options.tool + " " BW_VERSION;
    if (h.tool != tool)
      fail_input("{}: written by {}, this is {}: a run goes on only with the version it started with", path, h.tool,
                 tool);
    if (h.scene_text != scene.text)
      fail_input("{}: made for another scene ({}); resume without a scene to go on with that one", path, h.scene_path);
    if (h.end_time != s.end_time)
      fail_input("{}: the run goes to {} s, not {} s (--end-time)", path, h.end_time, s.end_time);
    if (h.device != device_identity(device))
      fail_input("{}: made on {}, this run would be on {}: a run goes on bit-identically only on the device it "
                 "started on (--device)",
                 path, h.device, device_identity(device));
    if (h.frame < 0 || h.frame >= scene::last_frame(s.end_time, scene.time.frame_rate))
      fail_input("{}: frame {} is not a frame of this run", path, h.frame);
    s.resuming = true;
  }
  s.setup = prepare(scene, s.end_time);
  s.fingerprint = setup_fingerprint(s.setup);
  if (s.resuming && s.fingerprint != s.resume.fingerprint)
    fail_input("{}: the scene's particle files changed since the checkpoint was made (setup {} then, {} now)",
               checkpoint_path(s.options.output), s.resume.fingerprint, s.fingerprint);
  // The time-step control never takes a step above its stability limits; a dt_min
  // above them (a fixed step, dt_min = dt_max, set too large) would override them
  // from the first step on, so it is refused here rather than left to blow up.
  const Parameters& p = s.setup.params;
  const double signal = signal_speed(p, p.rho0);
  const double cfl_limit = p.cfl * p.h / (signal + p.scene_speed);
  const double fluid_limit = std::min({cfl_limit, p.dt_viscous, p.dt_diffusion});
  if (p.dt_min > p.contact_dt && p.contact_dt < fluid_limit)
    fail_input("{}: time.dt_min: {} s is above the largest stable step of this scene's contacts, {:.3g} s (bodies "
               "touch with a contact frequency of {:.4g} /s, docs/scene.md); lower time.dt_min",
               scene.path, p.dt_min, p.contact_dt, p.contact_frequency);
  if (p.dt_min > fluid_limit) {
    if (cfl_limit == fluid_limit)
      fail_input("{}: time.dt_min: {} s is above the largest stable step of this scene, {:.3g} s (the CFL limit "
                 "time.cfl h / (c + its largest speed) = {} x {} / ({:.4g} + {:.4g}), c the signal speed at rest); "
                 "lower time.dt_min",
                 scene.path, p.dt_min, cfl_limit, p.cfl, p.h, signal, p.scene_speed);
    if (p.dt_viscous == fluid_limit)
      fail_input("{}: time.dt_min: {} s is above the largest stable step of this scene, {:.3g} s (the viscous limit "
                 "time.viscous_factor h^2 rho0 / max(mu, mu_b)); lower time.dt_min",
                 scene.path, p.dt_min, p.dt_viscous);
    const double rate = p.diffusion_factor / p.dt_diffusion;  // the lattice's, setup's lattice_diffusion_rate
    fail_input("{}: time.dt_min: {} s is above the largest stable step of this scene, {:.3g} s (the density "
               "diffusion's limit at rest, time.diffusion_factor / its rate = {} / {:.4g} /s, the rate {:.4g} "
               "fluid.diffusion c0 / h); lower time.dt_min or fluid.diffusion",
               scene.path, p.dt_min, p.dt_diffusion, p.diffusion_factor, rate, rate * p.h / (p.diffusion * p.c0));
  }
  s.context = std::make_unique<compute::Context>(device);
  s.solver = std::make_unique<Solver>(s.setup, *s.context);
  if (scene.loads) s.solver->measure_static_reactions(true);
  if (scene.fields.wall_pressure) s.solver->record_wall_pressure();
  if (!scene.sensors.empty()) {
    std::vector<SensorWeights> sensors;
    for (std::size_t i = 0; i < scene.sensors.size(); ++i)
      sensors.push_back(sensor_weights(s.setup.boundary, scene.sensors[i], s.setup.params.h,
                                       fmt::format("{}: sensor[{}] '{}'", scene.path, i, scene.sensors[i].name)));
    s.solver->set_sensors(std::move(sensors), 1 / scene.sensor_rate);
  }

  // Fluid placed on top of a solid or another block starts compressed, and a stiff
  // fluid turns that into a blast at once: refuse it with the place to look at.
  // The kernel sum tells, whichever density the solver integrates.
  const FrameData d = s.solver->frame(FrameFields{}, 0);
  const std::vector<float> rho = s.solver->summed_density();
  if (!rho.empty()) {
    const auto worst = std::max_element(rho.begin(), rho.end()) - rho.begin();
    const double compression = rho[worst] / s.setup.params.rho0 - 1;
    if (compression > kMaxInitialCompression) {
      // No two particles nearer than a lattice leaves them: the kernel reaches past what one
      // layer of boundary particles is calibrated for (gamma1, a flat wall), as a thin wall's far face.
      const double jitter = scene.fluid.seed > 0 ? scene.fluid.jitter : 0;
      const double nearest = nearest_pair(d, s.setup.boundary.particles, p.spacing) / p.spacing;
      if (nearest >= 1 - 2 * jitter - kOverlapMargin)
        fail_input("{}: fluid starts {:.0f}% compressed at ({:.4g}, {:.4g}, {:.4g}), though no two particles are "
                   "nearer than {:.2g} spacings: smoothing_length {:.4g} m ({:.3g} spacings) takes in more of the "
                   "solids' boundary particles there than one layer at a flat wall (a wall thinner than that, whose "
                   "far face counts); use a smaller smoothing_length or thicker walls",
                   scene.path, 100 * compression, d.x[worst], d.y[worst], d.z[worst], nearest, p.h, p.h / p.spacing);
      fail_input("{}: fluid starts {:.0f}% compressed at ({:.4g}, {:.4g}, {:.4g}): a fluid block overlaps a solid or "
                 "another block (fluid rests one spacing from a solid's boundary particles, which bw-sample puts "
                 "within half a spacing of the mesh's faces)",
                 scene.path, 100 * compression, d.x[worst], d.y[worst], d.z[worst]);
    }
  }
  if (s.resuming) read_checkpoint_state(checkpoint_path(s.options.output), *s.solver);
  else warn_of_emitters_after_the_end(scene, s.end_time, s.options.end_time > 0);
}

Simulation::~Simulation() = default;

Solver& Simulation::solver() { return *impl_->solver; }
const Setup& Simulation::setup() const { return impl_->setup; }

RunSummary Simulation::run() {
  Impl& s = *impl_;
  Solver& solver = *s.solver;
  const Parameters& p = solver.parameters();
  const scene::Scene& scene = s.scene;

  const fs::path out(s.options.output);
  const fs::path frames_dir = out / "frames";
  std::error_code ec;
  fs::create_directories(frames_dir, ec);
  if (ec) fail_run("{}: cannot create the folder: {}", frames_dir.string(), ec.message());
  s.lock.lock(out.string());
  const int first_frame = s.resuming ? s.resume.frame + 1 : 0;
  remove_old_frames(frames_dir, first_frame);
  const std::string run_path = (out / "run.h5").string();
  const std::string ckpt_path = checkpoint_path(s.options.output);
  // A run that starts afresh makes the checkpoint of an earlier one meaningless.
  if (!s.resuming) fs::remove(ckpt_path, ec);

  RunRecord record;
  record.scene_text = scene.text;
  record.scene_path = fs::absolute(scene.path, ec).lexically_normal().string();
  record.device = s.context->device().label();
  record.tool = s.options.tool + " " BW_VERSION;
  for (std::size_t i = 0; i < scene.solids.size(); ++i) {
    const scene::Solid& solid = scene.solids[i];
    SolidRecord r;
    r.name = solid.name;
    r.particles = solid.particles;
    r.kind = solid.breakable ? "breakable" : solid.dynamic ? "dynamic" : solid.moving() ? "moving" : "static";
    for (int b = 0; b < solver.body_count(); ++b)
      if (solver.body_info(b).solid == static_cast<std::int32_t>(i) && solver.body_info(b).parent < 0) r.body = b;
    r.translation = solid.translation;
    r.rotation = solid.rotation();
    r.scale = solid.scale;
    record.solids.push_back(r);
  }
  for (const SensorWeights& w : solver.sensors()) {
    record.sensors.names.push_back(w.name);
    record.sensors.at.push_back(w.at);
    record.sensors.normal.push_back(w.normal);
    record.sensors.radius.push_back(w.radius);
    record.sensors.particles.push_back(static_cast<std::int64_t>(w.particle.size()));
  }
  record.sensors.interval = 1 / scene.sensor_rate;
  record.parameters = {{"spacing", p.spacing},
                       {"smoothing_length", p.h},
                       {"particle_mass", p.mass},
                       {"kernel_mass", p.kernel_mass},
                       {"rho0", p.rho0},
                       {"stiffness", p.k},
                       {"c0", p.c0},
                       {"gamma", p.gamma},
                       {"mu", p.mu},
                       {"mu_b", p.mu_b},
                       {"gamma1", p.gamma1},
                       {"gamma2", p.gamma2},
                       {"continuity", p.continuity ? 1.0 : 0.0},
                       {"density_diffusion", p.continuity ? p.diffusion : 0.0},
                       {"wall_hydrostatic", p.wall_hydrostatic ? 1.0 : 0.0},
                       {"wall_images", p.wall_images ? 1.0 : 0.0},
                       {"end_time", p.end_time},
                       {"frame_rate", p.frame_rate},
                       {"dt_min", p.dt_min},
                       {"dt_max", p.dt_max},
                       {"speed_limit", p.speed_limit},
                       {"max_particles", static_cast<double>(p.max_particles)},
                       {"boundary_particles", static_cast<double>(solver.boundary_count())}};
  if (solver.body_count() > 0) {
    record.parameters.emplace_back("contact_frequency", p.contact_frequency);
    record.parameters.emplace_back("contact_dt", p.contact_dt);
  }

  RunSummary sum;
  sum.device = record.device;
  sum.boundary = solver.boundary_count();
  sum.capacity = solver.capacity();
  sum.device_bytes = solver.device_bytes();
  sum.dt_min = std::numeric_limits<double>::infinity();

  ProgressLine progress(s.options.progress);
  Stopwatch clock;
  double wall_offset = 0;  // a resumed run's wall time goes on from its checkpoint's
  auto wall_now = [&] { return wall_offset + clock.seconds(); };
  const int frames = scene::last_frame(s.end_time, p.frame_rate);
  double previous_energy = 0;
  double mean_error_sum = 0;
  RunIndex index;  // the frames written so far, for OUTDIR/run.xdmf2
  const std::string index_path = run_index_path(out.string());

  // What the run file's rows and summary are made of besides the solver's state: a
  // checkpoint keeps it, by name.
  auto run_values = [&]() -> std::vector<std::pair<std::string, double>> {
    return {{"frames", static_cast<double>(sum.frames)},
            {"steps", static_cast<double>(sum.steps)},
            {"simulated", sum.simulated},
            {"wall_time", sum.wall_seconds},
            {"particle_steps", sum.particle_steps},
            {"dt_min", sum.dt_min},
            {"dt_max", sum.dt_max},
            {"worst_density_error", sum.worst_density_error},
            {"worst_density_frame", static_cast<double>(sum.worst_density_frame)},
            {"worst_density_time", sum.worst_density_time},
            {"mean_density_error", sum.mean_density_error},
            {"energy_start", sum.energy_start},
            {"energy_end", sum.energy_end},
            {"energy_highest", sum.energy_highest},
            {"energy_max_rise", sum.energy_max_rise},
            {"emitted_energy", sum.emitted_energy},
            {"outflow_energy", sum.outflow_energy},
            {"fluid_end", static_cast<double>(sum.fluid_end)},
            {"removed", static_cast<double>(sum.removed)},
            {"previous_energy", previous_energy},
            {"mean_error_sum", mean_error_sum},
            {"boundary_start", static_cast<double>(sum.boundary)},
            {"images_near", static_cast<double>(sum.images_near)},
            {"images_imaged", static_cast<double>(sum.images_imaged)}};
  };
  if (s.resuming) {
    const CheckpointHeader& h = s.resume;
    sum.frames = static_cast<int>(h.value("frames"));
    sum.steps = static_cast<std::int64_t>(h.value("steps"));
    sum.simulated = h.value("simulated");
    sum.wall_seconds = h.value("wall_time");
    sum.particle_steps = h.value("particle_steps");
    sum.dt_min = h.value("dt_min");
    sum.dt_max = h.value("dt_max");
    sum.worst_density_error = h.value("worst_density_error");
    sum.worst_density_frame = static_cast<int>(h.value("worst_density_frame"));
    sum.worst_density_time = h.value("worst_density_time");
    sum.mean_density_error = h.value("mean_density_error");
    sum.energy_start = h.value("energy_start");
    sum.energy_end = h.value("energy_end");
    sum.energy_highest = h.value("energy_highest");
    sum.energy_max_rise = h.value("energy_max_rise");
    sum.emitted_energy = h.value("emitted_energy");
    sum.outflow_energy = h.value("outflow_energy");
    sum.fluid_end = static_cast<std::int64_t>(h.value("fluid_end"));
    sum.removed = static_cast<std::int64_t>(h.value("removed"));
    previous_energy = h.value("previous_energy");
    mean_error_sum = h.value("mean_error_sum");
    wall_offset = sum.wall_seconds;
    sum.resumed_from = h.frame;
    record.frames = h.rows;
    record.loads = h.loads;
    // The index lists the frames kept from before the stop, then the new ones.
    index = scan_run(out.string());
    std::erase_if(index.frames, [&](const IndexFrame& e) { return e.frame > h.frame; });
    // The boundary's size at the start (bodies made by fracture since added theirs).
    for (auto& [name, value] : record.parameters)
      if (name == "boundary_particles") value = h.value("boundary_start");
    sum.boundary = static_cast<std::int64_t>(h.value("boundary_start"));
    sum.images_near = static_cast<std::int64_t>(h.value_or("images_near", -1));
    sum.images_imaged = static_cast<std::int64_t>(h.value_or("images_imaged", -1));
  }
  auto write_checkpoint_now = [&](int f) {
    Stopwatch write_clock;
    CheckpointHeader h;
    h.tool = record.tool;
    h.device = device_identity(s.context->device());
    h.scene_text = scene.text;
    h.scene_path = record.scene_path;
    h.fingerprint = s.fingerprint;
    h.frame = f;
    h.time = solver.time();
    h.end_time = s.end_time;
    h.checkpoint_every = s.checkpoint_every;
    h.run_values = run_values();
    h.rows = record.frames;
    h.loads = record.loads;
    write_checkpoint(ckpt_path, h, solver);
    sum.checkpoint_seconds += write_clock.seconds();
    ++sum.checkpoints;
    sum.checkpoint = ckpt_path;
  };

  auto write_frame_now = [&](int f, double dt_lo, double dt_hi) {
    const FluidStats st = solver.stats();
    // What the scene holds and carried out, beyond what its emitters put in: without
    // losses, constant. The guard on energy: a scene only loses it, so a total that rises
    // far above its start is a blow-up in the making (an unstable step, too much density
    // diffusion), stopped before its frame is written.
    const double energy = (st.kinetic + st.body_kinetic) + (st.potential + st.body_potential) + st.elastic -
                          st.emitted + st.outflow;
    const double limit = scene.time.energy_limit;
    if (f > 0 && limit > 0) {
      const double scale = std::max(std::abs(sum.energy_start), st.emitted);
      if (scale > 0 && energy - sum.energy_start > limit * scale)
        fail_run("frame {} (t = {:.6f} s): the total energy is {:.1f}% above its start ({:.6g} J against {:.6g} J{}), "
                 "more than time.energy_limit = {}: the fluid gained energy that no force gave it; it blew up (lower "
                 "time.cfl, or fluid.diffusion)",
                 f, solver.time(), 100 * (energy - sum.energy_start) / scale, energy, sum.energy_start,
                 st.emitted > std::abs(sum.energy_start) ? fmt::format(", of the {:.6g} J emitted", st.emitted) : "",
                 limit);
    }
    FrameData data = solver.frame(scene.fields, f);
    data.time = f / p.frame_rate;
    write_frame(data, frame_file_name(frames_dir.string(), f));
    // ParaView opens the run so far as one time series (docs/formats.md, "The run index").
    index.frames.push_back(index_frame(data, frame_file_name("frames", f)));
    write_run_index(index, index_path);
    FrameStats row;
    row.frame = f;
    row.time = data.time;
    row.steps = solver.steps();
    row.dt_min = dt_lo;
    row.dt_max = dt_hi;
    row.fluid = st.fluid;
    row.boundary = solver.boundary_count();
    row.removed = solver.removed_count();
    row.density_error_max = st.density_error_max;
    row.density_error_mean = st.density_error_mean;
    row.kinetic_energy = st.kinetic + st.body_kinetic;
    row.potential_energy = st.potential + st.body_potential;
    row.elastic_energy = st.elastic;
    row.speed_max = st.speed_max;
    row.emitted_energy = st.emitted;
    row.outflow_energy = st.outflow;
    row.wall_time = wall_now();
    record.frames.push_back(row);
    if (scene.loads) record.loads.push_back(solver.solid_impulses());
    record.sensors.pressure = solver.sensor_samples();
    // Bodies, including those added since the last frame (rows are never reused).
    record.bodies.clear();
    for (int b = 0; b < solver.body_count(); ++b) {
      const BodyInfo& info = solver.body_info(b);
      const rigid::MassProperties& m = solver.body(b).mass();
      BodyRecord br;
      br.name = info.name;
      br.solid = info.solid;
      br.parent = info.parent;
      br.mass = m.mass;
      br.inertia = m.inertia;
      br.reference_center = m.center;
      br.created_time = info.created_time;
      br.voxels = info.voxels;
      record.bodies.push_back(br);
    }
    record.fractures = solver.fracture_events();

    sum.emitted_energy = st.emitted;
    sum.outflow_energy = st.outflow;
    if (f == 0) {
      sum.energy_start = energy;
      sum.energy_highest = energy;
      const Solver::ImageCoverage images = solver.image_coverage();
      sum.images_near = images.near;
      sum.images_imaged = images.imaged;
    } else {
      sum.energy_max_rise = std::max(sum.energy_max_rise, energy - previous_energy);
      sum.energy_highest = std::max(sum.energy_highest, energy);
    }
    previous_energy = energy;
    sum.energy_end = energy;
    if (st.density_error_max > sum.worst_density_error || f == 0) {
      sum.worst_density_error = st.density_error_max;
      sum.worst_density_frame = f;
      sum.worst_density_time = data.time;
    }
    mean_error_sum += st.density_error_mean;
    sum.frames = f + 1;
    sum.fluid_end = st.fluid;
    sum.steps = solver.steps();
    sum.simulated = data.time;
    sum.wall_seconds = row.wall_time;
    sum.removed = row.removed;
    sum.mean_density_error = mean_error_sum / sum.frames;
    record.summary = summary_values(sum);
    write_run(record, run_path);
  };

  install_stop_handlers();
  bool stop_noticed = false;
  try {
    if (!s.resuming) write_frame_now(0, 0, 0);
    for (int f = first_frame == 0 ? 1 : first_frame; f <= frames; ++f) {
      const double target = f / p.frame_rate;
      double lo = std::numeric_limits<double>::infinity(), hi = 0;
      while (solver.time() < target) {
        if (stop_signal() && !stop_noticed) {
          // The frame under way is finished first: a checkpoint is always of a frame.
          stop_noticed = true;
          progress.clear();
          if (s.options.progress)
            std::fprintf(stderr, "bw-sim: %s: finishing frame %d, then writing a checkpoint\n",
                         signal_name(stop_signal()), f);
        }
        const std::int64_t particles = solver.fluid_count();
        const StepInfo info = solver.step(target);
        sum.particle_steps += static_cast<double>(particles);
        lo = std::min(lo, info.dt);
        hi = std::max(hi, info.dt);
        if (progress.active()) {
          const double wall = wall_offset + clock.seconds();
          const double rate = wall > 0 ? solver.steps() / wall : 0;
          const double left = solver.time() > 0 ? wall / solver.time() * (s.end_time - solver.time()) : 0;
          progress.update(fmt::format("frame {}/{}  t {:.3f} s  {:.0f} steps/s  {} particles  {} particle-steps/s  "
                                      "left {}",
                                      f, frames, solver.time(), rate, human_count(static_cast<double>(particles)),
                                      human_count(wall > 0 ? sum.particle_steps / wall : 0), human_duration(left)));
        }
      }
      sum.dt_min = std::min(sum.dt_min, lo);
      sum.dt_max = std::max(sum.dt_max, hi);
      write_frame_now(f, lo, hi);
      const int sig = stop_signal();
      const bool stop = f < frames && (sig || f == s.options.stop_after_frame);
      if (stop || (f < frames && s.checkpoint_every > 0 && f % s.checkpoint_every == 0)) write_checkpoint_now(f);
      if (stop) {
        progress.clear();
        record.status = fmt::format("stopped {} at frame {} (t = {} s); bw-sim --resume {} goes on",
                                    sig ? fmt::format("by {}", signal_name(sig)) : std::string("as asked"), f,
                                    solver.time(), s.options.output);
        write_run(record, run_path);
        sum.stop_signal = sig;
        sum.stopped = true;
        sum.steps = solver.steps();
        sum.simulated = solver.time();
        sum.wall_seconds = wall_now();
        sum.emitters_capped = solver.emitters_capped();
        if (!std::isfinite(sum.dt_min)) sum.dt_min = 0;
        return sum;
      }
    }
  } catch (const Error& e) {
    progress.clear();
    record.status = e.what();
    try {
      write_run(record, run_path);
    } catch (const Error&) {
      // The original error matters more than a failure to record it.
    }
    throw;
  }
  progress.clear();
  record.status = "complete";
  write_run(record, run_path);
  // A complete run needs no checkpoint, and leaves the same files however often it
  // stopped.
  fs::remove(ckpt_path, ec);
  sum.checkpoint.clear();

  sum.steps = solver.steps();
  sum.simulated = solver.time();
  sum.wall_seconds = wall_now();
  sum.removed = solver.removed_count();
  sum.emitters_capped = solver.emitters_capped();
  sum.mean_density_error = sum.frames ? mean_error_sum / sum.frames : 0;
  if (!std::isfinite(sum.dt_min)) sum.dt_min = 0;
  return sum;
}

double RunSummary::energy_scale() const { return std::max(std::abs(energy_start), emitted_energy); }

double RunSummary::energy_drift() const {
  return energy_scale() > 0 ? (energy_end - energy_start) / energy_scale() : 0;
}

double RunSummary::energy_growth() const {
  return energy_scale() > 0 ? (energy_highest - energy_start) / energy_scale() : 0;
}

std::vector<std::pair<std::string, double>> summary_values(const RunSummary& r) {
  std::vector<std::pair<std::string, double>> out{{"wall_time", r.wall_seconds},
          {"simulated_time", r.simulated},
          {"steps", static_cast<double>(r.steps)},
          {"particle_steps", r.particle_steps},
          {"fluid", static_cast<double>(r.fluid_end)},
          {"removed", static_cast<double>(r.removed)},
          {"density_error_worst", r.worst_density_error},
          {"density_error_worst_time", r.worst_density_time},
          {"density_error_mean", r.mean_density_error},
          {"energy_initial", r.energy_start},
          {"energy_final", r.energy_end},
          {"energy_highest", r.energy_highest},
          {"energy_drift", r.energy_drift()},
          {"energy_growth", r.energy_growth()},
          {"energy_largest_rise", r.energy_max_rise},
          {"energy_emitted", r.emitted_energy},
          {"energy_outflow", r.outflow_energy}};
  if (r.images_near >= 0) {
    out.emplace_back("images_near", static_cast<double>(r.images_near));
    out.emplace_back("images_imaged", static_cast<double>(r.images_imaged));
  }
  return out;
}

std::string format_summary(const RunSummary& r) {
  std::string out;
  out += fmt::format("  frames       {} ({:.4g} s simulated) in {}\n", r.frames, r.simulated,
                     human_duration(r.wall_seconds));
  out += fmt::format("  steps        {}, dt {:.3g} .. {:.3g} s\n", r.steps, r.dt_min, r.dt_max);
  out += fmt::format("  throughput   {} particle-steps/s, {:.3g} s of wall time per simulated second\n",
                     human_count(r.wall_seconds > 0 ? r.particle_steps / r.wall_seconds : 0),
                     r.simulated > 0 ? r.wall_seconds / r.simulated : 0);
  out += fmt::format("  particles    {} fluid at the end, {} lost (removed at the domain), {} boundary{}\n",
                     r.fluid_end, r.removed, r.boundary,
                     r.emitters_capped ? "; emitters held back by max_particles" : "");
  out += fmt::format("  density      worst error {:.2f}% (frame {}, t = {:.4g} s), mean {:.3f}%\n",
                     100 * r.worst_density_error, r.worst_density_frame, r.worst_density_time,
                     100 * r.mean_density_error);
  const std::string growth =
      r.energy_highest > r.energy_start
          ? fmt::format("at most {:+.3f}% above it (largest rise between frames {:.3g} J)", 100 * r.energy_growth(),
                        r.energy_max_rise)
          : std::string("never above it");
  std::string terms;  // what the total counts besides the fluid's and bodies' energy
  if (r.emitted_energy > 0)
    terms += fmt::format(", less the {:.6g} J put in by emitters and moving solids", r.emitted_energy);
  else if (r.emitted_energy < 0)  // the fluid pushed a moving solid along its way
    terms += fmt::format(", plus the {:.6g} J the fluid gave moving solids", -r.emitted_energy);
  if (r.outflow_energy != 0) terms += fmt::format(", with the {:.6g} J carried out of the domain", r.outflow_energy);
  out += fmt::format("  energy       {:.6g} J -> {:.6g} J{}: drift {:+.2f}% of the {}, {}\n", r.energy_start, r.energy_end,
                     terms, 100 * r.energy_drift(),
                     r.emitted_energy > std::abs(r.energy_start) ? "energy put in" : "initial total", growth);
  if (r.images_near > 0 && r.images_imaged > 0)
    out += fmt::format("  walls        mirror images for {} of the {} fluid particles near solids at the start ({:.0f}%)\n",
                       r.images_imaged, r.images_near,
                       100 * static_cast<double>(r.images_imaged) / static_cast<double>(r.images_near));
  else if (r.images_near > 0)  // the solids' particles hold the water: the hydrostatic wall
    out += fmt::format("  walls        no mirror images for the {} fluid particles near solids at the start: no flat "
                       "face of a solid that stays put looks toward them (docs/scene.md, \"Walls as mirror images\")\n",
                       r.images_near);
  out += fmt::format("  device       {}, {} ({:.0f} bytes per fluid particle)\n", r.device, human_bytes(r.device_bytes),
                     r.capacity > 0 ? static_cast<double>(r.device_bytes) / static_cast<double>(r.capacity) : 0.0);
  return out;
}

}  // namespace bw::sim

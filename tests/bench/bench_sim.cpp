// bench-sim: throughput of the fluid solver on the default device (PoCL on a CPU
// here) for a dam break at about 30 k, 120 k and 500 k fluid particles: particle-steps
// per second (best and median of several rounds, and from process CPU time), device
// bytes per fluid particle, how the cost per particle-step grows with size, where the
// time goes (with the density diffusion's own share, against the density pass built
// without it), and the wall time per simulated second. Prints figures, asserts nothing.
//
//   build/tests/bench/bench-sim [--quick]      (--quick: the 30 k case only)
//   build/tests/bench/bench-sim --device gpu --sizes 30000,120000,1000000,4000000 --csv sim.csv
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cli/tool.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/terminal.h"
#include "common/text.h"
#include "compute/device.h"
#include "compute/kernels.h"
#include "scene/scene.h"
#include "sim/run.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

struct Result {
  std::int64_t fluid = 0, boundary = 0;
  double best = 0, median = 0, cpu = 0;  // particle-steps per second
  double bytes_per_particle = 0;
  double ns_per_particle_step = 0;       // from the best round
  double setup_seconds = 0;              // scene, solver and device buffers
  double wall_per_simulated = 0;         // wall s per simulated s (0: not measured)
  int n = 0;
  double step_ms = 0;                    // profiled cases: all the kernels' time per step
};

// A dam break: a column n x n x 2n spacings against the end of a closed tank
// 4n x n x 3n, spacing 1 cm, h = 2 spacings (~33 neighbours); its scene file in dir.
// With a wall pressure named, the tank has walls two spacings thick, its faces toward
// the water (what the images need: a box's faces with the water inside look away from
// it), the cavity 4n x n x 3n spacings.
bw::scene::Scene dam_break(const bw::test::TempDir& dir, int n, const std::string& density, double diffusion,
                           const std::string& wall) {
  const double s = 0.01;
  const bool thick = !wall.empty();
  if (thick) bw::test::write_thick_tank(dir.file("tank.h5"), {4 * n, n, 3 * n}, s, 2 * s);
  else bw::test::write_tank(dir.file("tank.h5"), {4 * n, n, 3 * n}, s);
  const double L = (4 * n + 0.5) * s, W = (n + 0.5) * s, H = (3 * n + 0.5) * s, lo = thick ? 0.0 : s;
  const double margin = thick ? 0.04 : 0.02;
  std::ofstream(dir.file("dam.toml")) << "spacing = 0.01\n[time]\nend = 10\n[domain]\nmin = [" << -margin << ", "
                                      << -margin << ", " << -margin << "]\n"
                                      << "max = [" << L + margin << ", " << W + margin << ", " << H + margin << "]\n"
                                      << "[[fluid.block]]\nmin = [" << lo << ", " << lo << ", " << lo << "]\nmax = ["
                                      << n * s << ", " << n * s << ", " << 2 * n * s
                                      << "]\n[[solid]]\nparticles = \"tank.h5\"\n"
                                      << "[fluid]\ndensity = \"" << density << "\"\n";
  if (diffusion >= 0) std::ofstream(dir.file("dam.toml"), std::ios::app) << "diffusion = " << diffusion << "\n";
  if (!wall.empty()) std::ofstream(dir.file("dam.toml"), std::ios::app) << "wall_pressure = \"" << wall << "\"\n";
  return bw::scene::load_scene(dir.file("dam.toml"));
}

bw::sim::RunOptions quiet_options(const bw::test::TempDir& dir) {
  bw::sim::RunOptions options;
  options.output = dir.file("out");
  options.progress = false;
  return options;
}

// Each kernel's ms per step over `steps` steps, every launch profiled (waited for).
std::vector<std::pair<std::string, double>> profile_steps(bw::sim::Solver& solver, int steps) {
  solver.context().set_profiling(true);
  solver.context().reset_kernel_times();
  for (int i = 0; i < steps; ++i) solver.step(10.0);
  std::vector<std::pair<std::string, double>> out;
  for (const auto& k : solver.context().kernel_times()) out.emplace_back(k.name, 1e3 * k.seconds / steps);
  solver.context().set_profiling(false);
  return out;
}

Result run_case(const bw::compute::DeviceInfo& device, int n, bool profile, double simulate_seconds,
               const std::string& density, double diffusion, const std::string& wall) {
  bw::Stopwatch setup;
  bw::test::TempDir dir;
  bw::sim::Simulation simulation(dam_break(dir, n, density, diffusion, wall), device, quiet_options(dir));
  bw::sim::Solver& solver = simulation.solver();

  Result r;
  r.n = n;
  r.setup_seconds = setup.seconds();
  r.fluid = solver.fluid_count();
  r.boundary = solver.boundary_count();
  r.bytes_per_particle = static_cast<double>(solver.device_bytes()) / static_cast<double>(r.fluid);
  for (int i = 0; i < 5; ++i) solver.step(10.0);  // warm-up: kernels compiled, caches filled

  constexpr int kRounds = 5, kSteps = 8;
  std::vector<double> rates;
  double cpu_total = 0, particle_steps_total = 0;
  for (int round = 0; round < kRounds; ++round) {
    bw::Stopwatch clock;
    const double cpu0 = cpu_seconds();
    double particle_steps = 0;
    for (int i = 0; i < kSteps; ++i) {
      particle_steps += static_cast<double>(solver.fluid_count());
      solver.step(10.0);
    }
    solver.context().finish();
    rates.push_back(particle_steps / clock.seconds());
    cpu_total += cpu_seconds() - cpu0;
    particle_steps_total += particle_steps;
  }
  std::sort(rates.begin(), rates.end());
  r.best = rates.back();
  r.median = rates[rates.size() / 2];
  // Process CPU time counts both cores' work: what two dedicated cores would give.
  // (On a GPU the host's CPU time measures nothing of the device: left out.)
  const int cores = std::max(1, solver.context().device().compute_units);
  if (solver.context().device().type == "cpu") r.cpu = particle_steps_total / cpu_total * cores;
  r.ns_per_particle_step = 1e9 / r.best;

  if (profile) {
    const auto kernels = profile_steps(solver, kSteps);
    for (const auto& [name, ms] : kernels) r.step_ms += ms;
    std::printf("  time per step by kernel (profiled, each launch waited for):\n");
    for (const auto& [name, ms] : kernels) {
      if (ms < 0.005 * r.step_ms) continue;
      std::printf("    %-20s %7.2f ms  %5.1f%%\n", name.c_str(), ms, 100 * ms / r.step_ms);
    }
  }

  if (simulate_seconds > 0) {
    bw::Stopwatch clock;
    const double t0 = solver.time();
    const std::int64_t steps0 = solver.steps();
    while (solver.time() < t0 + simulate_seconds) solver.step(t0 + simulate_seconds);
    const double elapsed = clock.seconds();
    r.wall_per_simulated = elapsed / simulate_seconds;
    std::printf("  simulated %.2f s of the dam break (%lld steps, mean dt %.3g s) in %.1f s: %.0f s of wall time "
                "per simulated second\n",
                simulate_seconds, static_cast<long long>(solver.steps() - steps0),
                simulate_seconds / static_cast<double>(solver.steps() - steps0), elapsed, elapsed / simulate_seconds);
  }
  return r;
}

// ms per step in the kernel `name` over `steps` profiled steps.
// The density pass per step over `steps` steps: fluid_density, and fluid_density_rate
// on the steps that also find the diffusion's rate for its step limit.
double density_ms(bw::sim::Solver& solver, int steps) {
  double ms = 0;
  for (const auto& [kernel, each] : profile_steps(solver, steps))
    if (kernel == "fluid_density" || kernel == "fluid_density_rate") ms += each;
  return ms;
}

// The density diffusion's own cost: the density pass of the case with it and of the
// same case built without its terms (fluid.diffusion = 0), profiled in turns, 8 steps
// at a time; the least of 6 turns each (one turn's launches vary by 10-20%).
std::pair<double, double> diffusion_cost(const bw::compute::DeviceInfo& device, int n, double diffusion,
                                         const std::string& wall) {
  bw::test::TempDir a, b;
  bw::sim::Simulation with(dam_break(a, n, "continuity", diffusion, wall), device, quiet_options(a));
  bw::sim::Simulation without(dam_break(b, n, "continuity", 0.0, wall), device, quiet_options(b));
  for (int i = 0; i < 5; ++i) with.solver().step(10.0), without.solver().step(10.0);
  double least_with = 1e300, least_without = 1e300;
  for (int turn = 0; turn < 6; ++turn) {
    least_with = std::min(least_with, density_ms(with.solver(), 8));
    least_without = std::min(least_without, density_ms(without.solver(), 8));
  }
  return {least_with, least_without};
}

// Column side n of the dam break holding about `count` fluid particles (2 n^3).
int column_for(double count) { return std::max(4, static_cast<int>(std::lround(std::cbrt(count / 2)))); }

void write_csv(const std::string& path, const bw::compute::DeviceInfo& device, const std::vector<Result>& results) {
  std::string text =
      "device,fluid,boundary,bytes_per_particle,best,median,cpu,ns_per_particle_step,setup_s,wall_per_simulated_s\n";
  std::string name = device.label();
  std::replace(name.begin(), name.end(), ',', ';');
  for (const Result& r : results) {
    text += fmt::format("{},{},{},{:.0f},{:.6g},{:.6g},{},{:.4g},{:.3g},{}\n", name, r.fluid, r.boundary,
                        r.bytes_per_particle, r.best, r.median, r.cpu > 0 ? fmt::format("{:.6g}", r.cpu) : "",
                        r.ns_per_particle_step, r.setup_seconds,
                        r.wall_per_simulated > 0 ? fmt::format("{:.4g}", r.wall_per_simulated) : "");
  }
  bw::write_file_atomically(path, text.data(), text.size());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Throughput of the fluid solver: a dam break at several sizes on one OpenCL device; prints "
               "figures, asserts nothing.",
               "bench-sim"};
  bw::cli::setup(app,
                 "  bench-sim\n"
                 "  bench-sim --quick\n"
                 "  bench-sim --device gpu --sizes 30000,120000,1000000,4000000 --csv sim.csv\n"
                 "  bench-sim --sizes 120000 --density summation\n"
                 "  bench-sim --sizes 120000 --wall-pressure images\n");
  bool quick = false;
  std::string device_choice = "auto", csv;
  std::vector<double> counts;
  double profile_near = 120000, simulate = 0.25;
  std::string density = "continuity";  // the scene's default
  double diffusion = -1;
  std::string wall;  // the scene's default
  auto* quick_flag = app.add_flag("--quick", quick, "The 30 k case only");
  app.add_option("--sizes", counts, "Fluid particle counts to run, about (default 30000,120000,500000)")
      ->delimiter(',')
      ->check(bw::cli::in_range(1000, 1e9))
      ->excludes(quick_flag);
  app.add_option("--device", device_choice, "OpenCL device: auto, cpu, gpu or a number (bw-sim --device list)")
      ->capture_default_str();
  app.add_option("--csv", csv, "Also write one CSV row per size to this file");
  app.add_option("--profile", profile_near,
                 "Time each kernel in the case nearest this many fluid particles (0: none)")
      ->capture_default_str()
      ->check(bw::cli::kNonNegative);
  app.add_option("--simulate", simulate,
                 "Simulated seconds of the smallest case, for wall time per simulated second (0: none)")
      ->capture_default_str()
      ->check(bw::cli::kNonNegative);
  app.add_option("--density", density,
                 "fluid.density of the runs: continuity (with its density diffusion and hydrostatic wall; the profile's "
                 "fluid_density row is what the continuity equation and the diffusion cost), or summation")
      ->check(CLI::IsMember({"summation", "continuity"}))
      ->capture_default_str();
  app.add_option("--diffusion", diffusion,
                 "fluid.diffusion (delta) with --density continuity (default: the scene's default; with a delta "
                 "above 0 the profiled case also prints the diffusion's own cost)")
      ->check(bw::cli::in_range(0, 1));
  app.add_option("--wall-pressure", wall,
                 "fluid.wall_pressure of the runs (default: the scene's default): hydrostatic, mirrored or images (the "
                 "tank's flat faces as mirror images of the fluid); named, the tank's walls are two spacings thick")
      ->check(CLI::IsMember({"hydrostatic", "mirrored", "images"}));
  return bw::cli::run(app, argc, argv, [&]() -> int {
    if (diffusion >= 0 && density != "continuity")
      bw::fail_input("--diffusion {}: only with --density continuity (the summation has no diffusion)", diffusion);
    if (!wall.empty() && wall != "mirrored" && density != "continuity")
      bw::fail_input("--wall-pressure {}: only with --density continuity (the summation has the mirrored wall)", wall);
    const bw::compute::DeviceInfo device = bw::compute::choose_device(device_choice);
    std::printf("bench-sim: %s, %d compute units, vector width %d; load average %s\n", device.label().c_str(),
                device.compute_units, bw::compute::kernel_vector_width(device), load_average().c_str());
    std::printf("dam break, spacing 1 cm, h = 2 spacings, %s density%s%s; rounds of 8 steps after 5 warm-up steps\n\n",
                density.c_str(), diffusion >= 0 ? fmt::format(", diffusion {}", diffusion).c_str() : "",
                wall.empty() ? "" : fmt::format(", {} wall", wall).c_str());
    std::vector<int> sizes = {25, 39, 63};
    if (quick) sizes = {25};
    if (!counts.empty()) {
      sizes.clear();
      for (double c : counts) sizes.push_back(column_for(c));
    }
    int profiled = -1;  // the case nearest profile_near
    if (profile_near > 0) {
      for (int n : sizes)
        if (profiled < 0 || std::abs(2.0 * n * n * n - profile_near) < std::abs(2.0 * profiled * profiled * profiled - profile_near))
          profiled = n;
    }
    const int smallest = *std::min_element(sizes.begin(), sizes.end());
    std::vector<Result> results;
    for (int n : sizes) {
      std::printf("column %d x %d x %d:\n", n, n, 2 * n);
      const Result r = run_case(device, n, n == profiled, n == smallest ? simulate : 0.0, density, diffusion, wall);
      if (n == profiled && density == "continuity" && diffusion != 0) {
        const auto [with, without] = diffusion_cost(device, n, diffusion, wall);
        std::printf("  density diffusion: fluid_density %.2f ms per step with it, %.2f ms built without it (least "
                    "of 6 turns of 8 steps each): %.2f ms, %.1f%% of the %.2f ms step above\n",
                    with, without, with - without, 100 * (with - without) / r.step_ms, r.step_ms);
      }
      std::printf("  %lld fluid + %lld boundary particles (set up in %.1f s)\n", static_cast<long long>(r.fluid),
                  static_cast<long long>(r.boundary), r.setup_seconds);
      std::printf("  particle-steps/s: best %s, median %s", bw::human_count(r.best).c_str(),
                  bw::human_count(r.median).c_str());
      if (r.cpu > 0) std::printf("; from process CPU time (2 dedicated cores) %s", bw::human_count(r.cpu).c_str());
      std::printf("\n  device memory: %.0f bytes per fluid particle\n\n", r.bytes_per_particle);
      std::fflush(stdout);
      results.push_back(r);
      // Rewritten after every size: a run stopped at a time limit keeps what it measured.
      if (!csv.empty()) write_csv(csv, device, results);
    }
    if (results.size() > 1) {
      std::printf("growth (cost per particle-step relative to the smallest case, best rounds):\n");
      for (const Result& r : results)
        std::printf("  %8lld particles: %.0f ns per particle-step, x %.2f\n", static_cast<long long>(r.fluid),
                    r.ns_per_particle_step, r.ns_per_particle_step / results.front().ns_per_particle_step);
    }
    std::printf("load average at the end %s\n", load_average().c_str());
    return bw::kExitOk;
  });
}

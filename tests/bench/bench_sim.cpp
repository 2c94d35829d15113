// bench-sim: throughput of the fluid solver on the default device (PoCL on a CPU
// here) for a dam break at about 30 k, 120 k and 500 k fluid particles: particle-steps
// per second (best and median of several rounds, and from process CPU time), device
// bytes per fluid particle, how the cost per particle-step grows with size, where the
// time goes, and the wall time per simulated second. Prints figures, asserts nothing.
//
//   build/tests/bench/bench-sim [--quick]      (--quick: the 30 k case only)
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

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
};

// A dam break: a column n x n x 2n spacings against the end of a closed tank
// 4n x n x 3n, spacing 1 cm, h = 2 spacings (~33 neighbours).
Result run_case(int n, bool profile, double simulate_seconds) {
  bw::test::TempDir dir;
  const double s = 0.01;
  bw::test::write_tank(dir.file("tank.h5"), {4 * n, n, 3 * n}, s);
  const double L = (4 * n + 0.5) * s, W = (n + 0.5) * s, H = (3 * n + 0.5) * s;
  std::ofstream(dir.file("dam.toml")) << "spacing = 0.01\n[time]\nend = 10\n[domain]\nmin = [-0.02, -0.02, -0.02]\n"
                                      << "max = [" << L + 0.02 << ", " << W + 0.02 << ", " << H + 0.02 << "]\n"
                                      << "[[fluid.block]]\nmin = [0.01, 0.01, 0.01]\nmax = [" << n * s << ", " << n * s
                                      << ", " << 2 * n * s << "]\n[[solid]]\nparticles = \"tank.h5\"\n";
  const bw::scene::Scene scene = bw::scene::load_scene(dir.file("dam.toml"));
  bw::sim::RunOptions options;
  options.output = dir.file("out");
  options.progress = false;
  bw::sim::Simulation simulation(scene, bw::compute::choose_device("auto"), options);
  bw::sim::Solver& solver = simulation.solver();

  Result r;
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
  const int cores = std::max(1, solver.context().device().compute_units);
  r.cpu = particle_steps_total / cpu_total * cores;
  r.ns_per_particle_step = 1e9 / r.best;

  if (profile) {
    solver.context().set_profiling(true);
    solver.context().reset_kernel_times();
    for (int i = 0; i < kSteps; ++i) solver.step(10.0);
    double total = 0;
    for (const auto& k : solver.context().kernel_times()) total += k.seconds;
    std::printf("  time per step by kernel (profiled, each launch waited for):\n");
    for (const auto& k : solver.context().kernel_times()) {
      if (k.seconds < 0.005 * total) continue;
      std::printf("    %-20s %7.2f ms  %5.1f%%\n", k.name.c_str(), 1e3 * k.seconds / kSteps, 100 * k.seconds / total);
    }
    solver.context().set_profiling(false);
  }

  if (simulate_seconds > 0) {
    bw::Stopwatch clock;
    const double t0 = solver.time();
    const std::int64_t steps0 = solver.steps();
    while (solver.time() < t0 + simulate_seconds) solver.step(t0 + simulate_seconds);
    const double wall = clock.seconds();
    std::printf("  simulated %.2f s of the dam break (%lld steps, mean dt %.3g s) in %.1f s: %.0f s of wall time "
                "per simulated second\n",
                simulate_seconds, static_cast<long long>(solver.steps() - steps0),
                simulate_seconds / static_cast<double>(solver.steps() - steps0), wall, wall / simulate_seconds);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const bw::compute::DeviceInfo device = bw::compute::choose_device("auto");
  std::printf("bench-sim: %s, %d compute units, vector width %d; load average %s\n", device.label().c_str(),
              device.compute_units, bw::compute::kernel_vector_width(device), load_average().c_str());
  std::printf("dam break, spacing 1 cm, h = 2 spacings; rounds of 8 steps after 5 warm-up steps\n\n");
  std::vector<int> sizes = {25, 39, 63};
  if (quick) sizes = {25};
  std::vector<Result> results;
  for (int n : sizes) {
    std::printf("column %d x %d x %d:\n", n, n, 2 * n);
    const Result r = run_case(n, n == 39 || quick, n == 25 ? 0.25 : 0.0);
    std::printf("  %lld fluid + %lld boundary particles\n", static_cast<long long>(r.fluid),
                static_cast<long long>(r.boundary));
    std::printf("  particle-steps/s: best %s, median %s; from process CPU time (2 dedicated cores) %s\n",
                bw::human_count(r.best).c_str(), bw::human_count(r.median).c_str(), bw::human_count(r.cpu).c_str());
    std::printf("  device memory: %.0f bytes per fluid particle\n\n", r.bytes_per_particle);
    results.push_back(r);
  }
  if (results.size() > 1) {
    std::printf("growth (cost per particle-step relative to the smallest case, best rounds):\n");
    for (const Result& r : results)
      std::printf("  %8lld particles: %.0f ns per particle-step, x %.2f\n", static_cast<long long>(r.fluid),
                  r.ns_per_particle_step, r.ns_per_particle_step / results.front().ns_per_particle_step);
  }
  std::printf("load average at the end %s\n", load_average().c_str());
  return 0;
}

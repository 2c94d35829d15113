// bench-checkpoint: what checkpoints cost (docs/performance.md, "Checkpoints").
//   - writing and reading one for a dam break of about 1 M fluid particles (the
//     solver's state at frame 0), best and median of three rounds, and its size;
//   - a reduced dam break (16 k particles, 0.5 s) run whole, and stopped at half
//     way and resumed in a second Simulation: the resumed pair's wall time over the
//     whole run's (the cost of resuming: one more start, a checkpoint written and
//     read). Prints figures, asserts nothing.
//
//   build/tests/bench/bench-checkpoint [--quick]   (--quick: 128 k particles for the first)
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/terminal.h"
#include "compute/device.h"
#include "scene/scene.h"
#include "sim/checkpoint.h"
#include "sim/run.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace {

// A column n x n x 2n spacings in a closed tank 4n x n x 3n (bench-sim's dam break).
bw::scene::Scene dam(const bw::test::TempDir& dir, int n, double end) {
  const double s = 0.01;
  bw::test::write_tank(dir.file("tank.h5"), {4 * n, n, 3 * n}, s);
  const double L = (4 * n + 0.5) * s, W = (n + 0.5) * s, H = (3 * n + 0.5) * s;
  std::ofstream(dir.file("dam.toml")) << "spacing = 0.01\n[time]\nend = " << end << "\nframe_rate = 60\n"
                                      << "[domain]\nmin = [-0.02, -0.02, -0.02]\n"
                                      << "max = [" << L + 0.02 << ", " << W + 0.02 << ", " << H + 0.02 << "]\n"
                                      << "[[fluid.block]]\nmin = [0.01, 0.01, 0.01]\nmax = [" << n * s << ", " << n * s
                                      << ", " << 2 * n * s << "]\n[[solid]]\nparticles = \"tank.h5\"\n";
  return bw::scene::load_scene(dir.file("dam.toml"));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const bw::compute::DeviceInfo device = bw::compute::choose_device("auto");
  std::printf("device: %s\n", device.label().c_str());

  {
    bw::test::TempDir dir;
    const int n = quick ? 40 : 81;  // about 2 n^3 fluid particles: 128 k or 1.04 M
    const bw::scene::Scene scene = dam(dir, n, 1.0);
    bw::sim::RunOptions o;
    o.output = dir.file("run");
    o.progress = false;
    bw::sim::Simulation simulation(scene, device, o);
    bw::sim::CheckpointHeader h;
    h.tool = "bench-checkpoint";
    h.device = bw::sim::device_identity(device);
    h.scene_text = scene.text;
    h.end_time = 1.0;
    h.rows.resize(1);
    std::filesystem::create_directories(dir.file("run"));
    const std::string path = dir.file("run/checkpoint.h5");
    std::vector<double> writes, reads;
    for (int round = 0; round < 3; ++round) {
      bw::Stopwatch w;
      bw::sim::write_checkpoint(path, h, simulation.solver());
      writes.push_back(w.seconds());
      bw::Stopwatch r;
      bw::sim::read_checkpoint_state(path, simulation.solver());
      reads.push_back(r.seconds());
    }
    const double mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
    const std::int64_t particles = simulation.solver().fluid_count();
    std::printf("checkpoint of %lld fluid particles (%lld boundary): %.1f MB\n", static_cast<long long>(particles),
                static_cast<long long>(simulation.solver().boundary_count()), mb);
    std::printf("  write  best %.3f s, median %.3f s (%.0f MB/s)\n", *std::min_element(writes.begin(), writes.end()),
                median(writes), mb / median(writes));
    std::printf("  read   best %.3f s, median %.3f s\n", *std::min_element(reads.begin(), reads.end()), median(reads));
    bw::test::figure("checkpoint_write_seconds", median(writes), "s");
  }

  {
    bw::test::TempDir dir;
    const double end = 0.5;
    const bw::scene::Scene scene = dam(dir, 20, end);  // 16 k particles
    double start_seconds = 0, write_seconds = 0;  // of the last run: its start, its checkpoints
    auto run = [&](const std::string& out, int stop_after, bool resume) {
      bw::sim::RunOptions o;
      o.output = dir.file(out);
      o.progress = false;
      o.stop_after_frame = stop_after;
      o.resume = resume;
      bw::Stopwatch clock;
      bw::sim::Simulation simulation(scene, device, o);
      start_seconds = clock.seconds();
      write_seconds = simulation.run().checkpoint_seconds;
      return clock.seconds();
    };
    run("warm", 2, false);  // kernels compiled and cached once before timing
    std::vector<double> whole, parts, extra;
    for (int round = 0; round < 2; ++round) {
      whole.push_back(run(std::string("whole") + char('0' + round), -1, false));
      const std::string out = std::string("parts") + char('0' + round);
      const double first = run(out, 15, false);
      const double written = write_seconds;
      parts.push_back(first + run(out, -1, true));
      extra.push_back(written + start_seconds);  // what a resume adds: the checkpoint, one more start
    }
    const double w = *std::min_element(whole.begin(), whole.end()), p = *std::min_element(parts.begin(), parts.end());
    std::printf("resume: 16 k particles, %.1f s simulated: whole %.2f s, stopped at frame 15 and resumed %.2f s: "
                "%+.1f%%\n",
                end, w, p, 100 * (p / w - 1));
    const double e = *std::min_element(extra.begin(), extra.end());
    std::printf("  what resuming adds: checkpoint written and one more start (kernels, setup, checkpoint read) "
                "%.2f s, %.1f%% of the whole run\n",
                e, 100 * e / w);
    bw::test::figure("resume_overhead_percent", 100 * (p / w - 1), "%");
    bw::test::figure("resume_added_percent", 100 * e / w, "%");
  }
  return 0;
}

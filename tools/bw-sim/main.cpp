// bw-sim: simulate a scene (WCSPH fluid on OpenCL with static solids) into frame
// files and a run file.
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cli/tool.h"
#include "compute/device.h"
#include "render/render_settings.h"
#include "scene/scene.h"
#include "sim/checkpoint.h"
#include "sim/run.h"

namespace {

struct Options {
  std::string scene;
  std::string output;
  std::string device;  // empty: auto (a resumed run: the checkpoint's device)
  double end_time = 0;
  int checkpoint_every = -1;
  std::string resume;  // OUTDIR
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
  bool quiet = false;

  bool listing() const { return device == "list"; }
  // One message per broken constraint (CLI11 checks types and ranges).
  void validate() const {
    if (listing()) return;
    if (!resume.empty()) {
      if (!output.empty() && std::filesystem::path(output).lexically_normal() != std::filesystem::path(resume).lexically_normal())
        bw::fail_input("--resume {} and -o {}: a resumed run writes where it started (leave out -o)", resume, output);
    } else {
      if (scene.empty()) bw::fail_input("no scene given (bw-sim SCENE -o OUTDIR; see --help)");
      if (output.empty()) bw::fail_input("no output folder given (-o OUTDIR)");
    }
    if (!device.empty() && !bw::compute::valid_device_choice(device))
      bw::fail_input("--device: '{}' is not auto, cpu, gpu, list or a device number", device);
  }
};

// The device a checkpoint was made on, when this machine has it.
bw::compute::DeviceInfo device_of_checkpoint(const std::string& path, const std::string& label) {
  for (const auto& d : bw::compute::list_devices())
    if (bw::sim::device_identity(d) == label) return d;
  bw::fail_input("{}: made on {}, which this machine does not have (bw-sim --device list): a run goes on "
                 "bit-identically only on the device it started on",
                 path, label);
}

int list_devices() {
  const auto devices = bw::compute::list_devices();
  if (devices.empty()) {
    std::printf("no OpenCL device (install an OpenCL driver, e.g. pocl-opencl-icd)\n");
    return bw::kExitOk;
  }
  for (const auto& d : devices) std::printf("%s\n", d.describe().c_str());
  return bw::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Simulate a scene: a weakly compressible SPH fluid on OpenCL with static solids and\n"
               "emitters, written as OUTDIR/frames/NNNNNN.h5 and OUTDIR/run.h5.",
               "bw-sim"};
  bw::cli::setup(app,
                 "  bw-sim examples/dambreak.toml -o out/dambreak\n"
                 "  bw-sim scene.toml -o out/scene --end-time 0.5 --device cpu --quiet\n"
                 "  bw-sim examples/dambreak.toml -o out/fine --set spacing=0.005 --set fluid.c0=40 \\\n"
                 "      --set 'solid[0].particles=../out/examples/tank-0.005.h5'\n"
                 "  bw-sim scene.toml -o out/scene --checkpoint-every 10   # then, after SIGTERM or a crash:\n"
                 "  bw-sim --resume out/scene\n"
                 "  bw-sim --device list\n"
                 "  bw-info out/dambreak/run.h5 --json\n");
  Options o;
  app.add_option("scene", o.scene, "Scene file (TOML, docs/scene.md)");
  app.add_option("-o,--output", o.output, "Output folder: frames/NNNNNN.h5 and run.h5 go there");
  app.add_option("--device", o.device, "OpenCL device: auto (a GPU if there is one), cpu, gpu, a number, or list")
      ->capture_default_str();
  app.add_option("--end-time", o.end_time, "Simulate up to this time instead of the scene's time.end (s)")
      ->check(bw::cli::kPositive);
  app.add_option("--set", o.overrides,
                 "Override a scene key, KEY=VALUE (repeatable): time.cfl=0.2, fluid.block[0].max=[0.1, 0.15, 0.2], "
                 "solid[0].particles=tank.h5; KEY+=VALUE appends to an array: output.fields+=[\"wall_pressure\"] "
                 "(docs/scene.md)")
      ->allow_extra_args(false);  // one KEY=VALUE per --set: the scene may follow it
  app.add_option("--checkpoint-every", o.checkpoint_every,
                 "Write OUTDIR/checkpoint.h5 every N frames (0: only when SIGTERM or SIGINT stops the run; default: the "
                 "scene's output.checkpoint_every)")
      ->check(CLI::Range(0, 1000000));
  app.add_option("--resume", o.resume,
                 "Go on from OUTDIR/checkpoint.h5, appending frames and run-file rows (the scene, its end time and the "
                 "device are the checkpoint's; SCENE, when given, must be the same)");
  app.add_flag("-q,--quiet", o.quiet, "No progress line and no summary");

  // From the start: a stop requested while the kernels compile still ends with the
  // first frame and a checkpoint.
  bw::sim::install_stop_handlers();
  return bw::cli::run(app, argc, argv, [&]() -> int {
    o.validate();
    if (o.listing()) return list_devices();
    bw::sim::RunOptions options;
    options.output = o.resume.empty() ? o.output : o.resume;
    options.end_time = o.end_time;
    options.progress = !o.quiet;
    options.checkpoint_every = o.checkpoint_every;
    bw::scene::Scene scene;
    bw::compute::DeviceInfo device;
    if (!o.resume.empty()) {
      // The checkpoint names the scene (its effective text), the end time and the
      // device; Simulation refuses a checkpoint that does not fit them.
      const std::string path = bw::sim::checkpoint_path(o.resume);
      bw::sim::require_checkpoint(o.resume);
      const bw::sim::CheckpointHeader h = bw::sim::read_checkpoint_header(path);
      scene = o.scene.empty() ? bw::scene::parse_scene(h.scene_text, h.scene_path)
                              : bw::scene::load_scene(o.scene, o.overrides);
      if (o.scene.empty() && !o.overrides.empty())
        bw::fail_input("--set: a resumed run goes on with the scene of its checkpoint; give no --set");
      if (o.end_time <= 0) options.end_time = h.end_time;
      if (o.checkpoint_every < 0) options.checkpoint_every = h.checkpoint_every;
      device = o.device.empty() ? device_of_checkpoint(path, h.device) : bw::compute::choose_device(o.device);
      options.resume = true;
    } else {
      scene = bw::scene::load_scene(o.scene, o.overrides);
      // bw-render's tables too, so that a long run does not end in a scene it cannot draw.
      const bw::render::RenderSettings look = bw::render::parse_render_settings(scene.text, scene.path);
      if (!look.camera_track.empty() && !bw::scene::may_have_body(scene, look.camera_track)) {
        const std::string bodies = bw::scene::body_names(scene);
        bw::fail_input("{}: camera.track: '{}' is not a body of the scene ({})", scene.path, look.camera_track,
                       bodies.empty() ? "it has none: dynamic, breakable and moving solids are bodies"
                                      : "its bodies: " + bodies + ", and the fragments of breakable ones, 'NAME.N'");
      }
      if (look.solids == bw::render::SolidColoring::kWallPressure && !scene.fields.wall_pressure)
        bw::fail_input("{}: render.solids: \"wall_pressure\" colours the solids by a field the frames would not "
                       "hold; add \"wall_pressure\" to [output] fields",
                       scene.path);
      device = bw::compute::choose_device(o.device.empty() ? "auto" : o.device);
    }
    bw::sim::Simulation simulation(scene, device, options);
    const bw::sim::RunSummary summary = simulation.run();
    if (summary.stop_signal) {
      // Always said, also with --quiet: the run did not finish.
      std::fprintf(stderr,
                   "bw-sim: stopped by %s after frame %d (t = %.6g s); checkpoint %s; go on with: bw-sim --resume %s\n",
                   summary.stop_signal == SIGINT ? "SIGINT" : "SIGTERM", summary.frames - 1, summary.simulated,
                   summary.checkpoint.c_str(), options.output.c_str());
      return 128 + summary.stop_signal;
    }
    if (!o.quiet) {
      std::fprintf(stderr, "bw-sim: %s -> %s%s\n%s", o.scene.empty() ? scene.path.c_str() : o.scene.c_str(),
                   options.output.c_str(),
                   summary.resumed_from >= 0 ? fmt::format(" (resumed after frame {})", summary.resumed_from).c_str() : "",
                   bw::sim::format_summary(summary).c_str());
    }
    return bw::kExitOk;
  });
}

// bw-sim: simulate a scene (WCSPH fluid on OpenCL with static solids) into frame
// files and a run file.
#include <cstdio>

#include "cli/tool.h"
#include "compute/device.h"
#include "scene/scene.h"
#include "sim/run.h"

namespace {

struct Options {
  std::string scene;
  std::string output;
  std::string device = "auto";
  double end_time = 0;
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
  bool quiet = false;

  bool listing() const { return device == "list"; }
  // One message per broken constraint (CLI11 checks types and ranges).
  void validate() const {
    if (listing()) return;
    if (scene.empty()) bw::fail_input("no scene given (bw-sim SCENE -o OUTDIR; see --help)");
    if (output.empty()) bw::fail_input("no output folder given (-o OUTDIR)");
    if (!bw::compute::valid_device_choice(device))
      bw::fail_input("--device: '{}' is not auto, cpu, gpu, list or a device number", device);
  }
};

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
                 "solid[0].particles=tank.h5 (docs/scene.md)")
      ->allow_extra_args(false);  // one KEY=VALUE per --set: the scene may follow it
  app.add_flag("-q,--quiet", o.quiet, "No progress line and no summary");

  return bw::cli::run(app, argc, argv, [&]() -> int {
    o.validate();
    if (o.listing()) return list_devices();
    const bw::scene::Scene scene = bw::scene::load_scene(o.scene, o.overrides);
    const bw::compute::DeviceInfo device = bw::compute::choose_device(o.device);
    bw::sim::RunOptions options;
    options.output = o.output;
    options.end_time = o.end_time;
    options.progress = !o.quiet;
    bw::sim::Simulation simulation(scene, device, options);
    const bw::sim::RunSummary summary = simulation.run();
    if (!o.quiet) {
      std::fprintf(stderr, "bw-sim: %s -> %s\n%s", o.scene.c_str(), o.output.c_str(),
                   bw::sim::format_summary(summary).c_str());
    }
    return bw::kExitOk;
  });
}

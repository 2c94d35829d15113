// A whole simulation run: frames, the run file, progress and the summary (what
// bw-sim does between parsing its options and printing its summary).
//
// Output (docs/formats.md): OUTDIR/frames/NNNNNN.h5 for frames 0, 1, ... at times
// frame / frame_rate up to the end time, and OUTDIR/run.h5, rewritten (atomically)
// after every frame with the statistics so far and status "running", then
// "complete", or the error that stopped the run. Frames written before an error stay
// valid. Checkpoints (sim/checkpoint.h) every RunOptions::checkpoint_every frames and
// on SIGTERM or SIGINT; a run resumed from one appends frames and rows as if it had
// never stopped.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compute/device.h"
#include "scene/scene.h"
#include "sim/solver.h"

namespace bw::sim {

struct RunOptions {
  std::string output;          // OUTDIR
  double end_time = 0;         // > 0: replaces the scene's time.end
  bool progress = true;        // a progress line on stderr when it is a terminal
  std::string tool = "bw-sim"; // recorded in the run file with the version
  // Frames between checkpoints (OUTDIR/checkpoint.h5; sim/checkpoint.h); 0: only when
  // stopped by SIGTERM or SIGINT; -1: the scene's output.checkpoint_every.
  int checkpoint_every = -1;
  // Go on from OUTDIR/checkpoint.h5 instead of starting: the checkpoint must be of
  // this scene (its text and files), this tool's version and this device.
  bool resume = false;
  // Stop after this frame as on SIGTERM (with a checkpoint); -1: run to the end.
  int stop_after_frame = -1;
};

struct RunSummary {
  int frames = 0;                      // frames written
  std::int64_t steps = 0;
  double simulated = 0;                // s
  double wall_seconds = 0;
  double particle_steps = 0;           // sum over steps of the fluid particles
  double dt_min = 0, dt_max = 0;
  double worst_density_error = 0;      // max over frames of max(0, rho/rho0 - 1)
  int worst_density_frame = 0;
  double worst_density_time = 0;       // s
  double mean_density_error = 0;       // mean over frames of the frame means
  // The total: kinetic + potential + elastic, less what the emitters and moving solids
  // put in, plus what left the domain (J).
  double energy_start = 0, energy_end = 0;
  double energy_highest = 0;           // largest total over the frames (J)
  double energy_max_rise = 0;          // largest rise of the total between frames (J)
  double emitted_energy = 0;           // what emitters and moving solids put in by the end (J)
  double outflow_energy = 0;           // what left the domain by the end (J)
  std::int64_t fluid_end = 0, removed = 0, boundary = 0;
  // fluid.wall_pressure = "images": at frame 0, the fluid particles within h of a
  // solid and how many of them had mirror planes (Solver::image_coverage; -1: another
  // wall, or a checkpoint of an earlier version).
  std::int64_t images_near = -1, images_imaged = -1;
  // (energy_end - energy_start) / scale and (energy_highest - energy_start) / scale:
  // what the run lost (negative) and the most it ever gained, scale the larger of
  // |energy_start| and emitted_energy.
  double energy_scale() const;
  double energy_drift() const;
  double energy_growth() const;
  bool emitters_capped = false;
  std::uint64_t device_bytes = 0;
  std::int64_t capacity = 0;
  std::string device;
  // Checkpoints: the frame a resumed run went on from (-1: it started at frame 0),
  // and, when the run stopped on SIGTERM or SIGINT, the signal (0: it ran to the
  // end) and the checkpoint it left.
  int resumed_from = -1;
  bool stopped = false;                // before the end, with a checkpoint
  int stop_signal = 0;
  std::string checkpoint;
  double checkpoint_seconds = 0;       // wall time spent writing checkpoints
  int checkpoints = 0;
};

class Simulation {
 public:
  // Checks the scene against everything it needs (particle files, sizes, memory),
  // compiles the kernels and uploads the initial state; writes nothing. Throws
  // InputError for bad input, RunError for a device failure.
  Simulation(const scene::Scene& scene, const compute::DeviceInfo& device, RunOptions options);
  ~Simulation();

  // Runs to the end, writing frames and the run file. Throws RunError when the run
  // stops on an error (after recording it in the run file).
  RunSummary run();

  Solver& solver();
  const Setup& setup() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The checkpoint a run in `output` left (OUTDIR/checkpoint.h5).
std::string checkpoint_path(const std::string& output);
// Throws InputError saying why when OUTDIR has no checkpoint (none written, or the
// run is complete).
void require_checkpoint(const std::string& output);

// Lines for people: steps, wall time, throughput, particles lost, density error,
// energy drift.
std::string format_summary(const RunSummary& summary);

// The summary as the run file's /summary values (docs/formats.md).
std::vector<std::pair<std::string, double>> summary_values(const RunSummary& summary);

}  // namespace bw::sim

// Checkpoints of a run (bw-sim --checkpoint-every, SIGTERM and SIGINT, --resume;
// docs/formats.md, kind "checkpoint").
//
// A checkpoint is taken just after a frame was written: the solver's whole state
// (Solver::save_state: the fluid's per-particle state, emitters, bodies and their
// contact memory, the fracture stage and its load memory, counters and energies)
// and what the run driver accumulates for the run file. A run resumed from it on the
// same device writes the same frames and run-file rows, bit for bit, as a run that
// was never stopped (wall times aside). There is no random state: nothing in the
// simulator draws random numbers.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "compute/device.h"
#include "io/run_file.h"
#include "sim/setup.h"
#include "sim/solver.h"

namespace bw::sim {

// Version of the checkpoint layout; a checkpoint of another version is refused.
inline constexpr int kCheckpointVersion = 1;
// OUTDIR/checkpoint.h5: one per run, replaced (atomically) by each new one, removed
// when the run completes.
inline constexpr const char* kCheckpointFile = "checkpoint.h5";

// What a checkpoint was made of and for, and where the run stood.
struct CheckpointHeader {
  int version = kCheckpointVersion;
  std::string tool;          // tool and version that wrote it
  std::string device;        // device_identity()
  std::string scene_text;    // Scene::text (with --set: the effective scene)
  std::string scene_path;    // absolute
  std::string fingerprint;   // setup_fingerprint() of the run's setup
  int frame = 0;             // the last frame written
  double time = 0;           // s, the solver's time (frame / frame_rate)
  double end_time = 0;       // s, what the run goes to
  int checkpoint_every = 0;  // frames
  // The run driver's accumulators (run.cpp), by name, and the run file's rows up to
  // `frame`: a checkpoint resumes without the run file.
  std::vector<std::pair<std::string, double>> run_values;
  std::vector<FrameStats> rows;
  std::vector<std::vector<Vec3d>> loads;  // the run file's /loads rows (with [output] loads)

  double value(const std::string& name) const;
  // The same, or `fallback` where the checkpoint (of an earlier version) has none.
  double value_or(const std::string& name, double fallback) const;
};

// What a run's results depend on of its device: the label, the compute units (the
// reductions' blocks follow them) and the driver.
std::string device_identity(const compute::DeviceInfo& device);

// A digest of what the scene's files put into the setup (particles, bodies, voxels,
// emitters and parameters): a checkpoint is refused when its files changed.
std::string setup_fingerprint(const Setup& setup);

// Writes the checkpoint through a temporary file (a checkpoint under its final name
// is always whole).
void write_checkpoint(const std::string& path, const CheckpointHeader& header, Solver& solver);
// Throws InputError naming the file when it is not a checkpoint of this version.
CheckpointHeader read_checkpoint_header(const std::string& path);
// Loads the solver's state (Solver::load_state) from the checkpoint.
void read_checkpoint_state(const std::string& path, Solver& solver);

// Stop requests. The handlers of SIGTERM and SIGINT only record the signal
// (async-signal-safe) and restore the default action, so that a second signal ends
// the process at once; the run checks stop_signal() between steps, finishes the
// frame it is in, writes a checkpoint and stops (RunStopped).
void install_stop_handlers();
int stop_signal();  // the signal received, 0 when none

}  // namespace bw::sim

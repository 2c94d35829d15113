// Files of kind "run": what a simulation was given and what it did, frame by frame
// (docs/formats.md). Written by bw-sim after every frame, read by bw-info,
// bw-voronoi replay and bw-render.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/geometry.h"

namespace bw {

struct SolidRecord {
  std::string name;
  std::string particles;          // absolute path of the particle file
  std::string kind;               // "static", "moving", "dynamic" or "breakable"
  Vec3d translation = Vec3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  double scale = 1;
  std::int32_t body = -1;         // body of a moving, dynamic or breakable solid
};

struct BodyRecord {
  std::string name;
  std::int32_t solid = -1;        // root solid
  std::int32_t parent = -1;       // parent body of a fragment, -1 otherwise
  double mass = 0;
  Mat3d inertia = Mat3d::Zero();  // about the centre of mass, reference frame
  Vec3d reference_center = Vec3d::Zero();
  double created_time = 0;
  std::int32_t voxels = 0;
};

// One row per written frame.
struct FrameStats {
  std::int32_t frame = 0;
  double time = 0;
  std::int64_t steps = 0;         // since the start
  double dt_min = 0, dt_max = 0;  // over the steps since the previous frame
  std::int64_t fluid = 0, boundary = 0, removed = 0;
  double density_error_max = 0, density_error_mean = 0;
  double kinetic_energy = 0, potential_energy = 0;
  double wall_time = 0;           // seconds since the start of the run
  double elastic_energy = 0;      // J, stored by compression (Tait law)
  double speed_max = 0;           // m/s, fastest fluid particle
  double emitted_energy = 0;      // J the emitters have put in since the start
  double outflow_energy = 0;      // J carried out of the domain since the start
};

struct FractureEvent {
  double time = 0;
  std::int32_t parent = -1;              // body that broke
  std::vector<Vec3d> seeds;              // reference configuration
  std::vector<std::int32_t> child_body;  // one entry per child
  std::vector<std::int32_t> child_seed;  // index into seeds
  std::vector<std::int32_t> child_component;
};

// With [[sensor]]s: what each sensor read (docs/formats.md, /sensors): sample k is the
// mean pressure on its disc over [k, k + 1] x interval (Pa).
struct SensorRecord {
  std::vector<std::string> names;
  std::vector<Vec3d> at, normal;    // on the face; unit, out of the solid
  std::vector<double> radius;       // m
  std::vector<std::int64_t> particles;  // boundary particles it reads
  double interval = 0;              // s
  std::vector<double> pressure;     // samples x sensors, sample-major
  std::size_t samples() const { return names.empty() ? 0 : pressure.size() / names.size(); }
  // The mean of sensor `sensor`'s samples whose middle is at or after `from` (s), and
  // how many there were (NaN and 0 when none).
  double mean_from(std::size_t sensor, double from, int* count = nullptr) const {
    double sum = 0;
    int n = 0;
    for (std::size_t k = 0; k < samples(); ++k)
      if ((static_cast<double>(k) + 0.5) * interval >= from) {
        sum += pressure[k * names.size() + sensor];
        ++n;
      }
    if (count) *count = n;
    return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
  }
};

struct RunRecord {
  std::string scene_text;
  std::string scene_path;
  std::string device;
  std::string tool;
  std::string status = "running";       // "complete", "running", or the error
  std::vector<SolidRecord> solids;
  std::vector<BodyRecord> bodies;
  std::vector<FrameStats> frames;
  std::vector<FractureEvent> fractures;
  // Derived values the simulator used (particle mass, smoothing length, stiffness,
  // ...), by name, so that a run can be understood and reproduced from its output.
  std::vector<std::pair<std::string, double>> parameters;
  // The parameter of that name (/parameters/NAME), if the run has it.
  std::optional<double> parameter(const std::string& name) const;
  // The run so far at its last written frame, by name: run time next to its error
  // indicators (worst density error, energy drift, particles lost), so that a run's
  // cost and quality read from one place (docs/formats.md lists the names).
  std::vector<std::pair<std::string, double>> summary;
  // With [output] loads: per frame, per scene solid (the order of `solids`), the
  // impulse of the fluid and of contacts on it since t = 0 (N s; docs/formats.md,
  // /loads). Empty otherwise.
  std::vector<std::vector<Vec3d>> loads;
  SensorRecord sensors;             // no names without sensors
};

// Every solid's mesh in its reference configuration, x_ref = t + R (s x_mesh), from
// its particle file (each file read once), in /solids order. Throws InputError naming
// the run file and the solid when a particle file cannot be read.
std::vector<TriMesh> reference_meshes(const RunRecord& run, const std::string& run_path);

// Writes the whole record through a temporary file (called after every frame).
void write_run(const RunRecord& run, const std::string& path);
RunRecord read_run(const std::string& path);

}  // namespace bw

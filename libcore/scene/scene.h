// Scene files (TOML): what bw-sim simulates. docs/scene.md is the reference of every
// key with its unit and default; this header is its in-memory form.
//
// Loading checks everything that can be checked without a device: syntax, unknown
// keys, types, ranges, that particle files exist, that blocks and emitters lie in the
// domain. Errors are InputError with one line naming the file and the key's path:
//   "scene.toml: solid[2].scale: -1 must be positive"
// Scenes are z-up, in SI units (m, s, kg). Paths are relative to the scene file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/geometry.h"
#include "io/frame_file.h"

namespace bw::scene {

struct TimeSettings {
  double end = 0;              // s, > 0 (required)
  double frame_rate = 60;      // frames per second
  double dt_min = 1e-6;        // s
  double dt_max = 2e-3;        // s
  double cfl = 0.4;            // lambda_v: dt <= cfl h / (c + max|v|), c the signal speed (sim/setup.h)
  double force_factor = 0.25;  // lambda_f: dt <= force_factor sqrt(h / max|a|)
  double viscous_factor = 0.125;  // dt <= viscous_factor h^2 rho0 / max(mu, mu_b)
  double diffusion_factor = 1;  // dt <= diffusion_factor / the largest density diffusion rate
  double energy_limit = 0.1;  // the run stops where its total energy rises this fraction above its start; 0: never
};

// How the fluid's density is found (docs/scene.md, "Density").
enum class DensityScheme { continuity, summation };
// The pressure a boundary particle stands for in the boundary force (docs/scene.md,
// "Density"): the fluid particle's own, or the wall's own, extrapolated from the fluid.
// "images": the hydrostatic wall, with the flat faces of static solids mirror images of
// the fluid in place of their particles where the wall there is those faces alone.
enum class WallPressure { mirrored, hydrostatic, images };

struct FluidSettings {
  double rho0 = 998;           // kg/m^3
  double k = 0;                // Tait stiffness (Pa); 0 = from c0
  double c0 = 0;               // speed of sound (m/s); 0 = 10 x the scene's largest speed
  double gamma = 7;
  double mu = 0.05;            // viscosity (Pa s)
  double mu_b = 0.05;          // boundary friction (Pa s); default: mu
  double gamma1 = -1;          // weight of the boundary term in the density; < 0: calibrated
                               // so that fluid one spacing from a flat wall has rho0
  double gamma2 = -1;          // weight of the boundary pressure force; < 0: gamma1 / 2, or gamma1
                               // with the hydrostatic wall pressure
  std::int64_t max_particles = 0;  // MFP; 0 = what the blocks and emitters need
  DensityScheme density = DensityScheme::continuity;
  double diffusion = 0.1;      // delta of the density diffusion (continuity only); 0: none
  WallPressure wall_pressure = WallPressure::images;  // continuity only; summation: mirrored
  // One draw of an ensemble (docs/scene.md, "Draws"): 0 leaves the blocks on their lattice;
  // N >= 1 moves each block particle off its lattice point by a uniform offset of up to
  // `jitter` spacings per axis, the same for the same N on every device.
  std::int64_t seed = 0;
  double jitter = 1e-3;        // spacings, in (0, 0.1]; only with seed >= 1
};

// A box filled with fluid particles on a cubic lattice of the scene's spacing:
// points min + (i + 1/2) spacing (per axis) that lie inside the box.
struct Block {
  Vec3d min = Vec3d::Zero(), max = Vec3d::Zero();
  Vec3d velocity = Vec3d::Zero();  // m/s
};

// A disc or rectangle that injects fluid along its normal at `speed` from `start`
// to `stop`: one layer of particles every time the fluid has moved one spacing.
struct Emitter {
  enum class Shape { disc, rectangle };
  Shape shape = Shape::disc;
  Vec3d center = Vec3d::Zero();
  Vec3d normal = Vec3d::UnitZ();   // unit, direction of the flow
  double radius = 0;               // disc (m)
  Eigen::Vector2d size = Eigen::Vector2d::Zero();  // rectangle: along `up` x normal and `up` (m)
  Vec3d up = Vec3d::Zero();        // rectangle: in-plane direction of size[1]; zero = automatic
  double speed = 0;                // m/s, > 0
  double start = 0;                // s
  double stop = 0;                 // s; infinity (the default): until the end of the run
};

// A solid sampled by bw-sample: static (its boundary particles stay put), dynamic
// (a rigid body pushed by the fluid and by contacts, docs/scene.md) or breakable (a
// body that the fluid's load can break into fragments, method.md 3 and 4).
struct Solid {
  std::string name;                // default: the particle file's stem
  std::string particles;           // absolute path of the particle file
  std::string particles_given;     // the path as written in the scene
  Vec3d translation = Vec3d::Zero();
  Vec3d rotation_degrees = Vec3d::Zero();  // about x, then y, then z (fixed axes)
  double scale = 1;
  bool dynamic = false;            // a rigid body (needs voxels and a density)
  double density = 0;              // kg/m^3, > 0 (required when dynamic; breakable: 2400)
  Vec3d velocity = Vec3d::Zero();          // dynamic: initial velocity of the centre of mass (m/s)
  Vec3d angular_velocity = Vec3d::Zero();  // dynamic: initial angular velocity, world frame (rad/s)
  double friction = 0.5;           // Coulomb coefficient of contacts with bodies, >= 0
  double restitution = 0.3;        // of contacts with bodies, in [0, 1]
  bool breakable = false;          // a body that fractures (needs voxels; density defaults)
  double frc = 0.5;                // fracture resistance coefficient, in (0, 1]
  bool anchored = true;            // breakable: fixed until it breaks; then the fragments
                                   // touching what it stood on stay fixed
  // A static solid moved as told (docs/scene.md, "Moving solids"). `motion`: the
  // velocity of its points (of the pivot when it also turns) at these times, linear
  // between them (rigid/motion.h); empty: it does not translate.
  std::vector<double> motion_times;
  std::vector<Vec3d> motion_velocities;
  // `angular_motion`: its angular velocity (rad/s) about `axis` through `pivot` at
  // these times, linear between them; empty: it does not turn.
  std::vector<double> angular_times;
  std::vector<double> angular_rates;
  Vec3d axis = Vec3d::UnitY();      // unit, right-hand rule
  Vec3d pivot = Vec3d::Zero();      // a point of the axis at t = 0 (world, m)
  // A rigid body of the solver: dynamic or breakable.
  bool body() const { return dynamic || breakable; }
  bool moving() const { return !motion_times.empty() || !angular_times.empty(); }
  // x_world = rotation * (scale * x_file) + translation
  Eigen::Quaterniond rotation() const;
  Vec3d to_world(const Vec3d& p) const;
};

// [fracture]: the energy criterion and the fragments (method.md 3 and 4, docs/scene.md).
struct FractureSettings {
  double window = 0.005;           // s: memory of the load's impulse (exponential)
  double energy_scale = 2.0;       // J/m: bond energy E_sigma = frc x energy_scale x spacing
  std::int64_t max_chunks = 64;    // MSC: most bodies of breakable origin at once
};

// [[sensor]]: a pressure sensor on a face of a static solid (docs/scene.md,
// "Sensors"; sim/sensors.h): what a membrane of `radius` at `at` feels, from the
// forces of the fluid on the face's boundary particles.
struct Sensor {
  std::string name;
  Vec3d at = Vec3d::Zero();
  Vec3d normal = Vec3d::Zero();    // unit, out of the solid into the fluid; zero: the face's own
  double radius = 0;               // m; 0: the pressure at the point
  std::int32_t solid = -1;         // scene index of the solid; -1: any static solid
};

struct Scene {
  std::string path;                // as given
  std::string text;                // the file's text
  std::string folder;              // absolute folder of the scene file
  double spacing = 0;              // particle spacing (m), > 0 (required)
  double smoothing_length = 0;     // h (m); default 2 x spacing
  Vec3d gravity = Vec3d(0, 0, -9.81);
  TimeSettings time;
  FluidSettings fluid;
  std::vector<Block> blocks;
  std::vector<Emitter> emitters;
  std::vector<Solid> solids;
  FractureSettings fracture;
  Aabb domain;                     // required
  FrameFields fields;              // what frames hold besides positions
  std::vector<std::string> field_names;
  bool loads = false;              // [output] loads: the run file records each solid's load
  int checkpoint_every = 0;        // output.checkpoint_every: frames between checkpoints, 0: none
  std::vector<Sensor> sensors;
  double sensor_rate = 1000;       // output.sensor_rate: samples per second of each sensor (Hz)
};

// The number of a run's last frame: frame f is written at f / frame_rate, the last
// one at or before `end` (up to rounding). Only for end times check_end_time accepts.
int last_frame(double end, double frame_rate);

// Checks an end time given for a run of `s` in place of its time.end (bw-sim
// --end-time) against the limits the scene's own is held to: at least one frame, at
// most as many frames and sensor samples as a run file holds. Throws InputError
// naming `what`, where the time came from.
void check_end_time(const Scene& s, double end, const std::string& what);

// Whether a run of `s` can have a body named `name`: a dynamic, breakable or moving
// solid's own, or a fragment of a breakable one ("plate.12", "plate.12.3": its
// parent's name, a dot and a number, as the fracture names them).
bool may_have_body(const Scene& s, const std::string& name);

// The names of the solids that are bodies, for messages ("crate, plate").
std::string body_names(const Scene& s);

// Reads and checks a scene file. Throws InputError "<path>: <key>: <problem>".
// `overrides` ("KEY=VALUE", bw-sim --set; scene/overrides.h) replace keys of the file
// before it is checked; Scene::text is then the effective scene as TOML, headed by a
// comment naming the file and the overrides, so that a run records what it ran.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Parses scene text; `path` names it in messages and anchors relative paths.
Scene parse_scene(std::string_view text, const std::string& path, const std::vector<std::string>& overrides = {});

// The field names [output] fields accepts.
const std::vector<std::string>& field_names();

}  // namespace bw::scene

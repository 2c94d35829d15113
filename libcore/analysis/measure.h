// Measuring simulated frames: quantities that validation and users compare against
// experiments and analytic solutions.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "io/frame_file.h"

namespace bw::analysis {

// The frame files (NNNNNN.h5) of a folder, in frame order. Throws InputError naming
// the folder when it does not exist or holds no frame.
std::vector<std::string> list_frames(const std::string& folder);

// The fields a probe can read.
enum class Field { pressure, density, speed, vx, vy, vz };
Field parse_field(const std::string& name);  // "p", "rho", "speed", "vx", ...
const char* field_name(Field field);

// Shepard-normalised kernel average (poly6 weights, support h) of a field of the
// fluid particles at `point`: sum_j f_j W_j / sum_j W_j. NaN when no fluid particle
// lies within h. Throws InputError when the frame does not hold the field.
double probe(const FrameData& frame, Field field, const Vec3d& point, double h);

// A pressure sensor on a solid's face (bw-measure sensor): a disc of `radius` (0: a
// point) centred at `point` on the face, `normal` the face's unit normal into the
// fluid. It reads the mean over its disc of the fluid's pressure extrapolated to the
// face: at sample points `offset` into the fluid (by default h / 2, inside the
// first layer of fluid, which rests half a spacing from the face), the Shepard
// average of probe() with support h, less the hydrostatic rise over the offset,
// rho0 g.normal offset. NaN when no sample point has fluid within h.
struct Sensor {
  std::string name;
  Vec3d point = Vec3d::Zero();
  Vec3d normal = Vec3d::UnitX();
  double radius = 0;
  double h = 0;
  double offset = -1;              // < 0: h / 2
  double rho0 = 998;
  Vec3d gravity{0, 0, -9.81};
  // The sample points (equal weights): the disc's centre and rings around it.
  std::vector<Vec3d> samples() const;
};
double sensor_pressure(const FrameData& frame, const Sensor& sensor);

// The free-surface elevation a wave gauge measures on the vertical line through
// (x, y): the centre of the highest fluid particle within `radius` of the line that
// the water column holds, climbing from the lowest particle (or from `bottom`, the
// floor under the gauge) up through the particles over the line and stopping at the
// first vertical gap wider than `gap`. A resistance gauge's wire reads the water it
// stands in, not the spray that flies over it; gap = infinity reads the highest
// particle. NaN when the line is dry: no particle, or (with a bottom) the lowest
// more than `gap` above it.
double surface_elevation(const FrameData& frame, double x, double y, double radius,
                         double gap = std::numeric_limits<double>::infinity(),
                         double bottom = -std::numeric_limits<double>::infinity());

// What a frame's wall pressure (field "wall_pressure", docs/formats.md) says of one
// solid: the highest patch pressure over its particles, where it is, and the mean over
// the loaded patches (those the frame's mean pressure is not 0 on: the fluid or a
// contact touched them during the interval). peak and mean NaN, and loaded 0, when no
// patch was loaded. Throws InputError when the frame lacks boundary/p or boundary/solid.
struct WallLoad {
  double peak = 0;
  Vec3d at = Vec3d::Zero();
  double mean = 0;
  std::size_t loaded = 0;   // patches
};
WallLoad wall_load(const FrameData& frame, int solid, const std::string& where);

}  // namespace bw::analysis

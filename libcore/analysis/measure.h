// Measuring simulated frames: quantities that validation and users compare against
// experiments and analytic solutions.
#pragma once

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

// Highest fluid particle within `radius` of the vertical line through (x, y):
// the free-surface elevation a wave gauge measures. NaN when there is none.
double surface_elevation(const FrameData& frame, double x, double y, double radius);

}  // namespace bw::analysis

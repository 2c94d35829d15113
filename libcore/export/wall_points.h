// The pressure on the solids as points: a frame's boundary particles with their wall
// pressure (the frames' wall_pressure field, docs/formats.md), written as an OpenVDB
// point data grid "wall_pressure" (the format Houdini's VDB Points nodes and OpenVDB's
// own tools read): positions "P" (metres, in the export's up axis), "pressure" (float,
// Pa, the patch's mean over the frame's interval) and "solid" (int32, the run file's
// solid row). This header keeps OpenVDB out of its users.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "export/water.h"
#include "io/frame_file.h"

namespace bw::exporter {

struct WallPoint {
  Vec3d position;
  float pressure = 0;
  std::int32_t solid = -1;
};

// Writes the frame's boundary particles (finite positions) through a temporary file,
// on a grid of voxel `voxel` (m). Throws InputError naming `where` when the frame
// holds no wall pressure, RunError when writing fails. Returns the points written.
std::size_t write_wall_points(const FrameData& frame, Up up, double voxel, const std::string& path,
                              const std::string& where);

// The points of such a file, in no particular order. Throws InputError for a file
// that is not one.
std::vector<WallPoint> read_wall_points(const std::string& path);

}  // namespace bw::exporter

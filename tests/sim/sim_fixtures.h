// Scenes for the simulator's tests: tanks sampled from box meshes, scene text, and
// running a scene through the library.
#pragma once

#include <string>

#include "common/geometry.h"
#include "io/run_file.h"
#include "sim/run.h"

namespace bw::test {

// A closed box tank of n[0] x n[1] x n[2] fluid cells of edge `spacing`, sampled as
// boundary particles into `path`. The box spans [0, (n + 1/2) spacing] per axis, so
// that its walls' particles lie at 1/2 spacing and (n + 1/2) spacing, and a fluid
// block [spacing, k spacing] (k <= n) rests one spacing from them.
void write_tank(const std::string& path, const Eigen::Vector3i& n, double spacing);

// A closed tank whose walls are `thickness` thick, sampled on both faces as the example
// tanks are (examples/meshes/spheric_tank.obj): the cavity [0, n spacing] per axis (its
// faces on the sampling grid's planes), the outer faces `thickness` beyond. The inner
// faces' particles lie half a spacing inside the walls, so a fluid block [0, k spacing]
// (k <= n) rests one spacing from them; at a thickness of two spacings the outer faces'
// particles lie one spacing behind the inner ones.
void write_thick_tank(const std::string& path, const Eigen::Vector3i& n, double spacing, double thickness);

// A solid block [lo, hi] sampled at `spacing` (its surface, as bw-sample samples a
// mesh) into `path`: a floor slab or a wall of a tank built of separate solids; with
// `volume`, its voxels too (bw-sample --volume: solid inside).
void write_block(const std::string& path, const Vec3d& lo, const Vec3d& hi, double spacing, bool volume = false);

// Outer size of that tank.
Vec3d tank_size(const Eigen::Vector3i& n, double spacing);

// Runs a scene file through the library into `output` on the default device.
sim::RunSummary run_scene(const std::string& scene_path, const std::string& output, bool quiet = true);

}  // namespace bw::test

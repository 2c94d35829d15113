// Scenes for the rigid-body tests: boxes sampled with their voxels, tanks, and the
// solver of a scene file on one shared device context (the kernels compile once per
// executable).
#pragma once

#include <string>

#include <fmt/format.h>

#include "common/geometry.h"
#include "compute/context.h"
#include "sim/setup.h"
#include "sim/solver.h"

namespace bw::test {

// A solid box [0, size] sampled at `spacing` with its voxels (bw-sample --volume;
// without them when `volume` is false) into `path`: its boundary particles lie half a
// spacing inside its faces.
void write_box(const std::string& path, const Vec3d& size, double spacing, bool volume = true);

// An open tank (floor and four walls, mesh::open_box) whose cavity is [0, inner] with
// walls `wall` thick, sampled at `spacing` into `path`: its particles lie half a
// spacing behind the cavity's faces.
void write_open_tank(const std::string& path, const Vec3d& inner, double wall, double spacing);

// The floating-box pool (coupled_test, buoyancy-study): a flat box of kPoolBox in
// water kPoolDepth deep in an open tank with a kPoolTank x kPoolTank floor, the box
// centred over it with its bottom `lift` above the water; tank.h5, box.h5 and
// pool.toml in `dir`, the scene at `spacing`. A box of half the water's density floats
// upright when it is wider than 1.22 times its height (its metacentre above its
// centre of mass); a cube would turn over.
constexpr double kPoolWidth = 0.12, kPoolHeight = 0.06, kPoolDepth = 0.06, kPoolTank = 0.24;
void write_pool(const std::string& dir, double spacing, double density, double end, double lift = 0.01);

// The level of the pool's water away from the box: over the columns of fluid (cells
// of one spacing) within 3 spacings of the tank's walls, the mean height of their
// highest particle plus half a spacing (the layer a particle stands for), so that the
// still pool of the scene is at kPoolDepth.
double pool_level(sim::Solver& solver, double spacing);

// The setup of a scene file (sim::prepare with the scene's end time).
sim::Setup prepare_file(const std::string& scene_path);

// One context on the default device for the whole executable.
compute::Context& shared_context();

}  // namespace bw::test

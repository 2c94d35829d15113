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

// The setup of a scene file (sim::prepare with the scene's end time).
sim::Setup prepare_file(const std::string& scene_path);

// One context on the default device for the whole executable.
compute::Context& shared_context();

}  // namespace bw::test

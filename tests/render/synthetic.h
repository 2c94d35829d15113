// Synthetic frames and runs for the renderer's tests, benchmark and documentation
// image: balls and pools of particles on jittered lattices, a wall sampled from a box
// mesh, written with the file layer exactly as bw-sim and bw-sample write them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "common/geometry.h"
#include "io/frame_file.h"

namespace bw::render::test {

// Particles of spacing `spacing` on a cubic lattice inside the ball, each moved by
// up to `jitter` * spacing along each axis (seeded).
void add_ball(FrameData& frame, const Vec3d& center, double radius, double spacing, double jitter,
              std::uint32_t seed);
// Particles filling the box [min, max] likewise.
void add_block(FrameData& frame, const Vec3d& min, const Vec3d& max, double spacing, double jitter,
               std::uint32_t seed);

// A splash of about `particles` particles: a pool 2 m x 1.2 m in front of a wall
// along x at y = 0.45, and a ball falling into it (the documentation picture and
// the benchmark). Spacing follows from the count.
FrameData splash_frame(std::size_t particles, int frame_number = 0);

// Writes a run file `dir`/run.h5 (its /parameters/spacing 0.05) with one static
// solid: a wall (box mesh sampled at 0.05 m into `dir`/wall.h5) spanning x in [-1, 1], y in [0.5, 0.65], z in [0, 1]
// after the given translation. With `tank`, a second static solid: an open tank
// around the splash's pool (inside x in [-1, 1], y in [-0.75, 0.45], z from 0, rim
// at 0.4 m, walls 5 cm), in `dir`/tank.h5. Returns the wall's bounds in the world.
Aabb write_wall_run(const std::string& dir, const Vec3d& translation = Vec3d::Zero(), bool tank = false);

// The wall pressure of write_wall_run's wall in `frame` (the wall_pressure field and
// boundary/solid, as bw-sim writes them): each of the wall's particles (at their
// sampled positions, plus the run's translation) with the pressure `pressure` gives it.
void add_wall_pressure(FrameData& frame, const std::string& dir, const std::function<double(const Vec3d&)>& pressure,
                       const Vec3d& translation = Vec3d::Zero());

// The dam break of examples/dambreak.toml: the example tank (examples/meshes/
// tank.obj: an open box whose cavity spans x in [0, 0.6], y in [0, 0.15], z in
// [0, 0.4], walls 3 cm), sampled at 1 cm into `dir`/tank.h5, in the run file
// `dir`/run.h5 as its one static solid. Returns the cavity.
Aabb write_tank_run(const std::string& dir);
// Water of that dam break at 1 cm spacing: frame 0 is the column (x in [0, 0.1],
// the cavity's width, z in [0, 0.2], as bw-sim places it); any later frame a surge
// 3 cm deep over the whole floor.
FrameData dambreak_frame(int frame_number);

// A crown around (0.15, -0.2, 0.25): a thin conical sheet of particles one spacing
// thick rising from the pool, and drops of one to a few particles flung out of it
// (seeded), at the spacing of the frame's particles.
void add_spray(FrameData& frame, std::uint32_t seed);

// Turns the wall of write_wall_run into a breakable solid (body 0) cut into three
// fragments along x (bodies 1, 2, 3, written to `dir`/fragments.h5), and gives the
// frame their poses: flung forward and up, each turned a little more.
void break_wall(const std::string& dir, FrameData& frame);

}  // namespace bw::render::test

// Files of kind "frame": one output frame of a simulation, in the H5Part layout
// (docs/formats.md): one step group, Step#0, whatever the frame number (files of
// earlier versions named it Step#F and still read). Written by bw-sim, read by bw-render and bw-voronoi.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace bw {

// Rigid body states at one frame (empty when the scene has no bodies).
struct BodyStates {
  std::vector<std::int32_t> id;
  std::vector<Vec3d> position;                 // centre of mass, world
  std::vector<Eigen::Quaterniond> orientation; // reference configuration -> world
  std::vector<Vec3d> linear_velocity;
  std::vector<Vec3d> angular_velocity;         // world frame
  std::size_t size() const { return id.size(); }
};

// Which optional fields a frame holds / a scene asks for.
struct FrameFields {
  bool velocity = false;   // vx, vy, vz
  bool density = false;    // rho
  bool pressure = false;   // p
  bool id = false;         // id
  bool boundary = false;   // boundary/x, y, z
  bool wall_pressure = false;  // boundary/p (with boundary)
  bool boundary_solid = false; // boundary/solid (written with boundary; files of earlier versions lack it)
};

struct FrameData {
  std::int32_t frame = 0;
  double time = 0;
  // Fluid particles, one entry per particle (positions always present; the other
  // arrays are empty unless their field is written).
  std::vector<float> x, y, z;
  std::vector<float> vx, vy, vz;
  std::vector<float> rho, p;
  std::vector<std::int64_t> id;
  // Boundary particles in world coordinates (field "boundary"), and the mean pressure
  // on each one's patch since the previous frame (field "wall_pressure", Pa).
  std::vector<float> bx, by, bz;
  std::vector<float> bp;
  std::vector<std::int32_t> bsolid;  // the scene solid of each (a body's: its solid's)
  BodyStates bodies;

  std::size_t fluid_count() const { return x.size(); }
  FrameFields fields() const;
};

// Writes the frame through a temporary file. Arrays of a field must have one entry
// per particle; optional fields are written when non-empty.
void write_frame(const FrameData& frame, const std::string& path);

// Reads a frame file ("-" for standard input). Throws InputError naming the file
// when it is not a frame or its arrays disagree in length.
FrameData read_frame(const std::string& path);

// The same without the fluid's arrays: frame, time, the boundary's and the bodies'
// (what a look at the solids needs, a fraction of the file where the water is large).
FrameData read_frame_boundary(const std::string& path);

// What a frame file holds, without its particles: for indexes and listings.
struct FrameHeader {
  std::int32_t frame = 0;
  double time = 0;
  std::string step;             // the step group, "/Step#0" (or "/Step#F" in older files)
  std::uint64_t fluid = 0;      // fluid particles
  std::uint64_t boundary = 0;   // boundary particles (field "boundary")
  std::uint64_t body_count = 0; // rows of the bodies group
  FrameFields fields;
  BodyStates bodies;            // read only when asked for
};

// Throws InputError naming `where` unless the fields hold the wall pressure and each
// boundary particle's solid (what a look at the loads on the solids needs).
void require_wall_pressure(const FrameFields& fields, const std::string& where);

// Reads the attributes and dataset shapes of a frame file, and its body states when
// `with_bodies`. Throws InputError naming the file as read_frame does.
FrameHeader read_frame_header(const std::string& path, bool with_bodies = false);

// "frames/000042.h5" for frame 42 under `folder`.
std::string frame_file_name(const std::string& folder, int frame);

}  // namespace bw

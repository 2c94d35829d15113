// The solids of a run as one glTF 2.0 binary file (.glb): one node per static solid
// and per rigid body (a dynamic solid, a breakable solid, a fragment) with its mesh,
// and one animation that moves every body through its poses in the frames.
//
// Coordinates: glTF is y-up, breakwater z-up; a point (x, y, z) is written as
// (x, z, -y), a rotation by the same change of axes (Blender's importer turns it
// back, so objects land at breakwater's coordinates there). Units are metres.
//
// A body's mesh is stored about its reference centre of mass (x_ref - c_ref), so
// that its node's translation is the body's position and its rotation the body's
// orientation (docs/formats.md, "Body poses"). Translation and rotation are LINEAR
// samplers at the frames' times; a body absent from a frame (a fragment before its
// fracture, a parent after it broke) has scale 0 there, by a STEP sampler, and keeps
// its nearest pose.
//
// The scene's camera ([camera], fixed, moving or tracking a body), when given, is a
// camera node placed as bw-render places it at each frame; glTF animates no field of
// view, so the camera's is that of the first frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "io/frame_file.h"
#include "io/fragments_file.h"
#include "io/run_file.h"
#include "render/camera_path.h"
#include "render/framing.h"

namespace bw::exporter {

// What the glTF is made of: the run's solids with their meshes in the reference
// configuration, and the fragments' meshes (bw-voronoi replay).
struct SolidSet {
  std::string run_path;
  RunRecord run;
  std::vector<TriMesh> solid_meshes;   // one per run.solids, reference configuration
  FragmentSet fragments;               // empty when there is no fragments file

  // Reads the run file, each particle file it names once, and the fragments file
  // (empty path: none). Throws InputError naming the file at fault.
  static SolidSet load(const std::string& run_path, const std::string& fragments_path);
};

struct PoseFrame {
  int number = 0;
  double time = 0;
  BodyStates bodies;
};

// The camera of the frames: [camera] of the run's scene, and the images' width over
// height ([render]).
struct GltfCamera {
  render::CameraPath path;
  double aspect = 16.0 / 9.0;
  render::TrackedBody track;   // [camera] track: the body it looks at (id -1: none)
};

struct GltfStats {
  std::size_t static_nodes = 0;
  std::size_t body_nodes = 0;
  std::size_t bodies_without_mesh = 0;  // present in a frame, but no mesh to show
  std::size_t keyframes = 0;
  std::size_t triangles = 0;
  std::size_t bytes = 0;
  bool camera = false;                  // a camera node was written
  render::Camera camera_first;          // the camera at the first frame
  double fov_first = 0, fov_least = 0, fov_most = 0;  // the camera's field of view over the frames (degrees)
};

// The .glb file's bytes. `source` is recorded in the asset's extras; `camera` adds a
// camera node.
std::vector<std::uint8_t> build_glb(const SolidSet& solids, const std::vector<PoseFrame>& frames,
                                    const std::string& source, GltfStats* stats = nullptr,
                                    const GltfCamera* camera = nullptr);

// The rotation of a glTF camera node (x, y, z, w) that looks as `camera` does: glTF's
// camera looks down its local -z with local +y up, in glTF's (y-up) axes.
std::array<double, 4> gltf_camera_rotation(const render::Camera& camera);

// The change of axes to glTF: (x, y, z) -> (x, z, -y), and for a rotation q the
// rotation C q C^T; returned as glTF stores it, (x, y, z, w).
Vec3d to_gltf(const Vec3d& p);
std::array<double, 4> to_gltf(const Eigen::Quaterniond& q);

}  // namespace bw::exporter

// What a sequence of frames takes from its reference frame, whichever part of it a
// process renders or exports: the particles' size, the ground's height and the
// camera (the scene's at the reference frame's time, or one fitted to it). bw-render
// draws with it; bw-export gives Blender the same camera. No OpenGL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/render_settings.h"
#include "render/solids.h"

namespace bw::render {

// The frames among which the reference frame is chosen: the folder's first ones, in
// order (not the range's, so that every part of a sequence agrees).
std::vector<std::string> reference_frame_candidates(const std::map<int, std::string>& frames);

// The body a camera tracks ([camera] track), as the run file names it.
struct TrackedBody {
  std::string name;
  std::int32_t id = -1;                   // row of the run's /bodies; -1: no tracking
  Vec3d reference_center = Vec3d::Zero(); // where it was made (c_ref)
};

// The body of settings.camera_track in the run file; id -1 when the settings track
// none. Throws InputError when the run has no body of that name, or there is no run
// file to say.
TrackedBody tracked_body(const RenderSettings& settings, const std::string& run_path);

// The camera of a frame: the scene's at the frame's time, looking at the tracked
// body's centre in `bodies` when there is one. Throws InputError naming `frame` (a
// path) when the body is not in the frame or the camera cannot be drawn.
Camera frame_camera(const CameraPath& path, const TrackedBody& track, double time, const BodyStates& bodies,
                    const std::string& frame);

struct Framing {
  std::string reference_frame;   // the first candidate with enough particles (framing.cpp)
  double reference_time = 0;
  double particle_spacing = 0;   // median nearest-neighbour distance; 0 when too few
  double particle_radius = 0;    // render.particle_radius, or the factor times the spacing
  double ground_height = 0;
  Camera camera;                 // at the reference frame's time
  bool camera_fitted = false;
  // A fitted camera's direction (degrees) and the fractions of the probes on the
  // water's surface and on the floor around it that it sees (view_fit.h; -1: none).
  double fit_azimuth = 0, fit_elevation = 0, fit_surface_seen = -1, fit_floor_seen = -1;
  // Particles of the reference frame, and the fraction of them that the camera sees:
  // in the image and hidden by no solid.
  std::size_t reference_water = 0;
  double water_seen = 0;
};

// Reads the candidates until one has enough particles. Throws InputError for a file
// that cannot be read.
Framing frame_sequence(const std::vector<std::string>& candidates, const RenderSettings& settings,
                       const SolidScene& solids, const TrackedBody& track = {});

}  // namespace bw::render

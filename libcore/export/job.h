// Exporting a simulation for artists' programs: the whole job of bw-export, so that
// the tool only parses its command line.
//
//   OUT_DIR/water_NNNNNN.vdb   the water of frame NNNNNN: level set "surface" (and
//                              fog volume "density" when asked), water.h
//   OUT_DIR/water_NNNNNN.obj   (or .ply) its surface as triangles, when asked
//   OUT_DIR/wall_pressure_NNNNNN.vdb  the boundary particles with their wall pressure
//                              as points, when asked, wall_points.h
//   OUT_DIR/solids.glb         every solid and body, animated over the range, gltf.h
//   OUT_DIR/blender_scene.py   sets up a Blender scene from those files, blender_scene.h
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "export/frames.h"
#include "export/gltf.h"
#include "export/water.h"
#include "render/render_settings.h"

namespace bw::exporter {

struct ExportJob {
  std::string frames_dir;        // OUTDIR/frames of a simulation
  std::string output_dir;        // created when missing
  FrameRange range;
  std::string run_path;          // empty: FRAMES_DIR/../run.h5 when it exists
  std::string fragments_path;    // empty: FRAMES_DIR/../fragments.h5 when it exists
  bool water = true;             // the .vdb files
  bool density = false;          // a "density" fog grid beside "surface"
  std::string mesh_format;       // "", "obj" or "ply": the surface as a mesh too
  double mesh_adaptivity = 0;
  bool wall_pressure = false;    // the boundary particles with their wall pressure, as points
  bool solids = true;            // solids.glb (when the run has solids) and blender_scene.py
  bool camera = true;            // the scene's [camera] in solids.glb, when it has one
  std::string scene_path;        // empty: the run's scene, as the run file keeps it
  WaterOptions water_options;    // spacing 0: the run's /parameters/spacing
};

// What run_export will do, checked before anything is written. Throws InputError.
struct ExportPlan {
  std::vector<FrameRef> frames;
  std::string run_path, fragments_path;  // resolved; empty when none
  WaterOptions water_options;            // resolved
  bool solids = false;                   // a solids.glb will be written
  bool blender_script = false;           // and blender_scene.py
  render::RenderSettings look;           // the scene's [camera], [light], [render] (defaults without one)
  double frame_rate = 30;                // the run's frames per second
  std::optional<GltfCamera> camera;      // the scene's camera, when solids.glb gets one
  std::string camera_source;             // the scene it came from
  // Without a [camera]: bw-render's camera, fitted with `look` by run_export from the
  // solids it reads.
  bool fit_camera = false;
  std::string spacing_source;            // where the spacing came from
};
ExportPlan plan_export(const ExportJob& job);

struct ExportProgress {
  std::size_t done = 0, total = 0;
  int frame = 0;
  double seconds = 0;
};

struct ExportReport {
  std::size_t frames = 0;
  int first = 0, last = 0;
  double seconds = 0;
  double water_ms_per_frame = 0;   // level set, filter and .vdb, per frame
  std::size_t max_particles = 0, max_voxels = 0, max_triangles = 0;
  std::size_t max_wall_points = 0;  // boundary particles in a wall_pressure file
  WaterOptions water_options;
  std::string spacing_source;
  std::string gltf_path;
  GltfStats gltf;
  std::string camera_source;       // where solids.glb's camera came from (gltf.camera)
  std::size_t camera_keys = 0;     // its keys in the scene (1: fixed)
  std::string camera_track;        // the body it looks at; empty: none
  std::string blender_script_path; // empty: not written
};

// Writes the files (each through a temporary name). Throws InputError for bad input,
// found before anything is written, and RunError when a write fails.
ExportReport run_export(const ExportJob& job, const std::function<void(const ExportProgress&)>& on_frame = {});

// "OUT_DIR/water_000042.vdb" and the like.
std::string water_file_name(const std::string& dir, int frame, const std::string& extension);
// "OUT_DIR/wall_pressure_000042.vdb".
std::string wall_points_file_name(const std::string& dir, int frame);

}  // namespace bw::exporter

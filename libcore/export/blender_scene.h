// OUT_DIR/blender_scene.py: a Python script that sets up a Blender scene from the
// files bw-export wrote beside it (solids.glb, water_NNNNNN.vdb): the run's frame
// rate and frames, the camera, the water as a surface with a water material, the sun
// and sky of the scene's look, its image size. Its body is libcore/export/
// blender_scene.py, embedded; bw-export puts in front of it what the files alone do
// not say (SETTINGS).
#pragma once

#include <string>

#include "export/water.h"
#include "render/render_settings.h"

namespace bw::exporter {

struct BlenderSceneSettings {
  std::string source;          // the run file (a comment)
  double frame_rate = 30;      // frames per second of the run: Blender frame F is the run's frame F
  int first = 0, last = 0;     // the exported frames
  Up up = Up::kZ;              // the axes of the water files
  render::RenderSettings look; // [render] size and colours, [light]
};

// The script's text.
std::string blender_scene_script(const BlenderSceneSettings& settings);

}  // namespace bw::exporter

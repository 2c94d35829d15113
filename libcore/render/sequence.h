// Rendering a sequence of frame files into PNG images (and a video): the whole job
// of bw-render, so that the tool only parses its command line.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/frame_range.h"
#include "render/framing.h"
#include "render/render_settings.h"
#include "render/wall_paint.h"

namespace bw::render {

// --frames (io/frame_range.h, shared with bw-export).
using bw::FrameRange;
using bw::parse_frame_range;

// "PX,PY,PZ:TX,TY,TZ[:FOV]": position, target and the vertical field of view in
// degrees (45 when left out); up is +z. Throws InputError.
Camera parse_camera(const std::string& text);

// The run file beside a frames folder, FRAMES_DIR/../run.h5, when it exists; else empty.
std::string default_run_path(const std::string& frames_dir);

// The look of the scene a run was made with: the [camera], [light] and [render]
// tables of the scene text the run file keeps (docs/formats.md), over the defaults.
// Throws InputError for a file that is not a run file or tables out of range.
RenderSettings run_render_settings(const std::string& run_path);

struct SequenceJob {
  std::string frames_dir;       // OUTDIR/frames of a simulation
  std::string output_dir;       // created when missing
  FrameRange range;
  std::string run_path;         // empty: default_run_path(frames_dir)
  std::string fragments_path;   // empty: no fragments
  std::string video_path;       // empty: no video
  double fps = 0;               // video frame rate; 0: from the frames' times
  int device = -1;              // EGL device index; -1: the first display that works
  RenderSettings settings;
};

struct FramePlan {
  int number = 0;               // from the file name, NNNNNN.h5
  std::string path;
  double time = 0;
};

// What render_sequence will do, checked before any rendering: every frame of the
// range exists and is a frame file (holding the wall pressure where the solids are
// coloured by it), the output folder is writable, the run and fragments files read.
// Throws InputError for bad input.
struct SequencePlan {
  std::vector<FramePlan> frames;       // to render, in order
  // The folder's first frames, in order: the reference frame is the first of them
  // with enough particles (sequence.cpp).
  std::vector<std::string> reference_frames;
  std::vector<std::string> folder_frames;  // every frame of the folder, in order
  std::string run_path;                // resolved; empty when none
  double fps = 30;
};
SequencePlan plan_sequence(const SequenceJob& job);

struct SequenceProgress {
  std::size_t done = 0, total = 0;
  int frame = 0;                 // number of the frame just written
  double seconds = 0;            // since the start
  double render_seconds = 0;     // reading, drawing and writing the frames so far
};

struct SequenceReport {
  std::size_t frames = 0;
  int first = 0, last = 0;
  double seconds = 0;            // wall clock, everything
  double render_ms_per_frame = 0;  // reading, drawing and writing one frame
  std::string renderer, display;   // GL_RENDERER; how the EGL display was found
  Framing framing;                 // reference frame, particle size, ground, camera (framing.h)
  std::size_t camera_keys = 0;     // keys of a given camera (1: fixed); 0: fitted
  std::size_t max_particles = 0;
  std::size_t bodies_without_mesh = 0;  // largest count in any frame
  std::size_t solids = 0, fragments = 0;
  std::string video_path;
  double fps = 0;
  // With the solids coloured by the wall pressure: the colour scale, and where it
  // came from ("render.pressure_range", or the frames' pooled percentiles).
  std::optional<PaintRange> paint;
  std::string paint_source;
};

// Renders every frame of the plan to OUTPUT_DIR/NNNNNN.png (through temporary files)
// and, when asked, the video. Throws InputError for bad input (before anything is
// written when it can be found out beforehand) and RunError when the GL context, a
// shader, a write or ffmpeg fails. `on_frame` is called after each written frame.
SequenceReport render_sequence(const SequenceJob& job,
                               const std::function<void(const SequenceProgress&)>& on_frame = {});

}  // namespace bw::render

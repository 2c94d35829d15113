// The frames of a simulation's folder that an export covers: a range A:B[:S] over
// OUTDIR/frames/NNNNNN.h5, with the conventions of bw-render's --frames.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/frame_range.h"

namespace bw::exporter {

// --frames (io/frame_range.h, shared with bw-render).
using bw::FrameRange;
using bw::parse_frame_range;

struct FrameRef {
  int number = 0;
  std::string path;
  double time = 0;   // the frame's /time, read when the range is resolved
};

// The frames of `range` in `dir`, each checked to be a frame file. Throws InputError
// naming the first missing or foreign file.
std::vector<FrameRef> resolve_frames(const std::string& dir, const FrameRange& range);

}  // namespace bw::exporter

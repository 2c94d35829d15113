// Frame ranges and the frame files of a folder, as bw-render and bw-export take them
// (--frames A:B[:S] over OUTDIR/frames/NNNNNN.h5), so that a cluster splits both the
// same way.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace bw {

// Frames first..last (inclusive) every step. An open end takes the first or last
// frame present in the folder.
struct FrameRange {
  std::optional<int> first;
  std::optional<int> last;
  int step = 1;
};

// "A:B", "A:B:S", "A:", ":B", "A" (that frame alone), "::S". Throws InputError naming
// --frames and the text.
FrameRange parse_frame_range(const std::string& text);

// Frame files of a folder by number: NNNNNN.h5 (digits only); empty when there is
// none. Throws InputError when the path is a file or does not exist.
std::map<int, std::string> frame_files(const std::string& dir);

// The same, and throws InputError when the folder holds no frame file; when it is a
// bw-sim output folder, whose frames are in its frames/ folder, the error says so.
std::map<int, std::string> require_frame_files(const std::string& dir);

}  // namespace bw

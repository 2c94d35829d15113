#include "export/frames.h"

#include <algorithm>

#include "common/error.h"
#include "io/frame_file.h"
#include "io/h5.h"

namespace bw::exporter {

std::vector<FrameRef> resolve_frames(const std::string& dir, const FrameRange& range) {
  const std::map<int, std::string> frames = require_frame_files(dir);
  const int first = range.first.value_or(frames.begin()->first);
  const int last = range.last.value_or(frames.rbegin()->first);
  if (first > last) fail_input("{}: the range {}:{} is empty", dir, first, last);
  std::vector<FrameRef> out;
  for (long n = first; n <= last; n += std::max(range.step, 1)) {
    auto it = frames.find(static_cast<int>(n));
    if (it == frames.end()) fail_input("frame {} is missing: {}", n, frame_file_name(dir, static_cast<int>(n)));
    FrameRef f{static_cast<int>(n), it->second, 0};
    h5::File file = h5::File::open(f.path, "frame");
    f.time = file.root().attr<double>("time");
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace bw::exporter

#include "export/frames.h"

#include <algorithm>
#include <charconv>
#include <filesystem>

#include "common/error.h"
#include "io/frame_file.h"
#include "io/h5.h"

namespace bw::exporter {
namespace fs = std::filesystem;
namespace {

std::optional<int> parse_int(const std::string& s) {
  int v = 0;
  if (s.empty()) return std::nullopt;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

FrameRange parse_frame_range(const std::string& text) {
  FrameRange r;
  const auto bad = [&](const char* why) { fail_input("--frames '{}': {}", text, why); };
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() > 3) bad("expected A:B or A:B:S");
  auto number = [&](const std::string& s) -> std::optional<int> {
    if (s.empty()) return std::nullopt;
    auto v = parse_int(s);
    if (!v || *v < 0) bad("frame numbers are integers >= 0");
    return v;
  };
  r.first = number(parts[0]);
  if (parts.size() == 1) {
    if (!r.first) bad("expected A:B or A:B:S");
    r.last = r.first;
    return r;
  }
  r.last = number(parts[1]);
  if (parts.size() == 3) {
    auto s = number(parts[2]);
    if (!s || *s < 1) bad("the step must be an integer >= 1");
    r.step = *s;
  }
  if (r.first && r.last && *r.first > *r.last) bad("the range is empty (first > last)");
  return r;
}

std::map<int, std::string> list_frames(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail_input("{}: no such folder of frames", dir);
  std::map<int, std::string> frames;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 4 || name.substr(name.size() - 3) != ".h5") continue;
    const std::string stem = name.substr(0, name.size() - 3);
    if (!std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    if (auto n = parse_int(stem)) frames[*n] = entry.path().string();
  }
  if (frames.empty()) fail_input("{}: holds no frame files (NNNNNN.h5)", dir);
  return frames;
}

std::vector<FrameRef> resolve_frames(const std::string& dir, const FrameRange& range) {
  const std::map<int, std::string> frames = list_frames(dir);
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

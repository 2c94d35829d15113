#include "io/frame_range.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <vector>

#include "common/error.h"
#include "common/text.h"

namespace bw {
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
  const std::vector<std::string> parts = split(text, ':');
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

std::map<int, std::string> frame_files(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    if (fs::exists(dir, ec)) fail_input("{}: is a file, not a folder of frames (bw-sim's OUTDIR/frames)", dir);
    fail_input("{}: no such folder of frames", dir);
  }
  std::map<int, std::string> frames;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 4 || name.substr(name.size() - 3) != ".h5" || !entry.is_regular_file(ec)) continue;
    const std::string stem = name.substr(0, name.size() - 3);
    if (!std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    if (auto n = parse_int(stem)) frames[*n] = entry.path().string();
  }
  return frames;
}

std::map<int, std::string> require_frame_files(const std::string& dir) {
  std::map<int, std::string> frames = frame_files(dir);
  if (!frames.empty()) return frames;
  // A run's folder given for its frames: the likeliest slip, so the error names the fix.
  const fs::path inner = fs::path(dir) / "frames";
  std::error_code ec;
  if (fs::is_directory(inner, ec) && !frame_files(inner.string()).empty())
    fail_input("{}: holds no frame files (NNNNNN.h5); its frames folder does: give {}", dir, inner.string());
  fail_input("{}: holds no frame files (NNNNNN.h5)", dir);
}

}  // namespace bw

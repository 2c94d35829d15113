#include "common/terminal.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

#include "common/text.h"

namespace bw {

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }
bool stdout_is_terminal() { return ::isatty(STDOUT_FILENO) == 1; }

ProgressLine::ProgressLine(bool enabled) : active_(enabled && stderr_is_terminal()) {}

ProgressLine::~ProgressLine() { clear(); }

void ProgressLine::update(const std::string& text, bool force) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  std::string line = "\r" + text;
  if (text.size() < last_width_) line.append(last_width_ - text.size(), ' ');
  last_width_ = text.size();
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

void ProgressLine::clear() {
  if (!active_ || last_width_ == 0) return;
  std::fprintf(stderr, "\r%*s\r", static_cast<int>(last_width_), "");
  std::fflush(stderr);
  last_width_ = 0;
}

std::string frame_progress_text(const std::string& tool, int frame, std::size_t done, std::size_t total,
                                double seconds) {
  const double per_frame = done > 0 ? seconds / static_cast<double>(done) : 0.0;
  return fmt::format("{}: frame {:06d} ({}/{}), {:.0f} ms per frame, {} left", tool, frame, done, total,
                     1000 * per_frame, human_duration(per_frame * static_cast<double>(total - done)));
}

}  // namespace bw

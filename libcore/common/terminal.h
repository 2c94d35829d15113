// Progress lines on a terminal; silence in pipes and CI.
//
// Messages and progress go to stderr, data to files or stdout. A progress line is
// redrawn in place ("\r") only when stderr is a terminal and the tool is not quiet.
#pragma once

#include <chrono>
#include <string>

namespace bw {

bool stderr_is_terminal();
bool stdout_is_terminal();

class ProgressLine {
 public:
  // Shows nothing unless stderr is a terminal and `enabled` is true.
  explicit ProgressLine(bool enabled = true);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool active() const { return active_; }
  // Redraws the line, at most every `min_interval` unless `force` is set.
  void update(const std::string& text, bool force = false);
  // Clears the line, so that the next message starts on a clean line.
  void clear();

 private:
  bool active_;
  std::size_t last_width_ = 0;
  std::chrono::steady_clock::time_point last_draw_{};
};

// "TOOL: frame 000042 (3/10), 120 ms per frame, 1 s left": the line of a tool that
// works through frames, `seconds` spent on the `done` of `total` so far.
std::string frame_progress_text(const std::string& tool, int frame, std::size_t done, std::size_t total,
                                double seconds);

// Wall-clock stopwatch in seconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace bw

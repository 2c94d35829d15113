// Encoding rendered frames into a video with ffmpeg (when it is installed).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bw::render {

// Full path of an executable found on PATH; empty when there is none.
std::string find_on_path(const std::string& name);

// An H.264 video (.mp4, .mov or .mkv) fed PNG images one by one through a pipe into
// ffmpeg; written to a temporary file and renamed into place by finish().
class VideoWriter {
 public:
  // Throws InputError for an unknown extension or an unwritable folder, RunError
  // when ffmpeg is not installed or does not start.
  VideoWriter(const std::string& path, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void add_png(const std::vector<std::uint8_t>& png);
  // Waits for ffmpeg and renames the video into place. Throws RunError.
  void finish();

  // Throws unless `path` has an extension VideoWriter knows and ffmpeg is installed;
  // for checking before a long render.
  static void check_available(const std::string& path);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::render

#include "render/video.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace bw::render {
namespace {

// ffmpeg's muxer for each extension bw-render accepts.
const char* muxer_for(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".mp4") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  return nullptr;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    // An empty entry means the current folder.
    const std::string candidate = fmt::format("{}/{}", dir.empty() ? std::string_view(".") : std::string_view(dir), name);
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

void VideoWriter::check_available(const std::string& path) {
  if (!muxer_for(path)) fail_input("{}: the video must end in .mp4, .mov or .mkv", path);
  check_writable_folder_of(path);
  if (find_on_path("ffmpeg").empty())
    fail_run("{}: --video needs ffmpeg, which is not installed (Debian package ffmpeg)", path);
}

struct VideoWriter::Impl {
  AtomicFile file;
  std::FILE* pipe = nullptr;
  explicit Impl(const std::string& path) : file(path) {}
};

VideoWriter::VideoWriter(const std::string& path, double fps) {
  check_available(path);
  impl_ = std::make_unique<Impl>(path);
  const std::string ffmpeg = find_on_path("ffmpeg");
  // yuv420p (what players expect) needs even sides; pad by one pixel when odd.
  const std::string command = fmt::format(
      "{} -hide_banner -loglevel error -nostdin -y -f image2pipe -c:v png -framerate {} -i - "
      "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -crf 18 -f {} {}",
      shell_quote(ffmpeg), fps, muxer_for(path), shell_quote(impl_->file.temp_path()));
  // A pipe closed by a failing ffmpeg must be an error, not a signal that kills us.
  std::signal(SIGPIPE, SIG_IGN);
  impl_->pipe = ::popen(command.c_str(), "w");
  if (!impl_->pipe) fail_run("{}: cannot start ffmpeg: {}", path, std::strerror(errno));
}

VideoWriter::~VideoWriter() {
  if (impl_ && impl_->pipe) ::pclose(impl_->pipe);
}

void VideoWriter::add_png(const std::vector<std::uint8_t>& png) {
  if (std::fwrite(png.data(), 1, png.size(), impl_->pipe) != png.size())
    fail_run("{}: ffmpeg stopped taking frames", impl_->file.final_path());
}

void VideoWriter::finish() {
  const int status = ::pclose(impl_->pipe);
  impl_->pipe = nullptr;
  if (status != 0) fail_run("{}: ffmpeg failed (status {})", impl_->file.final_path(), status);
  impl_->file.commit();
}

}  // namespace bw::render

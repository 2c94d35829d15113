#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "common/error.h"
#include "common/temp_files.h"

namespace bw {
namespace fs = std::filesystem;

namespace {

std::string folder_of(const std::string& path) {
  fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Unique within the process and across processes sharing a folder (make -j).
std::string temp_name_for(const std::string& path, const fs::path& folder) {
  static std::atomic<unsigned> counter{0};
  const std::string name =
      fmt::format(".{}.tmp-{}-{}", fs::path(path).filename().string(), static_cast<long>(::getpid()), counter++);
  return (folder / name).string();
}

// Where a write to `path` lands: a link's target (the link stays), and whether that
// is a device or a pipe, which takes bytes but cannot be renamed over.
struct Target {
  std::string path;
  bool stream = false;
};

Target target_of(const std::string& path) {
  Target t{path, false};
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path resolved = fs::weakly_canonical(path, ec);
    if (!ec) t.path = resolved.string();
  }
  const fs::file_status st = fs::status(t.path, ec);
  t.stream = fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st);
  return t;
}

// Copies the finished file into a device or a pipe, which a rename would replace.
void copy_bytes(const std::string& from, const std::string& to, const std::string& name) {
  const int fd = ::open(to.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail_run("{}: cannot write: {}", name, std::strerror(errno));
  int err = copy_file_into(from, fd);
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err) fail_run("{}: write failed: {}", name, std::strerror(err));
}

}  // namespace

void check_writable_folder_of(const std::string& path) {
  const std::string folder = folder_of(path);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) fail_input("{}: folder '{}' does not exist", path, folder);
  if (::access(folder.c_str(), W_OK) != 0) fail_input("{}: folder '{}' is not writable", path, folder);
}

namespace {

void check_file_path(const std::string& path, const Target& target) {
  std::error_code ec;
  if (fs::is_directory(target.path, ec)) fail_input("{}: is a folder, expected a file name", path);
  if (!target.stream) {
    check_writable_folder_of(target.path);
  } else if (::access(target.path.c_str(), W_OK) != 0) {
    fail_input("{}: cannot write: {}", path, std::strerror(errno));
  }
}

}  // namespace

void check_output_file(const std::string& path, const std::vector<std::string>& inputs) {
  if (path == "-") return;
  check_file_path(path, target_of(path));
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (input != "-" && fs::equivalent(path, input, ec))
      fail_input("{}: is the input file {} itself; write the output to another file", path, input);
  }
}

AtomicFile::AtomicFile(std::string path) : final_path_(std::move(path)) {
  const Target target = target_of(final_path_);
  check_file_path(final_path_, target);
  target_path_ = target.path;
  stream_ = target.stream;
  temp_path_ = temp_name_for(target_path_, stream_ ? fs::temp_directory_path() : fs::path(target_path_).parent_path());
  ticket_ = remember_temp_file(temp_path_);
}

AtomicFile::~AtomicFile() { discard(); }

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      target_path_(std::move(other.target_path_)),
      temp_path_(std::move(other.temp_path_)),
      stream_(other.stream_),
      committed_(other.committed_),
      ticket_(other.ticket_) {
  other.temp_path_.clear();
  other.ticket_ = -1;
}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    discard();
    final_path_ = std::move(other.final_path_);
    target_path_ = std::move(other.target_path_);
    temp_path_ = std::move(other.temp_path_);
    stream_ = other.stream_;
    committed_ = other.committed_;
    ticket_ = other.ticket_;
    other.temp_path_.clear();
    other.ticket_ = -1;
  }
  return *this;
}

void AtomicFile::commit() {
  if (committed_) return;
  if (stream_) {
    copy_bytes(temp_path_, target_path_, final_path_);
    discard();
    committed_ = true;
    return;
  }
  if (std::rename(temp_path_.c_str(), target_path_.c_str()) != 0) {
    const int err = errno;
    fail_run("{}: cannot rename the finished file into place: {}", final_path_, std::strerror(err));
  }
  committed_ = true;
  forget_temp_file(ticket_);
  ticket_ = -1;
}

void AtomicFile::discard() noexcept {
  if (!committed_ && !temp_path_.empty()) {
    std::error_code ec;
    fs::remove(temp_path_, ec);
    temp_path_.clear();
    forget_temp_file(ticket_);
    ticket_ = -1;
  }
}

int copy_file_into(const std::string& from, int fd) {
  std::FILE* in = std::fopen(from.c_str(), "rb");
  if (!in) return errno ? errno : EIO;
  std::vector<char> buffer(1 << 20);
  int err = 0;
  for (std::size_t n; err == 0 && (n = std::fread(buffer.data(), 1, buffer.size(), in)) > 0;) {
    for (std::size_t done = 0; done < n && err == 0;) {
      const ssize_t w = ::write(fd, buffer.data() + done, n - done);
      if (w < 0 && errno != EINTR) err = errno;
      if (w > 0) done += static_cast<std::size_t>(w);
    }
  }
  if (err == 0 && std::ferror(in)) err = errno ? errno : EIO;
  std::fclose(in);
  return err;
}

void write_file_atomically(const std::string& path, const void* bytes, std::size_t size) {
  AtomicFile file(path);
  std::FILE* f = std::fopen(file.temp_path().c_str(), "wb");
  if (!f) fail_run("{}: cannot create: {}", path, std::strerror(errno));
  const bool ok = std::fwrite(bytes, 1, size, f) == size;
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) fail_run("{}: write failed: {}", path, std::strerror(errno));
  file.commit();
}

}  // namespace bw

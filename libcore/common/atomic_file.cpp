#include "common/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/error.h"

namespace bw {
namespace fs = std::filesystem;

namespace {

std::string folder_of(const std::string& path) {
  fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Unique within the process and across processes sharing a folder (make -j).
std::string temp_name_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  const std::string name = fmt::format(".{}.tmp-{}-{}", p.filename().string(), static_cast<long>(::getpid()), counter++);
  return (p.parent_path() / name).string();
}

}  // namespace

void check_writable_folder_of(const std::string& path) {
  const std::string folder = folder_of(path);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) fail_input("{}: folder '{}' does not exist", path, folder);
  if (::access(folder.c_str(), W_OK) != 0) fail_input("{}: folder '{}' is not writable", path, folder);
}

namespace {

void check_file_path(const std::string& path) {
  check_writable_folder_of(path);
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail_input("{}: is a folder, expected a file name", path);
}

}  // namespace

void check_output_file(const std::string& path) {
  if (path != "-") check_file_path(path);
}

AtomicFile::AtomicFile(std::string path) : final_path_(std::move(path)) {
  check_file_path(final_path_);
  temp_path_ = temp_name_for(final_path_);
}

AtomicFile::~AtomicFile() { discard(); }

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      temp_path_(std::move(other.temp_path_)),
      committed_(other.committed_) {
  other.temp_path_.clear();
}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    discard();
    final_path_ = std::move(other.final_path_);
    temp_path_ = std::move(other.temp_path_);
    committed_ = other.committed_;
    other.temp_path_.clear();
  }
  return *this;
}

void AtomicFile::commit() {
  if (committed_) return;
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    const int err = errno;
    fail_run("{}: cannot rename the finished file into place: {}", final_path_, std::strerror(err));
  }
  committed_ = true;
}

void AtomicFile::discard() noexcept {
  if (!committed_ && !temp_path_.empty()) {
    std::error_code ec;
    fs::remove(temp_path_, ec);
    temp_path_.clear();
  }
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

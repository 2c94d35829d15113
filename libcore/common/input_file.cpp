#include "common/input_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/temp_files.h"

namespace bw {
namespace fs = std::filesystem;
namespace {

// The copies made so far, by the path they were read from; removed at exit, or by a
// signal (common/temp_files.h). HDF5 opens files by a name it resolves, so a copy
// keeps one (an unlinked file's /proc/self/fd link does not resolve).
class Spool {
 public:
  ~Spool() {
    for (const auto& [from, copy] : copies_) {
      std::error_code ec;
      fs::remove(copy, ec);
    }
  }

  std::string copy_of(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = copies_.find(path); it != copies_.end()) return it->second;
    std::string name = (fs::temp_directory_path() / "bw-input-XXXXXX").string();
    const int fd = ::mkstemp(name.data());
    if (fd < 0)
      fail_input("{}: cannot make a temporary copy of the pipe in {}: {}", path, fs::temp_directory_path().string(),
                 std::strerror(errno));
    remember_temp_file(name);
    copies_[path] = name;
    const int err = copy_file_into(path, fd);
    ::close(fd);
    if (err) {
      std::error_code ec;
      fs::remove(name, ec);
      copies_.erase(path);
      fail_input("{}: cannot read the pipe: {}", path, std::strerror(err));
    }
    return name;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::string> copies_;
};

Spool& spool() {
  static Spool instance;
  return instance;
}

}  // namespace

std::string seekable_path(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st) || fs::is_regular_file(st) || fs::is_directory(st)) return path;
  return spool().copy_of(path);
}

}  // namespace bw

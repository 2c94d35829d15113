#include "common/input_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"

namespace bw {
namespace fs = std::filesystem;
namespace {

// The copies made so far, by the path they were read from; removed at exit.
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
    const std::string copy =
        (fs::temp_directory_path() / fmt::format("bw-input-{}-{}{}", static_cast<long>(::getpid()), copies_.size(),
                                                          fs::path(path).extension().string()))
            .string();
    std::FILE* in = std::fopen(path.c_str(), "rb");
    if (!in) fail_input("{}: cannot open: {}", path, std::strerror(errno));
    std::FILE* out = std::fopen(copy.c_str(), "wb");
    if (!out) {
      const int err = errno;
      std::fclose(in);
      fail_input("{}: cannot copy the pipe to {}: {}", path, copy, std::strerror(err));
    }
    copies_[path] = copy;  // from here on removed at exit, whatever happens below
    std::vector<char> buffer(1 << 20);
    int err = 0;
    for (std::size_t n; err == 0 && (n = std::fread(buffer.data(), 1, buffer.size(), in)) > 0;)
      if (std::fwrite(buffer.data(), 1, n, out) != n) err = errno ? errno : EIO;
    if (err == 0 && std::ferror(in)) err = errno ? errno : EIO;
    std::fclose(in);
    if (std::fclose(out) != 0 && err == 0) err = errno ? errno : EIO;
    if (err) fail_input("{}: cannot read the pipe: {}", path, std::strerror(err));
    return copy;
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

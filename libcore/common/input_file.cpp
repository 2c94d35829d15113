#include "common/input_file.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "common/error.h"

namespace bw {
namespace fs = std::filesystem;
namespace {

// Writes the whole of `from` (a pipe) into the open file `fd`; 0 or an errno.
int copy_into(const std::string& from, int fd) {
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

// The copies' names where a signal handler can reach them: fixed buffers, filled
// before they are published. HDF5 opens files by a name it resolves, so a copy must
// keep one (an unlinked file's /proc/self/fd link does not resolve).
constexpr std::size_t kMaxCopies = 64;
std::array<std::array<char, 4096>, kMaxCopies> g_names;
std::atomic<std::size_t> g_published{0};

void remove_copies() {
  const std::size_t n = g_published.load();
  for (std::size_t k = 0; k < n; ++k) ::unlink(g_names[k].data());
}

// SIGINT, SIGTERM, SIGHUP: the copies go, then the signal does what it did before.
extern "C" void remove_copies_and_reraise(int signal) {
  remove_copies();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void remove_copies_on_signals() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction now {};
    // A tool that handles the signal itself (bw-sim stops at a frame) keeps its handler.
    if (::sigaction(signal, nullptr, &now) == 0 && now.sa_handler == SIG_DFL)
      std::signal(signal, remove_copies_and_reraise);
  }
}

// The copies made so far, by the path they were read from; removed at exit.
class Spool {
 public:
  ~Spool() { remove_copies(); }

  std::string copy_of(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = copies_.find(path); it != copies_.end()) return it->second;
    const std::size_t slot = g_published.load();
    if (slot == kMaxCopies) fail_input("{}: more than {} pipes given as inputs", path, kMaxCopies);
    std::string name = (fs::temp_directory_path() / "bw-input-XXXXXX").string();
    if (name.size() >= g_names[slot].size()) fail_input("{}: the temporary folder's name is too long", path);
    const int fd = ::mkstemp(name.data());
    if (fd < 0)
      fail_input("{}: cannot make a temporary copy of the pipe in {}: {}", path, fs::temp_directory_path().string(),
                 std::strerror(errno));
    std::memcpy(g_names[slot].data(), name.c_str(), name.size() + 1);
    if (slot == 0) remove_copies_on_signals();
    g_published.store(slot + 1);
    const int err = copy_into(path, fd);
    ::close(fd);
    if (err) fail_input("{}: cannot read the pipe: {}", path, std::strerror(err));
    return copies_[path] = name;
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

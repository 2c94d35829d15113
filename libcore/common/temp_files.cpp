#include "common/temp_files.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace bw {
namespace {

// Fixed slots that a signal handler can read: a slot's path is written before the
// slot is marked live.
enum : int { kFree = 0, kClaimed = 1, kLive = 2 };
constexpr std::size_t kSlots = 256;
struct Slot {
  std::atomic<int> state{kFree};
  std::array<char, 4096> path{};
};
std::array<Slot, kSlots> g_slots;

extern "C" void remove_temp_files_and_reraise(int signal) {
  for (Slot& slot : g_slots)
    if (slot.state.load() == kLive) ::unlink(slot.path.data());
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction now {};
      if (::sigaction(signal, nullptr, &now) == 0 && now.sa_handler == SIG_DFL)
        std::signal(signal, remove_temp_files_and_reraise);
    }
  });
}

}  // namespace

int remember_temp_file(const std::string& path) {
  if (path.size() >= g_slots[0].path.size()) return -1;
  install_handlers_once();
  for (std::size_t k = 0; k < kSlots; ++k) {
    int expected = kFree;
    if (!g_slots[k].state.compare_exchange_strong(expected, kClaimed)) continue;
    std::memcpy(g_slots[k].path.data(), path.c_str(), path.size() + 1);
    g_slots[k].state.store(kLive);
    return static_cast<int>(k);
  }
  return -1;
}

void forget_temp_file(int ticket) {
  if (ticket >= 0 && static_cast<std::size_t>(ticket) < kSlots) g_slots[static_cast<std::size_t>(ticket)].state.store(kFree);
}

}  // namespace bw

#include "common/memory.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/text.h"

namespace bw {

std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream in(line);
    std::string key;
    std::uint64_t kib = 0;
    if (in >> key >> kib && key == "MemAvailable:") return kib * 1024;
  }
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page_size > 0) return static_cast<std::uint64_t>(pages) * page_size;
  return UINT64_MAX;
}

void check_fits_in_memory(std::uint64_t bytes, const std::string& what) {
  const std::uint64_t available = available_memory_bytes();
  if (bytes > available) {
    fail_input("{} would need {} of memory, only {} are available", what, human_bytes(bytes),
               human_bytes(available));
  }
}

}  // namespace bw

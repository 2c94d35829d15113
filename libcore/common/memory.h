// How much memory the machine can give a tool, to refuse work that would not fit
// before starting it.
#pragma once

#include <cstdint>
#include <string>

namespace bw {

// Bytes of memory available to a new allocation: MemAvailable from /proc/meminfo,
// or physical memory where that is unknown.
std::uint64_t available_memory_bytes();

// Throws InputError "<what> would need <N> GiB of memory, <M> GiB are available"
// when `bytes` exceeds what is available.
void check_fits_in_memory(std::uint64_t bytes, const std::string& what);

}  // namespace bw

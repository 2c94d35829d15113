#include "compute/kernels.h"

#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "bw_sim_kernels/embedded.h"
#include "common/error.h"

namespace bw::compute {

SourceLookup embedded_kernels() {
  return [](std::string_view name) { return sim_kernels::embedded_file(name); };
}

int kernel_vector_width(const DeviceInfo& device) {
  // BW_KERNEL_VECTOR_WIDTH runs a device with another width than it prefers: on a CPU,
  // width 1 sums neighbours in the order a GPU does (tools/gpu-check.sh compares them).
  if (const char* forced = std::getenv("BW_KERNEL_VECTOR_WIDTH"); forced && *forced) {
    const std::string w = forced;
    if (w == "1" || w == "2" || w == "4" || w == "8" || w == "16") return std::stoi(w);
    fail_input("BW_KERNEL_VECTOR_WIDTH={}: not 1, 2, 4, 8 or 16", w);
  }
  // The widest power of two the device prefers, up to float16 (OpenCL's widest).
  int width = 1;
  while (width < 16 && width * 2 <= device.preferred_float_width) width *= 2;
  return width;
}

std::string kernel_build_options(const DeviceInfo& device) {
  return fmt::format("-cl-std=CL1.2 -cl-mad-enable -DBW_VW={}", kernel_vector_width(device));
}

}  // namespace bw::compute

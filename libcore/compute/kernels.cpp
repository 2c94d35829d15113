#include "compute/kernels.h"

#include <fmt/format.h>

#include "bw_sim_kernels/embedded.h"

namespace bw::compute {

SourceLookup embedded_kernels() {
  return [](std::string_view name) { return sim_kernels::embedded_file(name); };
}

int kernel_vector_width(const DeviceInfo& device) {
  // The widest power of two the device prefers, up to float16 (OpenCL's widest).
  int width = 1;
  while (width < 16 && width * 2 <= device.preferred_float_width) width *= 2;
  return width;
}

std::string kernel_build_options(const DeviceInfo& device) {
  return fmt::format("-cl-std=CL1.2 -cl-mad-enable -DBW_VW={}", kernel_vector_width(device));
}

}  // namespace bw::compute

// The simulator's embedded OpenCL C sources (shaders/*.cl and their headers, built in
// by shaders/sim.cmake) and the compiler options every program of them uses.
#pragma once

#include <string>

#include "compute/context.h"

namespace bw::compute {

// Looks up shaders/<name> in the embedded set.
SourceLookup embedded_kernels();

// Options for building the embedded kernels on `device`: OpenCL C 1.2 (what PoCL and
// every GPU driver compile), fused multiply-adds allowed, and BW_VW, the vector width
// of the neighbour loops (shaders/sph_vector.h), from the device's preferred float
// vector width (or the environment's BW_KERNEL_VECTOR_WIDTH).
std::string kernel_build_options(const DeviceInfo& device);

// The vector width kernel_build_options chooses: 1, 2, 4, 8 or 16.
int kernel_vector_width(const DeviceInfo& device);

}  // namespace bw::compute

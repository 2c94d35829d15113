// Private to libcore/compute: the one place that includes the OpenCL C++ bindings.
// Public headers of this folder never include it, so OpenCL types stay inside the
// compute layer's .cpp files.
#pragma once

// Debian's opencl.hpp needs both versions defined together. Minimum 2.0: with 1.2
// its command-queue constructors do not compile (getContextPlatformVersion is only
// defined for minimum versions below 1.2); every current driver and PoCL implement
// the 2.0 host API, while kernels stay in OpenCL C 1.2 (-cl-std=CL1.2).
#define CL_HPP_TARGET_OPENCL_VERSION 300
#define CL_HPP_MINIMUM_OPENCL_VERSION 200
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>

#include <string>

namespace bw::compute {

// Throws RunError "OpenCL: <call> failed: <NAME> (<code>)<context>".
[[noreturn]] void throw_cl_error(const cl::Error& e, const std::string& context = {});

}  // namespace bw::compute

#include "compute/device.h"

#include <cstdlib>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "compute/cl_impl.h"

namespace bw::compute {
namespace {

// What the ICD loader returns when no platform is installed (cl_khr_icd).
constexpr cl_int kPlatformNotFoundKhr = -1001;

std::string type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "gpu";
  if (type & CL_DEVICE_TYPE_CPU) return "cpu";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

// Strings from OpenCL queries may carry a trailing NUL and padding.
std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  std::size_t start = 0;
  while (start < s.size() && s[start] == ' ') ++start;
  return s.substr(start);
}

}  // namespace

std::string error_name(int code) {
  switch (code) {
#define BW_CL_CODE(name) \
  case name:             \
    return #name;
    BW_CL_CODE(CL_SUCCESS)
    BW_CL_CODE(CL_DEVICE_NOT_FOUND)
    BW_CL_CODE(CL_DEVICE_NOT_AVAILABLE)
    BW_CL_CODE(CL_COMPILER_NOT_AVAILABLE)
    BW_CL_CODE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    BW_CL_CODE(CL_OUT_OF_RESOURCES)
    BW_CL_CODE(CL_OUT_OF_HOST_MEMORY)
    BW_CL_CODE(CL_PROFILING_INFO_NOT_AVAILABLE)
    BW_CL_CODE(CL_MEM_COPY_OVERLAP)
    BW_CL_CODE(CL_IMAGE_FORMAT_MISMATCH)
    BW_CL_CODE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    BW_CL_CODE(CL_BUILD_PROGRAM_FAILURE)
    BW_CL_CODE(CL_MAP_FAILURE)
    BW_CL_CODE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
    BW_CL_CODE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    BW_CL_CODE(CL_COMPILE_PROGRAM_FAILURE)
    BW_CL_CODE(CL_LINKER_NOT_AVAILABLE)
    BW_CL_CODE(CL_LINK_PROGRAM_FAILURE)
    BW_CL_CODE(CL_DEVICE_PARTITION_FAILED)
    BW_CL_CODE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
    BW_CL_CODE(CL_INVALID_VALUE)
    BW_CL_CODE(CL_INVALID_DEVICE_TYPE)
    BW_CL_CODE(CL_INVALID_PLATFORM)
    BW_CL_CODE(CL_INVALID_DEVICE)
    BW_CL_CODE(CL_INVALID_CONTEXT)
    BW_CL_CODE(CL_INVALID_QUEUE_PROPERTIES)
    BW_CL_CODE(CL_INVALID_COMMAND_QUEUE)
    BW_CL_CODE(CL_INVALID_HOST_PTR)
    BW_CL_CODE(CL_INVALID_MEM_OBJECT)
    BW_CL_CODE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
    BW_CL_CODE(CL_INVALID_IMAGE_SIZE)
    BW_CL_CODE(CL_INVALID_SAMPLER)
    BW_CL_CODE(CL_INVALID_BINARY)
    BW_CL_CODE(CL_INVALID_BUILD_OPTIONS)
    BW_CL_CODE(CL_INVALID_PROGRAM)
    BW_CL_CODE(CL_INVALID_PROGRAM_EXECUTABLE)
    BW_CL_CODE(CL_INVALID_KERNEL_NAME)
    BW_CL_CODE(CL_INVALID_KERNEL_DEFINITION)
    BW_CL_CODE(CL_INVALID_KERNEL)
    BW_CL_CODE(CL_INVALID_ARG_INDEX)
    BW_CL_CODE(CL_INVALID_ARG_VALUE)
    BW_CL_CODE(CL_INVALID_ARG_SIZE)
    BW_CL_CODE(CL_INVALID_KERNEL_ARGS)
    BW_CL_CODE(CL_INVALID_WORK_DIMENSION)
    BW_CL_CODE(CL_INVALID_WORK_GROUP_SIZE)
    BW_CL_CODE(CL_INVALID_WORK_ITEM_SIZE)
    BW_CL_CODE(CL_INVALID_GLOBAL_OFFSET)
    BW_CL_CODE(CL_INVALID_EVENT_WAIT_LIST)
    BW_CL_CODE(CL_INVALID_EVENT)
    BW_CL_CODE(CL_INVALID_OPERATION)
    BW_CL_CODE(CL_INVALID_GL_OBJECT)
    BW_CL_CODE(CL_INVALID_BUFFER_SIZE)
    BW_CL_CODE(CL_INVALID_MIP_LEVEL)
    BW_CL_CODE(CL_INVALID_GLOBAL_WORK_SIZE)
    BW_CL_CODE(CL_INVALID_PROPERTY)
    BW_CL_CODE(CL_INVALID_IMAGE_DESCRIPTOR)
    BW_CL_CODE(CL_INVALID_COMPILER_OPTIONS)
    BW_CL_CODE(CL_INVALID_LINKER_OPTIONS)
    BW_CL_CODE(CL_INVALID_DEVICE_PARTITION_COUNT)
    BW_CL_CODE(CL_INVALID_PIPE_SIZE)
    BW_CL_CODE(CL_INVALID_DEVICE_QUEUE)
    BW_CL_CODE(CL_INVALID_SPEC_ID)
    BW_CL_CODE(CL_MAX_SIZE_RESTRICTION_EXCEEDED)
#undef BW_CL_CODE
    case kPlatformNotFoundKhr:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "CL_UNKNOWN_ERROR";
  }
}

void throw_cl_error(const cl::Error& e, const std::string& context) {
  fail_run("OpenCL: {} failed: {} ({}){}", e.what(), error_name(e.err()), e.err(), context);
}

std::string DeviceInfo::label() const { return fmt::format("{}: {} ({})", platform, name, type); }

std::string DeviceInfo::describe() const {
  return fmt::format("{:2}  {:<4} {}  [{}; {}, {} compute units, {} memory, float vector width {}]", index, type,
                     name, platform, version, compute_units, human_bytes(global_memory), preferred_float_width);
}

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    if (e.err() == kPlatformNotFoundKhr) return out;
    throw_cl_error(e);
  }
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error& e) {
      if (e.err() == CL_DEVICE_NOT_FOUND) continue;  // a platform without devices
      throw_cl_error(e);
    }
    for (const cl::Device& d : devices) {
      try {
        DeviceInfo info;
        info.index = static_cast<int>(out.size());
        info.platform = trim(platform.getInfo<CL_PLATFORM_NAME>());
        info.name = trim(d.getInfo<CL_DEVICE_NAME>());
        info.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
        info.version = trim(d.getInfo<CL_DEVICE_VERSION>());
        info.c_version = trim(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
        info.driver = trim(d.getInfo<CL_DRIVER_VERSION>());
        info.compute_units = static_cast<int>(d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
        info.global_memory = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
        info.max_allocation = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
        info.preferred_float_width = static_cast<int>(d.getInfo<CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT>());
        out.push_back(std::move(info));
      } catch (const cl::Error& e) {
        throw_cl_error(e, " while listing devices");
      }
    }
  }
  return out;
}

bool valid_device_choice(const std::string& choice) {
  if (choice == "auto" || choice == "cpu" || choice == "gpu") return true;
  if (choice.empty() || choice.size() > 6) return false;
  for (char c : choice)
    if (c < '0' || c > '9') return false;
  return true;
}

DeviceInfo choose_device(const std::string& choice) {
  if (!valid_device_choice(choice)) fail_input("--device: '{}' is not auto, cpu, gpu, list or a device number", choice);
  const std::vector<DeviceInfo> devices = list_devices();
  if (devices.empty()) {
    fail_input("--device {}: no OpenCL device found (install an OpenCL driver, e.g. pocl-opencl-icd)", choice);
  }
  auto first_of = [&](const std::string& type) -> const DeviceInfo* {
    for (const DeviceInfo& d : devices)
      if (d.type == type) return &d;
    return nullptr;
  };
  if (choice == "auto") {
    if (const DeviceInfo* d = first_of("gpu")) return *d;
    if (const DeviceInfo* d = first_of("cpu")) return *d;
    return devices.front();
  }
  if (choice == "cpu" || choice == "gpu") {
    if (const DeviceInfo* d = first_of(choice)) return *d;
    fail_input("--device {}: there is no {} device (see --device list)", choice, choice == "cpu" ? "CPU" : "GPU");
  }
  const long index = std::strtol(choice.c_str(), nullptr, 10);
  if (index < 0 || index >= static_cast<long>(devices.size())) {
    fail_input("--device {}: there are {} devices, numbered 0 to {} (see --device list)", choice, devices.size(),
               devices.size() - 1);
  }
  return devices[static_cast<std::size_t>(index)];
}

}  // namespace bw::compute

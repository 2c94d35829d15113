// OpenCL devices: listing what the machine has and choosing one by name.
//
// Devices are numbered over all platforms in the order the ICD loader reports them;
// that number is what `--device N` takes. `--device auto` prefers the first GPU and
// falls back to the first CPU device (PoCL on machines without a GPU), `cpu` and
// `gpu` take the first device of that type.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bw::compute {

struct DeviceInfo {
  int index = -1;                  // as --device N
  std::string platform;            // platform name ("Portable Computing Language")
  std::string name;                // device name
  std::string type;                // "gpu", "cpu", "accelerator" or "other"
  std::string version;             // OpenCL version of the device
  std::string c_version;           // OpenCL C version of the device's compiler
  std::string driver;              // driver version
  int compute_units = 0;
  std::uint64_t global_memory = 0; // bytes
  std::uint64_t max_allocation = 0;// bytes, largest single buffer
  int preferred_float_width = 1;   // CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT

  // "Portable Computing Language: pthread-skylake (cpu)" for run files and messages.
  std::string label() const;
  // One line for `--device list`.
  std::string describe() const;
};

// Every device of every platform; empty when there is no OpenCL platform at all.
std::vector<DeviceInfo> list_devices();

// "auto", "cpu", "gpu" or a device number. Throws InputError naming the choice when
// no such device exists (and how to list them).
DeviceInfo choose_device(const std::string& choice);

// True for the choices choose_device understands (the syntax, not availability).
bool valid_device_choice(const std::string& choice);

// The symbolic name of an OpenCL error code, e.g. "CL_OUT_OF_RESOURCES" for -5;
// "CL_UNKNOWN_ERROR" for codes outside the standard set.
std::string error_name(int code);

}  // namespace bw::compute

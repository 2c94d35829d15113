// An OpenCL device with its command queue, buffers and kernels, behind types that do
// not expose OpenCL (its headers stay in this folder's .cpp files).
//
// Kernels are OpenCL C files (shaders/*.cl) embedded in the executable and compiled
// at run time for the chosen device: Context::build resolves their `#include "x.h"`
// lines from the same embedded set, marking each file with #line so that the
// compiler's messages name the right file and line. A failed build throws RunError
// with the file name and the compiler log.
//
// Every OpenCL failure becomes a RunError naming the call and the error code's name:
//   "OpenCL: clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5) (kernel fluid_forces, 120000 items)"
//
// All commands go to one in-order queue, so results of a kernel are visible to the
// next one; read() waits for everything queued before it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "compute/device.h"

namespace bw::compute {

// Looks up the text of a source file by its base name; empty when there is none.
using SourceLookup = std::function<std::string_view(std::string_view name)>;

class Context;

// Device memory. Copies share the same memory; it is freed with the last copy.
class Buffer {
 public:
  Buffer() = default;
  bool valid() const { return impl_ != nullptr; }
  std::size_t bytes() const;
  const std::string& name() const;

  struct Impl;

 private:
  friend class Context;
  friend class Kernel;
  std::shared_ptr<Impl> impl_;
};

class Kernel {
 public:
  Kernel() = default;
  const std::string& name() const;

  // Sets argument `index` to a buffer or to a value of a trivially copyable type
  // (scalars, the parameter structs of shaders/sph_common.h, passed by value).
  Kernel& arg(unsigned index, const Buffer& buffer);
  template <class T>
    requires(std::is_trivially_copyable_v<T> && !std::is_same_v<T, Buffer>)
  Kernel& arg(unsigned index, const T& value) {
    return raw_arg(index, sizeof(T), &value);
  }
  // Sets arguments 0, 1, 2, ... in order.
  template <class... A>
  Kernel& args(const A&... a) {
    unsigned i = 0;
    (arg(i++, a), ...);
    return *this;
  }

  struct Impl;

 private:
  friend class Context;
  friend class Program;
  Kernel& raw_arg(unsigned index, std::size_t size, const void* value);
  std::shared_ptr<Impl> impl_;
};

class Program {
 public:
  Program() = default;
  const std::string& name() const;
  // Throws RunError naming the program when it has no such kernel.
  Kernel kernel(const std::string& name) const;

  struct Impl;

 private:
  friend class Context;
  std::shared_ptr<Impl> impl_;
};

// Wall time spent in one kernel (when profiling is on).
struct KernelTime {
  std::string name;
  double seconds = 0;
  std::int64_t launches = 0;
};

class Context {
 public:
  // Creates a context and an in-order queue on the device.
  explicit Context(const DeviceInfo& device);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DeviceInfo& device() const;

  // Allocates `bytes` of device memory, zero-filled. `name` appears in messages.
  Buffer buffer(std::size_t bytes, const std::string& name);

  // Compiles the file `file` (looked up with `lookup`) with the given options, after
  // resolving its quoted #include lines through `lookup`.
  Program build(const std::string& file, const SourceLookup& lookup, const std::string& options);

  // Blocking transfers between host memory and a buffer (byte offsets and sizes).
  void write(Buffer& buffer, const void* data, std::size_t bytes, std::size_t offset = 0);
  void read(const Buffer& buffer, void* data, std::size_t bytes, std::size_t offset = 0);
  template <class T>
  void write_vector(Buffer& buffer, const std::vector<T>& data, std::size_t first = 0) {
    if (!data.empty()) write(buffer, data.data(), data.size() * sizeof(T), first * sizeof(T));
  }
  template <class T>
  std::vector<T> read_vector(const Buffer& buffer, std::size_t count, std::size_t first = 0) {
    std::vector<T> out(count);
    if (count) read(buffer, out.data(), count * sizeof(T), first * sizeof(T));
    return out;
  }
  // Device-side copy of `bytes` from src to dst.
  void copy(const Buffer& src, Buffer& dst, std::size_t bytes, std::size_t src_offset = 0,
            std::size_t dst_offset = 0);

  // Runs `kernel` over `items` work-items (1-D). The work-group size is chosen per
  // kernel from what the device reports for it, and the global size rounded up to a
  // multiple of it, so kernels must check their index against their item count.
  void launch(Kernel& kernel, std::size_t items);
  // Runs `kernel` as `groups` work-groups of `local` work-items each (1-D), for
  // kernels that share local memory within a group. Throws RunError when the device
  // cannot run groups that large for this kernel.
  void launch_groups(Kernel& kernel, std::size_t groups, std::size_t local);
  // Waits until everything queued has run.
  void finish();

  // Bytes held by live buffers of this context.
  std::uint64_t allocated_bytes() const;

  // With profiling on, every launch waits for its kernel and its wall time is added
  // to that kernel's total (slower; for benchmarks).
  void set_profiling(bool on);
  std::vector<KernelTime> kernel_times() const;
  void reset_kernel_times();

 private:
  // Queues `kernel` over `global` work-items in groups of `local` (profiled when on).
  void enqueue(Kernel& kernel, std::size_t global, std::size_t local);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The source `file` with its quoted #include lines replaced by the included files
// (each once), marked with #line directives. Throws RunError naming a file that
// `lookup` does not know.
std::string resolve_includes(const std::string& file, const SourceLookup& lookup);

}  // namespace bw::compute

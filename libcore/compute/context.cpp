#include "compute/context.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "compute/cl_impl.h"

namespace bw::compute {
namespace {

// Work-group size aimed at: a few warps or wavefronts on GPUs, a few SIMD-widths of
// work-items on CPUs; rounded to the kernel's preferred multiple, capped by its limit.
constexpr std::size_t kTargetLocalSize = 64;

// OpenCL refuses zero-sized buffers; an empty array gets this many bytes.
constexpr std::size_t kMinBufferBytes = 16;

cl::Device find_device(const DeviceInfo& info) {
  std::vector<cl::Platform> platforms;
  cl::Platform::get(&platforms);
  int index = 0;
  for (const cl::Platform& p : platforms) {
    std::vector<cl::Device> devices;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error& e) {
      if (e.err() == CL_DEVICE_NOT_FOUND) continue;
      throw;
    }
    for (const cl::Device& d : devices) {
      if (index++ == info.index) return d;
    }
  }
  fail_run("OpenCL device {} ({}) is no longer available", info.index, info.label());
}

}  // namespace

struct Buffer::Impl {
  cl::Buffer buffer;
  std::size_t bytes = 0;
  std::string name;
  std::shared_ptr<std::atomic<std::uint64_t>> allocated;
  ~Impl() {
    if (allocated) *allocated -= bytes;
  }
};

struct Kernel::Impl {
  cl::Kernel kernel;
  std::string name;
  std::size_t local = 0;  // chosen work-group size, 0 until first launch
};

struct Program::Impl {
  cl::Program program;
  std::string name;
};

struct Context::Impl {
  DeviceInfo info;
  cl::Device device;
  cl::Context context;
  cl::CommandQueue queue;
  std::shared_ptr<std::atomic<std::uint64_t>> allocated = std::make_shared<std::atomic<std::uint64_t>>(0);
  bool profiling = false;
  std::map<std::string, KernelTime> times;
};

std::size_t Buffer::bytes() const { return impl_ ? impl_->bytes : 0; }

const std::string& Buffer::name() const {
  static const std::string none = "(none)";
  return impl_ ? impl_->name : none;
}

const std::string& Kernel::name() const {
  static const std::string none = "(none)";
  return impl_ ? impl_->name : none;
}

Kernel& Kernel::arg(unsigned index, const Buffer& buffer) {
  if (!impl_) fail_run("setting an argument of an empty kernel");
  if (!buffer.valid()) fail_run("kernel {}: argument {} is an empty buffer", impl_->name, index);
  try {
    impl_->kernel.setArg(index, buffer.impl_->buffer);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (kernel {}, argument {}, buffer {})", impl_->name, index, buffer.name()));
  }
  return *this;
}

Kernel& Kernel::raw_arg(unsigned index, std::size_t size, const void* value) {
  if (!impl_) fail_run("setting an argument of an empty kernel");
  try {
    impl_->kernel.setArg(index, size, value);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (kernel {}, argument {}, {} bytes)", impl_->name, index, size));
  }
  return *this;
}

const std::string& Program::name() const {
  static const std::string none = "(none)";
  return impl_ ? impl_->name : none;
}

Kernel Program::kernel(const std::string& name) const {
  if (!impl_) fail_run("kernel {} requested from an empty program", name);
  Kernel k;
  k.impl_ = std::make_shared<Kernel::Impl>();
  k.impl_->name = name;
  try {
    k.impl_->kernel = cl::Kernel(impl_->program, name.c_str());
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (kernel {} of {})", name, impl_->name));
  }
  return k;
}

std::string resolve_includes(const std::string& file, const SourceLookup& lookup) {
  std::set<std::string> seen;
  std::function<std::string(const std::string&, const std::string&)> expand = [&](const std::string& name,
                                                                                  const std::string& from) {
    const std::string_view text = lookup(name);
    if (text.empty()) {
      if (from.empty()) fail_run("kernel source {} is not embedded in this program", name);
      fail_run("{}: includes {}, which is not embedded in this program", from, name);
    }
    seen.insert(name);
    std::string out = fmt::format("#line 1 \"{}\"\n", name);
    std::istringstream in{std::string(text)};
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      const std::size_t first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
        const std::size_t open = line.find('"', first);
        const std::size_t close = open == std::string::npos ? open : line.find('"', open + 1);
        if (open != std::string::npos && close != std::string::npos) {
          const std::string inc = line.substr(open + 1, close - open - 1);
          if (!seen.count(inc)) out += expand(inc, name);
          out += fmt::format("#line {} \"{}\"\n", number + 1, name);
          continue;
        }
      }
      out += line;
      out += '\n';
    }
    return out;
  };
  return expand(file, "");
}

Context::Context(const DeviceInfo& device) : impl_(std::make_unique<Impl>()) {
  impl_->info = device;
  try {
    impl_->device = find_device(device);
    impl_->context = cl::Context(impl_->device);
    impl_->queue = cl::CommandQueue(impl_->context, impl_->device);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (creating a context on {})", device.label()));
  }
}

Context::~Context() = default;

const DeviceInfo& Context::device() const { return impl_->info; }

Buffer Context::buffer(std::size_t bytes, const std::string& name) {
  const std::size_t size = std::max(bytes, kMinBufferBytes);
  if (impl_->info.max_allocation && size > impl_->info.max_allocation) {
    fail_run("buffer {} needs {}, more than the {} the device allows in one allocation", name, human_bytes(size),
             human_bytes(impl_->info.max_allocation));
  }
  Buffer b;
  b.impl_ = std::make_shared<Buffer::Impl>();
  b.impl_->name = name;
  try {
    b.impl_->buffer = cl::Buffer(impl_->context, CL_MEM_READ_WRITE, size);
    const cl_uchar zero = 0;
    impl_->queue.enqueueFillBuffer(b.impl_->buffer, zero, 0, size);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (buffer {}, {})", name, human_bytes(size)));
  }
  b.impl_->bytes = size;
  b.impl_->allocated = impl_->allocated;
  *impl_->allocated += size;
  return b;
}

Program Context::build(const std::string& file, const SourceLookup& lookup, const std::string& options) {
  const std::string source = resolve_includes(file, lookup);
  Program p;
  p.impl_ = std::make_shared<Program::Impl>();
  p.impl_->name = file;
  try {
    p.impl_->program = cl::Program(impl_->context, source);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (creating program {})", file));
  }
  try {
    p.impl_->program.build(std::vector<cl::Device>{impl_->device}, options.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = p.impl_->program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(impl_->device);
    } catch (const cl::Error&) {
      log = "(no build log)";
    }
    while (!log.empty() && (log.back() == '\n' || log.back() == '\0' || log.back() == ' ')) log.pop_back();
    fail_run("OpenCL: building {} for {} failed: {} ({})\n{}", file, impl_->info.label(), error_name(e.err()),
             e.err(), log);
  }
  return p;
}

void Context::write(Buffer& buffer, const void* data, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > buffer.bytes())
    fail_run("writing {} bytes at {} into buffer {} of {} bytes", bytes, offset, buffer.name(), buffer.bytes());
  try {
    impl_->queue.enqueueWriteBuffer(buffer.impl_->buffer, CL_TRUE, offset, bytes, data);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (buffer {})", buffer.name()));
  }
}

void Context::read(const Buffer& buffer, void* data, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > buffer.bytes())
    fail_run("reading {} bytes at {} from buffer {} of {} bytes", bytes, offset, buffer.name(), buffer.bytes());
  try {
    impl_->queue.enqueueReadBuffer(buffer.impl_->buffer, CL_TRUE, offset, bytes, data);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (buffer {})", buffer.name()));
  }
}

void Context::copy(const Buffer& src, Buffer& dst, std::size_t bytes, std::size_t src_offset, std::size_t dst_offset) {
  if (bytes == 0) return;
  if (src_offset + bytes > src.bytes() || dst_offset + bytes > dst.bytes())
    fail_run("copying {} bytes from buffer {} to {} runs past the end", bytes, src.name(), dst.name());
  try {
    impl_->queue.enqueueCopyBuffer(src.impl_->buffer, dst.impl_->buffer, src_offset, dst_offset, bytes);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (copying buffer {} to {})", src.name(), dst.name()));
  }
}

void Context::launch(Kernel& kernel, std::size_t items) {
  if (!kernel.impl_) fail_run("launching an empty kernel");
  if (items == 0) return;
  Kernel::Impl& k = *kernel.impl_;
  try {
    if (k.local == 0) {
      const std::size_t limit = k.kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(impl_->device);
      std::size_t multiple = k.kernel.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(impl_->device);
      if (multiple == 0) multiple = 1;
      std::size_t local = (kTargetLocalSize + multiple - 1) / multiple * multiple;
      k.local = std::max<std::size_t>(1, std::min(local, limit));
    }
    enqueue(kernel, (items + k.local - 1) / k.local * k.local, k.local);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (kernel {}, {} items)", k.name, items));
  }
}

void Context::enqueue(Kernel& kernel, std::size_t global, std::size_t local) {
  Kernel::Impl& k = *kernel.impl_;
  const auto start = std::chrono::steady_clock::now();
  impl_->queue.enqueueNDRangeKernel(k.kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(local));
  if (impl_->profiling) {
    impl_->queue.finish();
    KernelTime& t = impl_->times[k.name];
    t.name = k.name;
    t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++t.launches;
  }
}

void Context::launch_groups(Kernel& kernel, std::size_t groups, std::size_t local) {
  if (!kernel.impl_) fail_run("launching an empty kernel");
  if (groups == 0) return;
  Kernel::Impl& k = *kernel.impl_;
  try {
    const std::size_t limit = k.kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(impl_->device);
    if (local > limit)
      fail_run("kernel {} needs work-groups of {} work-items; the device runs at most {}", k.name, local, limit);
    enqueue(kernel, groups * local, local);
  } catch (const cl::Error& e) {
    throw_cl_error(e, fmt::format(" (kernel {}, {} groups of {})", k.name, groups, local));
  }
}

void Context::finish() {
  try {
    impl_->queue.finish();
  } catch (const cl::Error& e) {
    throw_cl_error(e);
  }
}

std::uint64_t Context::allocated_bytes() const { return *impl_->allocated; }

void Context::set_profiling(bool on) {
  finish();
  impl_->profiling = on;
}

std::vector<KernelTime> Context::kernel_times() const {
  std::vector<KernelTime> out;
  for (const auto& [name, t] : impl_->times) out.push_back(t);
  std::sort(out.begin(), out.end(), [](const KernelTime& a, const KernelTime& b) { return a.seconds > b.seconds; });
  return out;
}

void Context::reset_kernel_times() { impl_->times.clear(); }

}  // namespace bw::compute

// The compute layer: device choice, OpenCL errors by name, kernel builds with their
// compiler log, buffers, and the radix sort against std::stable_sort.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"
#include "compute/context.h"
#include "compute/device.h"
#include "compute/kernels.h"
#include "compute/radix_sort.h"

namespace bw::compute {
namespace {

Context& context() {
  static Context c(choose_device("auto"));
  return c;
}

TEST(Device, ListsAndChooses) {
  const auto devices = list_devices();
  ASSERT_FALSE(devices.empty()) << "no OpenCL device: install pocl-opencl-icd";
  for (std::size_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].index, static_cast<int>(i));
    EXPECT_FALSE(devices[i].name.empty());
    EXPECT_GE(devices[i].compute_units, 1);
    EXPECT_FALSE(devices[i].describe().empty());
  }
  const DeviceInfo automatic = choose_device("auto");
  const bool has_gpu = std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.type == "gpu"; });
  EXPECT_EQ(automatic.type == "gpu", has_gpu) << "auto must prefer a GPU when there is one";
  EXPECT_EQ(choose_device("0").index, 0);
  if (!has_gpu) {
    EXPECT_THROW(choose_device("gpu"), InputError);
  }
}

TEST(Device, RejectsBadChoices) {
  EXPECT_FALSE(valid_device_choice("fast"));
  EXPECT_FALSE(valid_device_choice("-1"));
  EXPECT_TRUE(valid_device_choice("12"));
  EXPECT_THROW(choose_device("fast"), InputError);
  try {
    choose_device("999");
    FAIL() << "device 999 should not exist";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--device list"), std::string::npos) << e.what();
  }
}

TEST(Errors, NamesCodes) {
  EXPECT_EQ(error_name(-5), "CL_OUT_OF_RESOURCES");
  EXPECT_EQ(error_name(-4), "CL_MEM_OBJECT_ALLOCATION_FAILURE");
  EXPECT_EQ(error_name(-11), "CL_BUILD_PROGRAM_FAILURE");
  EXPECT_EQ(error_name(-52), "CL_INVALID_KERNEL_ARGS");
  EXPECT_EQ(error_name(-12345), "CL_UNKNOWN_ERROR");
}

TEST(Errors, FailedCallNamesCallAndCode) {
  const std::string src = "__kernel void k(__global float* a, float b) { a[get_global_id(0)] = b; }\n";
  SourceLookup lookup = [&](std::string_view name) { return name == "k.cl" ? std::string_view(src) : std::string_view(); };
  Program p = context().build("k.cl", lookup, "-cl-std=CL1.2");
  Kernel k = p.kernel("k");
  // Arguments never set: the launch fails inside the driver.
  try {
    context().launch(k, 16);
    context().finish();
    FAIL() << "launching a kernel without arguments must fail";
  } catch (const RunError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("clEnqueueNDRangeKernel"), std::string::npos) << m;
    EXPECT_NE(m.find("CL_INVALID_KERNEL_ARGS"), std::string::npos) << m;
    EXPECT_NE(m.find("kernel k"), std::string::npos) << m;
  }
  EXPECT_THROW(p.kernel("missing"), RunError);
}

TEST(Build, FailurePrintsLogWithFileName) {
  const std::string header = "#define TWO 2\n";
  const std::string broken = "#include \"two.h\"\n__kernel void k(__global int* a) {\n  a[0] = TWO + undefined_name;\n}\n";
  SourceLookup lookup = [&](std::string_view name) -> std::string_view {
    if (name == "broken.cl") return broken;
    if (name == "two.h") return header;
    return {};
  };
  try {
    context().build("broken.cl", lookup, "-cl-std=CL1.2");
    FAIL() << "the build should fail";
  } catch (const RunError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("building broken.cl"), std::string::npos) << m;
    EXPECT_NE(m.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << m;
    // The compiler's log points at the right file and line through #line.
    EXPECT_NE(m.find("broken.cl:3"), std::string::npos) << m;
    EXPECT_NE(m.find("undefined_name"), std::string::npos) << m;
  }
}

TEST(Build, ResolvesIncludesOnceAndNamesMissingOnes) {
  const std::string a = "#include \"b.h\"\n#include \"b.h\"\nint a;\n";
  const std::string b = "int b;\n";
  SourceLookup lookup = [&](std::string_view name) -> std::string_view {
    if (name == "a.cl") return a;
    if (name == "b.h") return b;
    return {};
  };
  const std::string out = resolve_includes("a.cl", lookup);
  const std::size_t first = out.find("int b;");
  ASSERT_NE(first, std::string::npos) << out;
  EXPECT_EQ(out.find("int b;", first + 1), std::string::npos) << "b.h included twice:\n" << out;
  EXPECT_NE(out.find("#line 1 \"b.h\""), std::string::npos) << out;
  EXPECT_NE(out.find("#line 3 \"a.cl\""), std::string::npos) << out;
  const std::string c = "#include \"nowhere.h\"\n";
  SourceLookup missing = [&](std::string_view name) -> std::string_view { return name == "c.cl" ? std::string_view(c) : std::string_view(); };
  try {
    resolve_includes("c.cl", missing);
    FAIL();
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.h"), std::string::npos) << e.what();
  }
}

TEST(Build, EmbeddedKernelsCompile) {
  for (const char* file : {"radix_sort.cl", "grid.cl", "fluid.cl"}) {
    EXPECT_NO_THROW(context().build(file, embedded_kernels(), kernel_build_options(context().device()))) << file;
  }
  const int width = kernel_vector_width(context().device());
  EXPECT_TRUE(width == 1 || width == 2 || width == 4 || width == 8 || width == 16);
}

TEST(Buffers, RoundTripAndAccounting) {
  Context& c = context();
  const std::uint64_t before = c.allocated_bytes();
  {
    Buffer b = c.buffer(1000 * sizeof(float), "test floats");
    EXPECT_EQ(c.allocated_bytes(), before + b.bytes());
    const auto zeros = c.read_vector<float>(b, 1000);
    EXPECT_TRUE(std::all_of(zeros.begin(), zeros.end(), [](float v) { return v == 0.0f; })) << "buffers start zeroed";
    std::vector<float> data(1000);
    std::iota(data.begin(), data.end(), 0.5f);
    c.write_vector(b, data);
    EXPECT_EQ(c.read_vector<float>(b, 1000), data);
    EXPECT_EQ(c.read_vector<float>(b, 10, 990), std::vector<float>(data.begin() + 990, data.end()));
    EXPECT_THROW(c.read_vector<float>(b, 10, 995), RunError);
  }
  EXPECT_EQ(c.allocated_bytes(), before);
}

// Sorts random pairs on the device and compares with std::stable_sort.
void check_sort(std::uint32_t n, std::uint32_t max_key, std::uint32_t seed) {
  Context& c = context();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> dist(0, max_key);
  std::vector<std::uint32_t> keys(n), values(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    keys[i] = dist(rng);
    values[i] = i;
  }
  const std::size_t bytes = std::max<std::size_t>(n, 1) * sizeof(std::uint32_t);
  Buffer k = c.buffer(bytes, "keys"), v = c.buffer(bytes, "values"), kt = c.buffer(bytes, "keys tmp"),
         vt = c.buffer(bytes, "values tmp");
  c.write_vector(k, keys);
  c.write_vector(v, values);
  RadixSort sort(c);
  sort.sort(k, v, kt, vt, n, max_key);
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  const auto got_keys = c.read_vector<std::uint32_t>(k, n);
  const auto got_values = c.read_vector<std::uint32_t>(v, n);
  for (std::uint32_t i = 0; i < n; ++i) {
    ASSERT_EQ(got_values[i], order[i]) << "n " << n << ", max key " << max_key << ", position " << i;
    ASSERT_EQ(got_keys[i], keys[order[i]]);
  }
}

TEST(RadixSort, EqualsStableSort) {
  check_sort(0, 10, 1);
  check_sort(1, 10, 2);
  check_sort(257, 3, 3);            // few keys: long runs of equal keys stay in order
  check_sort(100000, 1000, 4);
  check_sort(100000, (1u << 20) - 1, 5);
  check_sort(50000, (1u << 24), 6);  // needs more than two 12-bit digits
  check_sort(20000, 0xffffffffu, 7);
}

TEST(RadixSort, PassesAreEvenAndCoverTheKeys) {
  for (std::uint32_t max_key : {0u, 1u, 255u, 4095u, 4096u, (1u << 24) - 1, 1u << 24, 0xffffffffu}) {
    const int p = RadixSort::passes(max_key), bits = RadixSort::digit_bits(max_key);
    EXPECT_EQ(p % 2, 0) << max_key;
    EXPECT_GE(p * bits, static_cast<int>(std::max(1, static_cast<int>(std::bit_width(max_key))))) << max_key;
    EXPECT_LE(bits, 12) << max_key;
  }
}

}  // namespace
}  // namespace bw::compute

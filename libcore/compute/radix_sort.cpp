#include "compute/radix_sort.h"

#include <algorithm>
#include <bit>

#include "common/error.h"
#include "compute/kernels.h"

namespace bw::compute {
namespace {

// Widest digit: 4096 counters per block keeps a block's counters in a CPU's L1/L2
// and two passes cover 2^24 grid cells.
constexpr int kMaxDigitBits = 12;
// A block's serial loop should be long enough to pay for clearing its counters.
constexpr std::uint32_t kMinChunk = 256;
// Blocks per compute unit: enough work-items to fill a GPU, few enough on a CPU.
constexpr std::uint32_t kBlocksPerUnit = 64;
// Cap on nblocks x radix counters (16 MiB).
constexpr std::uint64_t kMaxCounters = 4u << 20;

}  // namespace

int RadixSort::passes(std::uint32_t max_key) {
  const int bits = std::max(1, static_cast<int>(std::bit_width(max_key)));
  int p = (bits + kMaxDigitBits - 1) / kMaxDigitBits;
  return p + (p % 2);
}

int RadixSort::digit_bits(std::uint32_t max_key) {
  const int bits = std::max(1, static_cast<int>(std::bit_width(max_key)));
  const int p = passes(max_key);
  return (bits + p - 1) / p;
}

RadixSort::RadixSort(Context& context) : context_(context) {
  program_ = context_.build("radix_sort.cl", embedded_kernels(), kernel_build_options(context_.device()));
  count_ = program_.kernel("radix_count");
  offsets_ = program_.kernel("radix_offsets");
  base_ = program_.kernel("radix_digit_base");
  scatter_ = program_.kernel("radix_scatter");
}

std::uint64_t RadixSort::scratch_bytes() const { return counts_.bytes() + totals_.bytes(); }

void RadixSort::sort(Buffer& keys, Buffer& values, Buffer& keys_tmp, Buffer& values_tmp, std::uint32_t n,
                     std::uint32_t max_key) {
  if (n <= 1) return;
  const std::size_t need = std::size_t(n) * sizeof(std::uint32_t);
  if (keys.bytes() < need || values.bytes() < need || keys_tmp.bytes() < need || values_tmp.bytes() < need)
    fail_run("radix sort of {} pairs: a buffer is too small", n);
  const int npasses = passes(max_key);
  const std::uint32_t bits = static_cast<std::uint32_t>(digit_bits(max_key));
  const std::uint32_t radix = 1u << bits;

  const std::uint32_t units = static_cast<std::uint32_t>(std::max(1, context_.device().compute_units));
  std::uint32_t nblocks = (n + kMinChunk - 1) / kMinChunk;
  nblocks = std::min<std::uint32_t>(nblocks, units * kBlocksPerUnit);
  nblocks = static_cast<std::uint32_t>(std::min<std::uint64_t>(nblocks, kMaxCounters / radix));
  nblocks = std::max<std::uint32_t>(nblocks, 1);
  const std::uint32_t chunk = (n + nblocks - 1) / nblocks;
  nblocks = (n + chunk - 1) / chunk;

  const std::size_t counter_bytes = std::size_t(nblocks) * radix * sizeof(std::uint32_t);
  if (counts_.bytes() < counter_bytes) counts_ = context_.buffer(counter_bytes, "radix sort counters");
  if (totals_.bytes() < radix * sizeof(std::uint32_t)) totals_ = context_.buffer(radix * sizeof(std::uint32_t), "radix sort totals");

  Buffer* in_k = &keys;
  Buffer* in_v = &values;
  Buffer* out_k = &keys_tmp;
  Buffer* out_v = &values_tmp;
  for (int pass = 0; pass < npasses; ++pass) {
    const std::uint32_t shift = static_cast<std::uint32_t>(pass) * bits;
    count_.args(*in_k, n, chunk, nblocks, shift, bits, counts_);
    context_.launch(count_, nblocks);
    offsets_.args(counts_, nblocks, bits, totals_);
    context_.launch(offsets_, radix);
    base_.args(totals_, bits);
    context_.launch(base_, 1);
    scatter_.args(*in_k, *in_v, n, chunk, nblocks, shift, bits, counts_, totals_, *out_k, *out_v);
    context_.launch(scatter_, nblocks);
    std::swap(in_k, out_k);
    std::swap(in_v, out_v);
  }
}

}  // namespace bw::compute

// Stable radix sort of (key, value) pairs of 32-bit unsigned integers on the device
// (shaders/radix_sort.cl). Deterministic: the result depends only on the input, never
// on scheduling. Used to order particles by grid cell every step.
#pragma once

#include <cstdint>

#include "compute/context.h"

namespace bw::compute {

class RadixSort {
 public:
  explicit RadixSort(Context& context);

  // Sorts the first n pairs (keys[i], values[i]) by key, keeping the input order of
  // equal keys. Every key must be <= max_key (fewer digit passes for small keys).
  // keys_tmp and values_tmp are scratch buffers of at least n entries; the result is
  // in keys and values.
  void sort(Buffer& keys, Buffer& values, Buffer& keys_tmp, Buffer& values_tmp, std::uint32_t n,
            std::uint32_t max_key);

  // Number of digit passes for keys up to max_key (always even, so that the result
  // lands back in the input buffers) and bits per digit.
  static int passes(std::uint32_t max_key);
  static int digit_bits(std::uint32_t max_key);

  // Device bytes of the sort's own scratch (counters), as last allocated.
  std::uint64_t scratch_bytes() const;

 private:
  Context& context_;
  Program program_;
  Kernel count_, offsets_, base_, scatter_;
  Buffer counts_, totals_;
};

}  // namespace bw::compute

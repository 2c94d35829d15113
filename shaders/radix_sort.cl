// Stable least-significant-digit radix sort of (key, value) pairs of uint
// (libcore/compute/radix_sort.h). Deterministic and portable: no atomics, no local
// memory, no barriers. The input is cut into contiguous blocks; one work-item owns a
// block and its own row of digit counters, so counting and scattering within a block
// keep the input order, which makes every pass, and so the whole sort, stable.
//
// counts: nblocks x radix, row b holds block b's counters (then its offsets).

// Block b counts the digits (key >> shift) & (radix - 1) of its elements.
__kernel void radix_count(__global const uint* keys, uint n, uint chunk, uint nblocks, uint shift,
                          uint digit_bits, __global uint* counts) {
  const uint b = get_global_id(0);
  if (b >= nblocks) return;
  const uint radix = 1u << digit_bits;
  const uint mask = radix - 1u;
  __global uint* c = counts + (size_t)b * radix;
  for (uint d = 0; d < radix; ++d) c[d] = 0;
  const uint begin = b * chunk;
  const uint end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) c[(keys[i] >> shift) & mask] += 1;
}

// One work-item per digit d: replaces column d of the counts by the number of
// elements with digit d in the blocks before (exclusive prefix over blocks) and
// writes the digit's total.
__kernel void radix_offsets(__global uint* counts, uint nblocks, uint digit_bits, __global uint* totals) {
  const uint d = get_global_id(0);
  const uint radix = 1u << digit_bits;
  if (d >= radix) return;
  uint sum = 0;
  for (uint b = 0; b < nblocks; ++b) {
    const size_t k = (size_t)b * radix + d;
    const uint c = counts[k];
    counts[k] = sum;
    sum += c;
  }
  totals[d] = sum;
}

// One work-item: turns the digit totals into the first output position of each digit.
__kernel void radix_digit_base(__global uint* totals, uint digit_bits) {
  if (get_global_id(0) != 0) return;
  const uint radix = 1u << digit_bits;
  uint sum = 0;
  for (uint d = 0; d < radix; ++d) {
    const uint t = totals[d];
    totals[d] = sum;
    sum += t;
  }
}

// Block b moves its elements, in order, to base[digit] + offset within the digit.
__kernel void radix_scatter(__global const uint* keys, __global const uint* values, uint n, uint chunk,
                            uint nblocks, uint shift, uint digit_bits, __global uint* counts,
                            __global const uint* base, __global uint* keys_out, __global uint* values_out) {
  const uint b = get_global_id(0);
  if (b >= nblocks) return;
  const uint radix = 1u << digit_bits;
  const uint mask = radix - 1u;
  __global uint* c = counts + (size_t)b * radix;
  const uint begin = b * chunk;
  const uint end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) {
    const uint key = keys[i];
    const uint d = (key >> shift) & mask;
    const uint pos = base[d] + c[d];
    c[d] += 1;
    keys_out[pos] = key;
    values_out[pos] = values[i];
  }
}

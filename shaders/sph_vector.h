// Vector types for the neighbour loops of the kernels (OpenCL C only).
//
// A fluid particle's neighbours lie in 9 rows of 3 grid cells, and the particles of a
// row are contiguous in memory (sorted by cell). The loops walk a row BW_VW
// candidates at a time with vector loads and masked sums, so CPUs (PoCL) use their
// SIMD units; on GPUs BW_VW is 1 and the same code is a plain scalar loop. The host
// picks BW_VW from the device's preferred float vector width (compute/kernels.h).
// Buffers read this way are padded by BW_VW elements past their capacity.
#ifndef BW_SPH_VECTOR_H
#define BW_SPH_VECTOR_H

#ifndef BW_VW
#define BW_VW 1
#endif

#if BW_VW == 1
typedef float vfloat;
typedef int vint;
#define VAS_INT as_int
#define VAS_FLOAT as_float
#define VLOAD(p) (*(p))
#define VLANES 0
#define VSUM(v) (v)
#elif BW_VW == 2
typedef float2 vfloat;
typedef int2 vint;
#define VAS_INT as_int2
#define VAS_FLOAT as_float2
#define VLOAD(p) vload2(0, p)
#define VLANES ((int2)(0, 1))
#define VSUM(v) ((v).s0 + (v).s1)
#elif BW_VW == 4
typedef float4 vfloat;
typedef int4 vint;
#define VAS_INT as_int4
#define VAS_FLOAT as_float4
#define VLOAD(p) vload4(0, p)
#define VLANES ((int4)(0, 1, 2, 3))
#define VSUM(v) (((v).s0 + (v).s1) + ((v).s2 + (v).s3))
#elif BW_VW == 8
typedef float8 vfloat;
typedef int8 vint;
#define VAS_INT as_int8
#define VAS_FLOAT as_float8
#define VLOAD(p) vload8(0, p)
#define VLANES ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#define VSUM(v) ((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7)))
#elif BW_VW == 16
typedef float16 vfloat;
typedef int16 vint;
#define VAS_INT as_int16
#define VAS_FLOAT as_float16
#define VLOAD(p) vload16(0, p)
#define VLANES ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define BW_VSUM8(v) ((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7)))
#define VSUM(v) (BW_VSUM8((v).lo) + BW_VSUM8((v).hi))
#else
#error "BW_VW must be 1, 2, 4, 8 or 16"
#endif

// 1 / sqrt(x) for x > 0 to about float precision (relative error < 1e-6), without
// the square root and division that rsqrt and native_rsqrt compile to on CPUs (PoCL):
// the classic bit-level estimate refined by three Newton steps, all FMAs and integer
// ops that vectorise. Deterministic like every other operation here.
static inline vfloat bw_rsqrt(vfloat x) {
  vfloat y = VAS_FLOAT(0x5f3759df - (VAS_INT(x) >> 1));
  const vfloat hx = 0.5f * x;
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  return y;
}

// Lanes j + lane < end are real candidates of the row; the rest read past it.
#define VIN_ROW(j, end) (((vint)(int)(j) + VLANES) < (vint)(int)(end))

#endif

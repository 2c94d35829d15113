// The neighbour grid (method.md 6, step 1): cubic cells of edge h over the domain.
// Every step the fluid particles get the index of their cell as key, are sorted by
// it (compute/radix_sort.h, stable), their arrays are gathered into that order, and
// start[c] is the index of the first particle of cell c or beyond, so that the
// particles of cells a..b are [start[a], start[b + 1]). A particle outside the
// domain gets the key ncells: it sorts after every cell and is dropped, and
// start[ncells] is the number of particles that stay. Boundary particles use the
// same kernels with their own arrays (clamped into the grid instead of dropped).
#include "sph_common.h"

// Cell keys of fluid particles; ncells for a particle outside the domain (or NaN).
__kernel void fluid_keys(SimParams P, uint n, __global const float* x, __global const float* y,
                         __global const float* z, __global uint* keys, __global uint* values) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const bool inside = xi >= P.ox && xi < P.max_x && yi >= P.oy && yi < P.max_y && zi >= P.oz && zi < P.max_z;
  uint key = (uint)P.ncells;
  if (inside) {
    key = (uint)bw_cell_index(bw_cell_coord(xi, P.ox, P.inv_cell, P.nx), bw_cell_coord(yi, P.oy, P.inv_cell, P.ny),
                              bw_cell_coord(zi, P.oz, P.inv_cell, P.nz), P.nx, P.ny);
  }
  keys[i] = key;
  values[i] = i;
}

// Cell keys of boundary particles, clamped into the grid (the host drops those
// farther than h outside it, which can touch no fluid).
__kernel void boundary_keys(SimParams P, uint n, __global const float* x, __global const float* y,
                            __global const float* z, __global uint* keys, __global uint* values) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  keys[i] = (uint)bw_cell_index(bw_cell_coord(x[i], P.ox, P.inv_cell, P.nx), bw_cell_coord(y[i], P.oy, P.inv_cell, P.ny),
                                bw_cell_coord(z[i], P.oz, P.inv_cell, P.nz), P.nx, P.ny);
  values[i] = i;
}

// start[c] for every c in [0, ncells]: the first sorted index whose key is >= c.
// Work-item i (0..n) writes the cells between the previous key and its own, so each
// cell is written exactly once and nothing needs clearing.
__kernel void cell_starts(uint n, uint ncells, __global const uint* keys, __global uint* start) {
  const uint i = get_global_id(0);
  if (i > n) return;
  const uint hi = i < n ? min(keys[i], ncells) : ncells;
  const uint lo = i == 0 ? 0u : min(keys[i - 1], ncells) + 1u;
  for (uint c = lo; c <= hi; ++c) start[c] = i;
}

// Gathers the fluid arrays into sorted order: out[i] = in[order[i]].
__kernel void fluid_reorder(uint n, __global const uint* order, __global const float* x, __global const float* y,
                            __global const float* z, __global const float* vx, __global const float* vy,
                            __global const float* vz, __global const uint* id, __global const uint* hold,
                            __global const float* rho, __global float* x2, __global float* y2, __global float* z2,
                            __global float* vx2, __global float* vy2, __global float* vz2, __global uint* id2,
                            __global uint* hold2, __global float* rho2) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint j = order[i];
  x2[i] = x[j];
  y2[i] = y[j];
  z2[i] = z[j];
  vx2[i] = vx[j];
  vy2[i] = vy[j];
  vz2[i] = vz[j];
  id2[i] = id[j];
  hold2[i] = hold[j];
  rho2[i] = rho[j];
}

// Gathers a float and a uint boundary array into sorted order (called per array set).
__kernel void gather_float(uint n, __global const uint* order, __global const float* in, __global float* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  out[i] = in[order[i]];
}

__kernel void gather_uint(uint n, __global const uint* order, __global const uint* in, __global uint* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  out[i] = in[order[i]];
}

// For tests: the sorted indices of the fluid particles within h of particle i
// (including i), up to max_count, and how many there are.
__kernel void neighbour_lists(SimParams P, __global const uint* start, __global const float* x,
                              __global const float* y, __global const float* z, uint max_count,
                              __global uint* count, __global uint* list) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  uint found = 0;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = start[row + x0], e = start[row + x1 + 1];
      for (uint j = s; j < e; ++j) {
        const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        if (dx * dx + dy * dy + dz * dz < P.h2) {
          if (found < max_count) list[(size_t)i * max_count + found] = j;
          ++found;
        }
      }
    }
  }
  count[i] = found;
}

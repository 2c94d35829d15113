// Boundary-particle rules shared by the fluid kernels (fluid.cl) and the rigid-body
// kernels (rigid.cl), so that a reaction the rigid side gathers is computed by the
// very code that applied the action on the fluid side (OpenCL C only).
//
// Boundary arrays are sorted by grid cell (grid.cl): bx, by, bz positions, bnx, bny,
// bnz unit surface normals (zero where unknown), bvx, bvy, bvz velocities, bsolid the
// owner (a static solid, or a body; rigid.cl).
#ifndef BW_SPH_BOUNDARY_H
#define BW_SPH_BOUNDARY_H

#include "sph_common.h"

// A boundary particle lies on a face of its solid when the normals of the surface in
// its cell agree this well (flatness, sim/setup.h surface_normals: 1 on a face, 0.71
// on a right-angled edge; 0.9 takes edges of up to 50 degrees between their faces, and
// curved surfaces sampled finer than their curvature, as faces).
#define BW_FACE_FLATNESS 0.9f

// 1 / sqrt(x) as sph_vector.h's bw_rsqrt computes it, one value at a time (the force
// kernel's lanes and this give the same bits).
static inline float bw_rsqrt1(float x) {
  float y = as_float(0x5f3759df - (as_int(x) >> 1));
  const float hx = 0.5f * x;
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  return y;
}

// The boundary pressure force on fluid particle f from boundary particle b is
// c Psi_b (h - r)^2 / r (x_f - x_b), c = gamma2 (p_f / rho_f^2 + p_b / rho0^2) / m_k in
// pterm's units (pt = kp p_f / rho_f^2): bw_boundary_kb(pt_f, rho_f) + bpt_b, with
// bpt_b = 0 for a mirrored wall, whose p_b is p_f (kb holds both halves), and for a
// hydrostatic one the pressure b holds (boundary_pressure, fluid.cl; bw_wall_term
// bounds it per pair), so that the layer
// next to a wall is held up as the fluid below it would hold it. Every kernel that
// applies or gathers the force uses these.
static inline float bw_boundary_kb(SimParams P, float pt, float rho) {
  return P.wall_hydrostatic ? P.gamma2 / P.kernel_mass * pt
                            : P.gamma2 / (P.kernel_mass * P.rho0 * P.rho0) * (pt * P.rho0 * P.rho0 + pt * rho * rho);
}

// The hydrostatic wall's term for fluid particle f at distance r from b: bpt_b, but no
// more than f's own pressure continued by the water's weight over r and one h more,
// gamma2 kp (p_f + rho_f |g| (r + h)) / (m_k rho0^2). At rest that bound is above p_b;
// it holds back what b's average brings from elsewhere: across a solid one particle
// thick the pressure of the far side's fluid (a jet on a baffle shot the fluid behind
// it off at 1400 m/s), in an impact a denser neighbour's (a block fired into a corner
// at the speed of sound gained 36% of its kinetic energy). bw_wall_cap's pair gives
// the bound as cap.x + cap.y r, the same bits in every kernel.
static inline float2 bw_wall_cap(SimParams P, float pt, float rho) {
  const float g = sqrt(P.gx * P.gx + P.gy * P.gy + P.gz * P.gz);
  const float k = P.gamma2 / (P.kernel_mass * P.rho0 * P.rho0);
  const float slope = k * (P.pressure_scale * rho * g);
  return (float2)(k * (pt * rho * rho) + slope * P.h, slope);
}

static inline float bw_wall_term(float bpt, float2 cap, float r) { return fmin(bpt, cap.x + cap.y * r); }

// Akinci's sum_k W_spiky(x_bk) over the boundary particles k of b's owner around the
// sorted boundary particle i (Psi_b = rho0 / the sum), leaving out the particles of a
// face turned away from b's (normals more than 120 degrees apart, BW_PSI_OPPOSED): the
// other side of a part as thin as a spacing, which the fluid at b's face does not
// reach (at h = 2 spacings it lies h from b's first fluid layer) and which would make b
// stand for less fluid than gamma1's calibration assumes (a tank wall two spacings
// thick sampled on both faces weighed 13% less). Particles without a normal (both
// faces of a part thinner than a cell) count.
#define BW_PSI_OPPOSED (-0.5f)
static inline float bw_psi_sum(SimParams P, uint i, __global const uint* bstart, __global const float* bx,
                               __global const float* by, __global const float* bz, __global const float* bnx,
                               __global const float* bny, __global const float* bnz, __global const uint* bsolid) {
  const float xi = bx[i], yi = by[i], zi = bz[i];
  const float nxi = bnx[i], nyi = bny[i], nzi = bnz[i];
  const uint solid = bsolid[i];
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  float sum = 0.0f;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = bstart[row + x0], e = bstart[row + x1 + 1];
      for (uint j = s; j < e; ++j) {
        if (bsolid[j] != solid || nxi * bnx[j] + nyi * bny[j] + nzi * bnz[j] < BW_PSI_OPPOSED) continue;
        const float dx = xi - bx[j], dy = yi - by[j], dz = zi - bz[j];
        const float r = sqrt(dx * dx + dy * dy + dz * dz);
        if (r < P.h) sum += P.spiky * (P.h - r) * (P.h - r) * (P.h - r);
      }
    }
  }
  return sum;
}

// Wall contact of one fluid particle at (xi, yi, zi) whose velocity after the force
// update is (*ux, *uy, *uz) (fluid_integrate, docs/scene.md "Physics"): each boundary
// particle b stands for a patch of its solid's surface, the disc of radius P.patch
// around it normal to bn (a sphere of radius P.contact where bn is zero). Over such a
// patch, closer than P.contact to its plane, the particle loses the part of its
// velocity relative to the patch (bv) that goes into the surface. Patches are taken
// one after the other in the grid's order. The velocity change made by the patch of
// sorted index `target` is returned in (*tx, *ty, *tz) (zero when it made none; pass
// 0xffffffff for no target).
static inline void bw_wall_contact(SimParams P, float xi, float yi, float zi, float* ux, float* uy, float* uz,
                                   __global const uint* bstart, __global const float* bx, __global const float* by,
                                   __global const float* bz, __global const float* bnx, __global const float* bny,
                                   __global const float* bnz, __global const float* bvx, __global const float* bvy,
                                   __global const float* bvz, __global const uint* bsolid,
                                   __global const uint* one_sided, uint target, float* tx, float* ty, float* tz) {
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float patch2 = P.patch * P.patch;
  float vx = *ux, vy = *uy, vz = *uz;
  *tx = 0.0f, *ty = 0.0f, *tz = 0.0f;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint bs = bstart[row + x0], be = bstart[row + x1 + 1];
      for (uint b = bs; b < be; ++b) {
        const float dx = xi - bx[b], dy = yi - by[b], dz = zi - bz[b];
        const float r2 = dx * dx + dy * dy + dz * dz;
        float nx = bnx[b], ny = bny[b], nz = bnz[b];
        float dn = dx * nx + dy * ny + dz * nz;
        if (nx == 0.0f && ny == 0.0f && nz == 0.0f) {  // no normal: a sphere around b
          if (r2 <= 0.0f) continue;
          dn = sqrt(r2);
          nx = dx / dn, ny = dy / dn, nz = dz / dn;
        } else if (dn < 0.0f) {
          // Behind b's plane. A surface alone is wetted on both sides: the particle is on
          // the other side, kept from crossing back. A volume's surface lies half a
          // spacing beyond its particles: up to there the particle is in the surface's
          // layer and may only leave it the way it came; further it is on the far side
          // of a part two cells thick. (Half the scene's spacing, P.layer: a solid
          // sampled coarser, up to 1.5 times, has a deeper layer whose last quarter
          // spacing still counts as the far side.)
          const uint o = bsolid[b];
          const bool volume = o >= P.static_owners || one_sided[o] != 0u;
          if (!volume || dn <= -P.layer) dn = -dn, nx = -nx, ny = -ny, nz = -nz;
        }
        if (dn >= P.contact || r2 - dn * dn >= patch2) continue;
        // Static patches have bv = 0, and v - 0 is v exactly.
        const float into = (vx - bvx[b]) * nx + (vy - bvy[b]) * ny + (vz - bvz[b]) * nz;
        if (into < 0.0f) {
          vx -= into * nx;
          vy -= into * ny;
          vz -= into * nz;
          if (b == target) *tx = -into * nx, *ty = -into * ny, *tz = -into * nz;
        }
      }
    }
  }
  *ux = vx, *uy = vy, *uz = vz;
}

#endif

// Fracture (method.md 3, "Ours"; docs/scene.md "Fracture"): the load the fluid puts
// on the boundary particles of breakable bodies, and the seed test. Only built and
// run when the scene has a breakable solid (sim/fracture_stage.cpp).
//
// Per boundary particle b of a breakable body (slot g, master index map[g]):
//   D_b <- exp(-dt / window) D_b + dt sum_j a_jb
// where a_jb is the acceleration b's pressure gives fluid particle j (the boundary
// pressure term of fluid_forces, without friction, viscosity or gravity): D_b is the
// velocity change b has caused in the fluid over the window. Handed out evenly to the
// n_b fluid particles within h of b, it is the kinetic energy
//   E_b = m |D_b|^2 / (2 n_b)
// the fluid gave up against b. The seed test compares it with b's binding energy:
// strength = E_b / E_r,b (a seed where >= 1).
#include "sph_common.h"
#include "sph_boundary.h"

#define BW_MIN_R2_FRACTION 1e-12f

__kernel void fracture_load(SimParams P, uint count, float dt, float decay, __global const uint* map,
                            __global const uint* rank, __global const uint* start, __global const float* x,
                            __global const float* y, __global const float* z, __global const float* rho,
                            __global const float* pterm, __global const float* bx, __global const float* by,
                            __global const float* bz, __global const float* bpsi, __global const float* bpt,
                            __global const float* binding,
                            __global float* dvx, __global float* dvy, __global float* dvz, __global float* energy,
                            __global float* strength) {
  const uint g = get_global_id(0);
  if (g >= count) return;
  const uint i = rank[map[g]];
  const float xb = bx[i], yb = by[i], zb = bz[i];
  const float psi = bpsi[i];
  // fluid_forces adds the wall's own pressure term, b's for every fluid particle
  const float bpti = P.wall_hydrostatic ? bpt[i] : 0.0f;
  const int cx = bw_cell_coord(xb, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yb, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zb, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  const float min_r2 = h2 * BW_MIN_R2_FRACTION;
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  float n = 0.0f;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = start[row + x0], e = start[row + x1 + 1];
      for (uint j = s; j < e; ++j) {
        const float dx = x[j] - xb, dy = y[j] - yb, dz = z[j] - zb;
        const float r2 = dx * dx + dy * dy + dz * dz;
        if (r2 < h2 && r2 > min_r2) {
          // rigid.cl boundary_forces: the pressure part of the boundary term of j
          const float ptj = pterm[j];
          const float rhoj = rho[j];
          const float ir = bw_rsqrt1(fmax(r2, min_r2));
          const float kbb = bw_boundary_kb(P, ptj, rhoj) +
                            (P.wall_hydrostatic ? bw_wall_term(bpti, bw_wall_cap(P, ptj, rhoj), r2 * ir) : 0.0f);
          const float q = h - r2 * ir;
          const float c = kbb * psi * q * q * ir;
          sx += c * dx;
          sy += c * dy;
          sz += c * dz;
          n += 1.0f;
        }
      }
    }
  }
  const float ux = decay * dvx[g] + dt * sx, uy = decay * dvy[g] + dt * sy, uz = decay * dvz[g] + dt * sz;
  dvx[g] = ux;
  dvy[g] = uy;
  dvz[g] = uz;
  const float e = 0.5f * P.mass * (ux * ux + uy * uy + uz * uz) / fmax(n, 1.0f);
  energy[g] = e;
  strength[g] = e / binding[g];
}

// The Voronoi cells of a fracture's seeds restricted to a body (method.md 4, "Ours";
// sim/fracture_stage.cpp): per voxel, the nearest seed. Coordinates are in voxel
// units relative to the centre of the body's voxels (the host converts them from
// the reference configuration in double), which keeps float's error to about 1e-7 of
// the body's size. The voxels come sorted by the cells of a uniform grid of 4 voxels
// edge ("bricks", at most 64 voxels each; brick_start[b] is the first voxel of brick
// b, brick_lo and brick_hi the box of its voxels), one work-group per brick: the
// group first lists the seeds that can be nearest to some point of its box (those
// no farther from the box than the least farthest-corner distance of any seed),
// then each voxel compares only those. The label is the nearest seed's index (ties:
// the lower), with BW_SEED_CLOSE set when another seed's squared distance is within
// `tol` of it: float cannot tell those apart reliably, and the host decides them in
// double (the same rule as fracture::nearest_seeds), so that the cells do not depend
// on the device.
#define BW_SEED_CLOSE 0x80000000u
#define BW_BRICK 64
// Candidate seeds a group lists in local memory (4 KiB); with more, its voxels
// compare every seed.
#define BW_LISTED_SEEDS 1024

__kernel __attribute__((reqd_work_group_size(BW_BRICK, 1, 1))) void voxel_seeds(
    uint nseeds, __global const float4* seeds, __global const uint* brick_start, __global const float4* brick_lo,
    __global const float4* brick_hi, __global const float* vx, __global const float* vy, __global const float* vz,
    float tol, __global uint* label) {
  __local float least[BW_BRICK];
  __local uint counts[BW_BRICK + 1];
  __local uint listed[BW_LISTED_SEEDS];
  const uint b = get_group_id(0), lid = get_local_id(0);
  const float4 lo = brick_lo[b], hi = brick_hi[b];
  float far = INFINITY;
  for (uint k = lid; k < nseeds; k += BW_BRICK) {
    const float4 q = seeds[k];
    const float fx = fmax(fabs(q.x - lo.x), fabs(q.x - hi.x)), fy = fmax(fabs(q.y - lo.y), fabs(q.y - hi.y)),
                fz = fmax(fabs(q.z - lo.z), fabs(q.z - hi.z));
    far = fmin(far, fx * fx + fy * fy + fz * fz);
  }
  least[lid] = far;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint w = BW_BRICK / 2; w > 0; w >>= 1) {
    if (lid < w) least[lid] = fmin(least[lid], least[lid + w]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  // A seed farther than this from every point of the box is never within tol of the
  // nearest. The seeds within it are listed in index order: each work-item marks a
  // contiguous share of the seeds, a scan of the shares' counts gives where each
  // share's marked seeds go.
  const float reach = least[0] + 2.0f * tol;
  const uint share = (nseeds + BW_BRICK - 1) / BW_BRICK;
  const uint k0 = min(lid * share, nseeds), k1 = min(k0 + share, nseeds);
  uint mine = 0;
  for (uint k = k0; k < k1; ++k) {
    const float4 q = seeds[k];
    const float nx = fmax(fmax(lo.x - q.x, q.x - hi.x), 0.0f), ny = fmax(fmax(lo.y - q.y, q.y - hi.y), 0.0f),
                nz = fmax(fmax(lo.z - q.z, q.z - hi.z), 0.0f);
    mine += nx * nx + ny * ny + nz * nz <= reach ? 1u : 0u;
  }
  counts[lid] = mine;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid == 0) {
    uint sum = 0;
    for (uint w = 0; w < BW_BRICK; ++w) {
      const uint c = counts[w];
      counts[w] = sum;
      sum += c;
    }
    counts[BW_BRICK] = sum;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  uint at = counts[lid];
  for (uint k = k0; k < k1; ++k) {
    const float4 q = seeds[k];
    const float nx = fmax(fmax(lo.x - q.x, q.x - hi.x), 0.0f), ny = fmax(fmax(lo.y - q.y, q.y - hi.y), 0.0f),
                nz = fmax(fmax(lo.z - q.z, q.z - hi.z), 0.0f);
    if (nx * nx + ny * ny + nz * nz <= reach) {
      if (at < BW_LISTED_SEEDS) listed[at] = k;
      ++at;
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  const uint ncand = counts[BW_BRICK];
  const uint first = brick_start[b];
  if (lid >= brick_start[b + 1] - first) return;
  const uint v = first + lid;
  const float px = vx[v], py = vy[v], pz = vz[v];
  float best = INFINITY, second = INFINITY;
  uint which = 0xffffffffu;
  // Candidates in index order, so that the first of equal distances (the lower seed)
  // stays; a list longer than local memory holds is not used (every seed compared).
  const bool use_list = ncand <= BW_LISTED_SEEDS;
  const uint loop = use_list ? ncand : nseeds;
  for (uint c = 0; c < loop; ++c) {
    const uint k = use_list ? listed[c] : c;
    const float4 q = seeds[k];
    const float dx = q.x - px, dy = q.y - py, dz = q.z - pz;
    const float d = dx * dx + dy * dy + dz * dz;
    const bool nearer = d < best;
    second = nearer ? best : fmin(second, d);
    which = nearer ? k : which;
    best = nearer ? d : best;
  }
  label[v] = which | (second - best <= tol ? BW_SEED_CLOSE : 0u);
}

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
                            __global const float* bz, __global const float* bpsi, __global const float* binding,
                            __global float* dvx, __global float* dvy, __global float* dvz, __global float* energy,
                            __global float* strength) {
  const uint g = get_global_id(0);
  if (g >= count) return;
  const uint i = rank[map[g]];
  const float xb = bx[i], yb = by[i], zb = bz[i];
  const float psi = bpsi[i];
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
          const float kb = P.gamma2 / (P.mass * P.rho0 * P.rho0) * (ptj * P.rho0 * P.rho0 + ptj * rhoj * rhoj);
          const float ir = bw_rsqrt1(fmax(r2, min_r2));
          const float q = h - r2 * ir;
          const float c = kb * psi * q * q * ir;
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

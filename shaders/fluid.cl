// The fluid step (method.md 1, 2, 6): density with the boundary term, Tait pressure,
// forces, symplectic Euler, emitters, and the reductions the host needs for the time
// step, the guard and the frame statistics.
//
// Fluid arrays are one float per particle and component (x, y, z, vx, ...), sorted by
// grid cell (grid.cl); boundary arrays likewise (bx, by, bz, bpsi = Psi_b, bvx, ...).
// Each fluid particle gathers from its neighbours: no atomics, no scattered writes,
// so a step is deterministic. Neighbour loops run BW_VW candidates at a time
// (sph_vector.h).
#include "sph_common.h"
#include "sph_vector.h"
#include "sph_boundary.h"
#include "sph_images.h"

// Pairs closer than this fraction of h^2 contribute no pressure or friction (the
// particle itself, or two particles on the same spot, which have no direction).
#define BW_MIN_R2_FRACTION 1e-12f
// The density diffusion's (0.1 h)^2, as Molteni & Colagrossi and DualSPHysics write it.
#define BW_DIFFUSION_ETA2 0.01f
// 0: the density pass without the diffusion's terms (the solver builds it so when
// fluid.diffusion is 0).
#ifndef BW_DIFFUSION
#define BW_DIFFUSION 1
#endif
// At rest the fluid next to a wall carries more density than the hydrostatic line,
// which the mirrored wall's boundary force (gamma2 = gamma1 / 2, p_i alone) needs: its
// excess over rho0 is about (1 + BW_WALL_STEP phi) times the hydrostatic one, phi its
// boundary fraction (fluid_density's diffusion; docs/scene.md, "Density"). The
// hydrostatic wall (sph_boundary.h) needs no step: 0.
#define BW_WALL_STEP (P.wall_layer_step)
// 0: no step (the hydrostatic wall), and the density pass's diffusion leaves out the
// neighbours' boundary fractions that only the step needs (the solver builds it so:
// their loads were a fifth of the pass).
#ifndef BW_WALL_STEP_ON
#define BW_WALL_STEP_ON 1
#endif
// 1: gravity along z (the solver builds it so when g has no x or y part), and the
// diffusion's hydrostatic part takes one product instead of three.
#ifndef BW_GRAVITY_ALONG_Z
#define BW_GRAVITY_ALONG_Z 0
#endif

// Non-finite test on the bits, immune to compiler options that assume finite math.
static inline bool bw_finite(float v) { return (as_uint(v) & 0x7f800000u) != 0x7f800000u; }

// (h - r)^3 at the end of a step less at its start, for a pair at squared distance r2
// whose squared distance at the start was r2 + d2 (d2 from the pair's velocity, so
// that slow pairs lose nothing to cancellation). Where both ends lie inside the
// support it is (r_start - r)((h - r)^2 + (h - r)(h - r_start) + (h - r_start)^2),
// with r_start - r = d2 / (r_start + r); 0 where both lie outside.
static inline vfloat bw_spiky_change(float h, float min_r2, vfloat r2, vfloat d2) {
  const vfloat rn = sqrt(fmax(r2, min_r2)), rp = sqrt(fmax(r2 + d2, min_r2));
  const vfloat qn = fmax(h - rn, 0.0f), qp = fmax(h - rp, 0.0f);
  const vfloat inside = d2 / (rp + rn) * (qn * qn + qn * qp + qp * qp);
  return select(qn * qn * qn - qp * qp * qp, inside, (qn > 0.0f) & (qp > 0.0f));
}

// A density with the wall layer's expected step taken out (BW_WALL_STEP): what the
// diffusion compares between neighbours, so that the step survives it.
// A macro, for one particle and for a vector of neighbours alike.
#define BW_WALL_REDUCED(rho0, rho, phi) ((rho0) + ((rho) - (rho0)) / (1.0f + BW_WALL_STEP * (phi)))

// Akinci's Psi_b = rho0 / sum_k W(x_bk), the sum over the boundary particles k of the
// same owner, a static solid or a body (including b), on b's side of the part
// (bw_psi_sum): the fluid mass a boundary particle stands for. W is the boundary
// kernel, W_spiky.
__kernel void boundary_psi(SimParams P, uint nb, __global const uint* bstart, __global const float* bx,
                           __global const float* by, __global const float* bz, __global const float* bnx,
                           __global const float* bny, __global const float* bnz, __global const uint* bsolid,
                           __global float* bpsi) {
  const uint i = get_global_id(0);
  if (i >= nb) return;
  bpsi[i] = P.rho0 / bw_psi_sum(P, i, bstart, bx, by, bz, bnx, bny, bnz, bsolid);
}

// The boundary fraction phi = sum_b Psi_b W_spiky(x_ib) / rho0 of every particle at
// its current position, before fluid_density with the continuity equation, whose
// diffusion reads it for each pair (there fluid_density leaves phi as it is).
__kernel void fluid_wall_fraction(SimParams P, __global const uint* start, __global const float* x,
                                  __global const float* y, __global const float* z, __global const uint* bstart,
                                  __global const float* bx, __global const float* by, __global const float* bz,
                                  __global const float* bpsi, __global float* phi) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  vfloat wb = 0.0f;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const int bs = (int)bstart[row + x0], be = (int)bstart[row + x1 + 1];
      for (int j = bs; j < be; j += BW_VW) {
        const vfloat dx = xi - VLOAD(bx + j), dy = yi - VLOAD(by + j), dz = zi - VLOAD(bz + j);
        const vfloat r2 = dx * dx + dy * dy + dz * dz;
        const vfloat q = h - sqrt(r2);
        wb += select((vfloat)0.0f, VLOAD(bpsi + j) * q * q * q, (r2 < h2) & VIN_ROW(j, be));
      }
    }
  }
  phi[i] = P.spiky * VSUM(wb) / P.rho0;
}

// At t = 0 with the continuity equation (after fluid_wall_fraction): the blocks'
// hydrostatic densities get the wall layer's step, rho0 + (1 + BW_WALL_STEP phi)
// (rho - rho0), the state at rest that the diffusion leaves alone and the boundary
// force needs, so that a pool against walls starts in balance.
__kernel void fluid_wall_step(SimParams P, __global const uint* start, __global const float* phi,
                              __global float* rho_state) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  rho_state[i] = P.rho0 + (1.0f + BW_WALL_STEP * phi[i]) * (rho_state[i] - P.rho0);
}

// The mirror planes of every fluid particle (sph_images.h), after a sort and before the
// density pass: the planes of the faces of static solids whose particles lie within h,
// when the wall there is those planes alone. A particle keeps the boundary particles
// (no plane) where its neighbourhood holds anything the planes would misrepresent: a
// boundary particle behind a plane that is neither on one of the planes' faces, nor
// behind two of them (the rows behind a concave edge), nor buried against another
// plane's solid (a wall block's end against the next wall, a box's bottom on the
// floor), nor the back of a part thinner than h; a body's particle behind a plane; a
// fluid neighbour behind one; planes neither at right angles nor facing across a gap of
// h or more; more than three. So convex edges, the rims of faces, curved parts and
// bodies keep their particles.
__kernel void fluid_wall_planes(SimParams P, __global const uint* start, __global const float* x,
                                __global const float* y, __global const float* z, __global const uint* bstart,
                                __global const float* bx, __global const float* by, __global const float* bz,
                                __global const float* bnx, __global const float* bny, __global const float* bnz,
                                __global const float* bflat, __global const uint* bsolid,
                                __global const OwnerParams* owners, __global uint4* wplane, __global uint4* wowner) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h2 = P.h2, same_d = BW_IMAGE_SAME_OFFSET * P.layer, spacing = 2.0f * P.layer;
  float4 pl[BW_IMAGE_PLANES] = {(float4)(0.0f), (float4)(0.0f), (float4)(0.0f)};
  uint at[BW_IMAGE_PLANES] = {BW_NO_PLANE, BW_NO_PLANE, BW_NO_PLANE};  // each plane's boundary particle
#if BW_GHOST_BODIES
  uint own[BW_IMAGE_PLANES] = {0u, 0u, 0u};  // each plane's solid, of its particle nearest to i
  float nearest[BW_IMAGE_PLANES] = {h2, h2, h2};
#endif
  int count = 0;
  bool ok = true;
  // The planes: faces within h with the particle in front of them, of solids that do
  // not give way to the water (static, moved as told, or fixed).
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1) && ok; ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1) && ok; ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = bstart[row + x0], e = bstart[row + x1 + 1];
      for (uint b = s; b < e; ++b) {
        const float dx = xi - bx[b], dy = yi - by[b], dz = zi - bz[b];
        const float r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= h2 || bw_image_gives_way(P, owners, bsolid[b]) || bflat[b] < BW_FACE_FLATNESS) continue;
        const float4 face = bw_image_plane(P, b, bx, by, bz, bnx, bny, bnz);
        const float nx = face.x, ny = face.y, nz = face.z, d = face.w;
        if (!(nx * xi + ny * yi + nz * zi > d)) continue;  // the particle is behind this face
        // Of parallel faces the particle is in front of (a part thinner than h, seen
        // through), the nearest is the wall; the farther one's particles lie behind it.
        bool known = false;
        for (int k = 0; k < count; ++k) {
          if (!(pl[k].x * nx + pl[k].y * ny + pl[k].z * nz > BW_IMAGE_SAME_COS)) continue;
          known = true;
          if (d > pl[k].w + same_d) {
            pl[k] = face;
            at[k] = b;
#if BW_GHOST_BODIES
            own[k] = bsolid[b], nearest[k] = r2;
          } else if (!(d < pl[k].w - same_d) && r2 < nearest[k]) {
            own[k] = bsolid[b], nearest[k] = r2;
#endif
          }
        }
        if (known) continue;
        if (count == BW_IMAGE_PLANES) {
          ok = false;
          break;
        }
#if BW_GHOST_BODIES
        own[count] = bsolid[b], nearest[count] = r2;
#endif
        at[count] = b;
        pl[count++] = face;
      }
    }
  }
  for (int a = 0; a < count && ok; ++a)
    for (int c = a + 1; c < count; ++c) {
      const float cosine = pl[a].x * pl[c].x + pl[a].y * pl[c].y + pl[a].z * pl[c].z;
      // A channel's two walls: the particle between n . x > d_a and -n . x > d_c, a gap
      // of -(d_a + d_c). Refusing them where the far wall just comes within h would
      // switch the particle between images and particles from step to step (a flume two
      // particles wide gained 10% of its energy in 9 s so).
      const bool facing = cosine < -BW_IMAGE_SAME_COS && -(pl[a].w + pl[c].w) >= BW_IMAGE_FACING_GAP * P.h;
      ok = ok && (fabs(cosine) < BW_IMAGE_PERPENDICULAR || facing);
    }
  // What lies behind the planes must be the planes' own wall.
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1) && ok && count > 0; ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1) && ok; ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = bstart[row + x0], e = bstart[row + x1 + 1];
      for (uint b = s; b < e && ok; ++b) {
        const float xb = bx[b], yb = by[b], zb = bz[b];
        const float dx = xi - xb, dy = yi - yb, dz = zi - zb;
        if (dx * dx + dy * dy + dz * dz >= h2) continue;
        int behind = 0;
        for (int k = 0; k < count; ++k) behind += bw_image_behind(pl[k], xb, yb, zb) ? 1 : 0;
        if (behind == 0) continue;  // in front of the wall: a particle of its own
        const float nx = bnx[b], ny = bny[b], nz = bnz[b];
        const bool face = bflat[b] >= BW_FACE_FLATNESS;
        const bool on = face && bw_image_face_of(P, pl, count, xb, yb, zb, nx, ny, nz, bflat[b]) >= 0;
        if (bw_image_gives_way(P, owners, bsolid[b])) {
          ok = false;
        } else if (behind == 1 && !on) {
          // A face or an edge buried against another plane's solid passes (a wall block's
          // end against the next wall); anything else is a wall the planes do not describe.
          const float ox = xb + spacing * nx, oy = yb + spacing * ny, oz = zb + spacing * nz;
          int buried = 0;
          for (int k = 0; k < count; ++k)
            buried += bw_image_behind(pl[k], ox, oy, oz) && !bw_image_behind(pl[k], xb, yb, zb) ? 1 : 0;
          // So does the back of the plane's own part, thinner than h: a face turned away
          // from the plane's.
          bool back = false;
          for (int k = 0; k < count; ++k)
            back = back || (bw_image_behind(pl[k], xb, yb, zb) &&
                            pl[k].x * nx + pl[k].y * ny + pl[k].z * nz < -BW_IMAGE_SAME_COS);
          ok = buried > 0 || (face && back);
        }
      }
    }
  }
  // No fluid behind the planes: the wall is there.
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1) && ok && count > 0; ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1) && ok; ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = start[row + x0], e = start[row + x1 + 1];
      for (uint j = s; j < e && ok; ++j) {
        const float dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
        if (dx * dx + dy * dy + dz * dz >= h2) continue;
        ok = !bw_image_replaced(pl, count, x[j], y[j], z[j]);
      }
    }
  }
  wplane[i] = ok ? (uint4)(at[0], at[1], at[2], 0u) : (uint4)(BW_NO_PLANE, BW_NO_PLANE, BW_NO_PLANE, 0u);
#if BW_GHOST_BODIES
  wowner[i] = (uint4)(own[0], own[1], own[2], 0u);
#endif
}

// The density of every particle, then the Tait pressure, the per-particle factors the
// force kernel reads, with the constants of its sums folded in (pterm = kp p / rho^2,
// vol = kv / rho, below), and the boundary fraction phi = sum_b Psi_b W_spiky(x_ib) /
// rho0 (1 on a wall's layer of particles, 0.15 one spacing from a flat wall, 0 far
// from walls; with the continuity equation and the mirrored wall's density step
// fluid_wall_fraction writes it before, for the diffusion).
//
// The density is the sum rho_i = m sum_j W(x_ij) + gamma1 sum_b Psi_b W(x_ib) with
// W = W_spiky, or, with P.continuity (docs/scene.md, "Density"), the particle's own,
// integrated over the step just taken (dt) from rho_state, its value at the start of
// that step (in the current order), by the continuity equation
//   drho_i/dt = m sum_j v_ij . grad W_ij + gamma1 sum_b Psi_b v_ib . grad W_ib + D_i,
// the time derivative of the sum above, plus Fourtakas et al. 2019's diffusion D_i.
// The boundary term is integrated exactly along the step: symplectic Euler moves a
// particle in a straight line, x_ib - v_ib dt at the step's start (a moving body's
// particles to first order), so its integral is the change of the boundary sum over
// the step, gamma1 sum_b Psi_b (W(x_ib) - W(x_ib - v_ib dt)), and a particle that
// leaves a wall gets back the density it had before it came: v . grad W dt from the
// step's end kept a quarter of rho0 after a bounce at the speed of sound, and the
// particle hit the next wall harder and came back faster each time. Wall particles
// that left the 27 cells during the step miss at most (v dt)^3 of h^3. (The same
// for the fluid pairs blew up SPHERIC Test 2 at 0.01 m, docs/scene.md.) The
// fluid's terms are v . grad W and the diffusion
//   D_i = 2 delta h c0 sum_j (m / rho_j) (rho_j - rho_i - rho_H,ji) x_ji . grad W_ij / (r^2 + eta^2),
// the Laplacian of the density less its hydrostatic part rho_H,ji = H.x_ji, so that a
// pool at rest does not diffuse (boundary particles carry no density: no diffusion
// with them). The densities it compares have the wall layer's step taken out,
// rho0 + (rho - rho0) / (1 + BW_WALL_STEP phi), phi from fluid_wall_fraction: at
// rest the layer against a wall carries more density than the hydrostatic line, which
// its boundary force needs, and diffusing that step away lets the layer sink and the
// column above it creep (docs/scene.md, "Density"); the pair's rate is multiplied by
// 1 + BW_WALL_STEP (phi_i + phi_j) / 2, so that the layer's own fluctuations, which
// the reduced densities show that much smaller, are damped as fast as the
// interior's. The fluid's rates are taken at the end of
// the step, from the positions and the velocities the step gave: with symplectic
// Euler's v += a dt that pairs like x += v dt does, where a rate from the start of
// the step would pump the sound waves up.
// The least carried density, over rho0 (docs/scene.md, "Density"): spray that flies
// apart keeps the water's density, and below rho0 there is no pressure to lose. Without
// it a jet's spray thinned to 0.1 rho0 and its diffusion and viscosity weights, m / rho,
// blew the jet on the baffle up.
#define BW_RHO_FLOOR 0.9f
// The density pass's parameters, for its body and its two kernels (below).
#define BW_DENSITY_PARAMS                                                                                 \
  SimParams P, float dt, __global const uint* start, __global const float* x, __global const float* y,  \
      __global const float* z, __global const float* vx, __global const float* vy,                      \
      __global const float* vz, __global const float* rho_state, __global const uint* bstart,           \
      __global const float* bx, __global const float* by, __global const float* bz,                    \
      __global const float* bpsi, __global const float* bvx, __global const float* bvy,                 \
      __global const float* bvz, __global float* rho, __global float* pres, __global float* pterm,      \
      __global float* vol, __global float* phi, __global float* diffusion_rate, __global const float* bnx, \
      __global const float* bny, __global const float* bnz, __global const uint4* wplane,               \
      __global const uint4* wowner, __global const BodyPose* poses
#define BW_DENSITY_ARGS \
  P, dt, start, x, y, z, vx, vy, vz, rho_state, bstart, bx, by, bz, bpsi, bvx, bvy, bvz, rho, pres, pterm, vol, phi, \
      diffusion_rate, bnx, bny, bnz, wplane, wowner, poses
#if BW_GHOST_WALLS
// The images' term of bw_fluid_density for the neighbours j .. j + BW_VW - 1 below row
// end e: j's images across every set of i's planes, at x_j' and with v_j' reflected in
// each plane's frame (the particle itself too: its own image), add the change of
// (h - r)^3 along the step to *si. Across a moving solid's plane v' = R (v - w(x)) +
// w(x'), w = V + W x (x - c) the solid's velocity field; w(x') = w(x) - dk W x n gives
// v' = v - 2 (n . (v - w(x))) n - dk W x n (compiled only for scenes with bodies,
// BW_GHOST_BODIES: the branch differs from particle to particle, and a device that
// runs particles in lockstep pays for both sides of it).
static inline void bw_images_change(const float4* pl, const int planes, const int* body,
                                    __global const BodyPose* poses,
                                    __global const float* x, __global const float* y, __global const float* z,
                                    __global const float* vx, __global const float* vy, __global const float* vz,
                                    const int j, const int e, const float xi, const float yi, const float zi,
                                    const float vxi, const float vyi, const float vzi, const float h,
                                    const float min_r2, const float dt, vfloat* si) {
  for (int set = 1; set < (1 << planes); ++set) {
    vfloat gx = VLOAD(x + j), gy = VLOAD(y + j), gz = VLOAD(z + j);
    vfloat ux = VLOAD(vx + j), uy = VLOAD(vy + j), uz = VLOAD(vz + j);
    for (int k = 0; k < planes; ++k) {
      if (!((set >> k) & 1)) continue;
      const vfloat dk = 2.0f * (pl[k].x * gx + pl[k].y * gy + pl[k].z * gz - pl[k].w);
      if (BW_GHOST_BODIES && body[k] >= 0) {
        const BodyPose B = poses[body[k]];
        const float3 W = (float3)(B.wx, B.wy, B.wz), n = pl[k].xyz;
        const vfloat rx = gx - B.cx, ry = gy - B.cy, rz = gz - B.cz;
        const vfloat wn = n.x * B.vx + n.y * B.vy + n.z * B.vz + n.x * (W.y * rz - W.z * ry) +
                          n.y * (W.z * rx - W.x * rz) + n.z * (W.x * ry - W.y * rx);
        const vfloat uk = 2.0f * (n.x * ux + n.y * uy + n.z * uz - wn);
        const float3 wxn = cross(W, n);
        ux -= uk * n.x + dk * wxn.x, uy -= uk * n.y + dk * wxn.y, uz -= uk * n.z + dk * wxn.z;
      } else {
        const vfloat uk = 2.0f * (pl[k].x * ux + pl[k].y * uy + pl[k].z * uz);
        ux -= uk * pl[k].x, uy -= uk * pl[k].y, uz -= uk * pl[k].z;
      }
      gx -= dk * pl[k].x, gy -= dk * pl[k].y, gz -= dk * pl[k].z;
    }
    gx = xi - gx, gy = yi - gy, gz = zi - gz;
    ux = vxi - ux, uy = vyi - uy, uz = vzi - uz;
    const vfloat g2 = gx * gx + gy * gy + gz * gz;
    const vfloat d2 = dt * (dt * (ux * ux + uy * uy + uz * uz) - 2.0f * (ux * gx + uy * gy + uz * gz));
    *si += select((vfloat)0.0f, bw_spiky_change(h, min_r2, g2, d2), VIN_ROW(j, e));
  }
}
#endif

inline void bw_fluid_density(BW_DENSITY_PARAMS, const uint want_rate) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  vfloat wf = 0.0f, wb = 0.0f;
  float r;
  if (!P.continuity) {
    for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
      for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
        const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
        const int s = (int)start[row + x0], e = (int)start[row + x1 + 1];
        for (int j = s; j < e; j += BW_VW) {
          const vfloat dx = xi - VLOAD(x + j), dy = yi - VLOAD(y + j), dz = zi - VLOAD(z + j);
          const vfloat r2 = dx * dx + dy * dy + dz * dz;
          const vfloat q = h - sqrt(r2);
          wf += select((vfloat)0.0f, q * q * q, (r2 < h2) & VIN_ROW(j, e));
        }
        const int bs = (int)bstart[row + x0], be = (int)bstart[row + x1 + 1];
        for (int j = bs; j < be; j += BW_VW) {
          const vfloat dx = xi - VLOAD(bx + j), dy = yi - VLOAD(by + j), dz = zi - VLOAD(bz + j);
          const vfloat r2 = dx * dx + dy * dy + dz * dz;
          const vfloat q = h - sqrt(r2);
          wb += select((vfloat)0.0f, VLOAD(bpsi + j) * q * q * q, (r2 < h2) & VIN_ROW(j, be));
        }
      }
    }
    r = P.spiky * P.kernel_mass * VSUM(wf) + P.gamma1 * (P.spiky * VSUM(wb));
  } else {
    const float vxi = vx[i], vyi = vy[i], vzi = vz[i];
    const float rhoi = rho_state[i];
#if BW_WALL_STEP_ON
    const float phii = phi[i], rti = BW_WALL_REDUCED(P.rho0, rhoi, phii);
#else
    const float rti = rhoi;
#endif
    const float min_r2 = h2 * BW_MIN_R2_FRACTION;  // keeps 1/r finite for the particle itself
    const float eta2 = BW_DIFFUSION_ETA2 * h2;
#if BW_GHOST_WALLS
    float4 pl[BW_IMAGE_PLANES];
    const int planes = bw_image_planes(P, i, wplane, bx, by, bz, bnx, bny, bnz, pl);
    // The body of each plane (moved as told, or fixed; -1: a static solid's), whose
    // pose gives its velocity field.
    int body[BW_IMAGE_PLANES] = {-1, -1, -1};
#if BW_GHOST_BODIES
    {
      const uint4 o4 = wowner[i];
      const uint o[BW_IMAGE_PLANES] = {o4.x, o4.y, o4.z};
      for (int k = 0; k < planes; ++k) body[k] = o[k] >= P.static_owners ? (int)(o[k] - P.static_owners) : -1;
    }
#endif
#endif
#if BW_GHOST_WALLS
    vfloat si = 0.0f;  // the images' change of sum (h - r)^3 over the step (as the boundary's)
#endif
    vfloat sd = 0.0f;  // the fluid's drho/dt over -3 spiky m
    vfloat sl = 0.0f;  // the diffusion's rate on rho_i itself over 3 spiky m delta'
    vfloat sb = 0.0f;  // the step's change of sum_b Psi_b (h - r)^3
    for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
      for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
        const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
        const int s = (int)start[row + x0], e = (int)start[row + x1 + 1];
        for (int j = s; j < e; j += BW_VW) {
          const vfloat dx = xi - VLOAD(x + j), dy = yi - VLOAD(y + j), dz = zi - VLOAD(z + j);
          const vfloat r2 = dx * dx + dy * dy + dz * dz;
          const vint ok = (r2 < h2) & VIN_ROW(j, e);
          const vfloat ir = bw_rsqrt(fmax(r2, min_r2));
          const vfloat q = h - r2 * ir;
          // v_ij . x_ij, and -rho_H,ji = H.x_ij; x_ji . grad W_ij / r^2 = 3 spiky (h - r)^2 / r.
          // Lanes past the row or the support may hold anything: select, never multiply by 0.
          const vfloat vij = (vxi - VLOAD(vx + j)) * dx + (vyi - VLOAD(vy + j)) * dy + (vzi - VLOAD(vz + j)) * dz;
#if BW_DIFFUSION
          const vfloat rhoj = VLOAD(rho_state + j);
#if BW_GRAVITY_ALONG_Z
          const vfloat hyd = P.hz * dz;  // the same bits: the other two terms add zeros
#else
          const vfloat hyd = P.hx * dx + P.hy * dy + P.hz * dz;
#endif
          // The diffusion's weight x_ji . grad W / (r^2 + eta^2): spiky's gradient does not
          // vanish at r = 0, and without eta two close particles would diffuse without bound.
          // rate (rti - rtj - hyd) / rho_j with rtj = rho0 + (rho_j - rho0) / sj, with one
          // division, taken as a reciprocal so that it need not wait for the numerator
          // (docs/performance.md).
          const vfloat r = r2 * ir;
#if BW_WALL_STEP_ON
          const vfloat phij = VLOAD(phi + j);
          const vfloat sj = 1.0f + BW_WALL_STEP * phij;
          const vfloat pair = 1.0f + 0.5f * BW_WALL_STEP * (phii + phij);
          const vfloat num = ((rti - P.rho0 - hyd) * sj - (rhoj - P.rho0)) * pair * r;
          const vfloat den = sj * (r2 + eta2) * rhoj;
          const vfloat self = pair * r * sj / (1.0f + BW_WALL_STEP * phii);  // d num / d rho_i
#else
          const vfloat num = (rti - rhoj - hyd) * r;
          const vfloat den = (r2 + eta2) * rhoj;
          const vfloat self = r;
#endif
          const vfloat inv = 1.0f / den;
          sd += select((vfloat)0.0f, q * q * (vij * ir + P.diffusion * num * inv), ok);
          if (want_rate) sl += select((vfloat)0.0f, q * q * self * inv, ok);
#else
          sd += select((vfloat)0.0f, q * q * (vij * ir), ok);
#endif
#if BW_GHOST_WALLS
          // j's images (bw_images_change). Like the boundary's term (below), their change
          // over the step is integrated exactly along it, (h - r)^3 at its end less at its
          // start: with the rate at the step's end, water that struck a wall and left it
          // kept density it had not lost, and the jet on the baffle gained 25% of its
          // energy in 40 ms.
          bw_images_change(pl, planes, body, poses, x, y, z, vx, vy, vz, j, e, xi, yi, zi, vxi, vyi, vzi, h, min_r2,
                           dt, &si);
#endif
        }
        const int bs = (int)bstart[row + x0], be = (int)bstart[row + x1 + 1];
        for (int j = bs; j < be; j += BW_VW) {
          const vfloat dx = xi - VLOAD(bx + j), dy = yi - VLOAD(by + j), dz = zi - VLOAD(bz + j);
          const vfloat ux = vxi - VLOAD(bvx + j), uy = vyi - VLOAD(bvy + j), uz = vzi - VLOAD(bvz + j);
          const vfloat r2 = dx * dx + dy * dy + dz * dz;
          const vfloat d2 = dt * (dt * (ux * ux + uy * uy + uz * uz) - 2.0f * (ux * dx + uy * dy + uz * dz));
#if BW_GHOST_WALLS
          vint kept = VIN_ROW(j, be);
          for (int k = 0; k < planes; ++k)
            kept = kept & (pl[k].x * VLOAD(bx + j) + pl[k].y * VLOAD(by + j) + pl[k].z * VLOAD(bz + j) >= pl[k].w);
          sb += select((vfloat)0.0f, VLOAD(bpsi + j) * bw_spiky_change(h, min_r2, r2, d2), kept);
#else
          sb += select((vfloat)0.0f, VLOAD(bpsi + j) * bw_spiky_change(h, min_r2, r2, d2), VIN_ROW(j, be));
#endif
#if !BW_WALL_STEP_ON
          const vfloat q = h - sqrt(r2);
          wb += select((vfloat)0.0f, VLOAD(bpsi + j) * q * q * q, (r2 < h2) & VIN_ROW(j, be));
#endif
        }
      }
    }
    r = rhoi + P.spiky * (P.gamma1 * VSUM(sb) - 3.0f * P.kernel_mass * VSUM(sd) * dt);
#if BW_GHOST_WALLS
    r += P.spiky * P.kernel_mass * VSUM(si);
#endif
    r = fmax(r, BW_RHO_FLOOR * P.rho0);
    // The rate at which the diffusion pulls rho_i toward its neighbours' (1/s), the
    // diagonal of the explicit update: the step's diffusion limit (solver.cpp), on the
    // steps the solver asks for it (want_rate; the term is the same either way).
    if (want_rate) diffusion_rate[i] = 3.0f * P.spiky * P.kernel_mass * P.diffusion * VSUM(sl);
  }
  const float p = bw_tait(r, P.rho0, P.stiffness, P.gamma, P.gamma_int);
  rho[i] = r;
  pres[i] = p;
  pterm[i] = P.pressure_scale * p / (r * r);
  vol[i] = P.viscosity_scale / r;
  // With the continuity equation and a wall step fluid_wall_fraction wrote phi before
  // (the diffusion reads the neighbours'); otherwise this pass finds it, as that one does.
#if BW_WALL_STEP_ON
  if (!P.continuity) phi[i] = P.spiky * VSUM(wb) / P.rho0;
#else
  phi[i] = P.spiky * VSUM(wb) / P.rho0;
#endif
}

// The density pass as two kernels, with and without the diffusion's rate, so that the
// steps that skip the rate (solver_impl.h, ensure_grid) do not pay for it; the
// term's arithmetic is the same in both.
__kernel void fluid_density(BW_DENSITY_PARAMS) {
  bw_fluid_density(BW_DENSITY_ARGS, 0u);
}

__kernel void fluid_density_rate(BW_DENSITY_PARAMS) {
  bw_fluid_density(BW_DENSITY_ARGS, 1u);
}

// The pressure a hydrostatic wall's boundary particle b holds (P.wall_hydrostatic),
// Adami et al. 2012's extrapolation from the fluid around it,
//   p_b = sum_f (p_f + rho_f g.(x_b - x_f)) W(x_bf) / sum_f W(x_bf)   (0 without fluid),
// as the fluid's own pressure would continue into the wall (not below 0, like the
// Tait law's), written as bpt_b = gamma2 kp p_b / (m_k rho0^2), its share of the
// boundary force's c (sph_boundary.h). A field of the wall's own, the same for every
// fluid particle near b up to the bound bw_wall_term sets per pair: the force between
// b and f is then along x_bf and the same on the fluid's side and the solid's.
__kernel void boundary_pressure(SimParams P, uint nb, __global const uint* start, __global const float* x,
                                __global const float* y, __global const float* z, __global const float* rho,
                                __global const float* pres, __global const float* bx, __global const float* by,
                                __global const float* bz, __global float* bpt) {
  const uint i = get_global_id(0);
  if (i >= nb) return;
  const float xb = bx[i], yb = by[i], zb = bz[i];
  const int cx = bw_cell_coord(xb, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yb, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zb, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  vfloat sw = 0.0f, sp = 0.0f;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const int s = (int)start[row + x0], e = (int)start[row + x1 + 1];
      for (int j = s; j < e; j += BW_VW) {
        const vfloat dx = VLOAD(x + j) - xb, dy = VLOAD(y + j) - yb, dz = VLOAD(z + j) - zb;
        const vfloat r2 = dx * dx + dy * dy + dz * dz;
        const vfloat q = h - sqrt(r2);
        const vint ok = (r2 < h2) & VIN_ROW(j, e);
        // g.(x_b - x_f) = -g.(x_f - x_b)
        const vfloat pf = VLOAD(pres + j) - VLOAD(rho + j) * (P.gx * dx + P.gy * dy + P.gz * dz);
        const vfloat w = select((vfloat)0.0f, q * q * q, ok);
        sw += w;
        sp += select((vfloat)0.0f, w * pf, ok);
      }
    }
  }
  const float w = VSUM(sw);
  const float pb = w > 0.0f ? fmax(VSUM(sp) / w, 0.0f) : 0.0f;
  bpt[i] = P.gamma2 / P.kernel_mass * P.pressure_scale * pb / (P.rho0 * P.rho0);
}

// Accelerations (method.md 1 and 2.3; the pressure forces use the gradient of the
// density's kernel, W_spiky, docs/scene.md "Physics"):
//   pressure   -m sum_j (p_i/rho_i^2 + p_j/rho_j^2) grad W_spiky(x_ij)
//   viscosity  (mu/rho_i) sum_j m (v_j - v_i)/rho_j lap W_visc(x_ij)
//   boundary   -gamma2 sum_b Psi_b (p_i/rho_i^2 + p_b/rho0^2) grad W_spiky(x_ib), p_b = p_i (mirrored)
//              or the wall's own (P.wall_hydrostatic, boundary_pressure)
//   friction   (mu_b/rho_i) sum_b (Psi_b/rho0) (v_b - v_i) lap W_visc(x_ib)
//   gravity    g
// with grad W_spiky(x) = -3 spiky (h - r)^2 x / r and lap W_visc = visc (h - r). A particle in contact with a wall
// (phi > contact) also gets the wall's normal n, pointing from the wall to it, for
// the contact rule of fluid_integrate; other particles get n = 0.
__kernel void fluid_forces(SimParams P, __global const uint* start, __global const float* x,
                           __global const float* y, __global const float* z, __global const float* vx,
                           __global const float* vy, __global const float* vz, __global const float* rho,
                           __global const float* pterm, __global const float* vol, __global const uint* bstart,
                           __global const float* bx, __global const float* by, __global const float* bz,
                           __global const float* bpsi, __global const float* bpt, __global const float* bvx,
                           __global const float* bvy, __global const float* bvz, __global float* ax,
                           __global float* ay, __global float* az, __global const uint4* wplane,
                           __global float4* image_share, __global const float* bnx, __global const float* bny,
                           __global const float* bnz, __global const float* bflat) {
  const uint i = get_global_id(0);
  if (i >= start[P.ncells]) return;
  const float xi = x[i], yi = y[i], zi = z[i];
  const float vxi = vx[i], vyi = vy[i], vzi = vz[i];
  const float pti = pterm[i];  // kp p_i / rho_i^2, kp = 3 spiky m / c
  const float rhoi = rho[i];
  const float inv_rhoi = 1.0f / rhoi;
  // The boundary terms' own factors, per particle: pressure (gamma2, mirrored p_i)
  // and friction (mu_b), scaled like the fluid terms so that one sum holds all.
  const float kb = bw_boundary_kb(P, pti, rhoi);
  const float2 cap = bw_wall_cap(P, pti, rhoi);
  const float kf = P.mu_b * P.visc / P.rho0 * inv_rhoi;
  const int cx = bw_cell_coord(xi, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yi, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zi, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  const float min_r2 = h2 * BW_MIN_R2_FRACTION;  // keeps 1/r finite for the particle itself
  vfloat sx = 0.0f, sy = 0.0f, sz = 0.0f;  // the acceleration, but gravity
#if BW_GHOST_WALLS
  float4 pl[BW_IMAGE_PLANES];
  const int planes = bw_image_planes(P, i, wplane, bx, by, bz, bnx, bny, bnz, pl);
  // per plane: the images' push along its normal (m/s^2), and the weight sum_b Psi_b
  // (h - r)^3 of the boundary particles it replaces (rigid.cl shares the push by it)
  vfloat gp0 = 0.0f, gp1 = 0.0f, gp2 = 0.0f;
  float gw[BW_IMAGE_PLANES] = {0.0f, 0.0f, 0.0f};
#endif
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = start[row + x0], e = start[row + x1 + 1];
      for (uint j = s; j < e; j += BW_VW) {
        const vfloat dx = xi - VLOAD(x + j), dy = yi - VLOAD(y + j), dz = zi - VLOAD(z + j);
        const vfloat r2 = dx * dx + dy * dy + dz * dz;
        const vint ok = (r2 < h2) & VIN_ROW(j, e);
        const vfloat ir = bw_rsqrt(fmax(r2, min_r2));
        const vfloat q = h - r2 * ir;
        // pressure: (Pi + Pj) (h - r)^2 / r x_ij; viscosity: (h - r)/rho_j (v_j - v_i)
        // over rho_i. The particle itself adds 0 to both (x_ii = 0, v_i - v_i = 0).
        const vfloat c = select((vfloat)0.0f, (pti + VLOAD(pterm + j)) * q * q * ir, ok);
        const vfloat w = select((vfloat)0.0f, q * VLOAD(vol + j) * inv_rhoi, ok);
        sx += c * dx + w * (VLOAD(vx + j) - vxi);
        sy += c * dy + w * (VLOAD(vy + j) - vyi);
        sz += c * dz + w * (VLOAD(vz + j) - vzi);
#if BW_GHOST_WALLS
        // j's images push with j's pressure (the particle's own image too).
        for (int set = 1; set < (1 << planes); ++set) {
          vfloat gx = VLOAD(x + j), gy = VLOAD(y + j), gz = VLOAD(z + j);
          for (int k = 0; k < planes; ++k) {
            if (!((set >> k) & 1)) continue;
            const vfloat dk = 2.0f * (pl[k].x * gx + pl[k].y * gy + pl[k].z * gz - pl[k].w);
            gx -= dk * pl[k].x, gy -= dk * pl[k].y, gz -= dk * pl[k].z;
          }
          gx = xi - gx, gy = yi - gy, gz = zi - gz;
          const vfloat g2 = gx * gx + gy * gy + gz * gz;
          const vfloat gir = bw_rsqrt(fmax(g2, min_r2));
          const vfloat gq = h - g2 * gir;
          const vfloat gc = select((vfloat)0.0f, (pti + VLOAD(pterm + j)) * gq * gq * gir, (g2 < h2) & VIN_ROW(j, e));
          sx += gc * gx;
          sy += gc * gy;
          sz += gc * gz;
          // The reaction on the face of each plane of the set: along its normal.
          if (set & 1) gp0 += gc * (pl[0].x * gx + pl[0].y * gy + pl[0].z * gz);
          if (set & 2) gp1 += gc * (pl[1].x * gx + pl[1].y * gy + pl[1].z * gz);
          if (set & 4) gp2 += gc * (pl[2].x * gx + pl[2].y * gy + pl[2].z * gz);
        }
#endif
      }
      const uint bs = bstart[row + x0], be = bstart[row + x1 + 1];
      for (uint j = bs; j < be; j += BW_VW) {
        const vfloat dx = xi - VLOAD(bx + j), dy = yi - VLOAD(by + j), dz = zi - VLOAD(bz + j);
        const vfloat r2 = dx * dx + dy * dy + dz * dz;
        const vint ok = (r2 < h2) & (r2 > min_r2) & VIN_ROW(j, be);
        const vfloat psi = VLOAD(bpsi + j);
        const vfloat ir = bw_rsqrt(fmax(r2, min_r2));
        const vfloat q = h - r2 * ir;
        const vfloat kbj = P.wall_hydrostatic ? kb + fmin(VLOAD(bpt + j), cap.x + cap.y * (r2 * ir)) : (vfloat)kb;
#if BW_GHOST_WALLS
        // Particles behind a plane give way to the images (their friction stays).
        vint kept = ok;
        for (int k = 0; k < planes; ++k)
          kept = kept & (pl[k].x * VLOAD(bx + j) + pl[k].y * VLOAD(by + j) + pl[k].z * VLOAD(bz + j) >= pl[k].w);
        const vfloat c = select((vfloat)0.0f, kbj * psi * q * q * ir, kept);
        if (planes > 0) {
          for (int l = 0; l < BW_VW; ++l) {
            if (j + l >= be) break;
            const float xb = bx[j + l], yb = by[j + l], zb = bz[j + l];
            const float ex = xi - xb, ey = yi - yb, ez = zi - zb;
            const float e2 = ex * ex + ey * ey + ez * ez;
            if (!(e2 < h2) || !bw_image_replaced(pl, planes, xb, yb, zb)) continue;
            const float eq = h - e2 * bw_rsqrt1(fmax(e2, min_r2));
            const int k = bw_image_face_of(P, pl, planes, xb, yb, zb, bnx[j + l], bny[j + l], bnz[j + l], bflat[j + l]);
            if (k >= 0) gw[k] += bpsi[j + l] * eq * eq * eq;
          }
        }
#else
        const vfloat c = select((vfloat)0.0f, kbj * psi * q * q * ir, ok);
#endif
        const vfloat w = select((vfloat)0.0f, kf * psi * q, ok);
        sx += c * dx + w * (VLOAD(bvx + j) - vxi);
        sy += c * dy + w * (VLOAD(bvy + j) - vyi);
        sz += c * dz + w * (VLOAD(bvz + j) - vzi);
      }
    }
  }
  ax[i] = VSUM(sx) + P.gx;
  ay[i] = VSUM(sy) + P.gy;
  az[i] = VSUM(sz) + P.gz;
#if BW_GHOST_WALLS
  // Per plane the push per unit of the replaced particles' weight: rigid.cl gives each
  // its share, Psi_b (h - r)^3 times this.
  const float push[BW_IMAGE_PLANES] = {VSUM(gp0), VSUM(gp1), VSUM(gp2)};
  float share[BW_IMAGE_PLANES];
  for (int k = 0; k < BW_IMAGE_PLANES; ++k) share[k] = gw[k] > 0.0f ? push[k] / gw[k] : 0.0f;
  image_share[i] = (float4)(share[0], share[1], share[2], 0.0f);
#endif
}

// Symplectic Euler: v += a dt, then x += v dt with the new velocity.
//
// Contact (bw_wall_contact, sph_boundary.h): a boundary particle b stands for a patch
// of its solid's surface, the disc of radius P.patch around it in the plane through
// it normal to the surface (bn). A particle near a solid (phi > 0) whose distance to
// such a plane is below P.contact while it lies over the patch loses the part of its
// velocity relative to the patch that goes into the surface (one pass over b, in the
// grid's order); sliding along the surface is free. Fluid at rest lies one spacing
// from the surface's particles, beyond the contact distance, and a CFL step moves a
// particle at most 0.4 spacings (at speeds up to c0), so no step carries a particle
// through a solid's single layer of particles, which method.md's boundary forces
// alone cannot promise. Where the normal is unknown (parts thinner than a cell) the
// patch is a sphere of radius P.contact. Dissipative. The momentum a moving body's
// patches take from the fluid here goes to the body (rigid.cl, boundary_forces).
//
// A particle held by emitter e (hold = e + 1) moves with the emitter's velocity
// instead, and is let go once it is the hold distance beyond the emitter's plane.
__kernel void fluid_integrate(SimParams P, uint n, float dt, __global float* x, __global float* y, __global float* z,
                              __global float* vx, __global float* vy, __global float* vz, __global const float* ax,
                              __global const float* ay, __global const float* az, __global const float* phi,
                              __global const uint* bstart, __global const float* bx, __global const float* by,
                              __global const float* bz, __global const float* bnx, __global const float* bny,
                              __global const float* bnz, __global const float* bvx, __global const float* bvy,
                              __global const float* bvz, __global const uint* bsolid, __global const uint* one_sided,
                              __global uint* hold, __global const EmitterParams* emitters) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint held = hold[i];
  if (held > 0) {
    const EmitterParams e = emitters[held - 1];
    const float px = x[i] + e.nx * e.speed * dt, py = y[i] + e.ny * e.speed * dt, pz = z[i] + e.nz * e.speed * dt;
    vx[i] = e.nx * e.speed;
    vy[i] = e.ny * e.speed;
    vz[i] = e.nz * e.speed;
    x[i] = px;
    y[i] = py;
    z[i] = pz;
    if ((px - e.cx) * e.nx + (py - e.cy) * e.ny + (pz - e.cz) * e.nz >= e.hold) hold[i] = 0;
    return;
  }
  float ux = vx[i] + ax[i] * dt, uy = vy[i] + ay[i] * dt, uz = vz[i] + az[i] * dt;
  const float xi = x[i], yi = y[i], zi = z[i];
  if (phi[i] > 0.0f) {
    float tx, ty, tz;
    bw_wall_contact(P, xi, yi, zi, &ux, &uy, &uz, bstart, bx, by, bz, bnx, bny, bnz, bvx, bvy, bvz, bsolid, one_sided,
                    0xffffffffu, &tx, &ty, &tz);
  }
  vx[i] = ux;
  vy[i] = uy;
  vz[i] = uz;
  x[i] = xi + ux * dt;
  y[i] = yi + uy * dt;
  z[i] = zi + uz * dt;
}

// Per block of `chunk` particles (all n particles of the step, including those that
// left the domain and sort after start[ncells]): the largest speed, acceleration and
// density (for the time step) and the fastest particle and the first with a non-finite value
// (for the guard), and the power the emitters put into the particles they hold.
// Accelerations and densities exist only for the live particles.
__kernel void fluid_step_reduce(uint n, uint chunk, uint nblocks, uint ncells, float mass, __global const uint* start,
                                __global const float* x, __global const float* y, __global const float* z,
                                __global const float* vx, __global const float* vy, __global const float* vz,
                                __global const float* ax, __global const float* ay, __global const float* az,
                                __global const float* rho, __global const float* diffusion_rate,
                                __global const uint* hold, __global StepReduce* out) {
  const uint b = get_global_id(0);
  if (b >= nblocks) return;
  const uint live = start[ncells];
  const uint begin = b * chunk;
  const uint end = min(begin + chunk, n);
  float max_v2 = 0.0f, max_a2 = 0.0f, max_rho = 0.0f, max_rate = 0.0f, held_power = 0.0f;
  int fastest = -1, bad = -1;
  for (uint i = begin; i < end; ++i) {
    const float v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
    bool finite = bw_finite(x[i]) && bw_finite(y[i]) && bw_finite(z[i]) && bw_finite(v2);
    float a2 = 0.0f;
    if (i < live) {
      a2 = ax[i] * ax[i] + ay[i] * ay[i] + az[i] * az[i];
      finite = finite && bw_finite(a2) && bw_finite(rho[i]);
    }
    if (!finite) {
      if (bad < 0) bad = (int)i;
      continue;
    }
    if (v2 > max_v2 || fastest < 0) {
      max_v2 = v2;
      fastest = (int)i;
    }
    max_a2 = fmax(max_a2, a2);
    if (i < live) {
      max_rho = fmax(max_rho, rho[i]);
      max_rate = fmax(max_rate, diffusion_rate[i]);
    }
    // A held particle keeps its velocity whatever the forces on it (fluid_integrate):
    // its emitter supplies -m a, at the power -m a.v.
    if (i < live && hold[i] > 0u) held_power -= mass * (ax[i] * vx[i] + ay[i] * vy[i] + az[i] * vz[i]);
  }
  StepReduce r;
  r.max_v2 = max_v2;
  r.max_a2 = max_a2;
  r.fastest = fastest;
  r.bad = bad;
  r.held_power = held_power;
  r.max_rho = max_rho;
  r.max_diffusion_rate = max_rate;
  out[b] = r;
}

// Per block: energies and density error for the frame statistics.
__kernel void fluid_frame_reduce(SimParams P, uint n, uint chunk, uint nblocks, __global const float* x,
                                 __global const float* y, __global const float* z, __global const float* vx,
                                 __global const float* vy, __global const float* vz, __global const float* rho,
                                 __global FrameReduce* out) {
  const uint b = get_global_id(0);
  if (b >= nblocks) return;
  const uint begin = b * chunk;
  const uint end = min(begin + chunk, n);
  FrameReduce r;
  r.kinetic = r.potential = r.elastic = r.error_sum = r.error_max = r.speed_max = 0.0f;
  r.pad0 = r.pad1 = 0.0f;
  for (uint i = begin; i < end; ++i) {
    const float v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
    r.kinetic += 0.5f * P.mass * v2;
    r.potential -= P.mass * (P.gx * (x[i] - P.ox) + P.gy * (y[i] - P.oy) + P.gz * (z[i] - P.oz));
    r.elastic += P.grad_scale * P.mass * bw_tait_energy(rho[i], P.rho0, P.stiffness, P.gamma);
    const float err = fmax(rho[i] / P.rho0 - 1.0f, 0.0f);
    r.error_sum += err;
    r.error_max = fmax(r.error_max, err);
    r.speed_max = fmax(r.speed_max, sqrt(v2));
  }
  out[b] = r;
}

// Writes `count` new particles at slots first.. : emitter lattice points
// px/py/pz[point0 + k] moved by (ox, oy, oz), velocity (ux, uy, uz), ids first_id + k,
// held by emitter `emitter` (hold = emitter + 1), density rho0 (they leave the
// emitter on the lattice, uncompressed).
__kernel void fluid_emit(uint count, uint first, uint first_id, uint point0, uint emitter, __global const float* px,
                         __global const float* py, __global const float* pz, float ox, float oy, float oz, float ux,
                         float uy, float uz, __global float* x, __global float* y, __global float* z,
                         __global float* vx, __global float* vy, __global float* vz, __global uint* id,
                         __global uint* hold, float rho0, __global float* rho) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const uint i = first + k;
  rho[i] = rho0;
  x[i] = px[point0 + k] + ox;
  y[i] = py[point0 + k] + oy;
  z[i] = pz[point0 + k] + oz;
  vx[i] = ux;
  vy[i] = uy;
  vz[i] = uz;
  id[i] = first_id + k;
  hold[i] = emitter + 1;
}

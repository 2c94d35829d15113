// Rigid bodies in the flow (method.md 2.3 and 5; docs/scene.md "Physics"): the
// boundary particles of bodies follow their poses, the forces of the fluid and of
// contacts on every boundary particle are gathered without atomics, and per-body sums
// over fixed blocks give force and torque (sim/solver.cpp adds the blocks on the host
// in a fixed order and integrates the bodies, rigid/body.h).
//
// Boundary particles live in two orders. The master order holds the static solids'
// particles first, then each body's particles in a contiguous range, body after body:
// it is where per-particle results (forces) and the reference arrays are. The sorted
// order (by grid cell, grid.cl) is what neighbour loops read: bx, by, bz, ...; the
// sort's `order` maps sorted to master indices and `rank` back.
#include "sph_common.h"
#include "sph_boundary.h"
#include "sph_images.h"

// Pairs closer than this fraction of h^2 get no fluid force (fluid.cl's rule).
#define BW_MIN_R2_FRACTION 1e-12f
// The drag below Coulomb's limit is c_t v_t with c_t = this factor m omega per pair, a
// body's M omega in all. An explicit step damps a velocity stably while c dt / m_eff
// < 2, and a sliding contact's effective mass at the contact point is down to M / 4
// (a tall box: its lever arm adds rotation): with omega dt <= 0.5 (the contact time
// step) this factor keeps c dt / m_eff <= 1. A larger one made a box resting on a
// floor chatter: the drag overshot, flipping sign every step at Coulomb's limit.
#define BW_TANGENT_DAMPING 0.5f
// A pair's spring energy (boundary_forces) is measured along a face normal while the
// touching particle lies at least BW_FACE_FAR of the contact distance d0 in front of
// the face, along the line between the particles while it lies less than
// BW_FACE_NEAR in front (beside the face: fragments side by side across a crack, a
// face beside an edge in its own plane, which a face normal would measure a whole
// spacing deep), and is blended smoothly in between, so that the energy has no jump
// for the forces to miss. A box's edge resting on a floor lies a whole contact
// distance above it; a face landing at the scene's largest speed goes about 0.25
// spacings deep, still above BW_FACE_FAR.
#define BW_FACE_NEAR 0.3f
#define BW_FACE_FAR 0.6f

// The spring energy of a contact pair and its derivatives (boundary_forces), for a
// touching particle at r from a particle on a face of unit normal n (d = r.n in front
// of it, l^2 = |r|^2 - d^2 across), or from any particle with face = false:
//   U = beta(d) U_face + (1 - beta(d)) U_line,
//   U_face = kA/2 a^2 (d0 - d)^2,  a = max(0, 1 - l^2 / R^2)  (the face's patch),
//   U_line = kA/2 (d0 - |r|)^2,
// each only while positive, beta the smoothstep from BW_FACE_NEAR d0 to BW_FACE_FAR d0.
// U depends on r only through |r|^2 and d, so the force on the touching particle,
//   F = -dU/dd n - 2 dU/d|r|^2 r,
// with its opposite on the face's particle, both acting at the touching particle, is
// the exact gradient of U also as the face turns with its body: the pair's work is
// the change of U, and its torques cancel. Also returns the pair's weight
// beta a^2 + (1 - beta) (of kA: the share of the pair in its owners' contact) and its
// depth beta (d0 - d) + (1 - beta) (d0 - |r|) (negative when apart).
float3 bw_contact_spring(float3 r, float3 n, bool face, float d0, float reach2, float kA, float* weight, float* depth) {
  const float r2 = dot(r, r);
  const float rl = sqrt(r2);
  const float dc = d0 - rl;
  const float du_line = dc > 0.0f ? -0.5f * kA * dc / rl : 0.0f;  // dU_line / d|r|^2
  if (!face) {
    *weight = 1.0f;
    *depth = dc;
    return -2.0f * du_line * r;
  }
  const float d = dot(r, n);
  const float df = d0 - d;
  const float a = fmax(1.0f - fmax(r2 - d * d, 0.0f) / reach2, 0.0f);
  const bool on = df > 0.0f && a > 0.0f;
  const float u_face = on ? 0.5f * kA * a * a * df * df : 0.0f;
  const float du_face_dd = on ? kA * a * df * (2.0f * d * df / reach2 - a) : 0.0f;
  const float du_face_dr2 = on ? -kA * a * df * df / reach2 : 0.0f;
  const float u_line = dc > 0.0f ? 0.5f * kA * dc * dc : 0.0f;
  const float width = (BW_FACE_FAR - BW_FACE_NEAR) * d0;
  const float t = clamp((d - BW_FACE_NEAR * d0) / width, 0.0f, 1.0f);
  const float beta = t * t * (3.0f - 2.0f * t);
  const float dbeta = 6.0f * t * (1.0f - t) / width;
  *weight = beta * a * a + (1.0f - beta);
  *depth = beta * df + (1.0f - beta) * dc;
  const float du_dd = dbeta * (u_face - u_line) + beta * du_face_dd;
  const float du_dr2 = beta * du_face_dr2 + (1.0f - beta) * du_line;
  return -du_dd * n - 2.0f * du_dr2 * r;
}

// World positions, velocities and normals of the bodies' boundary particles, master
// indices first + k for k < count, from their reference arrays (r = x_ref - c_ref and
// the reference normal, indexed by k) and their body's pose:
//   x = c + R r,  v = v_c + w x (R r),  n = R n_ref.
__kernel void body_pose(uint first, uint count, __global const BodyPose* poses, __global const uint* pbody,
                        __global const float* rx, __global const float* ry, __global const float* rz,
                        __global const float* rnx, __global const float* rny, __global const float* rnz,
                        __global float* mx, __global float* my, __global float* mz, __global float* mvx,
                        __global float* mvy, __global float* mvz, __global float* mnx, __global float* mny,
                        __global float* mnz) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const BodyPose b = poses[pbody[k]];
  const float ax = rx[k], ay = ry[k], az = rz[k];
  const float wx = b.r00 * ax + b.r01 * ay + b.r02 * az;
  const float wy = b.r10 * ax + b.r11 * ay + b.r12 * az;
  const float wz = b.r20 * ax + b.r21 * ay + b.r22 * az;
  const uint m = first + k;
  mx[m] = b.cx + wx;
  my[m] = b.cy + wy;
  mz[m] = b.cz + wz;
  mvx[m] = b.vx + (b.wy * wz - b.wz * wy);
  mvy[m] = b.vy + (b.wz * wx - b.wx * wz);
  mvz[m] = b.vz + (b.wx * wy - b.wy * wx);
  const float nx = rnx[k], ny = rny[k], nz = rnz[k];
  mnx[m] = b.r00 * nx + b.r01 * ny + b.r02 * nz;
  mny[m] = b.r10 * nx + b.r11 * ny + b.r12 * nz;
  mnz[m] = b.r20 * nx + b.r21 * ny + b.r22 * nz;
}

// The sorted boundary arrays from the master arrays (out[i] = in[order[i]]) and the
// inverse permutation rank[order[i]] = i.
__kernel void boundary_gather(uint nb, __global const uint* order, __global const float* mx, __global const float* my,
                              __global const float* mz, __global const float* mvx, __global const float* mvy,
                              __global const float* mvz, __global const float* mnx, __global const float* mny,
                              __global const float* mnz, __global const float* mflat, __global const float* mpsi,
                              __global const uint* mowner, __global float* bx, __global float* by, __global float* bz,
                              __global float* bvx, __global float* bvy, __global float* bvz, __global float* bnx,
                              __global float* bny, __global float* bnz, __global float* bflat, __global float* bpsi,
                              __global uint* bsolid, __global uint* rank) {
  const uint i = get_global_id(0);
  if (i >= nb) return;
  const uint k = order[i];
  bx[i] = mx[k];
  by[i] = my[k];
  bz[i] = mz[k];
  bvx[i] = mvx[k];
  bvy[i] = mvy[k];
  bvz[i] = mvz[k];
  bnx[i] = mnx[k];
  bny[i] = mny[k];
  bnz[i] = mnz[k];
  bflat[i] = mflat[k];
  bpsi[i] = mpsi[k];
  bsolid[i] = mowner[k];
  rank[k] = i;
}

// Psi_b (fluid.cl, boundary_psi) of the sorted particles whose owner is marked in
// `dirty` (ndirty owners): written in sorted and in master order.
__kernel void boundary_psi_owners(SimParams P, uint nb, __global const uint* bstart, __global const float* bx,
                                  __global const float* by, __global const float* bz, __global const float* bnx,
                                  __global const float* bny, __global const float* bnz, __global const uint* bsolid,
                                  __global const uint* order, uint ndirty, __global const uint* dirty,
                                  __global float* bpsi, __global float* mpsi) {
  const uint i = get_global_id(0);
  if (i >= nb) return;
  const uint owner = bsolid[i];
  if (owner >= ndirty || dirty[owner] == 0) return;
  const float psi = P.rho0 / bw_psi_sum(P, i, bstart, bx, by, bz, bnx, bny, bnz, bsolid);
  bpsi[i] = psi;
  mpsi[order[i]] = psi;
}

// The force on each boundary particle of master indices first .. first + count - 1,
// with its torque about the particle itself (tx, ty, tz), and the number of contact
// pairs it is in (touching):
//
// - the fluid's reaction: for every fluid neighbour j, minus the boundary pressure
//   and friction force that b exerts on j in fluid_forces, computed by the same
//   formula from the same values;
// - the wall contact: when dt > 0, minus the momentum that b's patch takes from each
//   fluid neighbour j in fluid_integrate (bw_wall_contact replayed for j up to b, with
//   j's velocity after the force update), over dt;
// - contacts with the particles of other owners (method.md 5, "Ours"; rigid/contact.h):
//   a spring whose energy is bw_contact_spring's (measured along a face normal or
//   the line between the particles, pushing when they are closer than d0 = the mean
//   of the two owners' spacings, weighted over the lateral reach R so that a particle
//   over a flat lattice of the other solid feels about one pair's stiffness wherever
//   it lies), with a dashpot along the spring's force, never pulling, and Coulomb
//   friction across it. The pair's mass m is the reduced mass of the owners' contact
//   masses (an owner's mass over the weight of its pairs at the last step,
//   OwnerParams.inv_mass), so that a body feels k = M omega^2 and c = 2 zeta M omega
//   in all: its bounce ends with the restitution and its depth under its weight is
//   g / omega^2 however many of its particles touch. Every quantity is symmetric in
//   the pair, so that the pair's forces are exact opposites, and both act at one
//   point, so that the pair's torques cancel too.
// touching: the weights of the pairs within d0 plus the margin.
// Forces are in N. All outputs are in master order. With dt < 0 only the contacts'
// weights are counted (touching), nothing else is written.
__kernel void boundary_forces(SimParams P, ContactParams C, uint first, uint count, float dt,
                              __global const uint* start, __global const float* x, __global const float* y,
                              __global const float* z, __global const float* vx, __global const float* vy,
                              __global const float* vz, __global const float* ax, __global const float* ay,
                              __global const float* az, __global const float* rho, __global const float* pterm,
                              __global const float* phi, __global const uint* hold, __global const uint* bstart,
                              __global const float* bx, __global const float* by, __global const float* bz,
                              __global const float* bvx, __global const float* bvy, __global const float* bvz,
                              __global const float* bnx, __global const float* bny, __global const float* bnz,
                              __global const float* bflat, __global const float* bpsi, __global const float* bpt,
                              __global const uint* bsolid, __global const uint* one_sided,
                              __global const uint* rank, __global const uint* order, __global const OwnerParams* owners,
                              __global const uint* wet_in, __global float* fx, __global float* fy, __global float* fz,
                              __global float* tx, __global float* ty, __global float* tz, __global float* touching,
                              __global uint* wet_out, __global const uint4* wplane,
                              __global const float4* image_share) {
  const uint g = get_global_id(0);
  if (g >= count) return;
  const uint k = first + g;
  const uint i = rank[k];
  const float xb = bx[i], yb = by[i], zb = bz[i];
  const float vbx = bvx[i], vby = bvy[i], vbz = bvz[i];
  const float nbx = bnx[i], nby = bny[i], nbz = bnz[i];
  const bool bface = bflat[i] >= BW_FACE_FLATNESS;
  const float psi = bpsi[i];
  // fluid_forces adds the wall's own pressure term, b's for every fluid particle
  const float bpti = P.wall_hydrostatic ? bpt[i] : 0.0f;
  const uint owner = bsolid[i];
  const OwnerParams own = owners[owner];
  const int cx = bw_cell_coord(xb, P.ox, P.inv_cell, P.nx);
  const int cy = bw_cell_coord(yb, P.oy, P.inv_cell, P.ny);
  const int cz = bw_cell_coord(zb, P.oz, P.inv_cell, P.nz);
  const int x0 = max(cx - 1, 0), x1 = min(cx + 1, P.nx - 1);
  const float h = P.h, h2 = P.h2;
  const float min_r2 = h2 * BW_MIN_R2_FRACTION;
  // A fluid particle can touch b's patch only within this distance of b.
  const float patch_reach2 = 1.01f * (P.contact * P.contact + P.patch * P.patch);
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;  // sum of the fluid's accelerations due to b
  float jx = 0.0f, jy = 0.0f, jz = 0.0f;  // sum of the velocity changes of b's patch contacts
  float cfx = 0.0f, cfy = 0.0f, cfz = 0.0f, ctx = 0.0f, cty = 0.0f, ctz = 0.0f;  // contacts: force, torque
  float pairs = 0.0f;
  bool wet = false;  // fluid within C.wet2 of b
  const bool wet_before = wet_in[k] != 0u;
  for (int gz = max(cz - 1, 0); gz <= min(cz + 1, P.nz - 1); ++gz) {
    for (int gy = max(cy - 1, 0); gy <= min(cy + 1, P.ny - 1); ++gy) {
      const int row = bw_cell_index(0, gy, gz, P.nx, P.ny);
      const uint s = dt < 0.0f ? 0u : start[row + x0], e = dt < 0.0f ? 0u : start[row + x1 + 1];
      for (uint j = s; j < e; ++j) {
        const float xj = x[j], yj = y[j], zj = z[j];
        const float dx = xj - xb, dy = yj - yb, dz = zj - zb;
        const float r2 = dx * dx + dy * dy + dz * dz;
        wet = wet || r2 < C.wet2;
        if (r2 < h2 && r2 > min_r2) {
          // fluid_forces, the boundary term of particle j
          const float ptj = pterm[j];
          const float rhoj = rho[j];
          const float ir = bw_rsqrt1(fmax(r2, min_r2));
          const float kbb = bw_boundary_kb(P, ptj, rhoj) +
                            (P.wall_hydrostatic ? bw_wall_term(bpti, bw_wall_cap(P, ptj, rhoj), r2 * ir) : 0.0f);
          const float kf = P.mu_b * P.visc / P.rho0 * (1.0f / rhoj);
          const float q = h - r2 * ir;
          float c = kbb * psi * q * q * ir;
          const float w = kf * psi * q;
#if BW_GHOST_WALLS
          // Behind one of j's mirror planes b gives way to the images (fluid_forces): it
          // takes its share, by Psi_b W, of their push along that plane's normal.
          float4 pl[BW_IMAGE_PLANES];
          const int planes = bw_image_planes(P, j, wplane, bx, by, bz, bnx, bny, bnz, pl);
          if (planes > 0 && bw_image_replaced(pl, planes, xb, yb, zb)) {
            const int face = bw_image_face_of(P, pl, planes, xb, yb, zb, nbx, nby, nbz, bflat[i]);
            const int k = max(face, 0);
            const float4 per_weight = image_share[j];
            const float sk = k == 0 ? per_weight.x : (k == 1 ? per_weight.y : per_weight.z);
            const float share = face >= 0 ? psi * q * q * q * sk : 0.0f;
            sx += share * pl[k].x;
            sy += share * pl[k].y;
            sz += share * pl[k].z;
            c = 0.0f;
          }
#endif
          sx += c * dx + w * (vbx - vx[j]);
          sy += c * dy + w * (vby - vy[j]);
          sz += c * dz + w * (vbz - vz[j]);
        }
        if (dt > 0.0f && r2 < patch_reach2 && phi[j] > 0.0f && hold[j] == 0) {
          float ux = vx[j] + ax[j] * dt, uy = vy[j] + ay[j] * dt, uz = vz[j] + az[j] * dt;
          float ex, ey, ez;
          bw_wall_contact(P, xj, yj, zj, &ux, &uy, &uz, bstart, bx, by, bz, bnx, bny, bnz, bvx, bvy, bvz, bsolid,
                          one_sided, i, &ex, &ey, &ez);
          jx += ex, jy += ey, jz += ez;
        }
      }
      const uint bs = bstart[row + x0], be = bstart[row + x1 + 1];
      for (uint o = bs; o < be; ++o) {
        const uint other = bsolid[o];
        if (other == owner) continue;
        const OwnerParams oth = owners[other];
        const float inv_mass = own.inv_mass + oth.inv_mass;
        if (!(inv_mass > 0.0f)) continue;  // two static solids or fixed bodies
        const float dx = xb - bx[o], dy = yb - by[o], dz = zb - bz[o];
        const float r2 = dx * dx + dy * dy + dz * dz;
        const float d0 = 0.5f * (own.spacing + oth.spacing);
        const float reach = fmin(C.reach * fmax(own.spacing, oth.spacing), sqrt(fmax(h2 - d0 * d0, 0.0f)));
        const float reach2 = reach * reach;
        if (r2 >= (d0 + C.margin) * (d0 + C.margin) + reach2 || !(r2 > 0.0f)) continue;
        // Which particle's face serves (bw_contact_spring): where one lies on a face of
        // its solid, that face; where both do, the face of the lower owner (a static
        // solid's before a body's; for parallel faces either gives the same); where
        // neither does (edge on edge, corner on edge), none. Edges' and corners' normals
        // never serve: measured along them, a corner over an edge would seem a third of
        // a spacing deep. The choice depends only on the pair, never on the step.
        const bool oface = bflat[o] >= BW_FACE_FLATNESS;
        const bool use_o = oface && (!bface || other < owner);
        const bool use_b = bface && !use_o;
        const float3 rb = (float3)(dx, dy, dz);  // from o to b
        const float m = 1.0f / inv_mass;
        const float kA = m * C.omega * C.omega * 3.0f * own.spacing * oth.spacing / (BW_PI_F * reach2);
        float weight, depth;
        // The spring's force on b, and the point it acts at relative to b (at the
        // touching particle; at the midpoint for two particles off faces).
        float3 fs, at;
        if (use_o) {
          fs = bw_contact_spring(rb, (float3)(bnx[o], bny[o], bnz[o]), true, d0, reach2, kA, &weight, &depth);
          at = (float3)(0.0f);
        } else if (use_b) {
          fs = -bw_contact_spring(-rb, (float3)(nbx, nby, nbz), true, d0, reach2, kA, &weight, &depth);
          at = -rb;
        } else {
          fs = bw_contact_spring(rb, rb, false, d0, reach2, kA, &weight, &depth);
          at = -0.5f * rb;
        }
        const float area = 3.0f * own.spacing * oth.spacing / (BW_PI_F * reach2);
        weight *= area;
        if (depth > -C.margin) pairs += weight;
        if (dt < 0.0f) continue;
        const float fs2 = dot(fs, fs);
        if (!(fs2 > 0.0f)) {
          // Apart, but closer than the margin with fluid at either particle at the last
          // step: a gap narrower than the fluid's particles can resolve, whose water
          // resists being squeezed out or drawn in and sheared (a squeeze film;
          // method.md 5, "Ours"; docs/scene.md, "Resting in water"). A dashpot on the
          // pair's relative velocity: it takes energy, never gives it.
          if (!(depth > -C.margin) || !(wet_before || wet_in[order[o]] != 0u)) continue;
          const float3 rv = (float3)(vbx - bvx[o], vby - bvy[o], vbz - bvz[o]);
          const float3 f = (-weight * 2.0f * C.squeeze * m * C.omega) * rv;
          cfx += f.x, cfy += f.y, cfz += f.z;
          const float3 tq = cross(at, f);
          ctx += tq.x, cty += tq.y, ctz += tq.z;
          continue;
        }
        // The dashpot and friction along and across the spring's force.
        const float3 n = fs * (1.0f / sqrt(fs2));
        const float zeta = fmin(own.damping, oth.damping);
        const float3 rv = (float3)(vbx - bvx[o], vby - bvy[o], vbz - bvz[o]);
        const float vn = dot(rv, n);
        const float fn = sqrt(fs2) - weight * 2.0f * zeta * m * C.omega * vn;
        if (!(fn > 0.0f)) continue;  // never pulling
        float3 f = fn * n;
        const float3 tv = rv - vn * n;
        const float vt = length(tv);
        if (vt > 0.0f) {
          // Coulomb's limit; below it a drag, so that slow sliding stops.
          const float ft = fmin(sqrt(own.friction * oth.friction) * fn, weight * BW_TANGENT_DAMPING * m * C.omega * vt);
          f -= (ft / vt) * tv;
        }
        cfx += f.x, cfy += f.y, cfz += f.z;
        const float3 tq = cross(at, f);
        ctx += tq.x, cty += tq.y, ctz += tq.z;
      }
    }
  }
  touching[k] = pairs;
  if (dt < 0.0f) return;
  wet_out[k] = wet ? 1u : 0u;
  const float inv_dt = dt > 0.0f ? 1.0f / dt : 0.0f;
  fx[k] = -P.mass * (sx + jx * inv_dt) + cfx;
  fy[k] = -P.mass * (sy + jy * inv_dt) + cfy;
  fz[k] = -P.mass * (sz + jz * inv_dt) + cfz;
  tx[k] = ctx;
  ty[k] = cty;
  tz[k] = ctz;
}

// Per block: the sum of the forces, and of their torques about the body's centre of
// mass (the lever x - c plus each particle's own torque), in master order.
__kernel void body_reduce(uint nblocks, __global const BodyBlock* blocks, __global const BodyPose* poses,
                          __global const float* mx, __global const float* my, __global const float* mz,
                          __global const float* fx, __global const float* fy, __global const float* fz,
                          __global const float* tx, __global const float* ty, __global const float* tz,
                          __global const float* touching, __global BodyReduce* out) {
  const uint g = get_global_id(0);
  if (g >= nblocks) return;
  const BodyBlock blk = blocks[g];
  BodyReduce r;
  r.fx = r.fy = r.fz = r.tx = r.ty = r.tz = r.touching = r.pad = 0.0f;
  float cx = 0.0f, cy = 0.0f, cz = 0.0f;
  const bool body = blk.body != BW_NO_BODY;
  if (body) {
    const BodyPose pose = poses[blk.body];
    cx = pose.cx, cy = pose.cy, cz = pose.cz;
  }
  for (uint k = blk.first; k < blk.first + blk.count; ++k) {
    const float f0 = fx[k], f1 = fy[k], f2 = fz[k];
    r.fx += f0, r.fy += f1, r.fz += f2;
    r.touching += touching[k];
    if (body) {
      const float lx = mx[k] - cx, ly = my[k] - cy, lz = mz[k] - cz;
      r.tx += (ly * f2 - lz * f1) + tx[k];
      r.ty += (lz * f0 - lx * f2) + ty[k];
      r.tz += (lx * f1 - ly * f0) + tz[k];
    }
  }
  out[g] = r;
}

// Per sensor s (sim/sensors.h): the pressure its face's particles carry at this step,
// -sum_k w_k F_k . n_s (Pa), over its particles first[s] .. first[s + 1] - 1 (master
// indices of static particles; forces from boundary_forces).
__kernel void sensor_pressure(uint count, __global const uint* first, __global const uint* particle,
                              __global const float* weight, __global const float* normal, __global const float* fx,
                              __global const float* fy, __global const float* fz, __global float* out) {
  const uint s = get_global_id(0);
  if (s >= count) return;
  const float nx = normal[3 * s], ny = normal[3 * s + 1], nz = normal[3 * s + 2];
  float sum = 0.0f;
  for (uint k = first[s]; k < first[s + 1]; ++k) {
    const uint m = particle[k];
    sum += weight[k] * (fx[m] * nx + fy[m] * ny + fz[m] * nz);
  }
  out[s] = -sum;
}

// [output] fields "wall_pressure": each boundary particle's patch pressure this step,
// -F . n / spacing^2 (the fluid's and contacts' force F on it, its normal n out of its
// solid, the patch spacing^2 it stands for), added to its time integral (Pa s), master
// indices first + k for k < count. A part thinner than a cell has no outward normal
// (its faces' normals cancel, n = 0): there the water presses on one face or the
// other, and the figure is |F| / spacing^2.
__kernel void wall_pressure_integrate(uint first, uint count, float dt, __global const float* fx,
                                      __global const float* fy, __global const float* fz,
                                      __global const float* mnx, __global const float* mny,
                                      __global const float* mnz, __global const uint* mowner,
                                      __global const OwnerParams* owners, __global float* integral) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const uint m = first + k;
  const float s = owners[mowner[m]].spacing;
  const float n2 = mnx[m] * mnx[m] + mny[m] * mny[m] + mnz[m] * mnz[m];
  const float push = n2 > 0.0f ? -(fx[m] * mnx[m] + fy[m] * mny[m] + fz[m] * mnz[m])
                               : sqrt(fx[m] * fx[m] + fy[m] * fy[m] + fz[m] * fz[m]);
  integral[m] += dt * push / (s * s);
}

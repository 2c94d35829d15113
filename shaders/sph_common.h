// Parameter structs and kernel math shared by the simulator's host code (C++) and its
// OpenCL C kernels (shaders/*.cl), so that both sides agree on layouts and formulas.
//
// Structs hold only 4-byte float and int fields (no vector types, no padding rules
// that differ between compilers), so their layout is the same on host and device; they
// are passed to kernels by value. The kernel functions follow method.md section 1:
// Mueller et al. 2003's poly6, spiky and viscosity kernels, all zero beyond the
// support radius h. The solver (docs/scene.md, "Physics") uses spiky for the density
// and its gradient for the pressure forces, so that forces are the gradient of the
// energy the density stores; viscosity and friction use the viscosity Laplacian.
// poly6 stays here for the tests.
#ifndef BW_SPH_COMMON_H
#define BW_SPH_COMMON_H

#ifdef __OPENCL_VERSION__
#define BW_FN static inline
#define BW_SQRT sqrt
#define BW_POW pow
typedef uint bw_uint;
#else
#include <cmath>
#include <cstdint>
#define BW_FN inline
#define BW_SQRT std::sqrt
#define BW_POW std::pow
typedef std::uint32_t bw_uint;
#endif

#define BW_PI_F 3.14159265358979323846f

// Everything the fluid kernels need, derived once from the scene (libcore/sim).
typedef struct {
  // kernel support radius h (m), h^2, and the constant factors of the three kernels
  float h, h2;
  float spiky;      // 15 / (pi h^6): W_spiky = spiky (h - r)^3
  float grad_scale; // 1 / c: corrects the spiky gradient's first moment c on the lattice
  float pressure_scale;   // kp = 3 spiky mk / c: pressure term of the force sums
  float viscosity_scale;  // kv = mu mk visc: viscosity term of the force sums
  float visc;       // 45 / (pi h^6): lap W_visc = visc (h - r)
  // fluid
  float mass;       // particle mass (kg): rho0 times the cell it stands for, spacing^3
  float kernel_mass;  // mk, what the sums weigh a neighbour with: a full lattice sums to rho0
  float rho0;       // rest density (kg/m^3)
  float stiffness;  // Tait k (Pa)
  float gamma;      // Tait exponent
  int gamma_int;    // gamma when it is a whole number (the usual 7), else 0
  float mu;         // viscosity (Pa s)
  float mu_b;       // boundary friction (Pa s)
  float gamma1;     // weight of the boundary term in the density
  float gamma2;     // weight of the boundary pressure force
  int wall_hydrostatic;   // 1: a boundary particle holds the fluid's extrapolated pressure (boundary_pressure)
  float wall_layer_step;  // the wall layer's density step with the continuity equation (fluid.cl, BW_WALL_STEP)
  // density (docs/scene.md, "Density"): 1 integrates the continuity equation with
  // Fourtakas et al. 2019's density diffusion, 0 sums the kernel over neighbours
  int continuity;
  float diffusion;  // 2 delta h c0: the diffusion term's coefficient (m^2/s), 0 without
  float hx, hy, hz; // rho0^2 g / (gamma k): rho_H(x_j) - rho_H(x_i) = H.(x_j - x_i), the hydrostatic part
  float contact;    // contact distance to a solid's surface (m), fluid_integrate
  float patch;      // radius of the surface patch a boundary particle stands for (m)
  float layer;      // half a spacing: how far a solid's surface lies beyond its particles' plane (m)
  uint static_owners;  // owners (bsolid) below this are the scene's solids, from it on bodies
  float gx, gy, gz; // gravity (m/s^2)
  // grid: cubic cells of edge `cell` from `origin`; the domain is the grid's box
  float ox, oy, oz;
  float cell, inv_cell;
  float max_x, max_y, max_z;  // domain maximum corner
  int nx, ny, nz;
  int ncells;       // nx * ny * nz; the key of a removed particle
} SimParams;

// An emitter as the integration sees it: the particles it injects move with the
// emitter's velocity, ignoring forces, until they are `hold` beyond its plane, so
// that the fluid leaves the emitter like a piston pushes it and a new layer never
// lands on the previous one.
typedef struct {
  float cx, cy, cz;   // a point of the emitter's plane (its centre)
  float nx, ny, nz;   // unit normal, the direction of the flow
  float speed;        // m/s
  float hold;         // m
} EmitterParams;

// Per-block results of the reduction that runs every step (adaptive dt and guard).
typedef struct {
  float max_v2;     // largest |v|^2
  float max_a2;     // largest |a|^2
  int fastest;      // index of the (first) particle with max_v2, -1 when none
  int bad;          // first particle with a non-finite value, -1 when none
  float held_power; // sum of -m a.v over the particles emitters hold: the power they put in (W)
  float max_rho;    // largest density of the live particles (the sound speed of the CFL limit)
  float max_diffusion_rate;  // largest rate of the density diffusion on a particle's own density (1/s)
} StepReduce;

// Per-block sums for the frame statistics (host adds the blocks in double).
typedef struct {
  float kinetic;        // sum 1/2 m |v|^2 (J)
  float potential;      // sum -m g.(x - domain minimum corner) (J)
  float elastic;        // sum m e(rho), e the Tait internal energy per unit mass (J)
  float error_sum;      // sum max(0, rho/rho0 - 1)
  float error_max;      // max max(0, rho/rho0 - 1)
  float speed_max;      // max |v|
  float pad0, pad1;
} FrameReduce;

// Rigid bodies (rigid.cl). Boundary particles have an owner: a static solid (owner =
// its scene index) or a body (owner = ContactParams.body_owner0 + the body's index).
// What contacts need of each owner:
typedef struct {
  float inv_mass;     // 1 / the owner's contact mass (its mass over the weight of its contact pairs
                      // at the last step, at least 1): 0 for static solids and fixed bodies
  float friction;     // Coulomb coefficient
  float damping;      // damping ratio zeta (from the restitution, rigid/contact.h)
  float spacing;      // sampling spacing of the owner's particles (m)
} OwnerParams;

// Contacts between boundary particles of different owners (rigid.cl, boundary_forces).
typedef struct {
  float omega;        // contact frequency (1/s): a pair of mass m has k = m omega^2
  float reach;        // lateral reach of a particle's contact, in the pair's widest spacing
  float margin;       // pairs within the contact distance plus this count as touching (m)
  float squeeze;      // damping ratio of a wet gap (fluid between two solids, closer than the margin)
  float wet2;         // a boundary particle is wet with fluid within this squared distance (m^2)
  bw_uint body_owner0;  // owner of body 0
} ContactParams;

// The pose of a body at the start of a step, in float for the device.
typedef struct {
  float cx, cy, cz;                    // centre of mass, world (m)
  float r00, r01, r02, r10, r11, r12, r20, r21, r22;  // rotation reference -> world, row-major
  float vx, vy, vz;                    // velocity of the centre of mass (m/s)
  float wx, wy, wz;                    // angular velocity, world (rad/s)
  float pad;
} BodyPose;

// A block of boundary particles (master order, one body's or one static solid's) for
// the per-body sums; body = BW_NO_BODY for static particles (force only).
#define BW_NO_BODY 0xffffffffu
typedef struct {
  bw_uint body, first, count, pad;
} BodyBlock;

// Per-block sums of the forces on boundary particles.
typedef struct {
  float fx, fy, fz;   // force (N)
  float tx, ty, tz;   // torque about the body's centre of mass (N m)
  float touching;     // weight of the contact pairs within the contact distance plus the margin
  float pad;
} BodyReduce;

// Grid cell coordinate of a position along one axis, clamped to [0, n - 1] (also for
// NaN, which lands in cell 0; such particles are removed before they are searched).
BW_FN int bw_cell_coord(float v, float origin, float inv_cell, int n) {
  float f = (v - origin) * inv_cell;
  f = f > 0.0f ? f : 0.0f;
  const float top = (float)(n - 1);
  f = f < top ? f : top;
  return (int)f;
}

// Linear cell index: x fastest, so the 3 cells of a row along x are contiguous.
BW_FN int bw_cell_index(int cx, int cy, int cz, int nx, int ny) { return (cz * ny + cy) * nx + cx; }

// W_poly6 from r^2 (no square root needed): 315/(64 pi h^9) (h^2 - r^2)^3.
BW_FN float bw_poly6(float r2, float h2, float poly6) {
  const float d = h2 - r2;
  return r2 < h2 ? poly6 * d * d * d : 0.0f;
}

// Gradient of W_poly6 with respect to x_i for x_ij = x_i - x_j: grad W = f x_ij with
// f = -6 poly6 (h^2 - r^2)^2 (returned), zero beyond h.
BW_FN float bw_poly6_grad_factor(float r2, float h2, float poly6) {
  const float d = h2 - r2;
  return r2 < h2 ? -6.0f * poly6 * d * d : 0.0f;
}

// Gradient of W_spiky with respect to x_i for x_ij = x_i - x_j at distance r > 0:
// grad W = -45/(pi h^6) (h - r)^2 x_ij / r. Returned: the factor f with grad W = f x_ij.
BW_FN float bw_spiky_grad_factor(float r, float h) {
  const float q = h - r;
  return (r < h && r > 0.0f) ? -45.0f / (BW_PI_F * h * h * h * h * h * h) * q * q / r : 0.0f;
}

// Laplacian of W_visc: 45/(pi h^6) (h - r).
BW_FN float bw_visc_lap(float r, float h, float visc) { return r < h ? visc * (h - r) : 0.0f; }

// W_spiky itself, 15/(pi h^6) (h - r)^3 (for tests: it integrates to 1).
BW_FN float bw_spiky(float r, float h) {
  const float q = h - r;
  return r < h ? 15.0f / (BW_PI_F * h * h * h * h * h * h) * q * q * q : 0.0f;
}

// W_visc itself (Mueller 2003), 15/(2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1),
// for tests: it integrates to 1 and its Laplacian is bw_visc_lap.
BW_FN float bw_visc(float r, float h) {
  if (r >= h || r <= 0.0f) return 0.0f;
  const float a = r / h;
  return 15.0f / (2.0f * BW_PI_F * h * h * h) * (-0.5f * a * a * a + a * a + 0.5f / a - 1.0f);
}

// x^n for a whole n >= 1 by repeated squaring: much cheaper than pow on CPUs.
BW_FN float bw_powi(float x, int n) {
  float result = 1.0f;
  while (n > 0) {
    if (n & 1) result *= x;
    x *= x;
    n >>= 1;
  }
  return result;
}

// Tait equation of state, negative pressures clamped to 0 (method.md 1).
// gamma_int > 0: gamma is that whole number.
BW_FN float bw_tait(float rho, float rho0, float k, float gamma, int gamma_int) {
  const float a = rho / rho0;
  const float p = k * ((gamma_int > 0 ? bw_powi(a, gamma_int) : BW_POW(a, gamma)) - 1.0f);
  return p > 0.0f ? p : 0.0f;
}

// Internal (elastic) energy per unit mass stored by compressing from rho0 to rho under
// the clamped Tait law: integral of p / rho^2 d rho. Zero below rho0, where p = 0.
BW_FN float bw_tait_energy(float rho, float rho0, float k, float gamma) {
  if (rho <= rho0) return 0.0f;
  const float a = BW_POW(rho / rho0, gamma - 1.0f);
  return k * ((a - 1.0f) / ((gamma - 1.0f) * rho0) - (1.0f / rho0 - 1.0f / rho));
}

#endif

// Mirror images of the fluid in place of the particles of flat faces of solids that
// do not give way to it: static solids, solids moved as told, fixed bodies
// (fluid.wall_pressure = "images", docs/scene.md "Walls as mirror images"): the rules
// shared by the fluid kernels (fluid.cl), which apply the images' push and density
// rate, and the rigid-body kernels (rigid.cl), which give their reaction to the faces'
// particles for the sensors and the loads (OpenCL C only).
//
// A fluid particle near such faces holds up to three planes (fluid_wall_planes), each
// as the boundary particle it was found at (a uint: 4 bytes where the plane is 16),
// from which every reader takes the same float4 (n, d): the face's outward unit normal
// n, toward the fluid, and n . x = d on the face, half a spacing beyond its particles. The images of a neighbour j are its
// reflections across every non-empty set of the particle's planes (perpendicular to
// one another, or facing across a channel at least h wide: 1, 3 or 7 images), with
// its velocity reflected alike in the frame of each plane, which moves along its
// normal with the solid's face (a wall without
// friction; the faces' particles keep their friction). Boundary particles behind one
// of the planes stand for the same wall and give way to the images.
#ifndef BW_SPH_IMAGES_H
#define BW_SPH_IMAGES_H

#include "sph_boundary.h"
#include "sph_common.h"

// 1: the flat faces of static solids are mirror images of the fluid (the solver builds
// the fluid's and the rigid bodies' kernels so for fluid.wall_pressure = "images").
#ifndef BW_GHOST_WALLS
#define BW_GHOST_WALLS 0
#endif

// 1: the scene has bodies, whose faces (moved as told, or fixed) can be mirror planes
// that move (the solver builds the fluid's kernels so).
#ifndef BW_GHOST_BODIES
#define BW_GHOST_BODIES 0
#endif

// Planes held per fluid particle at most (a corner of three faces).
#define BW_IMAGE_PLANES 3
// Two face particles lie on the same plane when their normals agree to this cosine
// and their planes' offsets to this fraction of the half spacing P.layer.
#define BW_IMAGE_SAME_COS 0.999f
#define BW_IMAGE_SAME_OFFSET 0.5f
// Planes whose normals' cosine exceeds this are not perpendicular: their reflections
// do not close into a group of images, and the particle keeps the faces' particles.
#define BW_IMAGE_PERPENDICULAR 0.02f
// Facing planes (normals opposite, the two walls of a channel) need no images across
// both when they stand at least h apart: those lie at least the gap away, where the
// kernel is 0 (at 0.999 h, below 1e-9 of a neighbour's weight). Nearer, the images'
// series does not end; the particle keeps the faces' particles.
#define BW_IMAGE_FACING_GAP 0.999f

// Whether a solid's particles give way to the water (a body moved by the fluid's
// forces): those keep their particles; static solids, solids moved as told and fixed
// bodies (no contact mass, rigid_stage.cpp upload_owners) can be mirror planes.
static inline bool bw_image_gives_way(SimParams P, __global const OwnerParams* owners, uint owner) {
  return owner >= P.static_owners && owners[owner].inv_mass > 0.0f;
}

// A plane's slot that holds none.
#define BW_NO_PLANE 0xffffffffu

// The plane of the face that boundary particle b lies half a spacing behind: (n_b, n_b .
// x_b + P.layer). The planes' pass and every reader take it from here, with the same bits.
static inline float4 bw_image_plane(SimParams P, uint b, __global const float* bx, __global const float* by,
                                    __global const float* bz, __global const float* bnx, __global const float* bny,
                                    __global const float* bnz) {
  const float nx = bnx[b], ny = bny[b], nz = bnz[b];
  return (float4)(nx, ny, nz, nx * bx[b] + ny * by[b] + nz * bz[b] + P.layer);
}

// The planes of fluid particle i (0 to 3, first; those past the count have n = 0), from
// the boundary particles the planes' pass found them at (wplane, in this step's order).
static inline int bw_image_planes(SimParams P, uint i, __global const uint4* wplane, __global const float* bx,
                                  __global const float* by, __global const float* bz, __global const float* bnx,
                                  __global const float* bny, __global const float* bnz, float4* pl) {
  const uint4 w = wplane[i];
  const uint b[BW_IMAGE_PLANES] = {w.x, w.y, w.z};
  int count = 0;
  for (int k = 0; k < BW_IMAGE_PLANES; ++k) {
    pl[k] = (float4)(0.0f);
    if (b[k] != BW_NO_PLANE) pl[count++] = bw_image_plane(P, b[k], bx, by, bz, bnx, bny, bnz);
  }
  return count;
}

// Whether a point lies behind plane p (on its solid's side).
static inline bool bw_image_behind(float4 p, float x, float y, float z) { return p.x * x + p.y * y + p.z * z < p.w; }

// Whether a boundary particle at (x, y, z) gives way to the images: it lies behind one
// of the particle's planes.
static inline bool bw_image_replaced(const float4* pl, int count, float x, float y, float z) {
  bool behind = false;
  for (int k = 0; k < count; ++k) behind = behind || bw_image_behind(pl[k], x, y, z);
  return behind;
}

// The plane whose face a replaced boundary particle b carries the images' push on
// (its share, by Psi_b W, of what they push along the plane's normal): the plane it
// lies on, as a face particle (its normal along the plane's, its face half a spacing
// beyond it on the plane); an edge's or a corner's particle (a concave edge's rows, or
// the edge where a box's face meets the floor it stands on, which is the face's first
// row) the plane nearest its normal among those it lies behind. -1 for the rest, a
// face buried against another solid or the back of a thin part, which carry none.
static inline int bw_image_face_of(SimParams P, const float4* pl, int count, float xb, float yb, float zb, float nx,
                                   float ny, float nz, float flatness) {
  int best = -1;
  float cos_best = 0.0f;
  for (int k = 0; k < count; ++k) {
    if (!bw_image_behind(pl[k], xb, yb, zb)) continue;
    const float c = pl[k].x * nx + pl[k].y * ny + pl[k].z * nz;
    if (flatness >= BW_FACE_FLATNESS) {
      const float d = nx * xb + ny * yb + nz * zb + P.layer;
      if (c > BW_IMAGE_SAME_COS && fabs(d - pl[k].w) < BW_IMAGE_SAME_OFFSET * P.layer) return k;
    } else if (c > cos_best) {
      cos_best = c;
      best = k;
    }
  }
  return flatness >= BW_FACE_FLATNESS ? -1 : best;
}

#endif

// What the solver starts from, prepared on the host from a scene: the derived
// physical parameters (particle mass, stiffness, time-step limits), the fluid
// particles of the blocks, the emitters' lattices and the boundary particles of the
// solids. Everything here that depends on the input is checked, so that a bad scene
// fails (InputError naming the key) before a device is touched or a file written.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "fracture/fracture.h"
#include "io/particles_file.h"
#include "rigid/body.h"
#include "rigid/motion.h"
#include "scene/scene.h"

namespace bw::sim {

// Sum of W_spiky(|x_j|, h), the density kernel, over a simple cubic lattice of the given spacing around a
// particle at a lattice point, the particle itself included (computed in double).
double lattice_kernel_sum(double spacing, double h);

// The default boundary weight gamma1: the value for which a fluid particle one
// spacing from a flat wall (one layer of boundary particles at the same spacing,
// with Akinci's Psi_b) has exactly rho0, like a particle inside the fluid, so that
// fluid placed next to walls starts at rest. (With gamma1 = 1 and W_poly6, method.md's
// literal choice, that particle would start 12% compressed, 25% in a corner, which a
// stiff fluid turns into a blast at t = 0.)
double calibrated_gamma1(double spacing, double h);

// c = -(1/3) trace of sum_j V x_ij (x) grad W(x_ij) over the same lattice, V = 1 /
// lattice_kernel_sum: how much the kernel gradient underestimates a linear field's
// gradient there (1 for an exact kernel; 0.774 for W_spiky at h = 2 spacings).
double lattice_gradient_moment(double spacing, double h);

// The rate (1/s) at which the density diffusion of coefficient delta pulls a
// particle's density toward its neighbours' on the same lattice, the diagonal of its
// explicit update (fluid.cl, fluid_density): about 13 delta c0 / h for W_spiky at h =
// 2 spacings. The diffusion's step limit is set from each step's own largest rate;
// this one is the limit at rest, which a fixed step must keep.
double lattice_diffusion_rate(double spacing, double h, double delta, double c0);

struct Parameters {
  double spacing = 0;
  double h = 0;                 // support radius
  // A particle is the fluid of one cell of the sampling lattice: mass rho0 spacing^3,
  // in its momentum, its energy and the forces it exchanges with solids. The SPH sums
  // weigh it with kernel_mass instead, for which a full lattice sums to rho0 (the
  // lattice sum of W_spiky at h = 2 spacings is 24% above its integral; weighed with
  // the mass, water would rest at 0.81 rho0 of mass per volume, and bodies would
  // float in it as in a liquid of that density).
  double mass = 0;
  double kernel_mass = 0;       // rho0 / lattice_kernel_sum
  double gradient_moment = 1;   // lattice_gradient_moment: pressure forces are divided by it
  double rho0 = 0;
  double k = 0;                 // Tait stiffness (Pa)
  double c0 = 0;                // speed of sound (m/s): k = rho0 c0^2 / gamma
  double gamma = 7;
  double mu = 0, mu_b = 0, gamma1 = 1, gamma2 = 1;
  Vec3d gravity = Vec3d::Zero();
  double end_time = 0;          // s
  double frame_rate = 0;
  double dt_min = 0, dt_max = 0, cfl = 0, force_factor = 0;
  double dt_viscous = 0;        // viscous limit (s), infinity without viscosity
  double dt_diffusion = 0;      // density diffusion's limit on the lattice at rest (s), infinity without it
  double diffusion_factor = 0;  // time.diffusion_factor: dt <= it / the largest diffusion rate
  double scene_speed = 0;       // largest speed the scene can give the fluid (m/s)
  double speed_limit = 0;       // the guard stops the run above this speed (m/s)
  std::int64_t max_particles = 0;  // MFP
  double contact_frequency = 0; // omega of contacts between bodies (1/s), 0 without bodies
  double contact_dt = 0;        // time-step limit while bodies touch (s), infinity without bodies
  double contact_step = 0;      // omega contact_dt: what the contacts' damping ratios are tuned to
  double contact_zeta_max = 0;  // the largest damping ratio stable at that step
  Aabb domain;                  // particles leaving it are removed
  std::array<std::int64_t, 3> grid{0, 0, 0};  // cells of edge h covering the domain
  // The density (docs/scene.md, "Density"): integrated by the continuity equation with
  // Fourtakas et al. 2019's diffusion of coefficient delta = diffusion (0: none), or
  // the kernel sum over neighbours (continuity false).
  bool continuity = false;
  double diffusion = 0.1;
  // The pressure a boundary particle stands for in the boundary force: the fluid
  // particle's own (mirrored), or the boundary particle's own, extrapolated from the
  // fluid around it (fluid.cl, boundary_pressure; continuity only).
  bool wall_hydrostatic = false;
  // The flat faces of static solids as mirror images of the fluid (sph_images.h; with
  // wall_hydrostatic for the rest of the walls).
  bool wall_images = false;
};

// The signal speed of the CFL limit where the densest particle has density rho: the
// Tait law's sound speed c0 (rho / rho0)^((gamma - 1) / 2) (c0 below rho0, where the
// law's pressure is clamped at 0), which grows fast with compression (8 c0 at 2 rho0
// with gamma = 7), times sqrt(2 gamma2 / gamma1) where the walls push harder than the
// fluid's own energy would (the hydrostatic wall: gamma2 = gamma1, sqrt 2).
double signal_speed(const Parameters& p, double rho);

// Particles in structure-of-arrays form (float, what the device computes in).
struct ParticleArrays {
  std::vector<float> x, y, z, vx, vy, vz;
  std::size_t size() const { return x.size(); }
  void push(const Vec3d& p, const Vec3d& v);
};

// The lattice of one emitter and its schedule.
struct EmitterLattice {
  std::vector<Vec3d> points;    // one layer, on the emitter's plane
  Vec3d center = Vec3d::Zero();
  Vec3d normal = Vec3d::UnitZ();
  double speed = 0, start = 0, stop = 0;  // stop clipped to the end of the run
  // Layers emitted by time t: one each time the fluid has moved one spacing.
  std::int64_t layers_by(double t, double spacing) const;
  // Distance the fluid has moved out of the emitter by time t.
  double distance_by(double t) const;
};

// The boundary particles of the static solids.
struct BoundarySet {
  ParticleArrays particles;     // world positions, zero velocities
  std::vector<float> nx, ny, nz;  // unit normal of the solid's surface at each particle (0 when unknown)
  std::vector<float> flatness;    // of the surface there (surface_normals; contacts with bodies)
  std::vector<std::uint32_t> solid;  // index of the scene solid of each particle
  // Per scene solid, 1 when it was sampled with its volume: its mesh is closed and
  // oriented, and fluid belongs only on its normals' side (wall contact, sph_boundary.h).
  // 0 for a surface alone, which fluid may wet on either side.
  std::vector<std::uint32_t> one_sided;
  std::vector<std::size_t> per_solid;  // kept particles per solid (0 for dynamic solids)
  std::size_t dropped = 0;      // farther than h outside the domain: never touch fluid
  std::vector<double> solid_spacing;   // effective sampling spacing (file spacing x scale)
};

// How a solid touches bodies (its [[solid]] friction and restitution).
struct SolidMaterial {
  double friction = 0.5;        // Coulomb coefficient
  double restitution = 0.3;
  double spacing = 0;           // effective sampling spacing of its particles (m)
};

// A dynamic solid as the solver starts it: a rigid body whose geometry is given in the
// reference configuration (the solid's world coordinates at t = 0, docs/formats.md).
struct BodySetup {
  std::size_t solid = 0;        // scene index
  std::string name;
  rigid::MassProperties mass;   // from the voxels (voxel edge = file spacing x scale)
  std::int32_t voxels = 0;
  std::vector<Vec3d> particles; // boundary particles, reference configuration
  std::vector<Vec3d> normals;   // unit surface normals there (zero where unknown)
  std::vector<double> flatness; // of the surface there (surface_normals)
  Vec3d velocity = Vec3d::Zero();          // of the centre of mass (m/s)
  Vec3d angular_velocity = Vec3d::Zero();  // world frame (rad/s)
  // A static solid with a `motion` or an `angular_motion`: it moves as told, whatever
  // the forces on it (its mass is nominal: nothing reads it).
  rigid::PrescribedMotion motion;
  // Breakable solids (method.md 3 and 4): its voxels (cells of the file's grid and
  // their centres in the reference configuration), the cell of each boundary
  // particle, and which voxels touch another solid at t = 0 (its anchor).
  bool breakable = false, anchored = false;
  double frc = 0, density = 0, voxel_size = 0;
  std::vector<CellIndex> voxel_cells, particle_cells;
  std::vector<Vec3d> voxel_centers;
  std::vector<std::uint8_t> voxel_anchor;
};

struct Setup {
  Parameters params;
  ParticleArrays fluid;         // the blocks' particles at t = 0
  std::vector<float> fluid_rho; // their densities at t = 0 (hydrostatic), with the continuity equation
  std::vector<EmitterLattice> emitters;
  BoundarySet boundary;         // static solids
  std::vector<BodySetup> bodies;        // dynamic and breakable solids, in scene order
  scene::FractureSettings fracture;     // [fracture] (used when a body is breakable)
  std::vector<SolidMaterial> materials; // one per scene solid
  std::vector<std::size_t> block_particles;  // fluid particles of each block, in order
  std::int64_t emitter_particles = 0;  // what the emitters inject over the run (before MFP)
};

// What fracture cuts of a breakable body: its voxels (with their anchor) and its
// boundary particles, as the solver's fracture stage starts from them.
fracture::Piece breakable_piece(const BodySetup& body);

// Derives the parameters and builds every initial particle and body. `end_time` is
// the run's end (the scene's, or the one given on the command line). Throws
// InputError, also for a dynamic solid without voxels or one that starts overlapping
// the fluid or another solid.
Setup prepare(const scene::Scene& scene, double end_time);

// The surface normal at each surface particle of a sampled solid (in the file's
// frame): the mean normal of the surface within its cell (each triangle that
// overlaps the cell weighted by its area inside it, faces lying on the cell's planes
// included), so that a box's edges and corners are exact bisectors whatever the
// triangulation; zero where the normals cancel (a part thinner than a cell).
// `flatness`, when given, receives per particle |sum of the weighted normals| / their
// total weight: 1 on a face, cos(45 deg) = 0.71 on a box's edge, 0.58 on its corner,
// 0 where the normal is zero.
std::vector<Vec3d> surface_normals(const SampledSolid& solid, std::vector<double>* flatness = nullptr);

// The points of one emitter layer, spaced `spacing` apart on its disc or rectangle.
std::vector<Vec3d> emitter_points(const scene::Emitter& emitter, double spacing);

}  // namespace bw::sim

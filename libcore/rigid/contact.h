// Contact parameters of rigid bodies (docs/scene.md, "Physics": contacts between
// bodies and with static solids, computed on their boundary particles by the
// simulator's kernels, shaders/rigid.cl).
//
// A pair of boundary particles in contact pushes apart like a spring with a dashpot
// along the contact normal (linear DEM): F_n = k delta - c v_n, never pulling, with
// k = m omega^2 and c = 2 zeta m omega for the pair's mass m. The damping ratio zeta
// is the one for which a linear spring-dashpot collision of two particles ends with
// the restitution e: zeta = -ln e / sqrt(pi^2 + ln^2 e) (0 for e = 1, 1 for e = 0).
// Friction is Coulomb's: the tangential force opposes sliding with at most mu F_n.
#pragma once

namespace bw::rigid {

// zeta for a restitution e in [0, 1].
double damping_ratio(double restitution);

// zeta for which the bounce as the simulator steps it ends with restitution e: the
// spring and dashpot never pulling (the force is max(0, k delta - c v_n)) and
// integrated by symplectic Euler with steps of omega_dt / omega, the restitution
// averaged over where the contact starts within a step. damping_ratio(e) is its
// limit for omega_dt -> 0 without the clamp; the clamp (which keeps the dashpot from
// pulling at the end of a bounce) and the step both make the bounce livelier (at
// omega dt = 0.5, damping_ratio(0.3) bounces with 0.38).
double damping_ratio_for_step(double restitution, double omega_dt);

// The restitution of that stepped bounce for a damping ratio zeta.
double stepped_restitution(double zeta, double omega_dt);

// The restitution a linear spring-dashpot collision of damping ratio zeta < 1 ends
// with, e = exp(-zeta pi / sqrt(1 - zeta^2)) (0 for zeta >= 1): the inverse of
// damping_ratio.
double restitution_of(double damping_ratio);

// How two solids' materials combine in a contact: friction by the geometric mean (a
// frictionless solid slides on anything), restitution by the larger (a bouncy solid
// bounces on anything).
double pair_friction(double a, double b);
double pair_restitution(double a, double b);

}  // namespace bw::rigid

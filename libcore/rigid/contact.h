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

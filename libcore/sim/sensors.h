// Pressure sensors on the faces of static solids (docs/scene.md, "Sensors"): the
// pressure a membrane feels, read from the forces the fluid puts on the face's
// boundary particles (shaders/rigid.cl, boundary_forces: the exact reaction of the
// fluid's boundary terms), not from the fluid's own pressure field. A face carries
// its load through its particles, each standing for spacing^2 of the face, so
// -F_b . n / spacing^2 is the pressure on particle b's patch; a sensor reads the mean
// over its disc of these patch pressures interpolated along the face. At rest the
// patches of a floor carry the water's weight exactly (momentum balance), whatever
// the fluid's density field does.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "scene/scene.h"
#include "sim/setup.h"

namespace bw::sim {

// A sensor as the solver reads it: pressure = -sum_k weight[k] F[particle[k]] . normal,
// with F the force on a static boundary particle (master index) and weights in 1/m^2.
struct SensorWeights {
  std::string name;
  Vec3d at = Vec3d::Zero();
  Vec3d normal = Vec3d::Zero();  // unit, out of the solid
  double radius = 0;
  std::vector<std::uint32_t> particle;
  std::vector<double> weight;
};

// The weights of one sensor over the static boundary `b` (smoothing length h): at each
// of the disc's points (common/geometry.h, disc_points), a Shepard average along the
// face of the patch pressures of the face's particles within h, with weights
// (1 - d^2/h^2)^3 of their distance d along the face; the points weigh equally.
// The face's particles: on a face (flatness >= 0.9), of the sensor's solid (any static
// solid when it names none), facing the sensor's normal (within 25 degrees) and within
// 0.75 spacings of the sensor's plane. Without a normal, the sensor takes the mean
// normal of the face particles within h. Throws InputError naming `where` (the scene
// and the sensor) when no face is there.
SensorWeights sensor_weights(const BoundarySet& b, const scene::Sensor& sensor, double h, const std::string& where);

}  // namespace bw::sim

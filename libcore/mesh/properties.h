// Volume, centroid and inertia of the solid a closed mesh bounds.
#pragma once

#include "common/geometry.h"

namespace bw::mesh {

struct MassProperties {
  double area = 0;              // surface area
  double volume = 0;            // signed: negative when the faces point inwards
  Vec3d centroid = Vec3d::Zero();
  // Inertia tensor about the centroid for density 1 (scale by density for mass).
  Mat3d inertia = Mat3d::Zero();
};

// Exact for a closed, consistently oriented mesh (divergence theorem over the
// tetrahedra the faces span with a reference point). Meaningless for open meshes.
MassProperties mass_properties(const TriMesh& mesh);

// Reverses every face (turns an inside-out mesh right).
void flip_faces(TriMesh& mesh);

}  // namespace bw::mesh

#include "mesh/properties.h"

namespace bw::mesh {

MassProperties mass_properties(const TriMesh& mesh) {
  MassProperties props;
  if (mesh.triangles.empty()) return props;
  // Integrate relative to the box centre: keeps the sums well conditioned for meshes
  // far from the origin.
  const Aabb box = mesh.bounds();
  const Vec3d ref = 0.5 * (box.min + box.max);

  double volume = 0;
  Vec3d first = Vec3d::Zero();              // integral of x dV
  Vec3d second = Vec3d::Zero();             // integral of x^2, y^2, z^2 dV
  Vec3d products = Vec3d::Zero();           // integral of yz, zx, xy dV
  for (const Triangle& t : mesh.triangles) {
    const Vec3d a = mesh.vertices[t[0]] - ref;
    const Vec3d b = mesh.vertices[t[1]] - ref;
    const Vec3d c = mesh.vertices[t[2]] - ref;
    props.area += 0.5 * (b - a).cross(c - a).norm();
    // Tetrahedron (0, a, b, c): signed volume det / 6.
    const double det = a.dot(b.cross(c));
    volume += det / 6.0;
    first += det / 24.0 * (a + b + c);
    for (int i = 0; i < 3; ++i) {
      second[i] += det / 60.0 * (a[i] * a[i] + b[i] * b[i] + c[i] * c[i] + a[i] * b[i] + a[i] * c[i] + b[i] * c[i]);
      const int j = (i + 1) % 3;
      const int k = (i + 2) % 3;
      products[i] += det / 120.0 *
                     (2 * a[j] * a[k] + 2 * b[j] * b[k] + 2 * c[j] * c[k] + a[j] * b[k] + a[k] * b[j] +
                      a[j] * c[k] + a[k] * c[j] + b[j] * c[k] + b[k] * c[j]);
    }
  }
  props.volume = volume;
  if (volume == 0) return props;
  const Vec3d centroid_rel = first / volume;
  props.centroid = ref + centroid_rel;
  // Inertia about the reference point, then shifted to the centroid (parallel axes).
  Mat3d inertia;
  inertia(0, 0) = second.y() + second.z();
  inertia(1, 1) = second.z() + second.x();
  inertia(2, 2) = second.x() + second.y();
  inertia(1, 2) = inertia(2, 1) = -products.x();
  inertia(2, 0) = inertia(0, 2) = -products.y();
  inertia(0, 1) = inertia(1, 0) = -products.z();
  const Vec3d& d = centroid_rel;
  inertia -= volume * (d.squaredNorm() * Mat3d::Identity() - d * d.transpose());
  props.inertia = inertia;
  return props;
}

void flip_faces(TriMesh& mesh) {
  for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
}

}  // namespace bw::mesh

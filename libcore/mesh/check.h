// Topological and numerical checks of a triangle mesh.
#pragma once

#include <cstddef>
#include <string>

#include "common/geometry.h"

namespace bw::mesh {

struct MeshReport {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t boundary_edges = 0;      // edges used by one face only
  std::size_t nonmanifold_edges = 0;   // edges used by more than two faces
  std::size_t misoriented_edges = 0;   // edges that two faces traverse the same way
  std::size_t degenerate_faces = 0;    // repeated index or zero area
  std::size_t nonfinite_vertices = 0;  // NaN or infinite coordinate
  std::size_t bad_indices = 0;         // faces with an index outside the vertex array
  std::size_t components = 0;          // edge-connected groups of faces

  // Every edge shared by exactly two faces.
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0 && triangles > 0; }
  // Each edge is traversed once in each direction by its two faces.
  bool consistently_oriented() const { return misoriented_edges == 0; }
  // Closed, oriented, finite, valid indices: a mesh that bounds a volume.
  bool bounds_volume() const {
    return closed() && consistently_oriented() && nonfinite_vertices == 0 && bad_indices == 0;
  }
  // "412 boundary edges, 3 misoriented edges" or "closed and consistently oriented".
  std::string summary() const;
};

// A face counts as degenerate when its area is below kDegenerateAreaFraction times
// the square of the mesh's bounding-box diagonal (relative, so units do not matter).
inline constexpr double kDegenerateAreaFraction = 1e-14;

MeshReport check_mesh(const TriMesh& mesh);

}  // namespace bw::mesh

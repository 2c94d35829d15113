// Merging coincident vertices, so that faces that share a position share an index
// (STL and many exporters write every triangle with its own corners).
#pragma once

#include "common/geometry.h"

namespace bw::mesh {

struct WeldStats {
  std::size_t merged_vertices = 0;   // vertices removed by merging
  std::size_t collapsed_faces = 0;   // faces removed because two corners merged
  std::size_t unused_vertices = 0;   // vertices no face used, removed
};

// tolerance == 0 merges bitwise-equal positions (-0 and +0 count as equal). A
// tolerance > 0 merges each vertex into the first earlier vertex within that distance
// (deterministic: the result depends only on the input order). Faces whose corners
// merge are removed; vertices no face uses are dropped.
WeldStats weld_vertices(TriMesh& mesh, double tolerance = 0.0);

}  // namespace bw::mesh

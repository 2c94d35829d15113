// Files of kind "fragments": closed meshes of fragments, each in the reference
// configuration of its root solid (docs/formats.md). Written by bw-voronoi, read by
// bw-render.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace bw {

struct Fragment {
  TriMesh mesh;
  std::int32_t seed = -1;       // Voronoi cell it came from
  std::int32_t component = 0;   // connected component within the cell
  double volume = 0;
  std::int32_t body = -1;       // body of a run (replay), -1 otherwise
};

struct FragmentSet {
  std::string source;           // what was cut: a mesh, a particle file or a run
  std::string tool;             // tool and version that wrote the file ("" when unknown)
  std::string options;          // the tool's effective options, to reproduce the file
  std::vector<Vec3d> seeds;
  std::vector<Fragment> fragments;
};

void write_fragments(const FragmentSet& set, const std::string& path);
FragmentSet read_fragments(const std::string& path);

}  // namespace bw

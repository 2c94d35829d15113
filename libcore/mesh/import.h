// Reading triangle meshes from any format assimp reads (OBJ, PLY, STL, OFF, glTF,
// FBX, Collada, 3DS, ...). This part is the only one that includes assimp.
#pragma once

#include <string>

#include "common/geometry.h"

namespace bw::mesh {

struct ImportOptions {
  double scale = 1.0;           // applied to every coordinate after import
  double weld_tolerance = 0.0;  // 0: weld bitwise-equal positions only (see weld.h)
};

struct ImportStats {
  std::size_t meshes = 0;            // meshes in the file, all merged into one
  std::size_t vertices_read = 0;     // before welding
  std::size_t collapsed_faces = 0;   // faces dropped because welding merged two corners
  std::size_t non_triangles = 0;     // points and lines in the file, ignored
};

// Reads every mesh of the file with its node transform, merges them, welds
// coincident vertices and applies the scale. Throws InputError naming the file when
// it cannot be read, holds no triangles, or has a non-finite coordinate.
TriMesh import_mesh(const std::string& path, const ImportOptions& options = {},
                    ImportStats* stats = nullptr);

// Writes a mesh through assimp; the format comes from the extension (.obj, .ply,
// .stl, .glb, ...). Written through a temporary file, renamed on success.
void export_mesh(const TriMesh& mesh, const std::string& path);

// File extensions assimp can read, for --help and messages (e.g. "*.obj;*.ply;...").
std::string readable_extensions();

}  // namespace bw::mesh

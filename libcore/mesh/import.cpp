#include "mesh/import.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "common/error.h"
#include "common/input_file.h"
#include "mesh/weld.h"

namespace bw::mesh {
namespace {

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, TriMesh& out,
             ImportStats& stats) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    ++stats.meshes;
    const auto base = static_cast<std::int32_t>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    stats.vertices_read += mesh.mNumVertices;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        ++stats.non_triangles;
        continue;
      }
      out.triangles.push_back({base + static_cast<std::int32_t>(face.mIndices[0]),
                               base + static_cast<std::int32_t>(face.mIndices[1]),
                               base + static_cast<std::int32_t>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], transform, out, stats);
}

}  // namespace

TriMesh import_mesh(const std::string& path, const ImportOptions& options, ImportStats* stats_out) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) fail_input("{}: scale {} must be a positive number", path, options.scale);
  const std::string source = seekable_path(path);  // a pipe's copy: assimp seeks
  {
    std::ifstream probe(source, std::ios::binary);
    if (!probe) fail_input("{}: cannot open: {}", path, std::strerror(errno));
    if (std::filesystem::is_directory(path)) fail_input("{}: is a folder, expected a mesh file", path);
    if (probe.peek() == std::ifstream::traits_type::eof()) fail_input("{}: empty file", path);
  }
  Assimp::Importer importer;
  // Points and lines are dropped; polygons are triangulated.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      source, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode) {
    std::string reason = importer.GetErrorString();
    for (char& c : reason)
      if (c == '\n') c = ' ';
    // assimp drops points and lines first, then finds nothing left.
    if (reason.find("No meshes remaining") != std::string::npos) fail_input("{}: the file holds no triangles", path);
    fail_input("{}: cannot read the mesh: {}", path, reason.empty() ? "unknown format" : reason);
  }
  TriMesh mesh;
  ImportStats stats;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), mesh, stats);
  if (mesh.triangles.empty()) fail_input("{}: the file holds no triangles", path);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!mesh.vertices[v].allFinite()) {
      const Vec3d& p = mesh.vertices[v];
      fail_input("{}: vertex {} has a non-finite coordinate ({}, {}, {})", path, v, p.x(), p.y(), p.z());
    }
    mesh.vertices[v] *= options.scale;
  }
  const WeldStats weld = weld_vertices(mesh, options.weld_tolerance * options.scale);
  stats.collapsed_faces = weld.collapsed_faces;
  if (mesh.triangles.empty()) fail_input("{}: every triangle collapsed to a point or a line when welding", path);
  if (stats_out) *stats_out = stats;
  return mesh;
}

std::string readable_extensions() {
  Assimp::Importer importer;
  std::string list;
  importer.GetExtensionList(list);
  return list;
}

}  // namespace bw::mesh

#include <algorithm>
#include <filesystem>
#include <memory>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "mesh/import.h"

#include <fmt/format.h>

namespace bw::mesh {
namespace {

std::string format_for(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") return "objnomtl";
  if (ext == ".ply") return "plyb";
  if (ext == ".stl") return "stlb";
  if (ext == ".glb") return "glb2";
  if (ext == ".gltf") return "gltf2";
  if (ext == ".off") fail_input("{}: assimp cannot write OFF; use .obj, .ply, .stl or .glb", path);
  if (ext.empty()) fail_input("{}: no extension to choose the mesh format (.obj, .ply, .stl, .glb)", path);
  return ext.substr(1);
}

}  // namespace

// OBJ is written here rather than by assimp, whose single-precision coordinates
// would not read back to the same doubles.
void export_obj(const TriMesh& mesh, const std::string& path) {
  std::string text = fmt::format("# breakwater mesh: {} vertices, {} triangles\n", mesh.vertices.size(),
                                 mesh.triangles.size());
  for (const Vec3d& v : mesh.vertices) text += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  for (const Triangle& t : mesh.triangles) text += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  write_file_atomically(path, text.data(), text.size());
}

void export_mesh(const TriMesh& mesh, const std::string& path) {
  const std::string format = format_for(path);
  if (format == "objnomtl") {
    export_obj(mesh, path);
    return;
  }
  // The aiScene owns its arrays and frees them with delete[] in its destructor.
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMaterials = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mRootNode->mNumMeshes = 1;
  aiMesh& out = *scene.mMeshes[0];
  out.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out.mMaterialIndex = 0;
  out.mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  out.mVertices = new aiVector3D[out.mNumVertices];
  for (unsigned v = 0; v < out.mNumVertices; ++v) {
    const Vec3d& p = mesh.vertices[v];
    out.mVertices[v] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
  }
  out.mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  out.mFaces = new aiFace[out.mNumFaces];
  for (unsigned f = 0; f < out.mNumFaces; ++f) {
    out.mFaces[f].mNumIndices = 3;
    out.mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) out.mFaces[f].mIndices[k] = static_cast<unsigned>(mesh.triangles[f][k]);
  }
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, format);
  if (!blob) fail_input("{}: cannot write the mesh: {}", path, exporter.GetErrorString());
  if (blob->next) fail_run("{}: the exporter produced several files; choose another format", path);
  write_file_atomically(path, blob->data, blob->size);
}

}  // namespace bw::mesh

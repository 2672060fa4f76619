#include "heavytop/io/mesh_file.hpp"

#include <dlfcn.h>

#include <cmath>
#include <filesystem>
#include <mutex>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#ifndef HEAVYTOP_ASSIMP_SONAME
#define HEAVYTOP_ASSIMP_SONAME "libassimp.so.5"
#endif

namespace heavytop::io {
namespace {

// Assimp's C interface (assimp/cimport.h), resolved at the first use: linking libassimp into
// heavytop would cost every command a few milliseconds of start-up for its relocations.
struct Assimp {
  const aiScene* (*import_file)(const char*, unsigned int) = nullptr;
  void (*release_import)(const aiScene*) = nullptr;
  bool loaded = false;
};

const Assimp& assimp() {
  static Assimp a;
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = ::dlopen(HEAVYTOP_ASSIMP_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!handle) return;  // kept open for the life of the process
    a.import_file = reinterpret_cast<const aiScene* (*)(const char*, unsigned int)>(::dlsym(handle, "aiImportFile"));
    a.release_import = reinterpret_cast<void (*)(const aiScene*)>(::dlsym(handle, "aiReleaseImport"));
    a.loaded = a.import_file && a.release_import;
  });
  return a;
}

// A path as it goes into a one-line message: control characters shown as '?'.
std::string shown(std::string path) {
  for (char& c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return path;
}

}  // namespace

TriangleMesh read_mesh(const std::string& path, double scale, const std::string& key) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InvalidInput(key, fmt::format("cannot read '{}': no such file", shown(path)));
  if (!fs::is_regular_file(path, ec))
    throw InvalidInput(key, fmt::format("cannot read '{}': not a regular file", shown(path)));
  // Assimp holds the whole file and its mesh in memory: a larger file is not a top's mesh.
  if (fs::file_size(path, ec) > kMaxMeshBytes)
    throw InvalidInput(key, fmt::format("'{}' is larger than {} bytes: too large a mesh", shown(path), kMaxMeshBytes));
  const Assimp& lib = assimp();
  if (!lib.loaded)
    throw InvalidInput(key, fmt::format("cannot read meshes: the Assimp library ({}) is not installed "
                                        "(scripts/install-deps.sh installs it)", HEAVYTOP_ASSIMP_SONAME));
  // Triangulate polygons, bake node transforms into the vertices; no other processing (the
  // geometry must stay exactly as the file gives it). Assimp logs nothing unless asked.
  const aiScene* scene = lib.import_file(path.c_str(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
  if (!scene) throw InvalidInput(key, fmt::format("cannot read '{}' as a mesh (STL, OBJ or PLY)", shown(path)));
  TriangleMesh mesh;
  bool finite = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      mesh.vertices.emplace_back(scale * double(p.x), scale * double(p.y), scale * double(p.z));
      finite = finite && mesh.vertices.back().allFinite();
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines: no surface
      mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  lib.release_import(scene);
  if (!finite) throw InvalidInput(key, fmt::format("'{}' has a vertex that is not a finite number", shown(path)));
  if (mesh.triangles.empty()) throw InvalidInput(key, fmt::format("'{}' holds no triangles", shown(path)));
  return mesh;
}

}  // namespace heavytop::io

#pragma once
/// \file
/// Reading a CAD mesh (STL binary or ASCII, OBJ, PLY) through Assimp, for SPEC section 10's
/// `shape = "mesh"` parts. Assimp is loaded when the first mesh is read (dlopen), so that no
/// command that reads none pays for loading it at start-up.

#include <string>

#include "heavytop/mass_properties.hpp"

namespace heavytop::io {

/// The largest mesh file read_mesh() reads (bytes): 1 GiB, some 20 million triangles of binary STL.
inline constexpr unsigned long long kMaxMeshBytes = 1ull << 30;

/// The triangles of every mesh in `path` (node transforms applied, polygons triangulated),
/// coordinates multiplied by `scale` (m per unit of the file). Throws InvalidInput naming
/// `key` (e.g. "body.part[1] (top.stl)") when the file is missing, cannot be read as a mesh, or
/// holds no triangles, is not a regular file or is larger than kMaxMeshBytes, and when
/// Assimp cannot be loaded.
TriangleMesh read_mesh(const std::string& path, double scale, const std::string& key);

}  // namespace heavytop::io

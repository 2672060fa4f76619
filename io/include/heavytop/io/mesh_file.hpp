#pragma once
/// \file
/// Reading a CAD mesh (STL binary or ASCII, OBJ, PLY ASCII or binary), for SPEC section 10's
/// `shape = "mesh"` parts, by readers of heavytop's own (no Assimp: a malformed file thrown
/// out of the dlopen'ed Assimp crashed the static heavytop; tests/test_mesh_file.cpp checks
/// the readers against Assimp's results).

#include <string>

#include "heavytop/mass_properties.hpp"

namespace heavytop::io {

/// The largest mesh file read_mesh() reads (bytes): 1 GiB, some 20 million triangles of binary STL.
inline constexpr unsigned long long kMaxMeshBytes = 1ull << 30;

/// The triangles in `path` (the format by its extension, .stl, .obj or .ply in any case;
/// polygons triangulated as fans), coordinates multiplied by `scale` (m per unit of the file).
/// Throws InvalidInput naming `key` (e.g. "body.part[1] (top.stl)") and the file when the file
/// is missing, empty, not a regular file, larger than kMaxMeshBytes, malformed (what and where:
/// a truncated binary STL, a face index out of range, a PLY count the file cannot hold...),
/// has a vertex that is not finite, or holds no triangles.
TriangleMesh read_mesh(const std::string& path, double scale, const std::string& key);

}  // namespace heavytop::io

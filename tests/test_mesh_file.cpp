// The mesh readers (io/src/mesh_file.cpp) against Assimp, which heavytop used before issue 30,
// on the same files: the same vertices (float32, as Assimp reads them) and the same triangles;
// and every malformed file refused with InvalidInput naming the part and the file (it was a
// segfault in the static heavytop).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#ifdef HEAVYTOP_TEST_ASSIMP
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#endif

#include "heavytop/body.hpp"
#include "heavytop/io/mesh_file.hpp"
#include "heavytop/mass_properties.hpp"

namespace {

namespace fs = std::filesystem;

struct Dir {
  fs::path path = fs::temp_directory_path() / ("heavytop_mesh_" + std::to_string(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const fs::path p = path / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
};

// A closed, outward box [0,1]x[0,2]x[0,3] with 8 vertices and 6 quads.
const double kBox[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 3}, {1, 0, 3}, {1, 2, 3}, {0, 2, 3}};
const int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

std::vector<std::array<int, 3>> box_triangles() {
  std::vector<std::array<int, 3>> t;
  for (const auto& q : kQuads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

std::string ascii_stl() {
  std::string s = "solid box\n";
  for (const auto& t : box_triangles()) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int v : t) s += "      vertex " + std::to_string(kBox[v][0]) + " " + std::to_string(kBox[v][1]) + " " + std::to_string(kBox[v][2]) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid box\n";
}

std::string binary_stl(bool solid_header = false) {
  std::string s(80, ' ');
  if (solid_header) s.replace(0, 5, "solid");
  const auto tris = box_triangles();
  const std::uint32_t n = static_cast<std::uint32_t>(tris.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : tris) {
    s.append(12, '\0');
    for (int v : t)
      for (int a = 0; a < 3; ++a) {
        const float f = static_cast<float>(kBox[v][a]);
        s.append(reinterpret_cast<const char*>(&f), 4);
      }
    s.append(2, '\0');
  }
  return s;
}

std::string obj() {
  std::string s = "# box\no box\n";
  for (const auto& v : kBox) s += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  s += "vn 0 0 1\nvt 0 0\ns off\n";
  for (const auto& q : kQuads) {
    // Mixed index forms: i, i/t, i//n, negative.
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + "/1 " + std::to_string(q[2] + 1) + "//1 " +
         std::to_string(q[3] - 8) + "\n";
  }
  return s;
}

std::string ply_header(const std::string& format, const std::string& extra = "") {
  return "ply\nformat " + format + " 1.0\ncomment a box\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\n" + extra + "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string ascii_ply() {
  std::string s = ply_header("ascii");
  for (const auto& v : kBox) s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  for (const auto& q : kQuads) s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " + std::to_string(q[3]) + "\n";
  return s;
}

template <class T>
void put(std::string& s, T value, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binary_ply(bool big) {
  std::string s = ply_header(big ? "binary_big_endian" : "binary_little_endian");
  for (const auto& v : kBox)
    for (double c : v) put(s, static_cast<float>(c), big);
  for (const auto& q : kQuads) {
    put(s, std::uint8_t{4}, big);
    for (int i : q) put(s, std::int32_t{i}, big);
  }
  return s;
}

// The mesh as a set of triangles of positions (independent of vertex numbering and of the
// triangle's starting corner and of the fan's choice of diagonal: compared by mass properties).
heavytop::MassProperties props(const heavytop::TriangleMesh& m) {
  return heavytop::mass_properties(m, 1000.0, std::nullopt, "test");
}

void expect_same(const heavytop::MassProperties& a, const heavytop::MassProperties& b) {
  EXPECT_DOUBLE_EQ(a.mass, b.mass);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.centre[i], b.centre[i], 1e-15);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a.inertia(i, j), b.inertia(i, j), 1e-12 * a.inertia.norm());
}

#ifdef HEAVYTOP_TEST_ASSIMP
// Assimp's reading, as mesh_file.cpp did it before issue 30.
heavytop::TriangleMesh assimp_mesh(const std::string& path) {
  const aiScene* scene = aiImportFile(path.c_str(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
  EXPECT_NE(scene, nullptr) << path;
  heavytop::TriangleMesh mesh;
  if (!scene) return mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < part->mNumVertices; ++v)
      mesh.vertices.emplace_back(double(part->mVertices[v].x), double(part->mVertices[v].y), double(part->mVertices[v].z));
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices == 3) mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  aiReleaseImport(scene);
  return mesh;
}

// The triangles as sorted triples of positions: the same surface, whatever the numbering.
std::multiset<std::array<double, 9>> surface(const heavytop::TriangleMesh& m) {
  std::multiset<std::array<double, 9>> s;
  for (const auto& t : m.triangles) {
    std::array<std::array<double, 3>, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = {m.vertices[t[k]].x(), m.vertices[t[k]].y(), m.vertices[t[k]].z()};
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());  // keeps the orientation
    s.insert({c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
  }
  return s;
}

TEST(MeshFile, SameTrianglesAsAssimp) {
  Dir d;
  for (const auto& [name, bytes] : std::map<std::string, std::string>{{"a.stl", ascii_stl()},
                                                                    {"b.stl", binary_stl()},
                                                                    {"c.stl", binary_stl(true)},
                                                                    {"d.obj", obj()},
                                                                    {"e.ply", ascii_ply()}}) {
    const std::string path = d.write(name, bytes);
    const heavytop::TriangleMesh ours = heavytop::io::read_mesh(path, 1.0, "part");
    const heavytop::TriangleMesh theirs = assimp_mesh(path);
    ASSERT_EQ(ours.triangles.size(), theirs.triangles.size()) << name;
    if (name.ends_with(".stl")) {
      EXPECT_EQ(surface(ours), surface(theirs)) << name;
    }
    expect_same(props(ours), props(theirs));
  }
}

// The example top (a generated binary STL of thousands of triangles), triangle for triangle.
TEST(MeshFile, ExampleTopAsAssimp) {
  const std::string path = HEAVYTOP_EXAMPLES "/meshes/spinning-top.stl";
  const heavytop::TriangleMesh ours = heavytop::io::read_mesh(path, 1e-3, "part");
  heavytop::TriangleMesh theirs = assimp_mesh(path);
  for (auto& v : theirs.vertices) v *= 1e-3;
  ASSERT_EQ(ours.triangles.size(), theirs.triangles.size());
  EXPECT_EQ(surface(ours), surface(theirs));
}
#endif

// Binary PLY (Assimp asserted on it) reads as the ASCII PLY of the same box, in both byte orders.
TEST(MeshFile, BinaryPlyAsAscii) {
  Dir d;
  const auto ascii = props(heavytop::io::read_mesh(d.write("a.ply", ascii_ply()), 1.0, "part"));
  expect_same(props(heavytop::io::read_mesh(d.write("le.ply", binary_ply(false)), 1.0, "part")), ascii);
  expect_same(props(heavytop::io::read_mesh(d.write("be.ply", binary_ply(true)), 1.0, "part")), ascii);
  EXPECT_NEAR(ascii.mass, 6000.0, 1e-9);  // 1 x 2 x 3 m of 1000 kg/m^3
  // Extra vertex properties (normals, colours as uchar) are skipped.
  std::string s = ply_header("binary_little_endian", "property float nx\nproperty uchar red\n");
  for (const auto& v : kBox) {
    for (double c : v) put(s, static_cast<float>(c), false);
    put(s, 1.0f, false);
    put(s, std::uint8_t{200}, false);
  }
  for (const auto& q : kQuads) {
    put(s, std::uint8_t{4}, false);
    for (int i : q) put(s, std::int32_t{i}, false);
  }
  expect_same(props(heavytop::io::read_mesh(d.write("extra.ply", s), 1.0, "part")), ascii);
}

// Every malformed file: InvalidInput naming the key and the file, and what is wrong.
TEST(MeshFile, MalformedFilesRefused) {
  Dir d;
  const std::string bin = binary_stl();
  std::string wrong_count = bin;
  wrong_count[80] = 13;
  std::string no_facets(84, '\0');
  const std::string ply_bin = binary_ply(false);
  std::string huge_count = ply_bin;
  huge_count.replace(huge_count.find("vertex 8"), 8, "vertex 4000000000");
  const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> cases = {
      {"empty.stl", {"", "is empty"}},
      {"text.stl", {"hello, this is not a mesh\n", "an ASCII STL starts with 'solid'"}},
      {"longtext.stl", {std::string(200, 'x'), "not an STL"}},
      {"nofacets.stl", {no_facets, "holds no triangles"}},
      {"asciinofacets.stl", {"solid x\nendsolid x\n", "holds no triangles"}},
      {"count.stl", {wrong_count, "a binary STL of 13 triangles has 684 bytes, not 734"}},
      {"truncated.stl", {bin.substr(0, bin.size() - 7), "bytes, not"}},
      {"truncated-ascii.stl", {ascii_stl().substr(0, 300), "line"}},
      {"notply.ply", {"solid x\nendsolid x\n", "a PLY file starts with the line 'ply'"}},
      {"truncated.ply", {ply_bin.substr(0, ply_bin.size() - 5), "it ends in face 5 (truncated?)"}},
      {"huge.ply", {huge_count, "more than the file can hold"}},
      {"noheaderend.ply", {"ply\nformat ascii 1.0\nelement vertex 3\n", "no 'end_header'"}},
      {"badindex.ply", {ply_header("ascii") + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n2 2 2\n3 3 3\n4 4 4\n3 0 1 9\n", "vertex 9 does not exist"}},
      {"badindex.obj", {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4: vertex 4 does not exist"}},
      {"zero.obj", {"v 0 0 0\nf 0 1 2\n", "is not a vertex index"}},
      {"badnumber.obj", {"v 0 x 0\n", "line 1: a vertex needs three numbers"}},
      {"nothing.obj", {"# just a comment\n", "holds no triangles"}},
      {"nan.obj", {"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite number"}},
      {"inf.obj", {"v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite number"}},
      {"mesh.3ds", {bin, "a mesh is a .stl, .obj or .ply file"}},
  };
  for (const auto& [name, c] : cases) {
    const std::string path = d.write(name, c.first);
    try {
      heavytop::io::read_mesh(path, 1.0, "body.part[0] (" + name + ")");
      ADD_FAILURE() << name << " was read";
    } catch (const heavytop::InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("body.part[0] (" + name + ")"), std::string::npos) << what;
      EXPECT_NE(what.find(name), what.rfind(name)) << "the file is named: " << what;
      EXPECT_NE(what.find(c.second), std::string::npos) << name << ": " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

}  // namespace

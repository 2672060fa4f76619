#include "heavytop/io/mesh_file.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>

#include <fmt/format.h>

// The three formats are read here, not through Assimp: an exception thrown inside the
// dlopen'ed Assimp cannot unwind through the static heavytop (every malformed file was a
// segfault there), and Assimp's triangulation asserts on binary PLY. The readers accept what
// Assimp accepts for closed surfaces (tests/test_mesh_file.cpp compares both on the same files)
// and refuse the rest with a message naming the file and where it goes wrong.

namespace heavytop::io {
namespace {

// A path as it goes into a one-line message: control characters shown as '?'.
std::string shown(std::string path) {
  for (char& c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return path;
}

// What went wrong in the file's content (the caller adds the key and the file's name).
struct Malformed {
  std::string what;
};

[[noreturn]] void malformed(std::string what) { throw Malformed{std::move(what)}; }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// A token as it goes into a message: at most 20 characters, control characters as '?'.
std::string token_shown(std::string_view t) {
  std::string s(t.substr(0, 20));
  if (t.size() > 20) s += "...";
  return shown(s);
}

bool parse_double(std::string_view t, double& out) {
  if (t.empty()) return false;
  if (t.front() == '+') t.remove_prefix(1);
#if defined(__EMSCRIPTEN__)  // its libc++ has no floating-point from_chars (the page, web/)
  const std::string copy(t);
  if (std::isspace(static_cast<unsigned char>(copy[0])) || copy[0] == '+' || copy[0] == '0' && copy.size() > 1 &&
      (copy[1] == 'x' || copy[1] == 'X'))
    return false;
  char* stop = nullptr;
  out = std::strtod(copy.c_str(), &stop);
  return stop == copy.c_str() + copy.size();
#else
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  if (end != t.data() + t.size()) return false;
  if (ec == std::errc::result_out_of_range) out = std::numeric_limits<double>::infinity();  // reported as not finite
  else if (ec != std::errc()) return false;
  return true;
#endif
}

bool parse_int(std::string_view t, long long& out) {
  if (t.empty()) return false;
  if (t.front() == '+') t.remove_prefix(1);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  return ec == std::errc() && end == t.data() + t.size();
}

// Whitespace-separated tokens with the line they are on.
class Tokens {
public:
  explicit Tokens(std::string_view text) : text_(text) {}
  // The next token, empty at the end of the text.
  std::string_view next() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  std::size_t line() const { return line_; }

private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

void add_polygon(TriangleMesh& mesh, const std::vector<std::uint32_t>& polygon) {
  // A fan: the polygons of these formats are planar and convex (Assimp triangulates the same).
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
}

// ---- STL ------------------------------------------------------------------------------------

float read_le_float(const unsigned char* p) {
  std::uint32_t u = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
  float f;
  std::memcpy(&f, &u, sizeof f);  // std::bit_cast, which Emscripten's libc++ lacks
  return f;
}

void read_binary_stl(std::string_view data, std::uint64_t count, TriangleMesh& mesh) {
  mesh.vertices.reserve(3 * count);
  mesh.triangles.reserve(count);
  const auto* p = reinterpret_cast<const unsigned char*>(data.data()) + 84;
  for (std::uint64_t t = 0; t < count; ++t, p += 50) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int v = 0; v < 3; ++v) {
      const unsigned char* q = p + 12 + 12 * v;
      mesh.vertices.emplace_back(read_le_float(q), read_le_float(q + 4), read_le_float(q + 8));
    }
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
}

void read_ascii_stl(std::string_view data, TriangleMesh& mesh) {
  Tokens tok(data);
  auto expect = [&](std::string_view word) {
    const std::string_view t = tok.next();
    if (lower(t) != word)
      malformed(fmt::format("line {}: expected '{}', found '{}'", tok.line(), word, t.empty() ? "the end of the file" : token_shown(t)));
  };
  auto number = [&] {
    const std::string_view t = tok.next();
    double x = 0.0;
    if (!parse_double(t, x)) malformed(fmt::format("line {}: '{}' is not a number", tok.line(), token_shown(t)));
    return x;
  };
  std::string_view t = tok.next();
  if (lower(t) != "solid") malformed("an ASCII STL starts with 'solid'");
  bool in_solid = true;
  // The solid's name runs to the end of its line: skip the rest of the line.
  for (std::size_t line = tok.line();;) {
    t = tok.next();
    if (t.empty()) break;
    if (tok.line() != line) break;
  }
  while (!t.empty()) {
    const std::string w = lower(t);
    if (w == "facet") {
      if (!in_solid) malformed(fmt::format("line {}: a facet outside 'solid ... endsolid'", tok.line()));
      expect("normal");
      for (int i = 0; i < 3; ++i) number();
      expect("outer");
      expect("loop");
      std::vector<std::uint32_t> polygon;
      for (;;) {
        t = tok.next();
        const std::string v = lower(t);
        if (v == "endloop") break;
        if (v != "vertex")
          malformed(fmt::format("line {}: expected 'vertex' or 'endloop', found '{}'", tok.line(),
                                t.empty() ? "the end of the file" : token_shown(t)));
        const double x = number(), y = number(), z = number();
        polygon.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.emplace_back(x, y, z);
        if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max() / 2) malformed("too many vertices");
      }
      if (polygon.size() < 3) malformed(fmt::format("line {}: a facet with {} vertices", tok.line(), polygon.size()));
      add_polygon(mesh, polygon);
      expect("endfacet");
    } else if (w == "endsolid") {
      if (!in_solid) malformed(fmt::format("line {}: 'endsolid' without 'solid'", tok.line()));
      in_solid = false;
      for (std::size_t line = tok.line();;) {  // its name, to the end of the line
        t = tok.next();
        if (t.empty() || tok.line() != line) break;
      }
      continue;
    } else if (w == "solid") {
      if (in_solid) malformed(fmt::format("line {}: 'solid' inside a solid", tok.line()));
      in_solid = true;
      for (std::size_t line = tok.line();;) {
        t = tok.next();
        if (t.empty() || tok.line() != line) break;
      }
      continue;
    } else {
      malformed(fmt::format("line {}: expected 'facet' or 'endsolid', found '{}'", tok.line(), token_shown(t)));
    }
    t = tok.next();
  }
  if (in_solid) malformed("it ends without 'endsolid' (truncated?)");
}

void read_stl(std::string_view data, TriangleMesh& mesh) {
  const std::uint64_t size = data.size();
  if (size >= 84) {
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    const std::uint64_t count = std::uint64_t(p[80]) | std::uint64_t(p[81]) << 8 | std::uint64_t(p[82]) << 16 |
                                std::uint64_t(p[83]) << 24;
    if (84 + 50 * count == size) return read_binary_stl(data, count, mesh);
    // Not binary by its size: ASCII if it says so, otherwise a binary STL cut short or padded.
    std::size_t i = 0;
    while (i < data.size() && is_space(data[i])) ++i;
    if (lower(data.substr(i, 5)) != "solid")
      malformed(fmt::format("a binary STL of {} triangles has {} bytes, not {} (truncated or not an STL)", count, size,
                            84 + 50 * count));
  }
  read_ascii_stl(data, mesh);
}

// ---- OBJ ------------------------------------------------------------------------------------

void read_obj(std::string_view data, TriangleMesh& mesh) {
  std::size_t line_no = 0;
  std::size_t pos = 0;
  std::vector<std::uint32_t> polygon;
  while (pos < data.size()) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    std::string_view line = data.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    Tokens tok(line);
    const std::string_view kind = tok.next();
    if (kind == "v") {
      double c[3];
      for (double& x : c) {
        const std::string_view t = tok.next();
        if (!parse_double(t, x))
          malformed(fmt::format("line {}: a vertex needs three numbers, found '{}'", line_no, t.empty() ? "none" : token_shown(t)));
      }
      mesh.vertices.emplace_back(c[0], c[1], c[2]);
      if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max() / 2) malformed("too many vertices");
    } else if (kind == "f") {
      polygon.clear();
      for (std::string_view t = tok.next(); !t.empty(); t = tok.next()) {
        long long i = 0;
        if (!parse_int(t.substr(0, t.find('/')), i) || i == 0)
          malformed(fmt::format("line {}: '{}' is not a vertex index", line_no, token_shown(t)));
        const auto n = static_cast<long long>(mesh.vertices.size());
        const long long index = i > 0 ? i - 1 : n + i;  // negative: relative to the last vertex
        if (index < 0 || index >= n)
          malformed(fmt::format("line {}: vertex {} does not exist ({} vertices so far)", line_no, i, n));
        polygon.push_back(static_cast<std::uint32_t>(index));
      }
      if (polygon.size() < 3) malformed(fmt::format("line {}: a face with {} vertices", line_no, polygon.size()));
      add_polygon(mesh, polygon);
    }
    // vt, vn, vp, g, o, s, usemtl, mtllib, l, p and the rest: no surface of a solid.
  }
}

// ---- PLY ------------------------------------------------------------------------------------

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

bool ply_type(std::string_view name, PlyType& t) {
  static const std::pair<std::string_view, PlyType> names[] = {
      {"char", PlyType::i8},    {"int8", PlyType::i8},     {"uchar", PlyType::u8},    {"uint8", PlyType::u8},
      {"short", PlyType::i16},  {"int16", PlyType::i16},   {"ushort", PlyType::u16},  {"uint16", PlyType::u16},
      {"int", PlyType::i32},    {"int32", PlyType::i32},   {"uint", PlyType::u32},    {"uint32", PlyType::u32},
      {"float", PlyType::f32},  {"float32", PlyType::f32}, {"double", PlyType::f64},  {"float64", PlyType::f64}};
  for (const auto& [n, type] : names)
    if (n == name) return t = type, true;
  return false;
}

std::size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 1;
}

bool ply_integral(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// Values of a PLY body, ASCII or binary, with the position for messages.
class PlyReader {
public:
  PlyReader(std::string_view body, int format) : body_(body), format_(format), tokens_(body) {}

  // The next value, of type t, of entry k of element `name` (for messages).
  double value(PlyType t, const std::string& name, std::uint64_t k) {
    if (format_ == 0) {
      const auto what = [&] { return fmt::format("{} {}", token_shown(name), k); };
      const std::string_view tok = tokens_.next();
      double x = 0.0;
      if (tok.empty()) malformed(fmt::format("it ends in {} (truncated?)", what()));
      if (!parse_double(tok, x)) malformed(fmt::format("{}: '{}' is not a number", what(), token_shown(tok)));
      return x;
    }
    const std::size_t n = ply_size(t);
    if (body_.size() - pos_ < n) malformed(fmt::format("it ends in {} {} (truncated?)", token_shown(name), k));
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    if (format_ == 2) std::reverse(b, b + n);  // big endian
    switch (t) {
      case PlyType::i8: return double(static_cast<std::int8_t>(b[0]));
      case PlyType::u8: return double(b[0]);
      case PlyType::i16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::u16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::i32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::u32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0.0;
  }
  // The smallest number of bytes one value can take (ASCII: a digit).
  std::size_t min_size(PlyType t) const { return format_ == 0 ? 1 : ply_size(t); }
  std::size_t remaining() const { return format_ == 0 ? body_.size() : body_.size() - pos_; }

private:
  std::string_view body_;
  int format_;  // 0 ascii, 1 little endian, 2 big endian
  Tokens tokens_;
  std::size_t pos_ = 0;
};

void read_ply(std::string_view data, TriangleMesh& mesh) {
  // The header: lines up to "end_header".
  std::size_t pos = 0;
  std::size_t line_no = 0;
  auto next_line = [&](std::string_view& line) {
    if (pos >= data.size()) return false;
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    line = data.substr(pos, end - pos);
    pos = std::min(end + 1, data.size());
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  };
  std::string_view line;
  if (!next_line(line) || line != "ply") malformed("a PLY file starts with the line 'ply'");
  int format = -1;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (next_line(line)) {
    Tokens tok(line);
    const std::string_view kind = tok.next();
    if (kind == "end_header") { ended = true; break; }
    if (kind.empty() || kind == "comment" || kind == "obj_info") continue;
    if (kind == "format") {
      const std::string_view f = tok.next(), version = tok.next();
      if (f == "ascii") format = 0;
      else if (f == "binary_little_endian") format = 1;
      else if (f == "binary_big_endian") format = 2;
      else malformed(fmt::format("header line {}: unknown format '{}'", line_no, token_shown(f)));
      if (version != "1.0") malformed(fmt::format("header line {}: PLY version '{}', not 1.0", line_no, token_shown(version)));
    } else if (kind == "element") {
      PlyElement e;
      e.name = std::string(tok.next());
      long long n = 0;
      const std::string_view count = tok.next();
      if (e.name.empty() || !parse_int(count, n) || n < 0)
        malformed(fmt::format("header line {}: an element needs a name and a count", line_no));
      e.count = static_cast<std::uint64_t>(n);
      elements.push_back(std::move(e));
    } else if (kind == "property") {
      if (elements.empty()) malformed(fmt::format("header line {}: a property before any element", line_no));
      PlyProperty p;
      std::string_view t = tok.next();
      if (t == "list") {
        p.list = true;
        if (!ply_type(tok.next(), p.count_type) || !ply_integral(p.count_type) || !ply_type(tok.next(), p.type))
          malformed(fmt::format("header line {}: a list property needs an integer count type and a value type", line_no));
      } else if (!ply_type(t, p.type)) {
        malformed(fmt::format("header line {}: unknown property type '{}'", line_no, token_shown(t)));
      }
      p.name = std::string(tok.next());
      if (p.name.empty()) malformed(fmt::format("header line {}: a property without a name", line_no));
      elements.back().properties.push_back(std::move(p));
    } else {
      malformed(fmt::format("header line {}: unknown keyword '{}'", line_no, token_shown(kind)));
    }
  }
  if (!ended) malformed("its header has no 'end_header' (truncated?)");
  if (format < 0) malformed("its header has no 'format' line");

  PlyReader in(data.substr(pos), format);
  bool have_vertices = false;
  std::uint64_t vertex_count = 0;
  for (const PlyElement& e : elements) {
    // Every element takes at least its fixed values: a count larger than the file can hold is refused
    // before anything is allocated.
    std::uint64_t min_bytes = 0;
    for (const PlyProperty& p : e.properties) min_bytes += p.list ? in.min_size(p.count_type) : in.min_size(p.type);
    if (min_bytes > 0 && e.count > in.remaining() / min_bytes)
      malformed(fmt::format("element '{}' has {} entries, more than the file can hold (truncated?)", token_shown(e.name), e.count));
    if (min_bytes == 0) continue;  // no properties: nothing to read
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const PlyProperty& p = e.properties[i];
      if (is_vertex && !p.list && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') xyz[p.name[0] - 'x'] = int(i);
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = int(i);
    }
    if (is_vertex) {
      if (have_vertices) malformed("it has two elements 'vertex'");
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) malformed("its vertices lack a property x, y or z");
      if (e.count > std::numeric_limits<std::uint32_t>::max() / 2) malformed("too many vertices");
      have_vertices = true;
      vertex_count = e.count;
      mesh.vertices.reserve(e.count);
    }
    if (is_face && indices < 0) malformed("its faces lack the list property vertex_indices");
    if (is_face && !have_vertices) malformed("its faces come before its vertices");
    if (is_face && !ply_integral(e.properties[indices].type)) malformed("its vertex indices are not integers");
    std::vector<std::uint32_t> polygon;
    for (std::uint64_t k = 0; k < e.count; ++k) {
      double c[3] = {0.0, 0.0, 0.0};
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const PlyProperty& p = e.properties[i];
        if (p.list) {
          const double n = in.value(p.count_type, e.name, k);
          if (n < 0 || n != std::floor(n)) malformed(fmt::format("{} {}: a list of {} values", token_shown(e.name), k, n));
          if (int(i) == indices) polygon.clear();
          for (double j = 0; j < n; ++j) {
            const double v = in.value(p.type, e.name, k);
            if (int(i) != indices) continue;
            if (v < 0 || v >= double(vertex_count) || v != std::floor(v))
              malformed(fmt::format("face {}: vertex {} does not exist ({} vertices)", k, v, vertex_count));
            polygon.push_back(static_cast<std::uint32_t>(v));
          }
        } else {
          const double v = in.value(p.type, e.name, k);
          if (is_vertex)
            for (int a = 0; a < 3; ++a)
              if (xyz[a] == int(i)) c[a] = v;
        }
      }
      if (is_vertex) mesh.vertices.emplace_back(c[0], c[1], c[2]);
      if (is_face) {
        if (polygon.size() < 3) malformed(fmt::format("face {}: {} vertices", k, polygon.size()));
        add_polygon(mesh, polygon);
      }
    }
  }
  if (!have_vertices) malformed("it has no element 'vertex'");
}

}  // namespace

TriangleMesh read_mesh(const std::string& path, double scale, const std::string& key) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InvalidInput(key, fmt::format("cannot read '{}': no such file", shown(path)));
  if (!fs::is_regular_file(path, ec))
    throw InvalidInput(key, fmt::format("cannot read '{}': not a regular file", shown(path)));
  const auto size = fs::file_size(path, ec);
  if (ec) throw InvalidInput(key, fmt::format("cannot read '{}': {}", shown(path), ec.message()));
  if (size > kMaxMeshBytes)
    throw InvalidInput(key, fmt::format("'{}' is larger than {} bytes: too large a mesh", shown(path), kMaxMeshBytes));
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    throw InvalidInput(key, fmt::format("cannot read '{}': a mesh is a .stl, .obj or .ply file", shown(path)));
  std::string data;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput(key, fmt::format("cannot read '{}': cannot open it", shown(path)));
    data.resize(static_cast<std::size_t>(size));
    in.read(data.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size)
      throw InvalidInput(key, fmt::format("cannot read '{}': it changed while being read", shown(path)));
  }
  if (data.empty()) throw InvalidInput(key, fmt::format("'{}' is empty", shown(path)));
  TriangleMesh mesh;
  const char* format = ext == ".stl" ? "STL" : ext == ".obj" ? "OBJ" : "PLY";
  try {
    if (ext == ".stl") read_stl(data, mesh);
    else if (ext == ".obj") read_obj(data, mesh);
    else read_ply(data, mesh);
  } catch (const Malformed& m) {
    throw InvalidInput(key, fmt::format("cannot read '{}' as {}: {}", shown(path), format, m.what));
  } catch (const std::bad_alloc&) {
    throw InvalidInput(key, fmt::format("cannot read '{}': too large a mesh for the memory", shown(path)));
  }
  // Coordinates as float32, as Assimp (ai_real) read them: a mesh's geometry is its float32
  // vertices, and every format gives the same body for the same vertices.
  // (A double beyond float's range is tested first: converting it is undefined, and GCC then
  // took every converted vertex for finite.)
  bool finite = true;
  for (Eigen::Vector3d& v : mesh.vertices) {
    for (int a = 0; a < 3; ++a) {
      if (!(std::abs(v[a]) <= double(std::numeric_limits<float>::max()))) {
        finite = false;
        break;
      }
      v[a] = scale * double(static_cast<float>(v[a]));
    }
    finite = finite && v.allFinite();
  }
  if (!finite) throw InvalidInput(key, fmt::format("'{}' has a vertex that is not a finite number", shown(path)));
  if (mesh.triangles.empty()) throw InvalidInput(key, fmt::format("'{}' holds no triangles", shown(path)));
  return mesh;
}

}  // namespace heavytop::io

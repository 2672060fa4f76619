// libFuzzer target: a mesh file through every path the command line takes it (issue 30: an
// empty file, a truncated STL, a non-PLY .ply were segfaults). The first byte picks the
// extension (.stl, .obj, .ply, upper case too); the rest is the file, written to a scratch
// file and read as a [[body.part]] of shape "mesh" (io::assemble_parts: read_mesh, the mass
// properties, their defects), then made a body (body_of: the linear models' refusal of a
// general body) and, when it is one, validated and analysed as `heavytop stability` does.
//
// Allowed: heavytop::InvalidInput naming the part and the file, in one line. A finding is
// anything else (another exception, a crash, a sanitizer report, a leak, a slow input).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "heavytop/body.hpp"
#include "heavytop/io/body_parts.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/mass_properties.hpp"
#include "heavytop/stability.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* const kExtensions[] = {".stl", ".obj", ".ply", ".STL", ".Obj", ".PLY"};
  if (size == 0) return 0;
  const std::string ext = kExtensions[data[0] % 6];
  static const std::string dir = [] {
    char pattern[] = "/tmp/fuzz_mesh_XXXXXX";
    return std::string(::mkdtemp(pattern));
  }();
  const std::string path = dir + "/part" + ext;
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  } else {
    std::abort();
  }
  heavytop::io::PartSpec part;
  part.label = "part" + ext;
  part.mesh = true;
  part.file = path;
  part.scale = (data[0] / 6) % 2 ? 1e-3 : 1.0;
  part.solid.density = 1000.0;
  try {
    const heavytop::io::AssembledBody body = heavytop::io::assemble_parts({part});
    const heavytop::Body b = heavytop::body_of(body.assembly, 9.81, body.names);
    heavytop::validate(b);
    (void)heavytop::is_realizable(b);
    (void)heavytop::analyse_stability(b, 300.0);
  } catch (const heavytop::InvalidInput& e) {
    const std::string message = e.key() + ": " + e.rule();
    if (e.key().find("body.part[0] (part" + ext + ")") != 0 && e.key().rfind("body.", 0) != 0) {
      std::fprintf(stderr, "fuzz_mesh: a message that does not name the part: '%s'\n", message.c_str());
      std::abort();
    }
    if (message.find_first_of("\n\r") != std::string::npos) {
      std::fprintf(stderr, "fuzz_mesh: a message that is not one line: '%s'\n", message.c_str());
      std::abort();
    }
  }
  return 0;
}

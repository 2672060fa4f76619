#include "heavytop/io/body_parts.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "heavytop/io/mesh_file.hpp"

namespace heavytop::io {

std::optional<double> touch_tilt(const std::vector<PartSpec>& parts, const Body& body) {
  std::vector<SolidPart> solids;
  for (const PartSpec& part : parts) {
    if (part.mesh) return std::nullopt;
    solids.push_back(part.solid);
  }
  if (solids.empty()) return std::nullopt;
  return heavytop::touch_tilt(solids, body.tip_radius, body.rim_radius);
}

AssembledBody assemble_parts(const std::vector<PartSpec>& parts) {
  AssembledBody out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const PartSpec& p = parts[i];
    out.names.push_back(p.name(i));
    // The core names the part "body.part[i]" or a field of it, "body.part[i].radius"; the
    // message adds its shape or file: "body.part[i].radius (cone)" (SPEC section 10).
    const std::string base = "body.part[" + std::to_string(i) + "]";
    try {
      out.parts.push_back(p.mesh ? mass_properties(read_mesh(p.file, p.scale, base), p.solid.density, p.solid.mass, base)
                                 : mass_properties(p.solid, base));
    } catch (const InvalidInput& e) {
      throw InvalidInput(e.key() + " (" + p.label + ")", e.rule());
    }
  }
  out.assembly = assemble(out.parts);
  return out;
}

std::string implausible_size_warning(const Body& body) {
  // The radius of gyration about O is the body's size as its moments give it (parts or not).
  const double size = std::max(std::abs(body.length), std::sqrt(std::max({body.A, body.B, body.C}) / body.mass));
  std::string what;
  if (body.mass > kPlausibleTopMass) what = fmt::format("a mass of {:.6g} kg", body.mass);
  if (size > kPlausibleTopSize)
    what += fmt::format("{}a radius of gyration about O of {:.6g} m", what.empty() ? "" : " and ", size);
  if (what.empty()) return "";
  return fmt::format("heavytop: warning: {} is implausible for a hand-held top: sizes typed in mm as m? (a "
                     "[[body.part]] takes units = \"mm\"); going on\n",
                     what);
}

Body as_given(const BodyAssembly& a, Body base) {
  base.A = a.A;
  base.B = a.B;
  base.C = a.C;
  base.mass = a.total.mass;
  base.length = a.length;
  base.general = {a.Ixy, a.Ixz, a.Iyz, a.offset_x, a.offset_y};
  return base;
}

AssembledBody assemble_moments(const Body& body, const std::map<std::string, double>& general) {
  auto value = [&](const char* key) {
    const auto it = general.find(key);
    if (it == general.end()) return 0.0;
    if (!std::isfinite(it->second)) throw InvalidInput(key, "must be a finite number");
    return it->second;
  };
  MassProperties p;
  p.mass = body.mass;
  p.centre = {value("body.offset_x"), value("body.offset_y"), body.length};
  const double xy = value("body.Ixy"), xz = value("body.Ixz"), yz = value("body.Iyz");
  p.inertia << body.A, -xy, -xz, -xy, body.B, -yz, -xz, -yz, body.C;
  AssembledBody out;
  out.parts.push_back(p);
  out.assembly = assemble(out.parts);
  return out;
}

}  // namespace heavytop::io

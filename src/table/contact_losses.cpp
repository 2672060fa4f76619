// The closed forms of a real top's losses (contact_losses.hpp; docs/table.md).
#include "heavytop/contact_losses.hpp"

#include <cmath>

#include <fmt/format.h>

#include "table/loss_laws.hpp"

namespace heavytop {

const std::vector<NamedMaterial>& common_materials() {
  // Young's modulus and Poisson's ratio at room temperature (docs/table.md gives the sources).
  // Wood is anisotropic: "wood" is pressed along its grain (a wooden top's tip, turned from a
  // spindle), "oak" across it (a table's top).
  static const std::vector<NamedMaterial> table = {
      {"steel", {200e9, 0.29}}, {"brass", {100e9, 0.34}}, {"aluminium", {69e9, 0.33}},
      {"glass", {70e9, 0.22}},  {"abs", {2.3e9, 0.35}},   {"nylon", {2.7e9, 0.39}},
      {"wood", {11e9, 0.30}},   {"oak", {1.6e9, 0.35}},   {"marble", {55e9, 0.25}},
  };
  return table;
}

std::optional<Material> material_from_name(std::string_view name) {
  for (const auto& m : common_materials())
    if (m.name == name) return m.material;
  return std::nullopt;
}

std::string material_names() {
  std::string out;
  const auto& all = common_materials();
  for (std::size_t i = 0; i < all.size(); ++i)
    out += fmt::format("{}\"{}\"", i == 0 ? "" : i + 1 == all.size() ? " or " : ", ", all[i].name);
  return out;
}

double contact_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson * a.poisson) / a.modulus + (1.0 - b.poisson * b.poisson) / b.modulus);
}

double hertz_contact_radius(double load, double sphere_radius, double modulus) {
  return detail::hertz_radius(load, sphere_radius, modulus);
}

std::vector<AirSurface> air_surfaces(const std::vector<SolidPart>& parts) {
  using Kind = AirSurface::Kind;
  std::vector<AirSurface> out;
  for (const SolidPart& p : parts) {
    switch (p.shape) {
      case PartShape::Cylinder:
        out.push_back({Kind::Face, p.radius, 0.0, 0.0});
        out.push_back({Kind::Face, p.radius, 0.0, 0.0});
        out.push_back({Kind::Cylinder, p.radius, 0.0, p.height});
        break;
      case PartShape::Tube:  // its bore's air turns with it: no shear there
        out.push_back({Kind::Face, p.radius, p.inner_radius, 0.0});
        out.push_back({Kind::Face, p.radius, p.inner_radius, 0.0});
        out.push_back({Kind::Cylinder, p.radius, 0.0, p.height});
        break;
      case PartShape::Cone:
        out.push_back({Kind::Face, p.radius, 0.0, 0.0});
        out.push_back({Kind::Cone, p.radius, 0.0, p.height});
        break;
      case PartShape::Sphere:
        out.push_back({Kind::Sphere, p.radius, 0.0, 0.0});
        break;
    }
  }
  return out;
}

std::vector<AirSurface> equivalent_disc(const Body& body) {
  const double radius = std::sqrt(2.0 * body.C / body.mass);
  return {{AirSurface::Kind::Face, radius, 0.0, 0.0}, {AirSurface::Kind::Face, radius, 0.0, 0.0}};
}

double air_torque(const AirSurface& surface, const Air& air, double spin) {
  return std::abs(detail::air_torque_of(surface, air, spin));
}

double air_torque(const std::vector<AirSurface>& surfaces, const Air& air, double spin) {
  double sum = 0.0;
  for (const auto& s : surfaces) sum += air_torque(s, air, spin);
  return sum;
}

}  // namespace heavytop

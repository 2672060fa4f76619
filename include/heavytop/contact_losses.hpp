#pragma once
/// \file
/// Where a real top's spin goes (docs/table.md, "Losses from the body and its materials"): the
/// closed forms of the contact patch (Hertz), its drilling friction (Contensou) and the air's
/// torque on the spinning parts. Pure functions of SI inputs; the table's equations use them.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/mass_properties.hpp"

namespace heavytop {

/// An isotropic elastic solid: what Hertz's contact needs of it.
struct Material {
  double modulus = 0.0;  ///< Pa, Young's modulus E (> 0)
  double poisson = 0.0;  ///< Poisson's ratio nu (in [0, 0.5))
};

/// A material of the table of common ones (docs/table.md lists them with their sources).
struct NamedMaterial {
  std::string_view name;  ///< "steel", "brass", "aluminium", "glass", "abs", "nylon", "wood", "oak", "marble"
  Material material;
};
/// The table of common materials, in the order docs/table.md lists them.
const std::vector<NamedMaterial>& common_materials();
/// The material called `name` in common_materials(), or nullopt.
std::optional<Material> material_from_name(std::string_view name);
/// The names of common_materials(), quoted and joined: "\"steel\", ... or \"marble\"".
std::string material_names();

/// Pa, the contact modulus E* of two solids: 1 / E* = (1 - nu_1^2) / E_1 + (1 - nu_2^2) / E_2.
double contact_modulus(const Material& a, const Material& b);

/// m, the radius of Hertz's circular contact patch of a sphere of radius `sphere_radius` (m)
/// pressed on a flat by `load` (N >= 0) with contact modulus `modulus` (Pa, E*):
/// a = (3 N R / (4 E*))^(1/3) (Johnson, Contact Mechanics, 1985, eq. 4.22).
double hertz_contact_radius(double load, double sphere_radius, double modulus);

/// Dimensionless: the drilling friction's arm over the patch radius for Hertz's pressure
/// p = p0 sqrt(1 - r^2 / a^2): the largest drilling torque is (3 pi / 16) mu N a.
inline constexpr double kHertzDrillingArm = 3.0 * 3.141592653589793 / 16.0;

/// Still air around the body (docs/table.md): density and dynamic viscosity. The defaults are
/// dry air at 20 degrees C and 101.325 kPa.
struct Air {
  double density = 1.204;      ///< kg/m^3, > 0
  double viscosity = 1.813e-5; ///< Pa s, > 0
};

/// One surface of revolution about the body's axis that the air drags on as the body spins.
struct AirSurface {
  enum class Kind {
    Face,      ///< a flat annulus perpendicular to the axis, radii inner_radius..radius (one side)
    Cylinder,  ///< the curved side of a cylinder, `radius`, `length` along the axis
    Cone,      ///< the curved side of a cone, base `radius`, `length` along the axis
    Sphere,    ///< a whole sphere of `radius`
  };
  Kind kind = Kind::Face;
  double radius = 0.0;        ///< m
  double inner_radius = 0.0;  ///< m, Face only
  double length = 0.0;        ///< m, Cylinder and Cone
};

/// The surfaces of `parts` (SPEC section 10's solids), each part as if alone in the air: a
/// cylinder's two faces and side, a tube's two annular faces and outer side, a cone's base and
/// side, a sphere. Where parts touch or shield each other the estimate counts both (docs/table.md).
std::vector<AirSurface> air_surfaces(const std::vector<SolidPart>& parts);

/// The surfaces of a body known only by its moments: both faces of the thin disc with its mass
/// and C (radius sqrt(2 C / m)).
std::vector<AirSurface> equivalent_disc(const Body& body);

/// N m, >= 0: the torque the air exerts against a surface spinning at |spin| (rad/s) about its
/// axis, from the published laws (docs/table.md): a face, von Karman's laminar boundary layer
/// with Cochran's coefficient (a whole disc's two faces: C_M = 3.87 Re^-1/2, M = C_M rho w^2 R^5 / 2,
/// Re = w R^2 / nu) below Re = 3e5 and von Karman's turbulent law (C_M = 0.146 Re^-1/5) above;
/// a cylinder's side, the exact laminar flow about a spinning cylinder (4 pi mu R^2 L w); a
/// cone's side, the face's law with w sin(alpha) in the boundary layer (Wu 1959; alpha the
/// half-angle); a sphere, Sawatzki's C_M = 6.45 Re^-1/2 + 32.1 Re^-1 (Stokes' 8 pi mu R^3 w
/// below Re of about 10).
double air_torque(const AirSurface& surface, const Air& air, double spin);

/// N m: the sum of air_torque() over `surfaces`.
double air_torque(const std::vector<AirSurface>& surfaces, const Air& air, double spin);

}  // namespace heavytop

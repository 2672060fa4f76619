#pragma once
/// \file
/// A body from its parts (SPEC section 10): the mass properties of solids of revolution about
/// the spin axis (closed forms, derived in docs/mass-properties.md) and of closed triangle
/// meshes (the divergence theorem: Eberly's polyhedral mass properties), summed into one body.
/// Every quantity is in the body frame x, y, z with origin at the fixed point O, SI units.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "heavytop/body.hpp"

namespace heavytop {

/// What a rigid body's dynamics needs of its matter: its mass, its centre of mass and its
/// inertia tensor about O, all in body axes. The general body (SPEC section 11); body_of()
/// gives the Body of the axisymmetric-principal case.
struct MassProperties {
  double mass = 0.0;                                   ///< kg
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();    ///< m, centre of mass in body axes from O
  /// kg m^2, inertia tensor about O in body axes: [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]]
  /// with Ixy = integral of x y dm (SPEC section 11's sign).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();

  /// The union of two bodies (overlaps counted twice): masses, first moments and tensors add.
  MassProperties& operator+=(const MassProperties& other);
};

/// The shapes of SPEC section 10's solid parts, each a solid of revolution about body z.
enum class PartShape { Cylinder, Tube, Cone, Sphere };

/// "cylinder", "tube", "cone", "sphere".
const char* name(PartShape shape) noexcept;
/// The shape named `text`, nullopt for any other text.
std::optional<PartShape> part_shape_from_name(const std::string& text) noexcept;

/// A solid of revolution on the spin axis z, placed by its lowest point (SPEC section 10).
struct SolidPart {
  PartShape shape = PartShape::Cylinder;
  double radius = 0.0;        ///< m, > 0 (tube: the outer radius)
  double inner_radius = 0.0;  ///< m, tube only: 0 <= inner_radius < radius
  double height = 0.0;        ///< m, > 0 (cylinder, tube, cone; a sphere's is 2 radius)
  double z0 = 0.0;            ///< m, height of the lowest point above O along z (may be < 0)
  bool apex_up = false;       ///< cone only: false, the tip at z0 (a top's point); true, the base at z0
  std::optional<double> density;  ///< kg/m^3, > 0; exactly one of density and mass
  std::optional<double> mass;     ///< kg, > 0
};

/// Throws InvalidInput("<key>.<field>", rule) for the first rule `part` breaks (a radius or
/// height not finite and > 0, an inner radius not in [0, radius), z0 not finite, both or
/// neither of density and mass, a density or mass not finite and > 0). `key` names the part,
/// e.g. "body.part[0]".
void validate(const SolidPart& part, const std::string& key);

/// rad, the smallest tilt in (0, pi] at which a point of one of `parts` goes below the table
/// that the body stands on with its tip (a sphere of radius tip_radius about O, or a ring of
/// radius rim_radius about the axis thickened by tip_radius; SPEC section 16): where the tip stops
/// being the lowest point and the body, on a table, has fallen over onto that part. A part's
/// lowest point at tilt theta is that of its outline's rings (z, radius):
/// z cos(theta) - radius sin(theta) (a sphere's centre z_c: z_c cos(theta) - radius), O being
/// tip_radius + rim_radius sin(theta) above the table. Found on a scan of 4096 tilts, then by
/// bisection to 1e-12 rad; a part reaching the table counts below 1e-9 of the body's size (the
/// tip's own part touches the table at 0). nullopt when no part does before pi. Validates first.
std::optional<double> touch_tilt(const std::vector<SolidPart>& parts, double tip_radius, double rim_radius);

/// The part's mass properties about O (closed forms, docs/mass-properties.md). Validates first.
MassProperties mass_properties(const SolidPart& part, const std::string& key);

/// A closed triangulated surface: vertices (m, body axes) and triangles as vertex indices,
/// counter-clockwise seen from outside (outward normals by the right-hand rule).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// What is wrong with a mesh as the surface of a solid: counted over undirected edges after
/// merging vertices at identical positions (an STL file repeats every vertex per triangle).
struct MeshDefects {
  std::size_t open_edges = 0;          ///< edges on one triangle only (a hole in the surface)
  std::size_t misoriented_edges = 0;   ///< edges two triangles traverse the same way (a flipped triangle)
  std::size_t nonmanifold_edges = 0;   ///< edges on more than two triangles
  std::size_t degenerate_triangles = 0;///< triangles with a repeated vertex, or an index out of range
  bool ok() const noexcept {
    return open_edges == 0 && misoriented_edges == 0 && nonmanifold_edges == 0 && degenerate_triangles == 0;
  }
};

/// The defects of `mesh` (none for a closed, consistently oriented 2-manifold surface).
MeshDefects mesh_defects(const TriangleMesh& mesh);

/// Mass properties of the solid `mesh` bounds, of uniform density (kg/m^3) or of total mass
/// (kg) (exactly one given): the volume integrals by the divergence theorem, exact for the
/// polyhedron (Eberly, "Polyhedral Mass Properties (Revisited)", 2003). A surface oriented
/// inwards throughout is accepted (its signed volume is negative; the result is the same).
/// Throws InvalidInput naming `key` ("body.part[2] (top.stl)") when the mesh has defects (how
/// many open edges, misoriented edges...), is empty, or encloses no volume.
MassProperties mass_properties(const TriangleMesh& mesh, std::optional<double> density, std::optional<double> mass,
                               const std::string& key);

/// The body made of parts, as SPEC section 10's `heavytop body` reports it.
struct BodyAssembly {
  MassProperties total;   ///< the sum of the parts, about O
  double A = 0.0;         ///< kg m^2, inertia about body x through O (the tensor's xx)
  double B = 0.0;         ///< kg m^2, about body y (yy)
  double C = 0.0;         ///< kg m^2, about body z (zz)
  double Ixy = 0.0, Ixz = 0.0, Iyz = 0.0;  ///< kg m^2, products of inertia about O (0 below the threshold)
  double offset_x = 0.0, offset_y = 0.0;   ///< m, centre of mass off the z axis (0 below the threshold)
  double length = 0.0;    ///< m, R: the centre of mass's z
  /// rad, angle between body z and the principal axis of the tensor about O nearest to it
  /// (0 when the products vanish).
  double principal_tilt = 0.0;
  /// The part (index) that contributes most to the products or the offset; meaningful when general().
  std::size_t main_part = 0;
  /// True when z is not a principal axis through O or the centre of mass is off it (SPEC 10).
  bool general() const noexcept { return Ixy != 0.0 || Ixz != 0.0 || Iyz != 0.0 || offset_x != 0.0 || offset_y != 0.0; }
};

/// Relative size below which offsets (to the radius of gyration sqrt(trace / (2 m))) and
/// products of inertia (to the trace of the tensor) count as zero (SPEC section 10).
inline constexpr double kGeneralBodyThreshold = 1e-9;

/// Sums the parts (each part's mass properties about O, in order) and reads off A, B, C, the
/// products and the offset, zeroing those below kGeneralBodyThreshold of the body's size.
/// Throws InvalidInput("body.part", ...) for no parts.
BodyAssembly assemble(const std::vector<MassProperties>& parts);

/// The Body (A, B, C, mass, length; `gravity` m/s^2) of an axisymmetric-principal assembly.
/// Throws InvalidInput naming the main part ("body.part[i]" + `part_names[i]`) and the size of
/// the products or the offset when the assembly is general: only the nonlinear model integrates
/// the general body (SPEC section 11, general_body.hpp; Body::general).
Body body_of(const BodyAssembly& assembly, double gravity, const std::vector<std::string>& part_names);

}  // namespace heavytop

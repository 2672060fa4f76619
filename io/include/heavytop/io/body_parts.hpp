#pragma once
/// \file
/// The body a configuration describes (SPEC sections 1, 10, 11) as one BodyAssembly: from its
/// [[body.part]] list (meshes read from their files) or from its A, B, C, mass, length and
/// the general body's offsets and products.

#include <map>
#include <string>
#include <vector>

#include "heavytop/io/config.hpp"
#include "heavytop/mass_properties.hpp"

namespace heavytop::io {

/// An assembled body and the names messages give its parts ("body.part[0] (cone)").
struct AssembledBody {
  BodyAssembly assembly;
  std::vector<std::string> names;          ///< one per part; empty for a body given by its moments
  std::vector<MassProperties> parts;       ///< each part's own mass properties about O
};

/// The parts' mass properties about O (each mesh read with read_mesh()), summed. Throws
/// InvalidInput naming the part and the key ("body.part[0].radius (cone)", "body.part[1]
/// (top.stl)") for the first bad part.
AssembledBody assemble_parts(const std::vector<PartSpec>& parts);

/// rad, where another of the parts first reaches the table (touch_tilt(), mass_properties.hpp)
/// for `body`'s tip and rim; nullopt for no parts or a mesh among them (its outline is not a
/// solid of revolution's).
std::optional<double> touch_tilt(const std::vector<PartSpec>& parts, const Body& body);

/// The same for a body given by its moments about O (A, B, C, mass, length) and SPEC section
/// 11's keys ("body.Ixy" ..., default 0): centre (offset_x, offset_y, length), the tensor
/// [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]].
AssembledBody assemble_moments(const Body& body, const std::map<std::string, double>& general);

/// kg and m: a body heavier, or with a radius of gyration about O (or |length|) larger, is
/// implausible for a hand-held top, the likely sign of sizes typed in mm as m.
inline constexpr double kPlausibleTopMass = 100.0;
inline constexpr double kPlausibleTopSize = 10.0;

/// One warning line (ending in a newline) naming what is implausible about `body` for a
/// hand-held top (kPlausibleTopMass, kPlausibleTopSize) and the likely unit slip; "" for a
/// plausible body. Not an error: a flywheel or a scaled body may be meant.
std::string implausible_size_warning(const Body& body);

/// `base` (its gravity and damping kept) with the assembly's moments, mass and length and its
/// general part (SPEC section 11) as they are, about the body axes the parts are given in: the
/// general body `simulate --model nonlinear` integrates (body_of() makes the ordinary body).
Body as_given(const BodyAssembly& assembly, Body base = {});

}  // namespace heavytop::io

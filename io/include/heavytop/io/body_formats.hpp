#pragma once
/// \file
/// The text and JSON of `heavytop body` (SPEC section 10) and `heavytop precession` (steady
/// precessions and permanent rotations at a tilt): one place for each, as io/formats.hpp.

#include <optional>
#include <string>
#include <vector>

#include "heavytop/io/body_parts.hpp"
#include "heavytop/precession.hpp"

namespace heavytop::io {

/// `heavytop body --format json`: {"A", "B", "C", "mass", "length", "gravity", "products":
/// {"xy", "xz", "yz"}, "offset": {"x", "y"}, "principal_axis_tilt" (rad), "general" (bool),
/// "parts": [{"name", "mass", "centre_of_mass": [x, y, z], "inertia": 3x3}]} (kg, m, kg m^2
/// about O in body axes); products and offset below SPEC's threshold are 0.
std::string body_json(const AssembledBody& body, double gravity);
/// What `heavytop body` says of the spin the body needs to stand upright: the critical spin of
/// the linearized model without damping (lifetime's, spin_decay()), for a body the models take.
struct UprightSpin {
  std::optional<double> critical;  ///< rad/s; 0: upright at any spin; nullopt: at no spin
};
/// The same for people: the parts, the body, the minimum spin in rad/s and rpm when `upright`
/// is given, whether the models accept it, and the body as a [body] section of a configuration.
std::string body_text(const AssembledBody& body, double gravity, const std::optional<UprightSpin>& upright = std::nullopt);

/// `heavytop precession --format json`: {"body", "tilt", "spin", "steady_precession": {"slow",
/// "fast" (each {"rate", "period", "nutation_frequency", "state"} or null), "min_spin",
/// "slow_limit", "fast_limit"} or null (A != B), "permanent_rotations": [{"plane" ("x-z" |
/// "y-z"), "rate", "period", "stable", "eigenvalues" [[re, im]...], "state"}]}; rad, rad/s, s,
/// the states as SPEC's [motion] keys.
std::string precession_json(const Body& body, double tilt, double spin, const PrecessionAnalysis* steady,
                            const std::vector<PermanentRotation>& rotations);
/// The same for people, spins in rad/s and rpm, each state as a [motion] section.
std::string precession_text(const Body& body, double tilt, double spin, const PrecessionAnalysis* steady,
                            const std::vector<PermanentRotation>& rotations);

}  // namespace heavytop::io

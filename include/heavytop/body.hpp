#pragma once
/// \file
/// The body: the immutable model every algorithm takes by `const Body&`.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "heavytop/damping.hpp"

namespace heavytop {

/// Text from the user (a path, a key, a field of a file) as it goes into a one-line message:
/// control characters shown escaped (\n, \x01); idempotent.
std::string printable(std::string_view text);

/// Bad user input. Names the offending key (as spelled in the configuration file,
/// e.g. "body.mass") and the rule it breaks; the CLI prints it on one line and exits 2. Both are
/// kept printable() (a key or a value from a file may hold a newline or an escape sequence), so
/// the message is one line whatever text went into it.
class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string key, std::string rule);
  const std::string& key() const noexcept { return key_; }
  const std::string& rule() const noexcept { return rule_; }

 private:
  std::string key_;
  std::string rule_;
};

/// The general body's terms (SPEC section 11), in the body axes x, y, z of Body (which are then
/// not principal): products of inertia about O, the inertia tensor being
/// [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]], and the centre of mass's x and y, the
/// centre of mass being (offset_x, offset_y, length). All zero (the default): the ordinary body.
/// Only the nonlinear model integrates a nonzero one (general_body.hpp); every other analysis
/// refuses it (refuse_general()).
struct GeneralInertia {
  double Ixy = 0.0;       ///< kg m^2, integral of x y dm about O
  double Ixz = 0.0;       ///< kg m^2, integral of x z dm about O
  double Iyz = 0.0;       ///< kg m^2, integral of y z dm about O
  double offset_x = 0.0;  ///< m, the centre of mass's x in body axes
  double offset_y = 0.0;  ///< m, the centre of mass's y in body axes

  /// True if every term is exactly zero (the ordinary body of SPEC section 1).
  bool is_zero() const noexcept {
    return Ixy == 0.0 && Ixz == 0.0 && Iyz == 0.0 && offset_x == 0.0 && offset_y == 0.0;
  }
};

/// A rigid body turning about a fixed point O in uniform gravity (SPEC section 1).
/// Body frame: principal axes x, y, z through O, z the spin (symmetry) axis.
struct Body {
  double A = 0.0;        ///< kg m^2, principal moment of inertia about body x through O
  double B = 0.0;        ///< kg m^2, principal moment of inertia about body y through O
  double C = 0.0;        ///< kg m^2, principal moment of inertia about body z (spin axis) through O
  double mass = 0.0;     ///< kg, m
  double gravity = 9.81; ///< m/s^2, g (>= 0), acting along -zeta of the fixed frame
  double length = 0.0;   ///< m, R: signed distance from O to the centre of mass along body +z
                         ///< (> 0: a top on its tip, < 0: a hanging body)
  Damping damping;       ///< the torques of SPEC section 6 (default none: conservative)
  /// The general body's products and offsets (SPEC section 11; default zero: x, y, z are
  /// principal axes and the centre of mass is on z). Nonzero, A, B, C are the tensor's
  /// diagonal about body axes that are not principal.
  GeneralInertia general;
  /// m, >= 0: the radius of the sphere centred at O on the axis with which the body touches a
  /// table (SPEC section 16; 0: a sharp point at O). Only its drawing on a pivot.
  double tip_radius = 0.0;
  /// m, >= 0: or the radius of the ring about the axis in the plane z = 0 through O (thickened
  /// by tip_radius: a coin, a disc); 0: the sphere above.
  double rim_radius = 0.0;
  /// rad, the tilt at which another part of the body first reaches the table the tip stands on
  /// (SPEC section 16: from the parts, touch_tilt() in mass_properties.hpp): on a table "falls"
  /// means that, not AnswerOptions::max_tilt. nullopt: not known (a body given by its moments,
  /// or one with a mesh part), or no part ever reaches the table before upside down.
  std::optional<double> touch_tilt;

  /// N m, the gravitational moment m g R (signed like R).
  double mgR() const noexcept { return mass * gravity * length; }
};

/// |A - B| / max(A, B) at or below which a body counts as symmetric (dimensionless); the same
/// slack validate() allows the triangle inequalities, so rounding in user-computed moments
/// (0.1 + 0.2 against 0.3) neither refuses a flat body nor makes a symmetric one asymmetric.
inline constexpr double kSymmetryTolerance = 1e-12;

/// True if A and B agree to kSymmetryTolerance relative: a dynamically symmetric body
/// (the Lagrange top), for which the paper's model (4) is the exact linearisation.
bool is_symmetric(const Body& body) noexcept;

/// True if A + B = C to kSymmetryTolerance relative: all the mass lies in the plane z = 0, so
/// a centre of mass off O (length != 0) makes the body an idealisation (erratum E0).
bool is_planar(const Body& body) noexcept;

/// s, the time scale of gravity, sqrt(min(A, B) / |m g R|) (a fall's e-folding time at zero
/// spin); +inf when m g R = 0.
double gravity_time(const Body& body) noexcept;

/// Throws InvalidInput for the first rule of SPEC section 1 that `body` breaks:
/// A, B, C, mass finite and > 0; gravity finite and >= 0; length finite;
/// the triangle inequalities A + B >= C, B + C >= A, C + A >= B; then validate(damping); then
/// SPEC section 11 for `general`: each term finite, the tensor positive definite and its
/// principal moments satisfying the triangle inequalities (key: the first nonzero product).
void validate(const Body& body);

/// False when the body cannot exist as given (SPEC section 1): its central moments of inertia
/// (about the centre of mass) break a triangle inequality, A + B - C < 2 m R^2 for the body of
/// SPEC section 1 (a scaled input such as m = g = R = 1, often), the principal central
/// moments' for the general body of section 11; to 1e-9 of the trace (a flat disc on the axis
/// is exactly on the edge). Callers warn and go on.
bool is_realizable(const Body& body);

/// True if the body has a nonzero term of SPEC section 11 (body.general not zero).
bool is_general(const Body& body) noexcept;

/// The general body's key ("body.offset_x", "body.offset_y", "body.Ixy", "body.Ixz",
/// "body.Iyz") of its first nonzero term, or nullptr for an ordinary body.
const char* first_general_key(const Body& body) noexcept;

/// Throws InvalidInput naming the first nonzero key of SPEC section 11 (e.g. "body.Ixy") when
/// `body` is general: `what` (e.g. "the linear models") covers only the ordinary body.
void refuse_general(const Body& body, const char* what);

/// The built-in example: a realistic toy top (SI units), spun well above its critical spin.
Body example_toy_top();

}  // namespace heavytop

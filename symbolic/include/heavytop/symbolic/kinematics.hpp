#pragma once
/// \file
/// Small rotations and angular velocities, truncated at a chosen order of smallness
/// (the paper's sections 1, 2 and 4).
///
/// Orders are counted with a bookkeeping parameter eps: every small quantity x (the angles,
/// their rates and accelerations) becomes eps x, the expression is expanded as a series in
/// eps, terms above eps^order are dropped and eps is set back to 1. The spin omega0 is not
/// small. The truncations are thus computed, never typed in.

#include <string_view>
#include <optional>
#include <vector>

#include <ginac/ginac.h>

namespace heavytop::symbolic {

/// Order of the two tilting rotations (the paper's section 4).
enum class Sequence {
  PhiTheta,  ///< phi about the fixed xi axis, then theta about the turned eta axis: A^(1) = A2 A1
  ThetaPhi,  ///< theta about the fixed eta axis, then phi about the turned x axis: A^(2) = A1 A2
};

/// Both sequences, phi-theta first.
inline constexpr Sequence kSequences[] = {Sequence::PhiTheta, Sequence::ThetaPhi};

/// CLI name: "phi-theta" or "theta-phi".
std::string_view name(Sequence sequence);

/// The sequence called `name` on the command line, or nullopt.
std::optional<Sequence> sequence_from_name(std::string_view name);

/// The terms of `e` of order <= `order` in the small quantities symbols().small().
GiNaC::ex truncate(const GiNaC::ex& e, int order);

/// truncate() applied to every entry.
GiNaC::matrix truncate(const GiNaC::matrix& a, int order);

/// How a generalised coordinate moves: its rate and acceleration (symbols, or a constant rate
/// with acceleration 0).
struct Coordinate {
  GiNaC::symbol q;         ///< the coordinate
  GiNaC::ex rate;          ///< dq/dt
  GiNaC::ex acceleration;  ///< d^2q/dt^2
};

/// The paper's coordinates phi, theta, psi with their symbolic rates and accelerations.
std::vector<Coordinate> coordinates();

/// d e / dt along `coords` (chain rule; the parameters are constant).
GiNaC::ex time_derivative(const GiNaC::ex& e, const std::vector<Coordinate>& coords);

/// time_derivative() applied to every entry.
GiNaC::matrix time_derivative(const GiNaC::matrix& a, const std::vector<Coordinate>& coords);

/// The paper's A1(phi), A2(theta), A3(psi) (transition matrices: rows are i, j, k in l, m, n),
/// their products and commutator, each truncated at `order`.
struct Rotations {
  int order = 1;            ///< 1 or 2
  GiNaC::matrix A1;         ///< rotation by phi about O-xi
  GiNaC::matrix A2;         ///< rotation by theta about O-eta
  GiNaC::matrix A3;         ///< rotation by psi about O-zeta
  GiNaC::matrix A1A2;       ///< theta first, then phi (the paper's A^(2))
  GiNaC::matrix A2A1;       ///< phi first, then theta (the paper's A^(1))
  GiNaC::matrix commutator; ///< A1A2 - A2A1: zero at order 1, matrix (1)'s phi theta terms at 2
};

/// The small-rotation matrices of the paper's section 1 at `order` (1 or 2).
Rotations rotations(int order);

/// Exact rotation of the axis frame Oxyz: its columns are i, j, k in fixed components (l, m, n),
/// i.e. the transpose of the paper's transition matrix A3 A2 A1 (PhiTheta) or A3 A1 A2 (ThetaPhi).
GiNaC::matrix frame_rotation(Sequence sequence);

/// The 3-vector w with S = [w]x for a skew-symmetric S (entries S(2,1), S(0,2), S(1,0)).
GiNaC::matrix vee(const GiNaC::matrix& skew);

/// a x b for 3x1 matrices.
GiNaC::matrix cross(const GiNaC::matrix& a, const GiNaC::matrix& b);

/// Angular velocities of the paper's section 2 and 4 for a sequence, truncated at an order.
struct AngularVelocities {
  Sequence sequence = Sequence::PhiTheta;  ///< the rotation sequence
  int order = 1;                           ///< 1 or 2
  GiNaC::matrix frame_axes;   ///< axis frame (w1), components on i, j, k
  GiNaC::matrix frame_fixed;  ///< axis frame (w1), components on l, m, n
  GiNaC::matrix body_axes;    ///< body, w1 + omega0 k, on i, j, k: the paper's (2)
  GiNaC::matrix body_fixed;   ///< body, on l, m, n: the paper's (3)
};

/// Angular velocities of the axis frame (from R^T R' and R' R^T) and of the body spinning at
/// omega0 relative to it, for `sequence` at `order` (1 or 2).
AngularVelocities angular_velocities(Sequence sequence, int order);

}  // namespace heavytop::symbolic

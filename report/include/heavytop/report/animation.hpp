#pragma once
/// \file
/// What the report's 3D view needs beyond the trajectory's columns: the body's full attitude.

#include <array>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::report {

/// The spin angle psi(t_i) (rad, unwrapped, psi(0) = 0) of the nonlinear motion `nonlinear`
/// (simulate_nonlinear's columns, with "axial_momentum" = C w3): the body's attitude
/// (body-to-fixed) is Q(phi, theta) Rz(psi), Q the axis frame of SPEC section 2, so that
/// psi = 0 at t = 0 as SPEC says. Since R = Q Rz(psi) turns at Omega_Q + psi' k and
/// Omega_Q . k = -theta' sin(phi), psi' = w3 + theta' sin(phi), integrated here by the
/// trapezoid rule over the samples (second order in the sample spacing; test_report_attitude
/// measures the error). Throws InvalidInput ("trajectory") without the axial_momentum column.
std::vector<double> spin_angles(const Body& body, const Trajectory& nonlinear);

/// The body as the 3D view draws it: the uniform solid ellipsoid with the body's mass and its
/// central moments (A - m R^2, B - m R^2, C about the centre of mass at R on z), so that
/// A = m (b^2 + c^2) / 5 + m R^2, B = m (a^2 + c^2) / 5 + m R^2, C = m (a^2 + b^2) / 5.
struct EquivalentEllipsoid {
  std::array<double, 3> semi_axes{};  ///< m, along the body axes x, y, z
  double centre = 0.0;                ///< m, its centre on body z (= R)
  /// Empty, or why a semi-axis was raised to kMinThickness of the largest (a flat body, whose
  /// ellipsoid is a disc, or moments no real body has): the drawing is then not to scale there.
  std::string note;
};
/// The smallest semi-axis drawn, as a fraction of the largest.
inline constexpr double kMinThickness = 0.04;
EquivalentEllipsoid equivalent_ellipsoid(const Body& body);

}  // namespace heavytop::report

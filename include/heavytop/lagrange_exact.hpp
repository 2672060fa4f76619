#pragma once
/// \file
/// `lagrange-exact` (SPEC section 3): the nonlinear motion of a dynamically symmetric body
/// (A = B) in closed form, the reference the integrators are measured against
/// (docs/integrators.md).
///
/// With u = cos(tilt) = k_zeta, the energy E, the vertical momentum L_zeta and the axial
/// momentum L_3 = C w3 give u'^2 = f(u), the Lagrange top's cubic
///     f(u) = (1 - u^2)(alpha - beta u) - (a - b u)^2,
///     a = L_zeta / A,  b = L_3 / A,  alpha = (2 E - C w3^2) / A,  beta = 2 m g R / A.
/// Between two roots u_a, u_b of f: u = u_a + (u_b - u_a) sn^2(tau, k), tau = lambda t + tau0.
/// The azimuth of the axis (Euler angle phi of z-x-z Euler angles) and the spin angle psi are
/// elliptic integrals of the third kind in tau. A sample at time t reduces tau modulo the
/// nutation period and adds whole-period increments of phi and psi, so its cost does not
/// depend on t. All the degenerate motions are handled: constant tilt (the sleeping top,
/// steady precession), a tilt that passes through the upward or downward vertical
/// (L_zeta = +-L_3), the hanging body (m g R < 0) and m g R = 0 (the free symmetric body,
/// where f is a quadratic).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

namespace detail {
struct LagrangeEvaluator;  // the closed form's constants, private to the library
}

/// Throws InvalidInput for a body validate() refuses, and InvalidInput("body.B", ...) unless
/// is_symmetric(body). The transverse moment used is (A + B)/2.
void validate_symmetric(const Body& body);

/// The precomputed closed-form motion of one symmetric body from one state. Build it with
/// lagrange_top(); every member is read-only data for callers (units as noted), the
/// `evaluator` is the evaluation's own and not part of the interface.
struct LagrangeTop {
  double A = 0.0;    ///< kg m^2, transverse moment of inertia about O ((A + B)/2 of the body)
  double C = 0.0;    ///< kg m^2, axial moment of inertia about O
  double mgR = 0.0;  ///< N m, m g R
  double w3 = 0.0;   ///< rad/s, body-axis component of the angular velocity (constant)
  double energy = 0.0;             ///< J, E = T + m g R k_zeta
  double vertical_momentum = 0.0;  ///< kg m^2/s, L_zeta
  double axial_momentum = 0.0;     ///< kg m^2/s, L_3 = C w3

  double u_min = 1.0;  ///< cos of the largest tilt: the lower motion root of f (in [-1, 1])
  double u_max = 1.0;  ///< cos of the smallest tilt: the upper motion root of f (in [-1, 1])
  /// The third root of f (dimensionless; >= 1 for m g R > 0, <= -1 for m g R < 0; +inf when
  /// m g R = 0, where f is a quadratic).
  double u_third = 0.0;

  bool constant_tilt = false;      ///< u_min == u_max: sleeping top, steady precession, rest
  /// The azimuth and spin angle are summed as Fourier series (checked against the elliptic
  /// integrals at setup to 1e-14 rad) rather than evaluated as elliptic integrals per sample.
  bool fourier_series = false;
  bool through_vertical = false;   ///< the axis passes through the upward vertical (u_max = 1)
  bool through_downward = false;   ///< the axis passes through the downward vertical (u_min = -1)
  /// s, the nutation period (time between two equal maxima of the tilt); +inf when the
  /// tilt is constant or approaches an unstable state asymptotically (k = 1).
  double nutation_period = 0.0;
  /// rad, increase of the azimuth of the axis about the upward vertical over one nutation
  /// period (0 when the period is infinite). For the exact motion k(t + T) = R_zeta(this) k(t).
  double precession_per_period = 0.0;
  /// rad, increase of the spin angle psi (z-x-z Euler angles) over one nutation period.
  double spin_per_period = 0.0;

  /// The number of terms of those series (0 when fourier_series is false).
  int series_terms = 0;

  /// The evaluator's precomputed constants (src/models/lagrange_evaluator.hpp; not part of the
  /// interface, shared by copies, set by lagrange_top()).
  std::shared_ptr<const detail::LagrangeEvaluator> evaluator;
};

/// How lagrange_top() prepares the evaluation.
struct LagrangeExactOptions {
  /// Sum the periodic parts of the azimuth and spin angle as Fourier series (precomputed from
  /// the elliptic integrals; a sample then costs half as much) wherever at most 60 terms reach
  /// rounding level and agree with the integrals at setup; false: elliptic integrals always.
  bool fourier_series = true;
};

/// The closed-form motion of `body` (symmetric, see validate_symmetric) from the user's
/// state, mapped as SPEC section 2 says (initial_rigid_body_state). Throws InvalidInput.
LagrangeTop lagrange_top(const Body& body, const InitialState& initial,
                         const LagrangeExactOptions& options = {});

/// The same from any rigid-body state (attitude body-to-fixed, angular velocity in body axes,
/// both finite; the attitude a rotation). Throws InvalidInput ("state") otherwise.
LagrangeTop lagrange_top(const Body& body, const RigidBodyState& state,
                         const LagrangeExactOptions& options = {});

/// The tilt bounds of the motion: the two roots of the cubic f between which u moves.
struct NutationBounds {
  double min_tilt = 0.0;  ///< rad, smallest angle of the axis from the upward vertical
  double max_tilt = 0.0;  ///< rad, largest
  double u_max = 1.0;     ///< cos(min_tilt), a root of f
  double u_min = 1.0;     ///< cos(max_tilt), a root of f
};
NutationBounds nutation_bounds(const LagrangeTop& top);

/// s, the nutation period (+inf if the tilt is constant or the motion is asymptotic).
double nutation_period(const LagrangeTop& top);

/// The spin axis k (unit, fixed frame) and its rate k' = w x k (1/s) at time t (s).
struct AxisMotion {
  Eigen::Vector3d k;
  Eigen::Vector3d k_rate;
};
AxisMotion lagrange_axis(const LagrangeTop& top, double t);

/// theta, phi and their rates (SPEC section 2) at time t (s): axis_angles(lagrange_axis(t)).
AxisAngles lagrange_axis_angles(const LagrangeTop& top, double t);

/// The full rigid-body state at time t (s): attitude (body-to-fixed) and angular velocity
/// (rad/s, body axes), for comparing integrators of the whole body.
RigidBodyState lagrange_rigid_body_state(const LagrangeTop& top, double t);

/// The `lagrange-exact` model: theta, phi, theta_rate, phi_rate at `times` (s; any finite
/// values, any order; InvalidInput key "times" otherwise), from `initial` mapped as SPEC
/// section 2 says. Throws InvalidInput for a bad or non-symmetric body (key "body.B") or state.
Trajectory simulate_lagrange_exact(const Body& body, const InitialState& initial,
                                   const std::vector<double>& times);

}  // namespace heavytop

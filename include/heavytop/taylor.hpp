#pragma once
/// \file
/// The `nonlinear` model integrated by a Taylor-series method (docs/integrators.md, "Taylor
/// and DOP853"; Jorba & Zou 2005, Biscani & Izzo 2021 (heyoka), Barrio et al. 2005 (TIDES)).
///
/// The equations of the rigid body are a quadratic polynomial in (quaternion, angular
/// velocity), so the Taylor coefficients of the solution to any order follow from Cauchy
/// products of the lower ones (automatic differentiation); order n costs n + 1 multiply-adds
/// per product term. The order comes from the tolerance (taylor_order(): Jorba-Zou's rule with
/// a larger constant, measured), the step from the last two coefficients (the h at which
/// |x_i[n]| h^n = atol + rtol |x_i| for n = p - 1, p), the dense output is the series itself,
/// and events are roots of the series of the event function on [0, h].
///
/// Variables, chosen by the body (reported in TaylorSummary::variables):
///  - A == B: the spin-factored state of nonlinear.hpp (quaternion p of the non-spinning
///    frame, transverse angular velocity v in it; w3 constant). Nothing turns at the spin.
///  - A != B: the plain state of rigid_body.hpp (quaternion q, body-axes w).
///  - the general body (SPEC section 11): the same plain state with general_body.hpp's
///    equations (full inertia tensor, centre of mass off the axis) and its conserved quantities.
///  - a damped body (SPEC section 6): the spin-factored (A == B, w3 no longer constant) or the
///    plain state (A != B), and the integrals of what the torques take away (dopri5's: the work, the vertical and the axial momentum lost). Within
///    a mode of dry friction (sliding either way, stuck, driven) the torques are polynomial;
///    a change of mode (the spin reaching 0, the gyroscopic torque outgrowing tau0) is a root
///    of the step's series, where the step ends, as in simulate_nonlinear().
/// Body frame, units and the output columns are simulate_nonlinear()'s (with damping its
/// dissipated_work, vertical_momentum_loss, axial_momentum_loss and, driven, motor_torque).

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The highest order the Taylor integrator uses (dimensionless).
inline constexpr int kTaylorMaxOrder = 24;

/// Which variables the Taylor integrator used.
enum class TaylorVariables {
  SpinFactored,  ///< A == B: (p, v1, v2), w3 constant
  Plain,         ///< A != B: (q, w1, w2, w3)
  General,       ///< the general body (SPEC section 11, general_body.hpp): (q, w1, w2, w3), full I, c anywhere
};

/// The variables the Taylor integrator takes for `body`: General if is_general(body), else
/// SpinFactored for A == B, else Plain.
TaylorVariables taylor_variables(const Body& body);

/// The Taylor order for the tolerances and variables (dimensionless): ceil(-k ln(eps) + 1),
/// eps = min(rtol, atol), k = 1 for the spin-factored variables and 0.75 for the plain ones
/// (Jorba-Zou's optimum for a fixed radius of convergence is k = 1/2; these were measured
/// faster at equal error, docs/integrators.md), clamped to [2, kTaylorMaxOrder].
int taylor_order(const Tolerances& options, TaylorVariables variables);

/// What one run of the Taylor integrator did (NonlinearSummary's fields, with
/// rhs_evaluations = steps x order: one pass of the recurrence per order, heyoka's count).
struct TaylorSummary {
  NonlinearSummary work;       ///< steps (no rejections: the step is chosen, not tried), drifts
  int order = 0;               ///< the series' order
  TaylorVariables variables = TaylorVariables::Plain;
  bool damped = false;         ///< the torques of SPEC section 6 were integrated
  std::size_t friction_events = 0;  ///< changes of the dry-friction mode (spin stopped, or freed)
};

/// simulate_nonlinear() by the Taylor method: same columns, same InvalidInput keys ("rtol",
/// "atol", "max_steps", "times"), std::runtime_error (one line, "taylor: ...") on max_steps,
/// a step lost in the rounding of t, or a state that stops being finite.
/// The tolerance is met per step componentwise: |error_i| <~ atol + rtol |x_i|.
Trajectory simulate_taylor(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const Tolerances& options = {}, TaylorSummary* summary = nullptr,
                           const Progress& progress = {});

/// tilt_extremes() by the Taylor method: the tilt extrema are the roots of the series of
/// d(k_zeta)/dt on each step, the threshold crossing (tilt = stop_above, rad) the root of the
/// series of k_zeta - cos(stop_above); both found by Newton's method on the polynomial (kept
/// inside the root's bracket, to 1e-15 of the step), in a step
/// split into 8 pieces to isolate them (two roots in one piece of 1/8 step would be missed).
/// The same contract as tilt_extremes(): when the scan stops early, t_end, t_max and max_tilt
/// are the crossing's (max_tilt == stop_above to rounding). Same keys ("horizon", "max_tilt")
/// and failures as simulate_taylor().
TiltExtremes taylor_tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                                  double stop_above = std::numeric_limits<double>::infinity(),
                                  const Tolerances& options = {}, TaylorSummary* summary = nullptr,
                                  const Progress& progress = {});

}  // namespace heavytop

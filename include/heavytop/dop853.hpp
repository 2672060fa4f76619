#pragma once
/// \file
/// The `nonlinear` model integrated by Dormand & Prince's 8(5,3) Runge-Kutta method with its
/// 7th-order dense output (Hairer, Norsett & Wanner, Solving ODEs I, section II.10: DOP853),
/// error-controlled as in Hairer's code. The robust alternative to the Taylor integrator
/// (taylor.hpp) and its independent check: different variables (always the plain state of
/// rigid_body.hpp: quaternion q body-to-fixed, body-axes w), a different method.
/// Columns, units and frames are simulate_nonlinear()'s.

#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// simulate_nonlinear() by DOP853 on RigidBodySystem: same columns and keys ("rtol", "atol",
/// "max_steps", "times"); std::runtime_error (one line, "dop853: ...") on max_steps, step
/// underflow, 100 consecutive rejections or a state that stops being finite. The summary's
/// rhs_evaluations counts every evaluation (12 per attempt, 3 more per step whose dense
/// output is used).
Trajectory simulate_dop853(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const Tolerances& options = {}, NonlinearSummary* summary = nullptr,
                           const Progress& progress = {});

/// tilt_extremes() (nonlinear.hpp) by DOP853: the tilt's extrema over [0, horizon] (s) located
/// on the dense output at the roots of d(k_zeta)/dt, stopping at the first crossing of
/// `stop_above` (rad; then t_end = t_max is the crossing and max_tilt the tilt there, as in
/// tilt_extremes()). For sweeps with --integrator dop853. Same keys ("horizon", "max_tilt") and
/// failures as simulate_dop853().
TiltExtremes dop853_tilt_extremes(const Body& body, const InitialState& initial, double horizon, double stop_above,
                                  const Tolerances& options = {}, const Progress& progress = {});

}  // namespace heavytop

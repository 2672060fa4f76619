#pragma once
/// \file
/// The `nonlinear` model (SPEC section 3): the full rigid body turning about a fixed point O
/// in uniform gravity, no approximation. It is the truth every approximate model is
/// measured against. docs/nonlinear.md gives the equations, the integrator and its accuracy.
///
/// Body frame: principal axes x, y, z through O, inertia diag(A, B, C), centre of mass at
/// R e3. Euler: I w' + w x I w = m g R (gamma x e3), gamma = R^T e_zeta the vertical in body
/// axes. The attitude is integrated as a unit quaternion with the spin about z factored out
/// (exact change of variables), with an error-controlled Dormand-Prince 5(4) stepper and its
/// dense output (Boost.Odeint).

#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/progress.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The error control and the budget of the adaptive integrators of the nonlinear model
/// (dopri5, dop853, taylor; simulate.hpp's SimulateOptions::adaptive), shared by all three.
/// The defaults keep the angle error of a stable motion below 1e-9 rad over 100 s for every
/// example in examples/ (measured in docs/nonlinear.md, "Accuracy"); in an unstable motion
/// errors grow like the motion does.
struct Tolerances {
  /// Relative tolerance per step (dimensionless), in [1e-15, 1].
  double rtol = 1e-12;
  /// Absolute tolerance per step, > 0: on the attitude quaternion (dimensionless), the
  /// angular velocity (rad/s) and the spin angle (rad) alike.
  double atol = 1e-12;
  /// Largest number of attempted steps (accepted + rejected) before giving up, > 0.
  std::size_t max_steps = 100'000'000;

  /// True if every setting is in range; otherwise false, and `why` (if not null) receives a
  /// one-line "key: rule" message (key "rtol", "atol" or "max_steps").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput (key "rtol", "atol" or "max_steps") unless options.IsValid().
void validate(const Tolerances& options);

/// The former name of Tolerances, for code written against heavytop 0.1.
using NonlinearOptions [[deprecated("heavytop::NonlinearOptions is now heavytop::Tolerances")]] = Tolerances;

/// How far the first integrals drifted over one run, in every integrator's summary: the largest
/// |Q(t) - Q(0)| / scale over every accepted step (every grid point for the splitting), with
/// E_scale = T(0) + |m g R| (J) and L_scale = sqrt(2 max(A, B, C) E_scale) (kg m^2/s); for the
/// general body m g |c| and the largest eigenvalue of its inertia tensor in their place.
struct Drifts {
  double max_relative_energy_drift = 0.0;             ///< of E (J/J)
  double max_relative_vertical_momentum_drift = 0.0;  ///< of L_zeta, over L_scale
  double max_relative_axial_momentum_drift = 0.0;     ///< of C w3, over L_scale (conserved only when A == B)
};

/// What one run of the integrator did (and its Drifts).
struct NonlinearSummary : Drifts {
  std::size_t steps = 0;            ///< accepted steps
  std::size_t rejected_steps = 0;   ///< steps rejected by the error control and retried
  std::size_t rhs_evaluations = 0;  ///< evaluations of the equations of motion
  double final_time = 0.0;          ///< s, end of the last accepted step (>= the last time asked)
  bool symmetric = false;           ///< true if A == B exactly (a cheaper right-hand side was used)
  /// max | |q| - 1 | of the attitude quaternion before its renormalisation at each step end.
  double max_quaternion_norm_error = 0.0;

  /// One line for people: steps, rejections, evaluations, drifts.
  std::string BriefReport() const;
};

/// The first integrals of the motion (each conserved by the exact flow, see below).
struct ConservedQuantities {
  double energy = 0.0;             ///< J, E = 1/2 w.I w + m g R gamma_3 (always conserved)
  double vertical_momentum = 0.0;  ///< kg m^2/s, L_zeta = (I w).gamma (always conserved)
  double axial_momentum = 0.0;     ///< kg m^2/s, C w_3 (conserved only when A == B)
};

/// E, L_zeta and C w3 of `body` in the rigid-body state `x` (attitude body-to-fixed, w in body axes).
ConservedQuantities conserved_quantities(const Body& body, const RigidBodyState& x);

/// The nonlinear motion from `initial` (SPEC section 2 mapping: psi = 0 at t = 0), sampled
/// at `times` (s; finite, >= 0, non-decreasing; InvalidInput key "times" otherwise).
/// Columns theta, phi, theta_rate, phi_rate by the exact formulas of SPEC section 2, then
/// Trajectory::extra columns, in this order: "energy" (J), "vertical_momentum" (kg m^2/s),
/// "axial_momentum" (kg m^2/s, conserved only when A == B), "energy_drift",
/// "vertical_momentum_drift", "axial_momentum_drift" (value minus its value at t = 0).
/// Throws InvalidInput for a bad body, state or options; std::runtime_error (one line) if
/// the integrator cannot meet the tolerance, exceeds max_steps or the state stops being finite.
Trajectory simulate_nonlinear(const Body& body, const InitialState& initial,
                              const std::vector<double>& times,
                              const Tolerances& options = {},
                              NonlinearSummary* summary = nullptr, const Progress& progress = {});

/// The extremes of the tilt acos(k_zeta) (rad, angle of the spin axis from the upward vertical).
struct TiltExtremes {
  double min_tilt = 0.0;   ///< rad, smallest tilt seen
  double t_min = 0.0;      ///< s, when
  double max_tilt = 0.0;   ///< rad, largest tilt seen (at a stop: the tilt at the crossing)
  double t_max = 0.0;      ///< s, when (at a stop: t_end)
  double t_end = 0.0;      ///< s, end of the scan: the horizon, or the first time the tilt
                           ///< passed stop_above (located inside its step)
  bool exceeded = false;   ///< true if the scan stopped early because max_tilt > stop_above
  double spin_at_end = 0.0;  ///< rad/s, w.k at t_end (the integrated spin, damped or not)
};

/// The extremes of the tilt over [0, horizon] (s, finite, >= 0; key "horizon"). Interior
/// extrema are located on the dense output by a root of d(k_zeta)/dt, so they are as exact
/// as the integration. Stops at the first point where the tilt exceeds `stop_above` (rad;
/// not NaN; key "max_tilt"), located inside its step by TOMS 748: then t_end = t_max is that
/// crossing and max_tilt the tilt there (stop_above to the root's tolerance), a lower bound of
/// the largest tilt the motion would reach. Throws like simulate_nonlinear (and what `progress`
/// throws).
TiltExtremes tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                           double stop_above = std::numeric_limits<double>::infinity(),
                           const Tolerances& options = {},
                           NonlinearSummary* summary = nullptr, const Progress& progress = {});

/// rad, the tilt past which a top started at `start_tilt` (rad) has fallen, for the limit
/// `max_tilt` (rad, in (0, pi]) the person gave: a fall is a tilt past max_tilt from below, so a
/// start below it keeps it; a start at or beyond it (Woodhouse's top set off at 60 degrees, with
/// the default 1 rad) would "fall" at t = 0 whatever it does next, so its fall is a tilt past
/// halfway from its start to upside down, (start_tilt + pi) / 2. The answer and lifetime() use
/// it and say so; a sweep, whose map holds every point to one limit, refuses such a start.
inline double fall_tilt(double start_tilt, double max_tilt) {
  return start_tilt < max_tilt ? max_tilt : 0.5 * (start_tilt + std::numbers::pi);
}

/// rad, the largest tilt acos(k_zeta) over [0, horizon] (s), stopping early once it exceeds
/// `stop_above` (rad; the result is then > stop_above). For stability sweeps.
double max_tilt(const Body& body, const InitialState& initial, double horizon, double stop_above,
                const Tolerances& options = {});

}  // namespace heavytop

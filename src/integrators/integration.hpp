#pragma once
// Private to the library: what the integrators of the nonlinear model share: option checking,
// the sample times, the drift monitor's scales and update, the report's drift part, the
// stream of samples and the angle columns (sampling.hpp has the one sample loop and the
// writer of the columns; lagrange_exact.cpp uses push_angles() alone).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop::detail {

// ---- Options ----------------------------------------------------------------------------------

// The first setting out of range, as (key, rule); none if all are in range.
using Violation = std::optional<std::pair<const char*, const char*>>;

// Options::IsValid from the options' first violation.
inline bool is_valid(const Violation& violation, std::string* why) {
  if (violation && why) *why = std::string(violation->first) + ": " + violation->second;
  return !violation;
}

// validate(options) from the options' first violation.
inline void throw_if_invalid(const Violation& violation) {
  if (violation) throw InvalidInput(violation->first, violation->second);
}

// The integrators whose equations hold no torques of SPEC section 6 (taylor, dop853) refuse a
// damped body rather than integrate it as if it were conservative (key "integrator").
inline void refuse_damping(const Body& body, const char* integrator) {
  if (!body.damping.conservative())
    throw InvalidInput("integrator", fmt::format("{} integrates the conservative body only: with damping, friction or "
                                                 "a motor use dopri5 (or auto)", integrator));
}

inline void validate_times(const std::vector<double>& times) {
  double previous = 0.0;
  for (double t : times) {
    if (!std::isfinite(t) || t < previous)
      throw InvalidInput("times", "must be finite, >= 0 and non-decreasing");
    previous = t;
  }
}

// ---- Outcomes ------------------------------------------------------------------------------------

// How a run of an error-controlled integrator fails (heyoka's taylor_outcome): too many steps,
// a step size lost in the rounding of t (the tolerance cannot be met), a state no longer finite.
enum class StepOutcome { MaxSteps, StepUnderflow, NotFinite };

// Throws the one-line failure (RunFailure, with t as how far the run got) of integrator `who` ("nonlinear", "taylor", "dop853") at t (s),
// the one message formatter of every integrator; `max_steps` is the limit passed (MaxSteps).
[[noreturn, gnu::cold]] inline void fail(const char* who, StepOutcome outcome, double t, std::size_t max_steps = 0) {
  switch (outcome) {
    case StepOutcome::MaxSteps:
      throw RunFailure(fmt::format("{}: more than max_steps = {} integration steps before t = {:.6g} s "
                                   "(raise max_steps or loosen rtol/atol)", who, max_steps, t), t);
    case StepOutcome::StepUnderflow:
      throw RunFailure(
          fmt::format("{}: step size underflow at t = {:.6g} s (the tolerance rtol/atol cannot be met)", who, t), t);
    case StepOutcome::NotFinite: break;
  }
  throw RunFailure(fmt::format("{}: the state stopped being finite at t = {:.6g} s", who, t), t);
}

// ---- One step of Odeint's controlled dopri5 (nonlinear.cpp, general_body.cpp) ----------------

// The most rejections in a row before a step is given up as lost in rounding.
inline constexpr int kMaxConsecutiveRejections = 100;

// One accepted step of `controlled` (Odeint's controlled_runge_kutta over dopri5, FSAL) from
// (x_old, dxdt_old) at t into (x, dxdt), t and dt updated as try_step does. Counts attempts
// against max_steps, and evaluations (six per attempt) and rejections into `summary` if set.
// Fails as one line (std::runtime_error): max_steps exceeded, a step size lost in the rounding
// of t or rejected kMaxConsecutiveRejections times running, a state no longer finite.
template <class Controlled, class System, class State>
void controlled_step(Controlled& controlled, System& system, const State& x_old, const State& dxdt_old, double& t,
                     State& x, State& dxdt, double& dt, std::size_t& attempts, std::size_t max_steps,
                     NonlinearSummary* summary) {
  for (int rejections = 0;;) {
    if (attempts >= max_steps) fail("nonlinear", StepOutcome::MaxSteps, t, max_steps);
    // Lost in the rounding of t (or not a number).
    if (!(t + dt > t)) fail("nonlinear", StepOutcome::StepUnderflow, t);
    ++attempts;
    const double t_before = t;
    const auto result = controlled.try_step(system, x_old, dxdt_old, t, x, dxdt, dt);
    if (summary) summary->rhs_evaluations += 6;  // FSAL: six new stages per attempt
    if (result == boost::numeric::odeint::success) {
      if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); }))
        fail("nonlinear", StepOutcome::NotFinite, t_before);
      return;
    }
    if (summary) ++summary->rejected_steps;
    // A long run of rejections: rounding, not the method, limits the error.
    if (++rejections > kMaxConsecutiveRejections) fail("nonlinear", StepOutcome::StepUnderflow, t);
  }
}

// ---- Drift monitor (only when a summary is asked for) ----------------------------------------

struct Scales {
  double energy = 1.0;    // J
  double momentum = 1.0;  // kg m^2/s
};

inline Scales scales_of(const Body& body, const RigidBodyState& x0) {
  const Eigen::Vector3d inertia(body.A, body.B, body.C);
  const double kinetic = 0.5 * x0.omega.dot(inertia.cwiseProduct(x0.omega));
  Scales s;
  s.energy = kinetic + std::abs(body.mgR());
  s.momentum = std::sqrt(2.0 * inertia.maxCoeff() * s.energy);
  // At rest without torque nothing moves: any positive scale reports the zero drift.
  if (!(s.energy > 0.0)) s.energy = 1.0;
  if (!(s.momentum > 0.0)) s.momentum = 1.0;
  return s;
}

// The general body's (general_body.cpp): E_scale = T(0) + m g |c|, L_scale = sqrt(2 max eig(I)
// E_scale), as scales_of() for diag(A, B, C) and c = R e3.
Scales general_scales(const Body& body, const RigidBodyState& x0);

// Throws InvalidInput naming the first damping key (or motion.driven) of a damped body: the
// general body is integrated without SPEC section 6's torques (general_body.cpp).
void refuse_damped_general(const Body& body);

// Raises the drifts (of a NonlinearSummary or SplittingSummary) to those of q against `initial`.
inline void note_drift(Drifts& s, const ConservedQuantities& q, const ConservedQuantities& initial,
                       const Scales& scales) {
  s.max_relative_energy_drift =
      std::max(s.max_relative_energy_drift, std::abs(q.energy - initial.energy) / scales.energy);
  s.max_relative_vertical_momentum_drift =
      std::max(s.max_relative_vertical_momentum_drift,
               std::abs(q.vertical_momentum - initial.vertical_momentum) / scales.momentum);
  s.max_relative_axial_momentum_drift =
      std::max(s.max_relative_axial_momentum_drift,
               std::abs(q.axial_momentum - initial.axial_momentum) / scales.momentum);
}

// The end of BriefReport, from "relative drift:" on.
template <class Summary>
std::string drift_report(const Summary& s) {
  return fmt::format(
      "relative drift: energy {:.2e}, vertical momentum {:.2e}, axial momentum {:.2e}{}",
      s.max_relative_energy_drift, s.max_relative_vertical_momentum_drift,
      s.max_relative_axial_momentum_drift, s.symmetric ? "" : " (not conserved: A != B)");
}

// ---- The first integrals and the attitude --------------------------------------------------------

// E, L_zeta and C w3 from the angular velocity w and the upward vertical gamma = R^T e_zeta,
// both in body axes: the one formula behind conserved_quantities() and the integrators' monitors.
inline ConservedQuantities conserved_from(const Body& body, double w1, double w2, double w3, double g1,
                                          double g2, double g3) {
  ConservedQuantities q;
  q.energy = 0.5 * (body.A * w1 * w1 + body.B * w2 * w2 + body.C * w3 * w3) + body.mgR() * g3;
  q.vertical_momentum = body.A * w1 * g1 + body.B * w2 * g2 + body.C * w3 * g3;
  q.axial_momentum = body.C * w3;
  return q;
}

// The unit quaternion of a rotation matrix (body-to-fixed attitude).
inline Eigen::Quaterniond unit_quaternion(const Eigen::Matrix3d& attitude) {
  Eigen::Quaterniond q(attitude);
  q.normalize();
  return q;
}

// ---- Samples -----------------------------------------------------------------------------------

// The samples of a run, streamed: how many, the time of each (s; finite, >= 0, non-decreasing),
// and where the trajectory goes, `chunk` samples at a time (then the rest), so that memory
// stays flat in the number of samples. `flush` may take the columns' contents (move them).
// `progress` is the run's (progress.hpp): the one sample loop calls it.
struct SampleStream {
  std::size_t count = 0;
  std::function<double(std::size_t)> time;
  std::size_t chunk = static_cast<std::size_t>(-1);
  std::function<void(Trajectory&)> flush;
  Progress progress;
  // The nonlinear model's writer puts the people's columns tilt and azimuth first among the
  // extra ones, from the axis k itself (simulate() asks; the simulate_* functions do not).
  bool axis_direction = false;

  // s, the last sample's time (0 without samples): the run's horizon.
  double horizon() const { return count == 0 ? 0.0 : time(count - 1); }
};

// A stream over `times` that gathers every sample into `out`, with the run's `progress`.
inline SampleStream gather(const std::vector<double>& times, Trajectory& out, const Progress& progress) {
  return {times.size(), [&times](std::size_t i) { return times[i]; }, static_cast<std::size_t>(-1),
          [&out](Trajectory& part) {
            if (out.size() == 0) out = std::move(part);
            else out.append(part);
          },
          progress};
}

// simulate_*(times) from its streaming twin: `stream(samples)` with every sample at `times`
// (validated: key "times") gathered into one trajectory.
template <class Stream>
Trajectory gathered(const std::vector<double>& times, const Progress& progress, const Stream& stream) {
  validate_times(times);
  Trajectory out;
  stream(gather(times, out, progress));
  return out;
}

// Empties every column of `out`, keeping the extra columns' names.
inline void clear_samples(Trajectory& out) {
  for (std::size_t c = 0; c < kTrajectoryColumns.size() + out.extra.size(); ++c) out.column(c).clear();
}

// After a sample is pushed: hands `out` on when a chunk is full, or when `last` is true.
inline void maybe_flush(const SampleStream& stream, Trajectory& out, bool last) {
  if (out.size() < stream.chunk && !last) return;
  stream.flush(out);
  clear_samples(out);
}

// ---- Output -----------------------------------------------------------------------------------

// SPEC section 2's angles of a rigid-body state: k = R e3, k' = R (w x e3) = w2 R e1 - w1 R e2.
inline AxisAngles axis_angles_of(const RigidBodyState& rb) {
  return axis_angles(rb.attitude.col(2),
                     rb.omega.y() * rb.attitude.col(0) - rb.omega.x() * rb.attitude.col(1));
}

// s, Hairer's first step: 1% of |x| / |x'| in the controller's error norm (x, x' any fixed-size
// state), the weights kept away from 0 (a tiny atol on a zero component) so that the ratio
// stays finite; 1e-6 s when either is ~0; at most the horizon.
template <class State>
double first_step_guess(const State& x, const State& dxdt, const Tolerances& o, double horizon) {
  double largest = 0.0;
  for (double v : x) largest = std::max(largest, std::abs(v));
  double d0 = 0.0, d1 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double sc = std::max(o.atol + o.rtol * std::abs(x[i]), o.rtol * largest);
    d0 += (x[i] / sc) * (x[i] / sc);
    d1 += (dxdt[i] / sc) * (dxdt[i] / sc);
  }
  double h = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * std::sqrt(d0 / d1);
  if (!(h > 0.0 && std::isfinite(h))) h = 1e-6;
  if (horizon > 0.0) h = std::min(h, horizon);
  return h;
}

// Steps between two progress calls inside a sample interval (~20 us of work each).
inline constexpr std::size_t kStepsPerProgress = 64;

// Steps a dense-output integrator (time(), step()) until it has passed t, calling `progress`
// every kStepsPerProgress steps too, so that a caller can stop a long run between samples. An
// integrator whose step can take the time it is heading for (step(t): the Taylor integrator,
// which then evaluates its series there along with the step's end) is told it.
template <class Integrator>
void advance_to(Integrator& integrator, double t, const Progress& progress) {
  for (std::size_t steps = 1; integrator.time() < t; ++steps) {
    if constexpr (requires { integrator.step(t); }) integrator.step(t);
    else integrator.step();
    if (progress && steps % kStepsPerProgress == 0) progress(std::min(t, integrator.time()));
  }
}

// One sample's angle columns.
inline void push_angles(Trajectory& out, double t, const AxisAngles& a) {
  out.t.push_back(t);
  out.theta.push_back(a.theta);
  out.phi.push_back(a.phi);
  out.theta_rate.push_back(a.theta_rate);
  out.phi_rate.push_back(a.phi_rate);
}

// ---- Damped bodies (SPEC section 6; nonlinear.cpp's dopri5, taylor.cpp) ----------------------------
//
// The axial torque tau_z depends on a mode: sliding in the direction `mode` = +-1 of w3
// (-d_a w3 - tau0 mode), or held (mode 0: static friction holds w3 = 0; likewise a motor
// while driven), tau_z = -(A - B) w1 w2 then cancelling the gyroscopic torque on the spin.

// The mode at a start (or restart) with spin w3 (rad/s) and gyroscopic torque (A - B) w1 w2
// (N m): sliding with w3, or, at w3 = 0, held while dry friction can hold it, else sliding
// the way the gyroscopic torque drives it. Without friction there are no modes: sliding,
// whose torque is then -d_a w3 for either sign.
inline double initial_friction_mode(const Damping& d, double w3, double gyroscopic) {
  if (w3 != 0.0) return w3 > 0.0 ? 1.0 : -1.0;
  if (d.friction == 0.0) return 1.0;
  return std::abs(gyroscopic) <= d.friction ? 0.0 : (gyroscopic > 0.0 ? 1.0 : -1.0);
}

// The mode after an event of dry friction (w3 reached 0 while sliding, or the gyroscopic
// torque outgrew tau0 while held), given the gyroscopic torque there (N m).
inline double next_friction_mode(const Damping& d, double mode, double gyroscopic) {
  if (mode != 0.0) return std::abs(gyroscopic) <= d.friction ? 0.0 : (gyroscopic > 0.0 ? 1.0 : -1.0);
  return gyroscopic > 0.0 ? 1.0 : -1.0;
}

// N m, the torque the motor of a driven body produces: what holds w3 (rad/s) against the
// gyroscopic torque (N m) and its own loads (d_a w3 + tau0 sign(w3)).
inline double motor_torque(const Damping& d, double w3, double gyroscopic) {
  return -gyroscopic + d.axial * w3 + d.friction * (w3 > 0.0 ? 1.0 : w3 < 0.0 ? -1.0 : 0.0);
}

}  // namespace heavytop::detail

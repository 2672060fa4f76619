#include "heavytop/nonlinear.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <fmt/format.h>

#include "integrators/integration.hpp"
#include "integrators/sampling.hpp"
#include "integrators/tilt_scan.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

namespace {

namespace odeint = boost::numeric::odeint;

// ---- State and equations of motion ----------------------------------------------------------
//
// The body's attitude is q = p (x) exp(psi e3 / 2): p a quaternion whose frame N shares the
// body's z axis but does not spin about it, psi the spin angle of the body in N. Choosing
// psi' = w3 leaves p only the transverse angular velocity v = Rz(psi) (w1, w2), so nothing in
// (p, v) turns at the spin rate: a fast top costs steps at its nutation frequency, not at its
// spin (docs/nonlinear.md). This is an exact change of variables, valid for any body.
//
// State: p = (w, x, y, z) [0..3], v = (v1, v2) in N axes [4, 5] (rad/s), w3 [6] (rad/s),
// psi [7] (rad). A damped body (SPEC section 6) adds the integrals of what its torques take
// away: the work [8] (J), the vertical [9] and the axial [10] angular momentum (kg m^2/s), so
// that E + work, L_zeta + loss and C w3 + loss are first integrals the monitor checks.
template <bool Damped>
using StateOf = std::array<double, Damped ? 11 : 8>;
using State = StateOf<false>;
constexpr int kPw = 0, kPx = 1, kPy = 2, kPz = 3, kV1 = 4, kV2 = 5, kW3 = 6, kPsi = 7;
constexpr int kWork = 8, kVerticalLoss = 9, kAxialLoss = 10;

// gamma = R_p^T e_zeta, the vertical in N axes (third row of R_p). Dividing by |p|^2 makes the
// equations depend on the direction of p only, so its norm can drift without effect.
struct Vertical {
  double g1, g2, g3;
};
template <class S>
inline Vertical vertical(const S& x) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz];
  const double inv = 1.0 / (w * w + qx * qx + qy * qy + qz * qz);
  return {2.0 * (qx * qz - w * qy) * inv, 2.0 * (qy * qz + w * qx) * inv,
          (w * w - qx * qx - qy * qy + qz * qz) * inv};
}

// p' = 1/2 p (x) (0, v1, v2, 0).
template <class S>
inline void attitude_rate(const S& x, S& d) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz], v1 = x[kV1], v2 = x[kV2];
  d[kPw] = -0.5 * (qx * v1 + qy * v2);
  d[kPx] = 0.5 * (w * v1 - qz * v2);
  d[kPy] = 0.5 * (w * v2 + qz * v1);
  d[kPz] = 0.5 * (qx * v2 - qy * v1);
}

// Euler: I w' + w x I w = m g R (gamma x e3) + tau in body axes; v = Rz(psi) (w1, w2) adds
// w3 J v. Symmetric (A == B): the transverse inertia is isotropic, psi drops out, no
// trigonometry. Damped: tau = -d_t w_perp + tau_z k, with tau_z the axial torque of the mode:
// sliding (-d_a w3 - tau0 sign, sign = `mode`), stuck (mode 0: static friction holds w3 = 0),
// or driven (the motor cancels what would change w3).
template <bool Symmetric, bool Damped = false>
struct Equations {
  using State = StateOf<Damped>;
  double c_over_a = 0.0;  // C / A (symmetric case)
  double bc_a = 0.0;      // (B - C) / A
  double ca_b = 0.0;      // (C - A) / B
  double ab_c = 0.0;      // (A - B) / C
  double k_a = 0.0;       // m g R / A, 1/s^2
  double k_b = 0.0;       // m g R / B, 1/s^2
  double drag = 0.0;      // d_t, N m s
  double axial = 0.0;     // d_a, N m s
  double friction = 0.0;  // tau0, N m
  double a = 0.0, b = 0.0, c = 0.0;  // A, B, C
  bool driven = false;
  double mode = 1.0;      // sign of w3 while sliding; 0 while dry friction holds it

  explicit Equations(const Body& b)
      : c_over_a(b.C / b.A),
        bc_a((b.B - b.C) / b.A),
        ca_b((b.C - b.A) / b.B),
        ab_c((b.A - b.B) / b.C),
        k_a(b.mgR() / b.A),
        k_b(b.mgR() / b.B),
        drag(b.damping.transverse),
        axial(b.damping.axial),
        friction(b.damping.friction),
        a(b.A), b(b.B), c(b.C),
        driven(b.damping.driven) {}

  // N m, the axial torque tau_z on the body, given the gyroscopic (A - B) w1 w2.
  double axial_torque(double w3, double gyroscopic) const {
    if (driven || mode == 0.0) return -gyroscopic;  // the motor or static friction holds w3
    return -axial * w3 - friction * mode;
  }

  void operator()(const State& x, State& d, double /*t*/) const {
    attitude_rate(x, d);
    const Vertical g = vertical(x);
    const double v1 = x[kV1], v2 = x[kV2], w3 = x[kW3];
    [[maybe_unused]] double gyroscopic = 0.0;  // (A - B) w1 w2, N m
    if constexpr (Symmetric) {
      const double n = c_over_a * w3;  // nutation frequency C w3 / A
      d[kV1] = -n * v2 + k_a * g.g2;
      d[kV2] = n * v1 - k_a * g.g1;
      d[kW3] = 0.0;
      if constexpr (Damped) {  // -d_t w_perp / A, the same in N axes as in body axes
        d[kV1] -= drag / a * v1;
        d[kV2] -= drag / a * v2;
      }
    } else {
      const double cs = std::cos(x[kPsi]), sn = std::sin(x[kPsi]);
      const double w1 = cs * v1 + sn * v2, w2 = cs * v2 - sn * v1;  // body axes: Rz(-psi)
      const double b1 = cs * g.g1 + sn * g.g2, b2 = cs * g.g2 - sn * g.g1;
      double dw1 = bc_a * w2 * w3 + k_a * b2;
      double dw2 = ca_b * w3 * w1 - k_b * b1;
      if constexpr (Damped) {
        dw1 -= drag / a * w1;
        dw2 -= drag / b * w2;
        gyroscopic = (a - b) * w1 * w2;
      }
      d[kV1] = cs * dw1 - sn * dw2 - w3 * v2;  // back to N: Rz(psi), plus w3 J v
      d[kV2] = sn * dw1 + cs * dw2 + w3 * v1;
      d[kW3] = ab_c * w1 * w2;
    }
    if constexpr (Damped) {
      const double tz = axial_torque(w3, gyroscopic);
      d[kW3] += tz / c;
      // What the torques take away: -tau.w, -tau.zeta (gravity's torque has none) and -tau_z.
      d[kWork] = drag * (v1 * v1 + v2 * v2) - tz * w3;
      d[kVerticalLoss] = drag * (v1 * g.g1 + v2 * g.g2) - tz * g.g3;
      d[kAxialLoss] = -tz;
    }
    d[kPsi] = w3;
  }
};

// ---- Conversions ------------------------------------------------------------------------------

template <class S = State>
S to_state(const RigidBodyState& rb) {
  const Eigen::Quaterniond q = unit_quaternion(rb.attitude);
  S x{};  // the integrals of a damped body start at 0
  const double head[] = {q.w(), q.x(), q.y(), q.z(), rb.omega.x(), rb.omega.y(), rb.omega.z(), 0.0};
  std::copy(std::begin(head), std::end(head), x.begin());
  return x;
}

template <class S>
Eigen::Matrix3d attitude_of_p(const S& x) {
  return Eigen::Quaterniond(x[kPw], x[kPx], x[kPy], x[kPz]).normalized().toRotationMatrix();
}

template <class S>
RigidBodyState to_rigid_body(const S& x) {
  const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
  Eigen::Matrix3d rz;
  rz << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  RigidBodyState rb;
  rb.attitude = attitude_of_p(x) * rz;
  rb.omega = Eigen::Vector3d(c * x[kV1] + s * x[kV2], c * x[kV2] - s * x[kV1], x[kW3]);
  return rb;
}

// The axis k = R_p e3 and k' = R (w x e3) = v2 n1 - v1 n2 (n1, n2 the first columns of R_p):
// the spin never enters, so k' carries no rounding error of size |w3|.
template <class S>
AxisAngles angles_of(const S& x) {
  const Eigen::Matrix3d rp = attitude_of_p(x);
  const Eigen::Vector3d k = rp.col(2);
  const Eigen::Vector3d k_rate = x[kV2] * rp.col(0) - x[kV1] * rp.col(1);
  return axis_angles(k, k_rate);
}

// Tilt acos(k_zeta), evaluated as atan2(|k_horizontal|, k_zeta): accurate near 0 as well.
template <class S>
double tilt_of(const S& x) {
  const Vertical g = vertical(x);  // (n1.zeta, n2.zeta, k.zeta), normalised
  return std::atan2(std::hypot(g.g1, g.g2), g.g3);
}

// d(k_zeta)/dt = (v2 n1 - v1 n2).zeta.
template <class S>
double tilt_cos_rate(const S& x) {
  const Vertical g = vertical(x);
  return x[kV2] * g.g1 - x[kV1] * g.g2;
}

// ---- Options --------------------------------------------------------------------------------

Violation first_violation(const Tolerances& o) {
  if (!(std::isfinite(o.rtol) && o.rtol >= 1e-15 && o.rtol <= 1.0))
    return std::pair{"rtol", "must be a finite number in [1e-15, 1]"};
  if (!(std::isfinite(o.atol) && o.atol > 0.0))
    return std::pair{"atol", "must be a finite number > 0"};
  if (o.max_steps == 0) return std::pair{"max_steps", "must be > 0"};
  return std::nullopt;
}

// ---- Drift monitor (only when a summary is asked for; scales_of() and note_drift() shared) ----

// E, L_zeta, C w3 straight from the integration state (no matrices; used at every step).
template <class S>
ConservedQuantities conserved_of_state(const Body& body, const S& x, bool symmetric) {
  const Vertical g = vertical(x);
  double w1 = x[kV1], w2 = x[kV2], b1 = g.g1, b2 = g.g2;
  if (!symmetric) {  // to body axes; for A == B the transverse terms are invariant under Rz
    const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
    w1 = c * x[kV1] + s * x[kV2];
    w2 = c * x[kV2] - s * x[kV1];
    b1 = c * g.g1 + s * g.g2;
    b2 = c * g.g2 - s * g.g1;
  }
  ConservedQuantities q = conserved_from(body, w1, w2, x[kW3], b1, b2, g.g3);
  if constexpr (std::tuple_size_v<S> > kWork) {  // damped: plus what the torques took away
    q.energy += x[kWork];
    q.vertical_momentum += x[kVerticalLoss];
    q.axial_momentum += x[kAxialLoss];
  }
  return q;
}

// ---- The integrator ---------------------------------------------------------------------------

// Dormand-Prince 5(4), error-controlled, with its own continuous extension for dense output.
// We drive the controlled stepper ourselves (rather than odeint's dense-output wrapper) to
// count rejected steps, to bound the work and to keep the state on its manifold between
// steps: |p| = 1 and psi in [-pi, pi]. A damped body with dry friction has one discontinuity,
// sign(w3): each mode's equations are smooth, and a change of mode is an event located on the
// dense output, where the integration restarts (w3 = 0 exactly once it sticks: no chattering).
template <bool Symmetric, bool Damped = false>
class Integrator {
 public:
  using State = StateOf<Damped>;
  using Stepper = odeint::runge_kutta_dopri5<State>;
  using Controlled = odeint::controlled_runge_kutta<Stepper>;

  Integrator(const Body& body, const State& x0, double horizon, const Tolerances& options,
             NonlinearSummary* summary)
      : body_(body),
        equations_(body),
        controlled_(typename Controlled::error_checker_type(options.atol, options.rtol)),
        max_steps_(options.max_steps),
        summary_(summary),
        horizon_(horizon),
        x_(x0) {
    if constexpr (Damped) equations_.mode = initial_friction_mode(body.damping, x0[kW3], gyroscopic(x0));
    equations_(x_, dxdt_, 0.0);
    end_x_ = x_;
    end_dxdt_ = dxdt_;
    dt_ = initial_step(options, horizon);
    if (summary_) {
      *summary_ = NonlinearSummary{};
      summary_->symmetric = Symmetric;
      summary_->rhs_evaluations = 1;
      scales_ = scales_of(body, to_rigid_body(x0));
      initial_ = conserved_of_state(body, x0, Symmetric);
    }
  }

  double time() const { return t_; }
  double previous_time() const { return t_old_; }

  // One accepted step from time() on (shortened to an event of dry friction); afterwards
  // interpolate() covers [previous_time(), time()].
  void step() {
    commit();
    x_old_ = x_;
    dxdt_old_ = dxdt_;
    t_old_ = t_;
    controlled_step(controlled_, equations_, x_old_, dxdt_old_, t_, x_, dxdt_, dt_, attempts_, max_steps_, summary_);
    if constexpr (Damped) {
      if (attempts_ == max_steps_ / 100) give_up_if_stiff();
    }
    end_x_ = x_;
    end_dxdt_ = dxdt_;
    end_t_ = t_;
    if constexpr (Damped) {
      if (equations_.friction > 0.0 && !equations_.driven) change_friction_mode();
    }
    if (summary_) monitor();
  }

  // The state at t in [previous_time(), time()] from the stepper's continuous extension.
  void interpolate(double t, State& out) const {
    if (t == t_) {
      out = x_;
      return;
    }
    controlled_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, end_x_, end_dxdt_, end_t_);
  }

 private:
  // (A - B) w1 w2 in the state x (N m): the gyroscopic torque on the spin.
  double gyroscopic(const State& x) const {
    if constexpr (Symmetric) return 0.0;
    const RigidBodyState rb = to_rigid_body(x);
    return (body_.A - body_.B) * rb.omega.x() * rb.omega.y();
  }


  // After a step in one friction mode: if the mode ended inside it (w3 reached 0 while
  // sliding, or the gyroscopic torque overcame the static friction while stuck), the step
  // is cut back to that moment, found on the dense output, and the next mode starts there.
  void change_friction_mode() {
    const double mode = equations_.mode;
    std::function<double(const State&)> event;
    if (mode != 0.0) {
      if (x_[kW3] * mode > 0.0) return;
      event = [mode](const State& y) { return y[kW3] * mode; };
    } else {
      if constexpr (Symmetric) return;  // (A - B) w1 w2 = 0: stuck for good
      if (std::abs(gyroscopic(x_)) <= body_.damping.friction) return;
      event = [this](const State& y) { return body_.damping.friction - std::abs(gyroscopic(y)); };
    }
    State y;
    auto at = [&](double t) {
      interpolate_step(t, y);
      return event(y);
    };
    double t_event = t_;
    if (const double f1 = at(t_); f1 < 0.0) {
      std::uintmax_t iterations = 100;
      const double width = t_ - t_old_;
      const auto bracket = boost::math::tools::toms748_solve(
          at, t_old_, t_, event(x_old_), f1,
          [width](double a, double b) { return std::abs(b - a) <= 1e-15 * width; }, iterations);
      t_event = bracket.second;
    }
    interpolate_step(t_event, y);
    if (mode != 0.0) y[kW3] = 0.0;  // stopped: from here on exactly zero while it sticks
    equations_.mode = next_friction_mode(body_.damping, mode, gyroscopic(y));
    x_ = y;
    t_ = t_event;
    equations_(x_, dxdt_, t_);
    if (summary_) ++summary_->rhs_evaluations;
  }

  // Strong damping makes the motion stiff: a drag rate d / I of 2e13 1/s (d_t = 1e9 on the toy
  // top) bounds an explicit step however slowly the body moves, and 1e8 steps took 80 s to
  // reach max_steps. Once a hundredth of max_steps is spent, a run that cannot reach its horizon
  // within max_steps stops with the reason. The bound: the drag's rates on w in body axes are
  // d_t / A, d_t / B and d_a / C, and dopri5 is stable on the negative real axis only to
  // h |lambda| = 3.31 (test_damping measures the steps there); taken at half, the steps left
  // are at least (horizon - t) rate / 6.62.
  void give_up_if_stiff() const {
    const Damping& d = body_.damping;
    const double rate = std::max(d.transverse / std::max(body_.A, body_.B), d.axial / body_.C);
    const double longest = 6.62 / rate;  // s
    const double left = (horizon_ - t_) / longest;
    if (!(double(attempts_) + left > double(max_steps_))) return;
    throw std::runtime_error(fmt::format(
        "nonlinear: the damping makes this motion stiff: dopri5's step stays below about {:.3g} s, so reaching "
        "t = {:.6g} s needs more than {:.3g} steps, beyond max_steps = {} (stopped at t = {:.6g} s after {} steps)",
        longest, horizon_, double(attempts_) + left, max_steps_, t_, attempts_));
  }

  void interpolate_step(double t, State& out) const {
    controlled_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, end_x_, end_dxdt_, end_t_);
  }

  double initial_step(const Tolerances& o, double horizon) const {
    return first_step_guess(x_, dxdt_, o, horizon);
  }

  // Back onto the manifold before the next step: |p| = 1 (its rate scales with p), psi
  // reduced to [-pi, pi] (the equations are 2 pi periodic in psi).
  void commit() {
    const double norm = std::sqrt(x_[kPw] * x_[kPw] + x_[kPx] * x_[kPx] + x_[kPy] * x_[kPy] +
                                  x_[kPz] * x_[kPz]);
    if (summary_) summary_->max_quaternion_norm_error =
        std::max(summary_->max_quaternion_norm_error, std::abs(norm - 1.0));
    const double inv = 1.0 / norm;
    for (int i = kPw; i <= kPz; ++i) {
      x_[i] *= inv;
      dxdt_[i] *= inv;
    }
    constexpr double kTwoPi = 6.283185307179586;
    if (std::abs(x_[kPsi]) > 3.141592653589793)
      x_[kPsi] -= kTwoPi * std::nearbyint(x_[kPsi] / kTwoPi);
  }

  void monitor() {
    ++summary_->steps;
    summary_->final_time = t_;
    note_drift(*summary_, conserved_of_state(body_, x_, Symmetric), initial_, scales_);
  }


  const Body& body_;
  Equations<Symmetric, Damped> equations_;
  Controlled controlled_;
  std::size_t max_steps_;
  NonlinearSummary* summary_;
  double horizon_;  // s, where the run ends
  std::size_t attempts_ = 0;
  Scales scales_;
  ConservedQuantities initial_;
  // The current state (x_, dxdt_ at t_), the last step's start and its end (end_*: the
  // continuous extension's ends, which an event leaves in place while t_ moves back).
  State x_, dxdt_{}, x_old_{}, dxdt_old_{}, end_x_{}, end_dxdt_{};
  double t_ = 0.0, t_old_ = 0.0, end_t_ = 0.0, dt_ = 0.0;
};


template <bool Symmetric, bool Damped>
void simulate(const Body& body, const RigidBodyState& rb0, const SampleStream& samples,
              const Tolerances& options, NonlinearSummary* summary) {
  using State = StateOf<Damped>;
  const double horizon = samples.horizon();
  Integrator<Symmetric, Damped> integrator(body, to_state<State>(rb0), horizon, options, summary);
  // Angles from p itself (k' = R (w x e3) as in angles_of()), E, L_zeta, C w3 from the body.
  write_samples(integrator, body, rb0, conserved_quantities(body, rb0), Damped, samples, options.progress,
                [&body](const State& x) {
                  SampleValues v{angles_of(x), to_rigid_body(x), {}, {}};
                  v.conserved = conserved_quantities(body, v.body);
                  if constexpr (Damped) v.taken = {x[kWork], x[kVerticalLoss], x[kAxialLoss]};
                  return v;
                });
}

template <bool Symmetric, bool Damped>
TiltExtremes scan_tilt(const Body& body, const RigidBodyState& rb0, double horizon, double stop_above,
                       const Tolerances& options, NonlinearSummary* summary) {
  using State = StateOf<Damped>;
  const State x0 = to_state<State>(rb0);
  TiltExtremes e;
  if (summary) *summary = NonlinearSummary{};
  const double tilt0 = tilt_of(x0);
  e.min_tilt = e.max_tilt = tilt0;
  e.exceeded = tilt0 > stop_above;
  e.spin_at_end = x0[kW3];  // w.k at t = 0, where the scan ends when it is past stop_above already
  if (e.exceeded || horizon == 0.0) return e;

  Integrator<Symmetric, Damped> integrator(body, x0, horizon, options, summary);
  return detail::scan_tilt_extremes(
      integrator, x0, horizon, stop_above, [](const State& x) { return tilt_of(x); },
      [](const State& x) { return tilt_cos_rate(x); }, [](const State& x) { return x[kW3]; }, options.progress);
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------

bool Tolerances::IsValid(std::string* why) const {
  return is_valid(first_violation(*this), why);
}

void validate(const Tolerances& options) { throw_if_invalid(first_violation(options)); }

std::string NonlinearSummary::BriefReport() const {
  return fmt::format("nonlinear: {} steps ({} rejected), {} evaluations, t = {:.6g} s, {}", steps,
                     rejected_steps, rhs_evaluations, final_time, drift_report(*this));
}

ConservedQuantities conserved_quantities(const Body& body, const RigidBodyState& x) {
  const Eigen::Vector3d gamma = x.attitude.row(2).transpose();  // R^T e_zeta
  return conserved_from(body, x.omega.x(), x.omega.y(), x.omega.z(), gamma.x(), gamma.y(), gamma.z());
}

Trajectory simulate_nonlinear(const Body& body, const InitialState& initial,
                              const std::vector<double>& times, const Tolerances& options,
                              NonlinearSummary* summary) {
  return gathered(times, [&](const SampleStream& samples) {
    detail::stream_nonlinear(body, initial, samples, options, summary);
  });
}

void detail::stream_nonlinear(const Body& body, const InitialState& initial, const SampleStream& samples,
                              const Tolerances& options, NonlinearSummary* summary) {
  validate(body);
  refuse_general(body, "this principal-axes integrator (simulate() and simulate_general_body() take it)");
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  // Exact equality picks the cheaper right-hand side whose transverse inertia is isotropic
  // (a body symmetric only to kSymmetryTolerance takes the general one).
  const bool damped = !body.damping.conservative();
  if (body.A == body.B) {
    if (damped) simulate<true, true>(body, rb0, samples, options, summary);
    else simulate<true, false>(body, rb0, samples, options, summary);
  } else {
    if (damped) simulate<false, true>(body, rb0, samples, options, summary);
    else simulate<false, false>(body, rb0, samples, options, summary);
  }
}

TiltExtremes tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                           double stop_above, const Tolerances& options,
                           NonlinearSummary* summary) {
  validate(body);
  refuse_general(body, "the tilt scan (sweep, lifetime, the wander)");
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0))
    throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  const bool damped = !body.damping.conservative();
  if (body.A == body.B)
    return damped ? scan_tilt<true, true>(body, rb0, horizon, stop_above, options, summary)
                  : scan_tilt<true, false>(body, rb0, horizon, stop_above, options, summary);
  return damped ? scan_tilt<false, true>(body, rb0, horizon, stop_above, options, summary)
                : scan_tilt<false, false>(body, rb0, horizon, stop_above, options, summary);
}

double max_tilt(const Body& body, const InitialState& initial, double horizon, double stop_above,
                const Tolerances& options) {
  return tilt_extremes(body, initial, horizon, stop_above, options).max_tilt;
}

}  // namespace heavytop

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

#include "detail/integration.hpp"
#include "detail/streams.hpp"

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
// psi [7] (rad).
using State = std::array<double, 8>;
constexpr int kPw = 0, kPx = 1, kPy = 2, kPz = 3, kV1 = 4, kV2 = 5, kW3 = 6, kPsi = 7;

// gamma = R_p^T e_zeta, the vertical in N axes (third row of R_p). Dividing by |p|^2 makes the
// equations depend on the direction of p only, so its norm can drift without effect.
struct Vertical {
  double g1, g2, g3;
};
inline Vertical vertical(const State& x) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz];
  const double inv = 1.0 / (w * w + qx * qx + qy * qy + qz * qz);
  return {2.0 * (qx * qz - w * qy) * inv, 2.0 * (qy * qz + w * qx) * inv,
          (w * w - qx * qx - qy * qy + qz * qz) * inv};
}

// p' = 1/2 p (x) (0, v1, v2, 0).
inline void attitude_rate(const State& x, State& d) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz], v1 = x[kV1], v2 = x[kV2];
  d[kPw] = -0.5 * (qx * v1 + qy * v2);
  d[kPx] = 0.5 * (w * v1 - qz * v2);
  d[kPy] = 0.5 * (w * v2 + qz * v1);
  d[kPz] = 0.5 * (qx * v2 - qy * v1);
}

// Euler: I w' + w x I w = m g R (gamma x e3) in body axes; v = Rz(psi) (w1, w2) adds w3 J v.
// Symmetric (A == B): the transverse inertia is isotropic, psi drops out, no trigonometry.
template <bool Symmetric>
struct Equations {
  double c_over_a = 0.0;  // C / A (symmetric case)
  double bc_a = 0.0;      // (B - C) / A
  double ca_b = 0.0;      // (C - A) / B
  double ab_c = 0.0;      // (A - B) / C
  double k_a = 0.0;       // m g R / A, 1/s^2
  double k_b = 0.0;       // m g R / B, 1/s^2

  explicit Equations(const Body& b)
      : c_over_a(b.C / b.A),
        bc_a((b.B - b.C) / b.A),
        ca_b((b.C - b.A) / b.B),
        ab_c((b.A - b.B) / b.C),
        k_a(b.mgR() / b.A),
        k_b(b.mgR() / b.B) {}

  void operator()(const State& x, State& d, double /*t*/) const {
    attitude_rate(x, d);
    const Vertical g = vertical(x);
    const double v1 = x[kV1], v2 = x[kV2], w3 = x[kW3];
    if constexpr (Symmetric) {
      const double n = c_over_a * w3;  // nutation frequency C w3 / A
      d[kV1] = -n * v2 + k_a * g.g2;
      d[kV2] = n * v1 - k_a * g.g1;
      d[kW3] = 0.0;
    } else {
      const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
      const double w1 = c * v1 + s * v2, w2 = c * v2 - s * v1;  // body axes: Rz(-psi)
      const double b1 = c * g.g1 + s * g.g2, b2 = c * g.g2 - s * g.g1;
      const double dw1 = bc_a * w2 * w3 + k_a * b2;
      const double dw2 = ca_b * w3 * w1 - k_b * b1;
      d[kV1] = c * dw1 - s * dw2 - w3 * v2;  // back to N: Rz(psi), plus w3 J v
      d[kV2] = s * dw1 + c * dw2 + w3 * v1;
      d[kW3] = ab_c * w1 * w2;
    }
    d[kPsi] = w3;
  }
};

// ---- Conversions ------------------------------------------------------------------------------

State to_state(const RigidBodyState& rb) {
  const Eigen::Quaterniond q = unit_quaternion(rb.attitude);
  return {q.w(), q.x(), q.y(), q.z(), rb.omega.x(), rb.omega.y(), rb.omega.z(), 0.0};
}

Eigen::Matrix3d attitude_of_p(const State& x) {
  return Eigen::Quaterniond(x[kPw], x[kPx], x[kPy], x[kPz]).normalized().toRotationMatrix();
}

RigidBodyState to_rigid_body(const State& x) {
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
AxisAngles angles_of(const State& x) {
  const Eigen::Matrix3d rp = attitude_of_p(x);
  const Eigen::Vector3d k = rp.col(2);
  const Eigen::Vector3d k_rate = x[kV2] * rp.col(0) - x[kV1] * rp.col(1);
  return axis_angles(k, k_rate);
}

// Tilt acos(k_zeta), evaluated as atan2(|k_horizontal|, k_zeta): accurate near 0 as well.
double tilt_of(const State& x) {
  const Vertical g = vertical(x);  // (n1.zeta, n2.zeta, k.zeta), normalised
  return std::atan2(std::hypot(g.g1, g.g2), g.g3);
}

// d(k_zeta)/dt = (v2 n1 - v1 n2).zeta.
double tilt_cos_rate(const State& x) {
  const Vertical g = vertical(x);
  return x[kV2] * g.g1 - x[kV1] * g.g2;
}

// ---- Options --------------------------------------------------------------------------------

Violation first_violation(const NonlinearOptions& o) {
  if (!(std::isfinite(o.rtol) && o.rtol >= 1e-15 && o.rtol <= 1.0))
    return std::pair{"rtol", "must be a finite number in [1e-15, 1]"};
  if (!(std::isfinite(o.atol) && o.atol > 0.0))
    return std::pair{"atol", "must be a finite number > 0"};
  if (o.max_steps == 0) return std::pair{"max_steps", "must be > 0"};
  return std::nullopt;
}

// ---- Drift monitor (only when a summary is asked for; scales_of() and note_drift() shared) ----

// E, L_zeta, C w3 straight from the integration state (no matrices; used at every step).
ConservedQuantities conserved_of_state(const Body& body, const State& x, bool symmetric) {
  const Vertical g = vertical(x);
  double w1 = x[kV1], w2 = x[kV2], b1 = g.g1, b2 = g.g2;
  if (!symmetric) {  // to body axes; for A == B the transverse terms are invariant under Rz
    const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
    w1 = c * x[kV1] + s * x[kV2];
    w2 = c * x[kV2] - s * x[kV1];
    b1 = c * g.g1 + s * g.g2;
    b2 = c * g.g2 - s * g.g1;
  }
  return conserved_from(body, w1, w2, x[kW3], b1, b2, g.g3);
}

// ---- The integrator ---------------------------------------------------------------------------

// Dormand-Prince 5(4), error-controlled, with its own continuous extension for dense output.
// We drive the controlled stepper ourselves (rather than odeint's dense-output wrapper) to
// count rejected steps, to bound the work and to keep the state on its manifold between
// steps: |p| = 1 and psi in [-pi, pi].
template <bool Symmetric>
class Integrator {
 public:
  using Stepper = odeint::runge_kutta_dopri5<State>;
  using Controlled = odeint::controlled_runge_kutta<Stepper>;

  Integrator(const Body& body, const State& x0, double horizon, const NonlinearOptions& options,
             NonlinearSummary* summary)
      : body_(body),
        equations_(body),
        controlled_(typename Controlled::error_checker_type(options.atol, options.rtol)),
        max_steps_(options.max_steps),
        summary_(summary),
        x_(x0) {
    equations_(x_, dxdt_, 0.0);
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

  // One accepted step from time() on; afterwards interpolate() covers [previous_time(), time()].
  void step() {
    commit();
    x_old_ = x_;
    dxdt_old_ = dxdt_;
    t_old_ = t_;
    int rejections = 0;
    for (;;) {
      if (attempts_ >= max_steps_)
        throw std::runtime_error(fmt::format(
            "nonlinear: more than max_steps = {} integration steps before t = {:.6g} s "
            "(raise max_steps or loosen rtol/atol)",
            max_steps_, t_));
      if (!(t_ + dt_ > t_))  // lost in the rounding of t (or not a number)
        throw std::runtime_error(fmt::format(
            "nonlinear: step size underflow at t = {:.6g} s (the tolerance rtol/atol cannot "
            "be met)",
            t_));
      ++attempts_;
      const double t_before = t_;
      const auto result = controlled_.try_step(equations_, x_old_, dxdt_old_, t_, x_, dxdt_, dt_);
      if (summary_) summary_->rhs_evaluations += 6;  // FSAL: six new stages per attempt
      if (result == odeint::success) {
        if (!std::all_of(x_.begin(), x_.end(), [](double v) { return std::isfinite(v); }))
          throw std::runtime_error(fmt::format(
              "nonlinear: the state stopped being finite at t = {:.6g} s", t_before));
        break;
      }
      if (summary_) ++summary_->rejected_steps;
      // A long run of rejections: rounding, not the method, limits the error.
      if (++rejections > kMaxConsecutiveRejections)
        throw std::runtime_error(fmt::format(
            "nonlinear: step size underflow at t = {:.6g} s (the tolerance rtol/atol cannot "
            "be met)",
            t_));
    }
    if (summary_) monitor();
  }

  // The state at t in [previous_time(), time()] from the stepper's continuous extension.
  void interpolate(double t, State& out) const {
    if (t == t_) {
      out = x_;
      return;
    }
    controlled_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, x_, dxdt_, t_);
  }

 private:
  double initial_step(const NonlinearOptions& o, double horizon) const {
    // Hairer's first guess, 1% of |x| / |x'| in the controller's error norm; the weights are
    // kept away from 0 (a tiny atol on a zero component) so that the ratio stays finite.
    double largest = 0.0;
    for (double v : x_) largest = std::max(largest, std::abs(v));
    double d0 = 0.0, d1 = 0.0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const double sc = std::max(o.atol + o.rtol * std::abs(x_[i]), o.rtol * largest);
      d0 += (x_[i] / sc) * (x_[i] / sc);
      d1 += (dxdt_[i] / sc) * (dxdt_[i] / sc);
    }
    double h = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * std::sqrt(d0 / d1);
    if (!(h > 0.0 && std::isfinite(h))) h = 1e-6;
    if (horizon > 0.0) h = std::min(h, horizon);
    return h;
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

  static constexpr int kMaxConsecutiveRejections = 100;

  const Body& body_;
  Equations<Symmetric> equations_;
  Controlled controlled_;
  std::size_t max_steps_;
  NonlinearSummary* summary_;
  std::size_t attempts_ = 0;
  Scales scales_;
  ConservedQuantities initial_;
  State x_, dxdt_{}, x_old_{}, dxdt_old_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
};

// Steps between two progress calls inside a sample interval (~20 us of work each).
constexpr std::size_t kStepsPerProgress = 64;

template <bool Symmetric>
void simulate(const Body& body, const RigidBodyState& rb0, const SampleStream& samples,
              const NonlinearOptions& options, NonlinearSummary* summary) {
  const State x0 = to_state(rb0);
  const double horizon = samples.count == 0 ? 0.0 : samples.time(samples.count - 1);
  Integrator<Symmetric> integrator(body, x0, horizon, options, summary);
  const ConservedQuantities initial = conserved_quantities(body, rb0);

  const std::size_t room = std::min(samples.count, samples.chunk);
  Trajectory out;
  out.reserve(room);
  add_conserved_columns(out, room);

  // At t = 0 the angles come from the initial attitude itself (SPEC section 2), not from a
  // round trip through the quaternion; k' = R (w x e3) as in angles_of().
  const AxisAngles a0 = axis_angles_of(rb0);
  State x;
  for (std::size_t i = 0; i < samples.count; ++i) {
    const double t = samples.time(i);
    ConservedQuantities q = initial;
    AxisAngles a = a0;
    if (t > 0.0) {
      // Progress also between samples, so that a caller can stop a long run at once.
      for (std::size_t steps = 1; integrator.time() < t; ++steps) {
        integrator.step();
        if (options.progress && steps % kStepsPerProgress == 0) options.progress(std::min(t, integrator.time()));
      }
      integrator.interpolate(t, x);
      q = conserved_quantities(body, to_rigid_body(x));
      a = angles_of(x);
    }
    push_angles(out, t, a);
    push_conserved(out, q, initial);
    maybe_flush(samples, out, i + 1 == samples.count);
    if (options.progress) options.progress(t);
  }
}

template <bool Symmetric>
TiltExtremes scan_tilt(const Body& body, const State& x0, double horizon, double stop_above,
                       const NonlinearOptions& options, NonlinearSummary* summary) {
  TiltExtremes e;
  if (summary) *summary = NonlinearSummary{};
  const double tilt0 = tilt_of(x0);
  e.min_tilt = e.max_tilt = tilt0;
  e.exceeded = tilt0 > stop_above;
  if (e.exceeded || horizon == 0.0) return e;

  Integrator<Symmetric> integrator(body, x0, horizon, options, summary);
  auto note = [&](double t, const State& x) {
    const double tilt = tilt_of(x);
    if (tilt < e.min_tilt) e.min_tilt = tilt, e.t_min = t;
    if (tilt > e.max_tilt) e.max_tilt = tilt, e.t_max = t;
    return tilt > stop_above;
  };

  double rate_old = tilt_cos_rate(x0);
  State x;
  while (integrator.time() < horizon) {
    integrator.step();
    const double t0 = integrator.previous_time();
    const double t1 = std::min(integrator.time(), horizon);
    integrator.interpolate(t1, x);
    const double rate_new = tilt_cos_rate(x);
    // A sign change of d(k_zeta)/dt inside the step is an extremum of the tilt: find it on
    // the dense output (its time to ~1e-12 of the step; the tilt error is quadratic in it).
    if ((rate_old < 0.0 && rate_new > 0.0) || (rate_old > 0.0 && rate_new < 0.0)) {
      State y;
      auto rate_at = [&](double t) {
        integrator.interpolate(t, y);
        return tilt_cos_rate(y);
      };
      const double width = t1 - t0;
      std::uintmax_t iterations = 60;
      const auto bracket = boost::math::tools::toms748_solve(
          rate_at, t0, t1, rate_old, rate_new,
          [width](double a, double b) { return std::abs(b - a) <= 1e-12 * width; }, iterations);
      const double tr = 0.5 * (bracket.first + bracket.second);
      integrator.interpolate(tr, y);
      if (note(tr, y)) {
        e.exceeded = true;
        e.t_end = tr;
        return e;
      }
    }
    if (note(t1, x)) {
      e.exceeded = true;
      e.t_end = t1;
      return e;
    }
    rate_old = rate_new;
  }
  e.t_end = horizon;
  return e;
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------

bool NonlinearOptions::IsValid(std::string* why) const {
  return is_valid(first_violation(*this), why);
}

void validate(const NonlinearOptions& options) { throw_if_invalid(first_violation(options)); }

std::string NonlinearSummary::BriefReport() const {
  return fmt::format("nonlinear: {} steps ({} rejected), {} evaluations, t = {:.6g} s, {}", steps,
                     rejected_steps, rhs_evaluations, final_time, drift_report(*this));
}

ConservedQuantities conserved_quantities(const Body& body, const RigidBodyState& x) {
  const Eigen::Vector3d gamma = x.attitude.row(2).transpose();  // R^T e_zeta
  return conserved_from(body, x.omega.x(), x.omega.y(), x.omega.z(), gamma.x(), gamma.y(), gamma.z());
}

Trajectory simulate_nonlinear(const Body& body, const InitialState& initial,
                              const std::vector<double>& times, const NonlinearOptions& options,
                              NonlinearSummary* summary) {
  validate_times(times);
  Trajectory out;
  detail::stream_nonlinear(body, initial, gather(times, out), options, summary);
  return out;
}

void detail::stream_nonlinear(const Body& body, const InitialState& initial, const SampleStream& samples,
                              const NonlinearOptions& options, NonlinearSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  // Exact equality picks the cheaper right-hand side whose transverse inertia is isotropic
  // (a body symmetric only to kSymmetryTolerance takes the general one).
  if (body.A == body.B) simulate<true>(body, rb0, samples, options, summary);
  else simulate<false>(body, rb0, samples, options, summary);
}

TiltExtremes tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                           double stop_above, const NonlinearOptions& options,
                           NonlinearSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0))
    throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const State x0 = to_state(initial_rigid_body_state(initial));
  return body.A == body.B ? scan_tilt<true>(body, x0, horizon, stop_above, options, summary)
                          : scan_tilt<false>(body, x0, horizon, stop_above, options, summary);
}

double max_tilt(const Body& body, const InitialState& initial, double horizon, double stop_above,
                const NonlinearOptions& options) {
  return tilt_extremes(body, initial, horizon, stop_above, options).max_tilt;
}

}  // namespace heavytop

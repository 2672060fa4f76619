#pragma once
// Private to the Taylor integrator (src/integrators/taylor/): the stepper over a set of
// variables. One step: the series at time() by the set's recurrence, its step from the last
// two terms, the state at its end; interpolate() from the same series (a DenseStepper,
// integrators/sampling.hpp). A damped body's step ends at a change of its friction mode.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/taylor.hpp"

#include "integrators/integration.hpp"
#include "integrators/monitor.hpp"
#include "integrators/taylor/recurrence.hpp"
#include "integrators/taylor/series.hpp"
#include "integrators/taylor/variables.hpp"

namespace heavytop::detail::taylor {

// ---- The integrator -----------------------------------------------------------------------------------

template <class System>
class TaylorIntegrator {
 public:
  static constexpr int N = System::kSize, W = System::kWidth;
  using State = std::array<double, N>;
  using Jet = JetOf<W>;

  TaylorIntegrator(const Body& body, const System& system, const State& x0, double horizon,
                   const Tolerances& options, TaylorSummary* summary)
      : body_(body),
        system_(system),
        order_(taylor_order(options, System::kVariables)),
        rtol_(options.rtol),
        atol_(options.atol),
        horizon_(horizon),
        max_steps_(options.max_steps),
        summary_(summary),
        monitor_(summary ? &summary->work : nullptr),
        x_(x0) {
    if constexpr (System::kDamped)
      system_.mode = initial_friction_mode(body.damping, x0[6], (body.A - body.B) * x0[4] * x0[5]);
    if (summary_) {
      *summary_ = TaylorSummary{};
      summary_->order = order_;
      summary_->variables = System::kVariables;
      summary_->damped = System::kDamped;
      monitor_.start(System::kVariables == TaylorVariables::SpinFactored, System::scales(body, System::rigid_body(x0)),
                     conserved(x0));
    }
  }

  int order() const { return order_; }
  double time() const { return t_; }
  double previous_time() const { return t_old_; }
  const Jet& series() const { return jet_; }
  const Gamma& gamma() const { return gamma_; }

  // One step from time(): the series at time(), its step, the state at its end. Afterwards
  // interpolate() covers [previous_time(), time()] from the same series. Given the time
  // `ahead` the caller will interpolate at next (the sample loop's), a step that passes it
  // evaluates its series there in the same Horner pass as its end (horner_pair: the same bits,
  // the two chains of dependent multiply-adds overlapped), and interpolate(ahead) reads that.
  void step(double ahead = -1.0) {
    if (steps_ >= max_steps_) fail("taylor", StepOutcome::MaxSteps, t_, max_steps_);
    normalise();
    for (int i = 0; i < N; ++i) jet_.c[0][i] = x_[i];
    for (int i = N; i < W; ++i) jet_.c[0][i] = 0.0;
    system_.coefficients(jet_, gamma_, order_);

    // The step at which the last two terms reach the tolerance, componentwise:
    // |x_i[n]| h^n = eps_i = atol + rtol |x_i| for n = p - 1 and p (the estimate Jorba & Zou
    // start from; their rho / e^2 exp(-0.7/(p-1)) is its asymptotic simplification, and
    // measured at equal error it costs 10-30% more steps here: docs/integrators.md).
    double norm_pm1 = 0.0, norm_p = 0.0;
    for (int i = 0; i < N; ++i) {
      const double weight = 1.0 / (atol_ + rtol_ * std::abs(x_[i]));
      norm_pm1 = std::max(norm_pm1, std::abs(jet_.c[order_ - 1][i]) * weight);
      norm_p = std::max(norm_p, std::abs(jet_.c[order_][i]) * weight);
    }
    // +inf when the series ends below order p - 1 (a polynomial motion: the step is exact).
    double h = step_from_norms(norm_pm1, norm_p, order_);  // one pow where it can (series.hpp)
    const double left = horizon_ - t_;
    if (left > 0.0 && !(h < left)) h = left;  // never beyond the horizon (dense output inside)
    if (!(t_ + h > t_) || !std::isfinite(h)) fail("taylor", StepOutcome::StepUnderflow, t_);

    // Dry friction: the step ends where its mode does (the series holds for that mode only).
    double event = -1.0;
    if constexpr (System::kDamped) {
      event = friction_event(h);
      if (event >= 0.0) h = event;
    }

    t_old_ = t_;
    h_ = h;
    double end[W];
    const double tau = ahead - t_old_;  // as interpolate(ahead) forms it
    ahead_ = tau > 0.0 && tau < h ? ahead : -1.0;
    if (ahead_ >= 0.0) {
      double at[W];
      horner_pair(jet_, order_, h, tau, end, at);
      std::copy(at, at + N, x_ahead_.begin());
    } else {
      horner(jet_, order_, h, end);
    }
    std::copy(end, end + N, x_.begin());
    t_ = (h == left) ? horizon_ : t_old_ + h;
    ++steps_;
    if constexpr (System::kDamped) {
      if (event >= 0.0) change_friction_mode();
    }
    if (!std::all_of(x_.begin(), x_.end(), [](double v) { return std::isfinite(v); }))
      fail("taylor", StepOutcome::NotFinite, t_old_);
    if (summary_) monitor();
  }

  // The state at t in [previous_time(), time()], from the series.
  void interpolate(double t, State& out) const {
    if (t == t_ || t == ahead_) {
      out = t == t_ ? x_ : x_ahead_;
      return;
    }
    double at[W];
    horner(jet_, order_, t - t_old_, at);
    std::copy(at, at + N, out.begin());
  }

  double step_size() const { return h_; }

 private:
  // tau in [0, h] where the step's friction mode ends, or -1 if it lasts the step: while
  // sliding, the first root of w3 mode (the spin stops); while stuck, of tau0 - |(A - B) w1 w2|
  // (the gyroscopic torque outgrows static friction). The step is split into 8 pieces to find
  // the first sign change, which TOMS 748 solves on the series (nonlinear.cpp's events, which
  // look at the step's end only, on the dense output).
  double friction_event(double h) const {
    const Damping& d = body_.damping;
    const double mode = system_.mode, a_minus_b = body_.A - body_.B;
    if (!(d.friction > 0.0) || d.driven || (mode == 0.0 && a_minus_b == 0.0)) return -1.0;
    const int p = order_;
    auto event = [&](double tau) {
      if (mode != 0.0) return horner(jet_, 6, p, tau) * mode;
      return d.friction - std::abs(a_minus_b * horner(jet_, 4, p, tau) * horner(jet_, 5, p, tau));
    };
    constexpr int kPieces = 8;
    double a = 0.0, fa = event(0.0);
    for (int k = 1; k <= kPieces; ++k) {
      const double b = k == kPieces ? h : h * k / kPieces, fb = event(b);
      if (mode != 0.0 ? !(fb > 0.0) : fb < 0.0) return fb < 0.0 ? root(event, a, b, fa, fb, h) : b;
      a = b, fa = fb;
    }
    return -1.0;
  }

  // At the end of a mode (x_ there): a stopped spin is exactly 0 from here on, and the next
  // mode is nonlinear.cpp's (detail::next_friction_mode).
  void change_friction_mode() {
    const double mode = system_.mode;
    if (mode != 0.0) x_[6] = 0.0;
    system_.mode = next_friction_mode(body_.damping, mode, (body_.A - body_.B) * x_[4] * x_[5]);
    if (summary_) ++summary_->friction_events;
  }

  // |q| = 1 before each step: the vertical's formula is quadratic only on the unit sphere.
  void normalise() { monitor_.note_norm(renormalise_quaternion(x_)); }

  ConservedQuantities conserved(const State& x) const {
    if constexpr (System::kVariables == TaylorVariables::General) {
      return System::conserved(body_, System::rigid_body(x));
    } else {
      const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
      const double inv = 1.0 / (qw * qw + qx * qx + qy * qy + qz * qz);
      ConservedQuantities q =
          conserved_from(body_, x[4], x[5], x[6], 2.0 * (qx * qz - qw * qy) * inv, 2.0 * (qy * qz + qw * qx) * inv,
                         (qw * qw - qx * qx - qy * qy + qz * qz) * inv);
      if constexpr (System::kDamped) {  // plus what the torques took away
        q.energy += x[System::kWork];
        q.vertical_momentum += x[System::kVerticalLoss];
        q.axial_momentum += x[System::kAxialLoss];
      }
      return q;
    }
  }

  void monitor() {
    summary_->work.rhs_evaluations += static_cast<std::size_t>(order_);
    monitor_.note_step(t_, conserved(x_));
  }

  const Body& body_;
  System system_;
  int order_;
  double rtol_, atol_, horizon_;
  std::size_t max_steps_;
  TaylorSummary* summary_;
  StepMonitor<NonlinearSummary> monitor_;  // summary_->work
  std::size_t steps_ = 0;
  Jet jet_{};
  Gamma gamma_;
  State x_;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0;
  double ahead_ = -1.0;  // s, a time inside the last step where the state is x_ahead_ (-1: none)
  State x_ahead_;
};

}  // namespace heavytop::detail::taylor

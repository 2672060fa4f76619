#pragma once
// Private to the library: the one Dormand-Prince 5(4) driver of the nonlinear model, over the
// equations of a set of variables: the principal-axes body in spin-factored variables, damped
// or not (nonlinear.cpp), and the general body in the plain state (general_body.cpp).
//
// Odeint's controlled dopri5 with its own continuous extension, driven one accepted step at a
// time (rather than by odeint's dense-output wrapper) to count rejected steps, to bound the
// work and to keep the state on its manifold between steps (the variables' project()). A
// damped body with dry friction has one discontinuity, sign(w3): each mode's equations are
// smooth, and a change of mode is an event located on the dense output, where the integration
// restarts (w3 = 0 exactly once it sticks: no chattering).
//
// A set of variables V provides: State; kSymmetric (A == B: the summary says so); kDamped;
// Equations (Odeint's system x' = f(x); for kDamped with the members mode, friction, driven);
// V::equations(body); V::state_of(rb0); V::project(x, dxdt) (back onto the manifold, returning
// the quaternion's norm before); for the monitor V::scales(body, rb0, x0), V::initial(body,
// rb0, x0) (the first integrals at the start) and V::conserved(body, x); for kDamped
// also kW3 (the slot of w3) and V::gyroscopic(body, x) ((A - B) w1 w2, N m).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"

#include "integrators/integration.hpp"
#include "integrators/monitor.hpp"

namespace heavytop::detail {

template <class Variables>
class Dopri5Driver {
 public:
  using State = typename Variables::State;
  using Equations = typename Variables::Equations;
  using Stepper = boost::numeric::odeint::runge_kutta_dopri5<State>;
  using Controlled = boost::numeric::odeint::controlled_runge_kutta<Stepper>;

  Dopri5Driver(const Body& body, const RigidBodyState& rb0, double horizon, const Tolerances& options,
               NonlinearSummary* summary)
      : body_(body),
        equations_(Variables::equations(body)),
        controlled_(typename Controlled::error_checker_type(options.atol, options.rtol)),
        max_steps_(options.max_steps),
        monitor_(summary),
        horizon_(horizon),
        x_(Variables::state_of(rb0)) {
    const State& x0 = x_;
    if constexpr (Variables::kDamped)
      equations_.mode = initial_friction_mode(body.damping, x0[Variables::kW3], Variables::gyroscopic(body, x0));
    equations_(x_, dxdt_, 0.0);
    end_x_ = x_;
    end_dxdt_ = dxdt_;
    dt_ = first_step_guess(x_, dxdt_, options, horizon);
    if (monitor_) {
      monitor_.start(Variables::kSymmetric, Variables::scales(body, rb0, x0), Variables::initial(body, rb0, x0));
      monitor_.summary().rhs_evaluations = 1;
    }
  }

  double time() const { return t_; }
  double previous_time() const { return t_old_; }

  // One accepted step from time() on (shortened to an event of dry friction); afterwards
  // interpolate() covers [previous_time(), time()].
  void step() {
    monitor_.note_norm(Variables::project(x_, dxdt_));
    x_old_ = x_;
    dxdt_old_ = dxdt_;
    t_old_ = t_;
    controlled_step(controlled_, equations_, x_old_, dxdt_old_, t_, x_, dxdt_, dt_, attempts_, max_steps_,
                    monitor_ ? &monitor_.summary() : nullptr);
    if constexpr (Variables::kDamped) {
      if (attempts_ == max_steps_ / 100) give_up_if_stiff();
    }
    end_x_ = x_;
    end_dxdt_ = dxdt_;
    end_t_ = t_;
    if constexpr (Variables::kDamped) {
      if (equations_.friction > 0.0 && !equations_.driven) change_friction_mode();
    }
    if (monitor_) monitor_.note_step(t_, Variables::conserved(body_, x_));
  }

  // The state at t in [previous_time(), time()] from the stepper's continuous extension.
  void interpolate(double t, State& out) const {
    if (t == t_) {
      out = x_;
      return;
    }
    interpolate_step(t, out);
  }

 private:
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
    throw RunFailure(fmt::format(
        "nonlinear: the damping makes this motion stiff: dopri5's step stays below about {:.3g} s, so reaching "
        "t = {:.6g} s needs more than {:.3g} steps, beyond max_steps = {} (stopped at t = {:.6g} s after {} steps)",
        longest, horizon_, double(attempts_) + left, max_steps_, t_, attempts_), t_);
  }

  void interpolate_step(double t, State& out) const {
    controlled_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, end_x_, end_dxdt_, end_t_);
  }

  // After a step in one friction mode: if the mode ended inside it (w3 reached 0 while
  // sliding, or the gyroscopic torque overcame the static friction while stuck), the step
  // is cut back to that moment, found on the dense output, and the next mode starts there.
  void change_friction_mode() {
    constexpr int kW3 = Variables::kW3;
    const double mode = equations_.mode;
    std::function<double(const State&)> event;
    if (mode != 0.0) {
      if (x_[kW3] * mode > 0.0) return;
      event = [mode](const State& y) { return y[kW3] * mode; };
    } else {
      if constexpr (Variables::kSymmetric) return;  // (A - B) w1 w2 = 0: stuck for good
      if (std::abs(Variables::gyroscopic(body_, x_)) <= body_.damping.friction) return;
      event = [this](const State& y) { return body_.damping.friction - std::abs(Variables::gyroscopic(body_, y)); };
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
    equations_.mode = next_friction_mode(body_.damping, mode, Variables::gyroscopic(body_, y));
    x_ = y;
    t_ = t_event;
    equations_(x_, dxdt_, t_);
    if (monitor_) ++monitor_.summary().rhs_evaluations;
  }

  const Body& body_;
  Equations equations_;
  Controlled controlled_;
  std::size_t max_steps_;
  StepMonitor<NonlinearSummary> monitor_;
  double horizon_;  // s, where the run ends
  std::size_t attempts_ = 0;
  // The current state (x_, dxdt_ at t_), the last step's start and its end (end_*: the
  // continuous extension's ends, which an event leaves in place while t_ moves back).
  State x_, dxdt_{}, x_old_{}, dxdt_old_{}, end_x_{}, end_dxdt_{};
  double t_ = 0.0, t_old_ = 0.0, end_t_ = 0.0, dt_ = 0.0;
};

}  // namespace heavytop::detail

#pragma once
// Private to the library: Rosenbrock 4 (rosenbrock4.hpp, Boost.Odeint's) behind Dop853Stepper's
// face, so that one event loop serves both: the stiff equations of a body sliding on a table
// under the viscous law at a small slip_speed, where an explicit method's step is held by
// stability, not accuracy.
//
// System: Dop853Stepper's void(const State& y, State& dydt, double t), and
//   void jacobian(const State& y, Eigen::Matrix<double, N, N>& J) const   (exact, e.g. the complex step)
// Hooks: Dop853Stepper's (project() is not called: odeint owns the state; the systems normalise
// what they read).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include <Eigen/Core>

#include "heavytop/nonlinear.hpp"
#include "integrators/integration.hpp"
#include "integrators/rosenbrock/rosenbrock4.hpp"

namespace heavytop::detail {

template <std::size_t N, class System, class Hooks>
class RosenbrockStepper {
 public:
  using State = std::array<double, N>;
  static constexpr int kN = static_cast<int>(N);

  RosenbrockStepper(System system, const State& x0, double horizon, const Tolerances& options, Hooks hooks = {})
      : system_(std::move(system)), hooks_(std::move(hooks)), horizon_(horizon), max_steps_(options.max_steps),
        y_(x0), y_old_(x0),
        method_(N, [this](const double* y, double* f) { rates(y, f); },
                [this](const double* y, double* J) { jacobian(y, J); }, x0.data(), initial_step(x0, options),
                options.atol, options.rtol) {}

  double time() const { return t_; }
  double previous_time() const { return t_old_; }
  const State& state() const { return y_; }
  const State& previous_state() const { return y_old_; }

  void step() {
    if (steps_ >= max_steps_) fail("rosenbrock4", StepOutcome::MaxSteps, t_, max_steps_);
    // The last step ends at the horizon: odeint's dense output does not stop there by itself.
    if (method_.time() + method_.next_step() > horizon_) method_.set_next_step(horizon_ - method_.time());
    if (!(method_.time() + method_.next_step() > method_.time()))
      fail("rosenbrock4", StepOutcome::StepUnderflow, t_);
    ++steps_;
    std::pair<double, double> span;
    try {
      span = method_.step();
    } catch (const RunFailure&) {
      throw;
    } catch (const std::runtime_error&) {  // odeint's 500 rejections in a row
      fail("rosenbrock4", StepOutcome::StepUnderflow, t_);
    }
    t_old_ = span.first;
    t_ = std::min(span.second, horizon_);
    y_old_ = y_;
    std::copy(method_.state(), method_.state() + N, y_.begin());
    if (!std::all_of(y_.begin(), y_.end(), [](double v) { return std::isfinite(v); }))
      fail("rosenbrock4", StepOutcome::NotFinite, t_old_);
    hooks_.accepted(t_, y_, evaluations_);
  }

  // The state at t in [t_old, t] from the method's order-3 continuous extension.
  void interpolate(double t, State& out) {
    if (t == t_) {
      out = y_;
      return;
    }
    method_.state_at(t, out.data());
  }

 private:
  void rates(const double* y, double* f) {
    State x, dx;
    std::copy(y, y + N, x.begin());
    system_(x, dx, 0.0);
    ++evaluations_;
    std::copy(dx.begin(), dx.end(), f);
  }
  void jacobian(const double* y, double* J) {
    State x;
    std::copy(y, y + N, x.begin());
    Eigen::Matrix<double, kN, kN, Eigen::RowMajor> jac;
    Eigen::Matrix<double, kN, kN> col;
    system_.jacobian(x, col);
    jac = col;
    std::copy(jac.data(), jac.data() + N * N, J);
  }

  // Hairer's first guess, 0.01 |y| / |f| in the tolerances' norm, within the horizon.
  double initial_step(const State& y, const Tolerances& options) {
    State f;
    system_(y, f, 0.0);
    ++evaluations_;
    double d0 = 0.0, d1 = 0.0;
    for (int i = 0; i < kN; ++i) {
      const double sc = options.atol + options.rtol * std::abs(y[i]);
      d0 += (y[i] / sc) * (y[i] / sc);
      d1 += (f[i] / sc) * (f[i] / sc);
    }
    const double h = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * std::sqrt(d0 / d1);
    return horizon_ > 0.0 ? std::min(h, horizon_) : h;
  }

  System system_;
  Hooks hooks_;
  double horizon_;
  std::size_t max_steps_;
  std::size_t steps_ = 0, evaluations_ = 0;
  State y_, y_old_;
  double t_ = 0.0, t_old_ = 0.0;
  Rosenbrock4Dense method_;  // last: its first step guess reads system_
};

}  // namespace heavytop::detail

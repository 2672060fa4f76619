#pragma once
// Private to the library: Dormand & Prince's 8(5,3) with its 7th-order dense output over any
// autonomous system of N equations: the one DOP853 of the rigid body on a pivot (dop853.cpp)
// and of the body on a table (table/). Hairer's step-size control (safety 0.9, factor in
// [1/3, 6], no PI term) and his initial-step guess; the dense output's extra stages are
// computed only for steps that are sampled.
//
// System: void(const State& y, State& dydt, double t), t unused.
// Hooks (what a body adds to the method, nothing at all by default):
//   void project(State& y, State& dydt)      at each step's start (e.g. |q| = 1, rate scaled too)
//   void rejected()                          a step was rejected
//   void accepted(double t, const State& y, std::size_t evaluations)
//   void evaluated(std::size_t evaluations)  after an interpolation's extra stages

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "heavytop/nonlinear.hpp"
#include "integrators/dop853/dop853_tableau.hpp"
#include "integrators/integration.hpp"

namespace heavytop::detail {

struct NoDop853Hooks {
  template <class State>
  void project(State&, State&) {}
  void rejected() {}
  template <class State>
  void accepted(double, const State&, std::size_t) {}
  void evaluated(std::size_t) {}
};

template <std::size_t N, class System, class Hooks = NoDop853Hooks>
class Dop853Stepper {
 public:
  using State = std::array<double, N>;
  static constexpr int kN = static_cast<int>(N);

  Dop853Stepper(System system, const State& x0, double horizon, const Tolerances& options, Hooks hooks = {})
      : system_(std::move(system)), hooks_(std::move(hooks)), rtol_(options.rtol), atol_(options.atol),
        horizon_(horizon), max_steps_(options.max_steps), y_(x0) {
    system_(y_, k_[0], 0.0);
    evaluations_ = 1;
    h_ = initial_step();
  }

  double time() const { return t_; }
  double previous_time() const { return t_old_; }
  const State& state() const { return y_; }
  const State& previous_state() const { return y_old_; }
  std::size_t evaluations() const { return evaluations_; }
  Hooks& hooks() { return hooks_; }
  const System& system() const { return system_; }

  void step() {
    hooks_.project(y_, k_[0]);
    k_old_ = k_[0];
    y_old_ = y_;
    t_old_ = t_;
    dense_ready_ = false;
    int rejections = 0;
    bool rejected = false;
    for (;;) {
      if (attempts_ >= max_steps_)
        fail("dop853", StepOutcome::MaxSteps, t_, max_steps_);
      const double left = horizon_ - t_old_;
      double h = h_;
      const bool last = left > 0.0 && !(h < left);
      if (last) h = left;
      if (!(t_old_ + h > t_old_))
        fail("dop853", StepOutcome::StepUnderflow, t_old_);
      ++attempts_;
      const double err = attempt(h);
      const double fac11 = std::pow(err, 1.0 / 8.0);
      if (err <= 1.0) {
        double hnew = h / std::clamp(fac11 / 0.9, 1.0 / 6.0, 1.0 / 0.333);
        if (rejected) hnew = std::min(hnew, h);
        if (!std::all_of(y_new_.begin(), y_new_.end(), [](double v) { return std::isfinite(v); }))
          fail("dop853", StepOutcome::NotFinite, t_old_);
        h_done_ = h;
        h_ = last ? std::max(h_, hnew) : hnew;
        t_ = last ? horizon_ : t_old_ + h;
        y_ = y_new_;
        k_[0] = k_[12];  // first same as last
        break;
      }
      hooks_.rejected();
      if (++rejections > 100 || !std::isfinite(err))
        fail("dop853", StepOutcome::StepUnderflow, t_old_);
      rejected = true;
      h_ = h / std::min(1.0 / 0.333, fac11 / 0.9);
    }
    hooks_.accepted(t_, y_, evaluations_);
  }

  // The state at t in [t_old, t] from the 7th-order continuous extension.
  void interpolate(double t, State& out) {
    if (t == t_) {
      out = y_;
      return;
    }
    if (!dense_ready_) prepare_dense();
    const double s = (t - t_old_) / h_done_, s1 = 1.0 - s;
    for (int i = 0; i < kN; ++i)
      out[i] = y_old_[i] + s * (f_[0][i] + s1 * (f_[1][i] + s * (f_[2][i] + s1 * (f_[3][i] + s * (f_[4][i] +
                              s1 * (f_[5][i] + s * f_[6][i]))))));
    hooks_.evaluated(evaluations_);
  }

 private:
  // One attempt of size h from (t_old_, y_old_, k_[0]): y_new_, k_[1..12], the error norm.
  double attempt(double h) {
    namespace tab = dop853;
    State y;
    for (int s = 1; s < tab::kStages; ++s) stage(s, h, y);
    for (int i = 0; i < kN; ++i) {
      double sum = 0.0;
      for (int j = 0; j < tab::kStages; ++j) sum += tab::a[12][j] * k_[j][i];
      y_new_[i] = y_old_[i] + h * sum;
    }
    system_(y_new_, k_[12], 0.0);
    evaluations_ += 12;
    double err5 = 0.0, err3 = 0.0;
    for (int i = 0; i < kN; ++i) {
      const double sc = atol_ + rtol_ * std::max(std::abs(y_old_[i]), std::abs(y_new_[i]));
      double e5 = 0.0, bsum = 0.0;
      for (int j = 0; j < tab::kStages; ++j) {
        e5 += tab::e5[j] * k_[j][i];
        bsum += tab::a[12][j] * k_[j][i];
      }
      const double e3 = bsum - tab::bhh0 * k_[0][i] - tab::bhh8 * k_[8][i] - tab::bhh11 * k_[11][i];
      err5 += (e5 / sc) * (e5 / sc);
      err3 += (e3 / sc) * (e3 / sc);
    }
    double deno = err5 + 0.01 * err3;
    if (!(deno > 0.0)) deno = 1.0;
    return std::abs(h) * err5 / std::sqrt(kN * deno);
  }

  void stage(int s, double h, State& y) {
    for (int i = 0; i < kN; ++i) {
      double sum = 0.0;
      for (int j = 0; j < s; ++j) sum += dop853::a[s][j] * dense_stage(j)[i];
      y[i] = y_old_[i] + h * sum;
    }
    system_(y, k_[s], 0.0);
  }

  void prepare_dense() {
    namespace tab = dop853;
    State y;
    for (int s = 13; s < tab::kDenseStages; ++s) stage(s, h_done_, y);
    evaluations_ += 3;
    const double h = h_done_;
    const State& f_old = k_old_;  // the step's first stage (k_[0] now holds f(y_new))
    for (int i = 0; i < kN; ++i) {
      const double dy = y_[i] - y_old_[i];
      f_[0][i] = dy;
      f_[1][i] = h * f_old[i] - dy;
      f_[2][i] = 2.0 * dy - h * (k_[12][i] + f_old[i]);
      for (int r = 0; r < 4; ++r) {
        double sum = 0.0;
        for (int j = 0; j < tab::kDenseStages; ++j) sum += tab::d[r][j] * dense_stage(j)[i];
        f_[3 + r][i] = h * sum;
      }
    }
    dense_ready_ = true;
  }

  // Stage j of the current step: k_[0] is overwritten by f(y_new) on acceptance (first same as
  // last), so the step's first stage is read from k_old_.
  const State& dense_stage(int j) const { return j == 0 ? k_old_ : k_[j]; }

  double initial_step() {
    // Hairer's hinit: h0 from |y| / |f|, one Euler step, then h1 from the second derivative.
    auto norm = [&](const State& v) {
      double s = 0.0;
      for (int i = 0; i < kN; ++i) {
        const double sc = atol_ + rtol_ * std::abs(y_[i]);
        s += (v[i] / sc) * (v[i] / sc);
      }
      return std::sqrt(s / kN);
    };
    const double d0 = norm(y_), d1 = norm(k_[0]);
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    if (horizon_ > 0.0) h0 = std::min(h0, horizon_);
    State y1, f1;
    for (int i = 0; i < kN; ++i) y1[i] = y_[i] + h0 * k_[0][i];
    system_(y1, f1, 0.0);
    ++evaluations_;
    for (int i = 0; i < kN; ++i) f1[i] -= k_[0][i];
    const double d2 = norm(f1) / h0;
    const double big = std::max(d1, d2);
    const double h1 = big <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / big, 1.0 / 8.0);
    double h = std::min(100.0 * h0, h1);
    if (horizon_ > 0.0) h = std::min(h, horizon_);
    return h;
  }

  System system_;
  Hooks hooks_;
  double rtol_, atol_, horizon_;
  std::size_t max_steps_;
  std::size_t attempts_ = 0, evaluations_ = 0;
  State y_, y_old_{}, y_new_{}, k_old_{};
  std::array<State, dop853::kDenseStages> k_{};
  std::array<State, 7> f_{};
  bool dense_ready_ = false;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_done_ = 0.0;
};

}  // namespace heavytop::detail

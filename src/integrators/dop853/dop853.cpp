#include "heavytop/dop853.hpp"
#include "heavytop/frames.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "heavytop/rigid_body.hpp"

#include "integrators/dop853/dop853_tableau.hpp"
#include "integrators/integration.hpp"
#include "integrators/monitor.hpp"
#include "integrators/sampling.hpp"
#include "integrators/tilt_scan.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

namespace {

namespace tab = detail::dop853;
using State = RigidBodyVector;
constexpr int kN = 7;

// DOP853 with Hairer's step-size control (safety 0.9, factor in [1/3, 6], no PI term) and
// his initial-step guess; the dense output's extra stages are computed only for steps that
// are sampled.
class Dop853 {
 public:
  using State = heavytop::State;
  Dop853(const Body& body, const State& x0, double horizon, const Tolerances& options,
         NonlinearSummary* summary)
      : body_(body), system_{body}, rtol_(options.rtol), atol_(options.atol), horizon_(horizon),
        max_steps_(options.max_steps), summary_(summary), monitor_(summary), y_(x0) {
    system_(y_, k_[0], 0.0);
    evaluations_ = 1;
    h_ = initial_step();
    if (monitor_) monitor_.start(body.A == body.B, scales_of(body, from_vector(x0)), conserved(x0));
  }

  double time() const { return t_; }
  double previous_time() const { return t_old_; }

  void step() {
    normalise();
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
      if (summary_) ++summary_->rejected_steps;
      if (++rejections > 100 || !std::isfinite(err))
        fail("dop853", StepOutcome::StepUnderflow, t_old_);
      rejected = true;
      h_ = h / std::min(1.0 / 0.333, fac11 / 0.9);
    }
    if (summary_) {
      summary_->rhs_evaluations = evaluations_;
      monitor_.note_step(t_, conserved(y_));
    }
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
    if (summary_) summary_->rhs_evaluations = evaluations_;
  }

 private:
  // One attempt of size h from (t_old_, y_old_, k_[0]): y_new_, k_[1..12], the error norm.
  double attempt(double h) {
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
      for (int j = 0; j < s; ++j) sum += tab::a[s][j] * dense_stage(j)[i];
      y[i] = y_old_[i] + h * sum;
    }
    system_(y, k_[s], 0.0);
  }

  void prepare_dense() {
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

  // q and its rate k_[0] back onto |q| = 1 (renormalise_quaternion), the step's first stage kept.
  void normalise() {
    monitor_.note_norm(renormalise_quaternion(y_, k_[0]));
    k_old_ = k_[0];
  }

  ConservedQuantities conserved(const State& x) const { return conserved_quantities(body_, from_vector(x)); }

  const Body& body_;
  RigidBodySystem system_;
  double rtol_, atol_, horizon_;
  std::size_t max_steps_;
  NonlinearSummary* summary_;
  StepMonitor<NonlinearSummary> monitor_;
  std::size_t attempts_ = 0, evaluations_ = 0;
  State y_, y_old_{}, y_new_{}, k_old_{};
  std::array<State, tab::kDenseStages> k_{};
  std::array<State, 7> f_{};
  bool dense_ready_ = false;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_done_ = 0.0;
};


// Tilt acos(k_zeta) and d(k_zeta)/dt of the plain state: k_zeta = gamma_3, with gamma = R(q)^T
// e_zeta in body axes and gamma' = gamma x w, so d(gamma_3)/dt = gamma_1 w2 - gamma_2 w1.
struct TiltOf {
  double g1, g2, g3;
  explicit TiltOf(const State& x) {
    const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
    const double inv = 1.0 / (qw * qw + qx * qx + qy * qy + qz * qz);
    g1 = 2.0 * (qx * qz - qw * qy) * inv, g2 = 2.0 * (qy * qz + qw * qx) * inv;
    g3 = (qw * qw - qx * qx - qy * qy + qz * qz) * inv;
  }
  double tilt() const { return tilt_of_axis(g1, g2, g3); }
  double rate(const State& x) const { return g1 * x[5] - g2 * x[4]; }
};

// nonlinear.cpp's scan_tilt on DOP853's dense output: extrema at the roots of d(k_zeta)/dt,
// the crossing of stop_above located by TOMS 748.
TiltExtremes scan_tilt(const Body& body, const State& x0, double horizon, double stop_above,
                       const Tolerances& options, const Progress& progress) {
  const TiltRecord start = start_tilt_scan(TiltOf(x0).tilt(), x0[6], stop_above);
  if (start.e.exceeded || horizon == 0.0) return start.e;
  Dop853 integrator(body, x0, horizon, options, nullptr);
  auto tilt = [](const State& x) { return TiltOf(x).tilt(); };
  auto rate = [](const State& x) { return TiltOf(x).rate(x); };
  return scan_tilt_extremes(integrator, horizon, start, DenseOutputEvents<State, decltype(tilt), decltype(rate)>(x0, tilt, rate),
                            [](const State& x) { return x[6]; }, progress);
}

}  // namespace

TiltExtremes dop853_tilt_extremes(const Body& body, const InitialState& initial, double horizon, double stop_above,
                                  const Tolerances& options, const Progress& progress) {
  validate(body);
  refuse_general(body, "dop853 (use dopri5 or auto)");
  detail::refuse_damping(body, "dop853");
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  return scan_tilt(body, to_vector(initial_rigid_body_state(initial)), horizon, stop_above, options, progress);
}

void detail::stream_dop853(const Body& body, const InitialState& initial, const SampleStream& samples,
                           const Tolerances& options, NonlinearSummary* summary) {
  validate(body);
  refuse_general(body, "dop853 (use dopri5 or auto)");
  detail::refuse_damping(body, "dop853");
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  const double horizon = samples.horizon();
  Dop853 integrator(body, to_vector(rb0), horizon, options, summary);
  write_samples(integrator, body, rb0, conserved_quantities(body, rb0), false, samples,
                [&body](const State& x) {
                  const RigidBodyState rb = from_vector(x);
                  return sample_of(rb, conserved_quantities(body, rb));
                });
}

Trajectory simulate_dop853(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const Tolerances& options, NonlinearSummary* summary, const Progress& progress) {
  return gathered(times, progress, [&](const SampleStream& samples) {
    detail::stream_dop853(body, initial, samples, options, summary);
  });
}

}  // namespace heavytop

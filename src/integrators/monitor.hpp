#pragma once
// Private to the library: the step monitor every integrator of the nonlinear model keeps when a
// summary is asked for (dopri5, the general body's dopri5, DOP853, Taylor; the splitting's grid
// drifts too): the summary reset at the start, the drift of E, L_zeta and C w3 against the
// run's scales after each step, the quaternion's norm error at each renormalisation, and the
// renormalisation itself (one formula for every integrator that keeps q in slots 0..3).

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "heavytop/nonlinear.hpp"

#include "integrators/integration.hpp"

namespace heavytop::detail {

// q back onto |q| = 1 before a step: slots 0..3 of x divided by their norm, and the same slots
// of each of `rates` alike (q' is linear in q, and the other rates depend on q's direction
// only). Returns the norm it had (the monitor's norm error).
template <class State, class... Rates>
double renormalise_quaternion(State& x, Rates&... rates) {
  const double norm = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]);
  for (int i = 0; i < 4; ++i) {
    x[i] /= norm;
    ((rates[i] /= norm), ...);
  }
  return norm;
}

// The drifts of one run into `summary` (NonlinearSummary, or SplittingSummary for the grid),
// nothing at all without one: start() resets the summary and keeps the scales and the initial
// first integrals; note_step() counts an accepted step at t and raises the drifts to those of q.
template <class Summary>
class StepMonitor {
 public:
  explicit StepMonitor(Summary* summary) : summary_(summary) {}

  explicit operator bool() const { return summary_ != nullptr; }
  Summary& summary() const { return *summary_; }

  void start(bool symmetric, const Scales& scales, const ConservedQuantities& initial) {
    if (!summary_) return;
    *summary_ = Summary{};
    summary_->symmetric = symmetric;
    scales_ = scales;
    initial_ = initial;
  }

  void note_norm(double norm) {
    if (summary_)
      summary_->max_quaternion_norm_error = std::max(summary_->max_quaternion_norm_error, std::abs(norm - 1.0));
  }

  // Call only when summary() is set (`q` is computed for the monitor alone).
  void note_step(double t, const ConservedQuantities& q) {
    ++summary_->steps;
    summary_->final_time = t;
    note_drift(*summary_, q, initial_, scales_);
  }

 private:
  Summary* summary_;
  Scales scales_;
  ConservedQuantities initial_;
};

}  // namespace heavytop::detail

#pragma once
// Private to the library: the one scan of tilt_extremes() for every integrator of the nonlinear
// model (dopri5, the general body's, DOP853, Taylor), and the events it looks for in a step.
//
// The contract (nonlinear.hpp's tilt_extremes): the tilt's extrema over [0, horizon], each
// located inside its step (a root of d(k_zeta)/dt), and the scan's end at the first crossing of
// stop_above (located inside its step to 1e-15 of the step), with the spin there.
//
// How a stepper finds a step's events is its capability: DenseOutputEvents (below) looks for
// them on the continuous extension by TOMS 748 (dopri5, DOP853); the Taylor integrator finds
// them as roots of the step's own series (taylor.cpp's SeriesEvents). Either notes what it
// finds through `note` and returns the crossing's time, or -1 if the step has none.
//
// At a crossing both note the crossing itself: max_tilt and t_max are the tilt there (stop_above
// to the root's tolerance) and its time, which is t_end; spin_at_end is w.k there.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include <boost/math/tools/toms748_solve.hpp>

#include "heavytop/nonlinear.hpp"
#include "integrators/integration.hpp"

namespace heavytop::detail {

// The extremes so far: note(t, tilt) keeps the smallest and largest tilt and their times; the
// events compare a tilt with stop_above themselves, before they note it.
struct TiltRecord {
  TiltExtremes e;
  double stop_above;
  void note(double t, double tilt) {
    if (tilt < e.min_tilt) e.min_tilt = tilt, e.t_min = t;
    if (tilt > e.max_tilt) e.max_tilt = tilt, e.t_max = t;
  }
};

// The scan's start: the tilt (rad) and the spin w.k (rad/s) at t = 0, and the scan's result
// already if it is over there (the start past stop_above, or no horizon): then no stepper need
// be built.
inline TiltRecord start_tilt_scan(double tilt0, double spin0, double stop_above) {
  TiltRecord r{{}, stop_above};
  r.e.min_tilt = r.e.max_tilt = tilt0;
  r.e.exceeded = tilt0 > stop_above;
  r.e.spin_at_end = spin0;
  return r;
}

// The one loop: steps `stepper` (step(), time(), previous_time(), interpolate(t, x)) over
// [0, horizon] from `record` (start_tilt_scan's), each step's events found by
// events(stepper, t0, t1, record) (the crossing's time, or -1); spin(x) is w.k (rad/s) for
// spin_at_end. `progress`, if set, gets the time every kStepsPerProgress steps and at the end.
template <class Stepper, class Events, class Spin>
TiltExtremes scan_tilt_extremes(Stepper& stepper, double horizon, TiltRecord record, Events&& events, Spin spin,
                                const Progress& progress = {}) {
  typename Stepper::State y;
  for (std::size_t steps = 1; stepper.time() < horizon; ++steps) {
    stepper.step();
    if (progress && steps % kStepsPerProgress == 0) progress(std::min(stepper.time(), horizon));
    const double crossing =
        events(stepper, stepper.previous_time(), std::min(stepper.time(), horizon), record);
    if (crossing >= 0.0) {
      stepper.interpolate(crossing, y);
      record.e.exceeded = true;
      record.e.t_end = crossing;
      record.e.spin_at_end = spin(y);
      if (progress) progress(crossing);
      return record.e;
    }
  }
  record.e.t_end = horizon;
  stepper.interpolate(std::min(stepper.time(), horizon), y);
  record.e.spin_at_end = spin(y);
  if (progress) progress(horizon);
  return record.e;
}

// A step's events on the continuous extension: a sign change of d(k_zeta)/dt between the
// step's ends is an extremum (its time to ~1e-12 of the step by TOMS 748; the tilt's error is
// quadratic in it), noted, then the step's end; the first of them past stop_above ends the
// scan at the crossing before it (TOMS 748 to 1e-15 of the width). tilt(x) is the tilt (rad),
// rate(x) is d(k_zeta)/dt (1/s).
template <class State, class Tilt, class Rate>
class DenseOutputEvents {
 public:
  DenseOutputEvents(const State& x0, Tilt tilt, Rate rate) : tilt_(tilt), rate_(rate), rate_old_(rate(x0)) {}

  template <class Stepper>
  double operator()(Stepper& stepper, double t0, double t1, TiltRecord& record) {
    stepper.interpolate(t1, x_);
    const double rate_new = rate_(x_);
    if ((rate_old_ < 0.0 && rate_new > 0.0) || (rate_old_ > 0.0 && rate_new < 0.0)) {
      auto rate_at = [&](double t) {
        stepper.interpolate(t, y_);
        return rate_(y_);
      };
      const double width = t1 - t0;
      std::uintmax_t iterations = 60;
      const auto bracket = boost::math::tools::toms748_solve(
          rate_at, t0, t1, rate_old_, rate_new,
          [width](double a, double b) { return std::abs(b - a) <= 1e-12 * width; }, iterations);
      const double tr = 0.5 * (bracket.first + bracket.second);
      stepper.interpolate(tr, y_);
      const double tilt_r = tilt_(y_);
      if (tilt_r > record.stop_above) return stop_at(stepper, t0, tr, record);
      record.note(tr, tilt_r);
    }
    if (tilt_(x_) > record.stop_above) return stop_at(stepper, t0, t1, record);
    record.note(t1, tilt_(x_));
    rate_old_ = rate_new;
    return -1.0;
  }

 private:
  // The scan's end: the first time in [t0, t_hi] the tilt passes stop_above (below at t0,
  // past it at t_hi), noted with its tilt as the series' scan notes its own crossing.
  template <class Stepper>
  double stop_at(Stepper& stepper, double t0, double t_hi, TiltRecord& record) {
    auto excess = [&](double t) {
      stepper.interpolate(t, y_);
      return tilt_(y_) - record.stop_above;
    };
    const double below = excess(t0), above = excess(t_hi);
    double t_cross = t0;
    if (below < 0.0 && above > 0.0) {
      std::uintmax_t iterations = 100;
      const double width = t_hi - t0;
      t_cross = boost::math::tools::toms748_solve(
                    excess, t0, t_hi, below, above,
                    [width](double lo, double hi) { return std::abs(hi - lo) <= 1e-15 * width; }, iterations)
                    .second;
    }
    stepper.interpolate(t_cross, y_);
    record.note(t_cross, tilt_(y_));
    return t_cross;
  }

  Tilt tilt_;
  Rate rate_;
  double rate_old_;
  State x_{}, y_{};
};

}  // namespace heavytop::detail

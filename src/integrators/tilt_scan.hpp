#pragma once
// Private to the library: the scan of tilt_extremes() on any integrator with a continuous
// extension (nonlinear.cpp's dopri5, dop853.cpp): the tilt's extrema at the roots of
// d(k_zeta)/dt inside a step, and the first crossing of stop_above, both located by TOMS 748
// on the dense output.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include <boost/math/tools/toms748_solve.hpp>

#include "heavytop/nonlinear.hpp"
#include "integrators/integration.hpp"

namespace heavytop::detail {

// Scans [0, horizon] from x0 (tilt(x0) <= stop_above, horizon > 0). `integrator` has step(),
// time(), previous_time() and interpolate(t, x); tilt(x) is the tilt (rad), rate(x) is
// d(k_zeta)/dt, spin(x) is w.k (rad/s). `progress`, if set, gets the time every
// kStepsPerProgress steps.
template <class Stepper, class State, class Tilt, class Rate, class Spin>
TiltExtremes scan_tilt_extremes(Stepper& integrator, const State& x0, double horizon, double stop_above, Tilt tilt,
                                Rate rate, Spin spin, const std::function<void(double)>& progress = {}) {
  TiltExtremes e;
  e.min_tilt = e.max_tilt = tilt(x0);
  auto note = [&](double t, const State& x) {
    const double now = tilt(x);
    if (now < e.min_tilt) e.min_tilt = now, e.t_min = t;
    if (now > e.max_tilt) e.max_tilt = now, e.t_max = t;
    return now > stop_above;
  };
  State y;
  // The first time in [t0, t_hi] the tilt passes stop_above (it is below at t0): the scan's end.
  auto stop_at_crossing = [&](double t0, double t_hi) {
    auto excess = [&](double t) {
      integrator.interpolate(t, y);
      return tilt(y) - stop_above;
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
    integrator.interpolate(t_cross, y);
    e.exceeded = true;
    e.t_end = t_cross;
    e.spin_at_end = spin(y);
    return e;
  };
  double rate_old = rate(x0);
  State x;
  for (std::size_t steps = 1; integrator.time() < horizon; ++steps) {
    integrator.step();
    if (progress && steps % kStepsPerProgress == 0) progress(std::min(integrator.time(), horizon));
    const double t0 = integrator.previous_time();
    const double t1 = std::min(integrator.time(), horizon);
    integrator.interpolate(t1, x);
    const double rate_new = rate(x);
    // A sign change of d(k_zeta)/dt inside the step is an extremum of the tilt: find it on
    // the dense output (its time to ~1e-12 of the step; the tilt error is quadratic in it).
    if ((rate_old < 0.0 && rate_new > 0.0) || (rate_old > 0.0 && rate_new < 0.0)) {
      auto rate_at = [&](double t) {
        integrator.interpolate(t, y);
        return rate(y);
      };
      const double width = t1 - t0;
      std::uintmax_t iterations = 60;
      const auto bracket = boost::math::tools::toms748_solve(
          rate_at, t0, t1, rate_old, rate_new,
          [width](double a, double b) { return std::abs(b - a) <= 1e-12 * width; }, iterations);
      const double tr = 0.5 * (bracket.first + bracket.second);
      integrator.interpolate(tr, y);
      if (note(tr, y)) return stop_at_crossing(t0, tr);
    }
    if (note(t1, x)) return stop_at_crossing(t0, t1);
    rate_old = rate_new;
  }
  e.t_end = horizon;
  integrator.interpolate(std::min(integrator.time(), horizon), x);
  e.spin_at_end = spin(x);
  return e;
}

}  // namespace heavytop::detail

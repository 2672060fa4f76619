// The Taylor-series integrator (taylor.hpp) and DOP853 (dop853.hpp): each against the exact
// solution (lagrange-exact, A = B) and against the other (different method, different
// variables for A = B), the Taylor integrator's events against bisection on its dense output,
// its energy over 1e5 nutation periods, DOP853's order (its tableau), the selection in
// simulate(). Every bound says what it was measured at (Release, GCC 12, x86-64).

#include "heavytop/dop853.hpp"
#include "heavytop/taylor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/simulate.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;
using test_support::make_state;
using test_support::sci;

// rad, max over the samples of |theta - theta_ref| and |phi - phi_ref|.
double max_angle_error(const Trajectory& a, const Trajectory& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    e = std::max({e, std::abs(a.theta[i] - b.theta[i]), std::abs(a.phi[i] - b.phi[i])});
  return e;
}

Tolerances tolerance(double tol) {
  Tolerances o;
  o.rtol = o.atol = tol;
  return o;
}

// The two benchmark problems of issue 14 (bench/bench_integrators.cpp).
Body toy_top() { return example_toy_top(); }
InitialState toy_start() { return make_state(200.0, 0.05); }
Body asymmetric_body() {
  Body b;
  b.A = 1.0, b.B = 1.5, b.C = 2.0, b.mass = 1.0, b.gravity = 9.81, b.length = 0.1;
  return b;
}
InitialState asymmetric_start() { return make_state(10.0, 0.2); }

// The examples of examples/*.toml (body, motion), with the horizon over which two integrators
// can agree to 1e-12: 10 s for the stable ones and for asymmetric-plate (it falls at ~33 s);
// equal-moments falls at once (below its threshold spin, e-folding in ~0.13 s): the rounding
// of the initial state grows with the motion in every route (over 1 s the two integrators
// agree to 1.7e-13 but both differ from lagrange-exact by 1.8e-12), so it is compared over 0.5 s.
struct Example {
  std::string name;
  Body body;
  InitialState start;
  double horizon;
};

std::vector<Example> examples() {
  auto body = [](double A, double B, double C, double m, double R) {
    Body b;
    b.A = A, b.B = B, b.C = C, b.mass = m, b.gravity = 9.81, b.length = R;
    return b;
  };
  InitialState lab = make_state(300.0, 0.02);
  lab.phi_rate0 = 0.1;
  return {
      {"toy_top", toy_top(), toy_start(), 10.0},
      {"lab_gyroscope", body(3.5125e-3, 3.5125e-3, 6.25e-4, 0.5, 0.08), lab, 10.0},
      {"hanging_gyroscope", body(3.5125e-3, 3.5125e-3, 6.25e-4, 0.5, -0.08), make_state(30.0, 0.1), 10.0},
      {"asymmetric_plate", body(0.010, 0.015, 0.020, 1.0, 1.0193679918450561e-3), make_state(1.3, 1e-4), 10.0},
      {"equal_moments", body(1e-3, 1e-3, 1e-3, 0.5, 0.02), make_state(12.0, 0.01), 0.5},
      {"asymmetric_benchmark", asymmetric_body(), asymmetric_start(), 20.0},
  };
}

// ---- Accuracy ----------------------------------------------------------------------------------

// The error against the exact motion (toy top, lagrange-exact) or DOP853 at 1e-15 (asymmetric
// body; DOP853 and the Taylor integrator at 1e-15 agree to 5.6e-15) over the benchmark
// horizons (10 s, 20 s), 201 samples, at tol = 1e-6 ... 1e-13: below 10 tol, and smaller at
// each tighter tolerance by at least 2x (measured: toy top 1.5e-7, 1.7e-10, 5.6e-13,
// 1.2e-14, 4.9e-15; asymmetric 4.2e-7, 1.6e-9, 3.3e-11, 7.5e-13, 1.4e-14, the last near the
// reference's own error).
TEST(Taylor, ErrorShrinksWithTheToleranceDownTo1e13) {
  const std::vector<double> toy_times = sample_times(10.0, 201), asym_times = sample_times(20.0, 201);
  const Trajectory exact = simulate_lagrange_exact(toy_top(), toy_start(), toy_times);
  const Trajectory reference = simulate_dop853(asymmetric_body(), asymmetric_start(), asym_times, tolerance(1e-15));
  double previous_toy = 1.0, previous_asym = 1.0;
  std::string record;
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12, 1e-13}) {
    const double toy =
        max_angle_error(simulate_taylor(toy_top(), toy_start(), toy_times, tolerance(tol)), exact);
    const double asym = max_angle_error(
        simulate_taylor(asymmetric_body(), asymmetric_start(), asym_times, tolerance(tol)), reference);
    // tol is per step; over hundreds of steps the global error is a few tol (dopri5's test
    // allows 10 tol too).
    EXPECT_LT(toy, 10 * tol) << "tol " << tol;
    EXPECT_LT(asym, 10 * tol) << "tol " << tol;
    EXPECT_LT(toy, previous_toy / 2) << "tol " << tol;
    EXPECT_LT(asym, previous_asym / 2) << "tol " << tol;
    previous_toy = toy, previous_asym = asym;
    record += sci(toy) + "/" + sci(asym) + " ";
  }
  RecordProperty("toy_asym_at_1e-6_1e-8_1e-10_1e-12_1e-13", record);
}

// Every example, 1001 samples over its horizon at tol = 1e-14: the Taylor integrator against
// DOP853 (plain variables; for A = B the Taylor integrator uses the spin-factored ones), and
// for A = B against lagrange-exact, within 1e-12 rad in theta and phi.
// Measured (Taylor-DOP853; Taylor-exact; DOP853-exact): toy top 2.0e-13, 3.0e-15, 2.0e-13;
// lab gyroscope 1.6e-13, 9.9e-16, 1.6e-13; hanging 7.5e-14, 4.7e-15, 7.4e-14; asymmetric
// plate 4.5e-15; equal moments 2.3e-14, 8.8e-14, 8.6e-14; asymmetric benchmark 4.2e-14.
TEST(Taylor, AgreesWithDop853AndLagrangeExactOnEveryExample) {
  for (const Example& e : examples()) {
    const std::vector<double> times = sample_times(e.horizon, 1001);
    TaylorSummary summary;
    const Trajectory taylor = simulate_taylor(e.body, e.start, times, tolerance(1e-14), &summary);
    const Trajectory dop853 = simulate_dop853(e.body, e.start, times, tolerance(1e-14));
    const double against_dop853 = max_angle_error(taylor, dop853);
    EXPECT_LT(against_dop853, 1e-12) << e.name;
    EXPECT_EQ(summary.variables, e.body.A == e.body.B ? TaylorVariables::SpinFactored : TaylorVariables::Plain);
    std::string record = sci(against_dop853);
    if (is_symmetric(e.body)) {
      const Trajectory exact = simulate_lagrange_exact(e.body, e.start, times);
      const double t = max_angle_error(taylor, exact), d = max_angle_error(dop853, exact);
      EXPECT_LT(t, 1e-12) << e.name;
      EXPECT_LT(d, 1e-12) << e.name;
      record += " exact " + sci(t) + " dop853-exact " + sci(d);
    }
    RecordProperty(e.name, record);
  }
}

// The dense output is the series of the step: sampling does not move the steps. The state at
// 5 s is the same bit for bit whether 3 or 1001 samples are asked over the same 10 s.
TEST(Taylor, SamplingDoesNotChangeTheSteps) {
  for (const Body& body : {toy_top(), asymmetric_body()}) {
    const InitialState s = body.A == body.B ? toy_start() : asymmetric_start();
    const Trajectory few = simulate_taylor(body, s, {0.0, 5.0, 10.0}, tolerance(1e-12));
    const Trajectory many = simulate_taylor(body, s, sample_times(10.0, 1001), tolerance(1e-12));
    EXPECT_EQ(few.theta[1], many.theta[500]);
    EXPECT_EQ(few.phi[1], many.phi[500]);
    EXPECT_EQ(few.theta[2], many.theta[1000]);
  }
}

// ---- Events ------------------------------------------------------------------------------------

// d(k_zeta)/dt from a sample's angles and rates: k_zeta = cos(phi) cos(theta) (SPEC section 2).
double tilt_cos_rate(const Trajectory& tr, std::size_t i) {
  return -std::sin(tr.phi[i]) * std::cos(tr.theta[i]) * tr.phi_rate[i] -
         std::cos(tr.phi[i]) * std::sin(tr.theta[i]) * tr.theta_rate[i];
}
double tilt(const Trajectory& tr, std::size_t i) {
  return std::acos(std::cos(tr.phi[i]) * std::cos(tr.theta[i]));
}

// Bisection on the dense output for the root of f(sample at t) in [a, b]: each evaluation is
// a run of simulate_taylor sampled at t (the same steps; the last is cut at t, which leaves
// its series unchanged).
template <class F>
double bisect_dense_output(const Body& body, const InitialState& s, const Tolerances& o, double a,
                           double b, const F& f) {
  auto at = [&](double t) { return f(simulate_taylor(body, s, {0.0, t}, o), 1); };
  double fa = at(a);
  EXPECT_LT(fa * at(b), 0.0) << "no bracket";
  for (int i = 0; i < 80 && b - a > 1e-15 * b; ++i) {
    const double m = 0.5 * (a + b), fm = at(m);
    if ((fm < 0.0) == (fa < 0.0)) a = m, fa = fm;
    else b = m;
  }
  return 0.5 * (a + b);
}

// The extrema of the tilt found on the series (roots of the series of d(k_zeta)/dt) equal
// those found by bisection on the dense output of d(k_zeta)/dt computed from the samples'
// angles and rates (another function of the same polynomials), to 1e-12 s; at tol = 1e-15.
// Toy top (spin-factored) over 1 s, asymmetric body (plain) over 3 s. Measured: 3.3e-16 s,
// 2.8e-17 s (toy top t_min, t_max); 6.7e-16, 1.6e-15 s (asymmetric). The extrema agree with
// tilt_extremes() (dopri5 at 1e-14, TOMS 748 on its dense output) to 1e-9 rad (their times
// are not compared: the motion touches the same bounds every period, and which touch is
// largest is decided by rounding).
TEST(TaylorEvents, TiltExtremaOnTheSeriesEqualBisectionOnTheDenseOutput) {
  struct Case {
    Body body;
    InitialState start;
    double horizon;
  };
  // Started with a tilt rate, so that neither extreme is the start itself.
  const InitialState toy = make_state(200.0, 0.05, 0.0, 0.1), asym = make_state(10.0, 0.2, 0.0, 0.1);
  for (const Case& c : {Case{toy_top(), toy, 1.0}, Case{asymmetric_body(), asym, 3.0}}) {
    const Tolerances o = tolerance(1e-15);
    const TiltExtremes e = taylor_tilt_extremes(c.body, c.start, c.horizon, 10.0, o);
    ASSERT_FALSE(e.exceeded);
    ASSERT_GT(e.t_min, 0.0);
    ASSERT_GT(e.t_max, 0.0);
    const double w = 1e-3;  // s, well inside half a nutation period (>= 0.07 s)
    const double t_min = bisect_dense_output(c.body, c.start, o, e.t_min - w, e.t_min + w, tilt_cos_rate);
    const double t_max = bisect_dense_output(c.body, c.start, o, e.t_max - w, e.t_max + w, tilt_cos_rate);
    EXPECT_NEAR(e.t_min, t_min, 1e-12);
    EXPECT_NEAR(e.t_max, t_max, 1e-12);
    const TiltExtremes d = tilt_extremes(c.body, c.start, c.horizon, 10.0, tolerance(1e-14));
    EXPECT_NEAR(e.min_tilt, d.min_tilt, 1e-9);
    EXPECT_NEAR(e.max_tilt, d.max_tilt, 1e-9);
    RecordProperty(c.body.A == c.body.B ? "toy_top_dt" : "asymmetric_dt",
                   sci(std::abs(e.t_min - t_min)) + " " + sci(std::abs(e.t_max - t_max)));
  }
}

// The fall of examples/asymmetric-plate.toml (1.3 rad/s, erratum E3): the time the tilt
// passes 1 rad, found on the series of k_zeta - cos(1), equals bisection on the dense
// output's tilt acos(cos(phi) cos(theta)) - 1 to 1e-12 s (measured 1.1e-14 s; crossing
// at 29.7 s), and tilt_extremes (dopri5 at 1e-14) to 1e-6 s (an unstable motion: the two
// integrations differ by 1e-8 rad there).
TEST(TaylorEvents, ThresholdCrossingOnTheSeriesEqualsBisection) {
  const Example plate = examples()[3];
  const Tolerances o = tolerance(1e-15);
  const TiltExtremes e = taylor_tilt_extremes(plate.body, plate.start, 60.0, 1.0, o);
  ASSERT_TRUE(e.exceeded);
  EXPECT_NEAR(e.max_tilt, 1.0, 1e-12);
  const double t = bisect_dense_output(plate.body, plate.start, o, e.t_end - 0.01, e.t_end + 0.01,
                                       [](const Trajectory& tr, std::size_t i) { return tilt(tr, i) - 1.0; });
  EXPECT_NEAR(e.t_end, t, 1e-12);
  RecordProperty("crossing_s", sci(e.t_end));
  RecordProperty("against_bisection_s", sci(std::abs(e.t_end - t)));
  const TiltExtremes d = tilt_extremes(plate.body, plate.start, 60.0, 1.0, tolerance(1e-14));
  ASSERT_TRUE(d.exceeded);
  // tilt_extremes stops at the first step end past the threshold: its t_end is later by up
  // to one step; the crossing itself lies inside its last step.
  EXPECT_GT(d.t_end, e.t_end - 1e-6);
  EXPECT_LT(d.t_end - e.t_end, 0.2);
}

// ---- Long runs ---------------------------------------------------------------------------------

// The long-run top of test_splitting (A = B = 1, C = 0.5, m g R = 1, spin 5, tilt 0.3, rate
// 0.1; nutation period 3.85 s) over 1e5 nutation periods (3.85e5 s) at tol = 1e-14: the
// largest relative energy drift over every step (the summary's) below 1e-12, L_zeta and C w3
// too. Measured: energy 6.4e-13, L_zeta 5.2e-13, C w3 0 (w3 is constant in the spin-factored
// variables), 509,807 steps of order 24; about 0.6 s in Release (no `long` label needed).
TEST(TaylorLongRun, EnergyDriftOver1e5NutationPeriodsBelow1e12) {
  const Body top = make_body(1.0, 1.0, 0.5, 1.0);
  const InitialState start = make_state(5.0, 0.3, 0.0, 0.1, 0.0);
  const double period = nutation_period(lagrange_top(top, start));
  TaylorSummary summary;
  simulate_taylor(top, start, {0.0, 1e5 * period}, tolerance(1e-14), &summary);
  EXPECT_LT(summary.work.max_relative_energy_drift, 1e-12);
  EXPECT_LT(summary.work.max_relative_vertical_momentum_drift, 1e-12);
  EXPECT_LT(summary.work.max_relative_axial_momentum_drift, 1e-12);
  RecordProperty("steps", std::to_string(summary.work.steps));
  RecordProperty("energy", sci(summary.work.max_relative_energy_drift));
  RecordProperty("vertical_momentum", sci(summary.work.max_relative_vertical_momentum_drift));
}

// ---- DOP853 ------------------------------------------------------------------------------------

// The steps of DOP853, whose controller scales the step by err^(-1/8) (the 8th-order solution's
// combined 5th/3rd-order error estimate), steps(1e-9) / steps(1e-12) -> 10^(3/8) = 2.37 (a 5th-order
// method: 10^(3/5) = 3.98). A wrong coefficient in the tableau lowers the order and moves the
// ratio (and the accuracy, next test). Measured 2.375 (toy top), 2.36 (asymmetric).
TEST(Dop853, StepsGrowAsTheEighthRootOfTheTolerance) {
  for (const Body& body : {toy_top(), asymmetric_body()}) {
    const InitialState s = body.A == body.B ? toy_start() : asymmetric_start();
    NonlinearSummary loose, tight;
    simulate_dop853(body, s, {0.0, 10.0}, tolerance(1e-9), &loose);
    simulate_dop853(body, s, {0.0, 10.0}, tolerance(1e-12), &tight);
    const double ratio = static_cast<double>(tight.steps) / static_cast<double>(loose.steps);
    EXPECT_NEAR(ratio, std::pow(10.0, 3.0 / 8.0), 0.15);
    RecordProperty(body.A == body.B ? "toy_top_ratio" : "asymmetric_ratio", sci(ratio));
  }
}

// DOP853 against the exact motion, 201 samples over 10 s of the toy top (dense output): error
// below 100 tol at 1e-8 ... 1e-14 (measured 1.8e-7, 1.7e-9, 1.7e-11, 2.0e-13: 17 tol, the
// global error of ~1e4 steps resolving the 200 rad/s spin in plain variables), and it counts
// its work: 12 evaluations per attempt, 3 per sampled step, 1 + 1 to start.
TEST(Dop853, ErrorFollowsTheTolerance) {
  const std::vector<double> times = sample_times(10.0, 201);
  const Trajectory exact = simulate_lagrange_exact(toy_top(), toy_start(), times);
  std::string record;
  for (double tol : {1e-8, 1e-10, 1e-12, 1e-14}) {
    NonlinearSummary summary;
    const double error =
        max_angle_error(simulate_dop853(toy_top(), toy_start(), times, tolerance(tol), &summary), exact);
    EXPECT_LT(error, 100 * tol) << tol;
    EXPECT_GE(summary.rhs_evaluations, 2 + 12 * (summary.steps + summary.rejected_steps));
    EXPECT_LE(summary.rhs_evaluations, 2 + 15 * (summary.steps + summary.rejected_steps));
    record += sci(error) + " ";
  }
  RecordProperty("errors_at_1e-8_1e-10_1e-12_1e-14", record);
}

// ---- Options, failures, selection --------------------------------------------------------------

TEST(Taylor, OrderFollowsTheMeasuredRule) {
  constexpr auto factored = TaylorVariables::SpinFactored, plain = TaylorVariables::Plain;
  EXPECT_EQ(taylor_order(tolerance(1e-6), factored), 15);   // ceil(13.82 + 1)
  EXPECT_EQ(taylor_order(tolerance(1e-3), factored), 8);    // ceil(6.91 + 1)
  EXPECT_EQ(taylor_order(tolerance(1e-12), factored), 24);  // ceil(27.63 + 1), clamped
  EXPECT_EQ(taylor_order(tolerance(1e-6), plain), 12);      // ceil(0.75 x 13.82 + 1)
  EXPECT_EQ(taylor_order(tolerance(1e-12), plain), 22);     // ceil(0.75 x 27.63 + 1)
  EXPECT_EQ(taylor_order(tolerance(1e-15), plain), 24);     // clamped
  EXPECT_EQ(taylor_order(tolerance(1.0), plain), 2);        // clamped
  Tolerances mixed;
  mixed.rtol = 1e-3, mixed.atol = 1e-6;
  EXPECT_EQ(taylor_order(mixed, plain), 12);
}

TEST(Taylor, RefusesBadInputAndFailsOnOneLine) {
  Tolerances bad;
  bad.rtol = std::nan("");
  try {
    simulate_taylor(toy_top(), toy_start(), {0.0, 1.0}, bad);
    ADD_FAILURE() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "rtol");
  }
  try {
    simulate_dop853(toy_top(), toy_start(), {0.0, 1.0}, bad);
    ADD_FAILURE() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "rtol");
  }
  EXPECT_THROW(simulate_taylor(toy_top(), toy_start(), {1.0, 0.5}), InvalidInput);
  EXPECT_THROW(taylor_tilt_extremes(toy_top(), toy_start(), -1.0), InvalidInput);
  Tolerances few = tolerance(1e-12);
  few.max_steps = 3;
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0) simulate_taylor(toy_top(), toy_start(), {0.0, 10.0}, few);
      else simulate_dop853(toy_top(), toy_start(), {0.0, 10.0}, few);
      ADD_FAILURE() << "did not fail";
    } catch (const InvalidInput&) {
      ADD_FAILURE() << "a numerical failure reported as bad input";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos);
      EXPECT_EQ(what.rfind(which == 0 ? "taylor: more than max_steps" : "dop853: more than max_steps", 0), 0u)
          << what;
    }
  }
  // A motion without torque or spin is a polynomial of low degree: one step to the horizon.
  Body free = toy_top();
  free.length = 0.0;
  TaylorSummary summary;
  const Trajectory rest = simulate_taylor(free, make_state(0.0, 0.3), {0.0, 5.0}, {}, &summary);
  EXPECT_EQ(summary.work.steps, 1u);
  EXPECT_NEAR(rest.theta[1], 0.3, 1e-15);
}

TEST(Integrators, NamesAndTheAutomaticChoice) {
  for (Integrator i : {Integrator::Adaptive, Integrator::Splitting, Integrator::Taylor, Integrator::Dop853,
                       Integrator::Auto})
    EXPECT_EQ(integrator_from_name(name(i)), i);
  EXPECT_EQ(name(Integrator::Adaptive), "dopri5");
  EXPECT_EQ(integrator_from_name("adaptive"), Integrator::Adaptive);
  EXPECT_FALSE(integrator_from_name("rk4"));
  EXPECT_EQ(SimulateOptions{}.integrator, Integrator::Auto);

  // The default (auto at rtol = atol = 1e-12) runs the Taylor integrator and reports it.
  const Simulation sim = simulate(Model::Nonlinear, toy_top(), toy_start(), {0.0, 1.0});
  ASSERT_TRUE(sim.summary.ok());
  EXPECT_EQ(sim.summary.solver, "Taylor, order 24, spin-factored variables");
  ASSERT_TRUE(sim.adaptive.has_value());
  EXPECT_EQ(sim.adaptive->steps, sim.summary.steps);
  SimulateOptions dop;
  dop.integrator = Integrator::Dop853;
  EXPECT_EQ(simulate(Model::Nonlinear, asymmetric_body(), asymmetric_start(), {0.0, 1.0}, dop).summary.solver,
            "Dormand-Prince 8(5,3)");
  // The measured rule: Taylor from 1e-2 down, and at any tolerance for A != B and for a
  // general body; dopri5 for a symmetric body at looser tolerances.
  Body general = toy_top();
  general.general.offset_x = 1e-4;
  for (double tol : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3, 1e-2}) {
    EXPECT_EQ(choose_integrator(toy_top(), tolerance(tol)), Integrator::Taylor) << tol;
    EXPECT_EQ(choose_integrator(asymmetric_body(), tolerance(tol)), Integrator::Taylor) << tol;
  }
  EXPECT_EQ(choose_integrator(toy_top(), tolerance(0.05)), Integrator::Adaptive);
  EXPECT_EQ(choose_integrator(asymmetric_body(), tolerance(0.05)), Integrator::Taylor);
  EXPECT_EQ(choose_integrator(general, tolerance(0.05)), Integrator::Taylor);
}

}  // namespace
}  // namespace heavytop

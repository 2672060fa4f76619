// The Taylor integrator on a damped body (SPEC section 6; taylor.hpp's DampedPlain variables):
// against dopri5's damped equations (another method, other variables), against the balances
// of energy and momentum its own quadratures must close, against the closed-form spin law
// of a symmetric body (damping.hpp), dry friction's stop and stick-slip included. Every bound
// says what it was measured at (Release, GCC 12, x86-64).

#include "heavytop/taylor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "heavytop/damping.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/simulate.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::angle_between;
using test_support::axis_of;
using test_support::column;
using test_support::make_body;
using test_support::make_state;
using test_support::sci;

Tolerances tolerance(double tol) {
  Tolerances o;
  o.rtol = o.atol = tol;
  return o;
}

Body with(Body b, Damping d) {
  b.damping = d;
  return b;
}

struct Case {
  std::string name;
  Body body;
  InitialState start;
};

// Two bodies (A != B, A = B), each with every kind of torque: transverse, axial, both, a
// motor, dry friction that stops the spin within the 10 s (C w0 / tau0 = 8 s and 6 s), and
// for A != B a stick-slip case: the gyroscopic torque (A - B) w1 w2 of a wide nutation frees
// the stopped spin again, which stops and sticks again: five changes of mode in the 10 s.
std::vector<Case> cases() {
  const Body asym = make_body(1.0, 1.5, 2.0, 1.0), sym = make_body(1.0, 1.0, 1.5, 1.0);
  std::vector<Case> out;
  for (const auto& [name, b] : {std::pair{std::string("asymmetric"), asym}, std::pair{std::string("symmetric"), sym}}) {
    const InitialState s = make_state(8.0, 0.2, 0.05);
    out.push_back({name + " transverse", with(b, {.transverse = 0.02}), s});
    out.push_back({name + " axial", with(b, {.axial = 0.05}), s});
    out.push_back({name + " both", with(b, {.transverse = 0.02, .axial = 0.05}), s});
    out.push_back({name + " driven", with(b, {.transverse = 0.02, .axial = 0.05, .friction = 0.03, .driven = true}), s});
    out.push_back({name + " friction stop", with(b, {.transverse = 0.01, .friction = 0.5}), make_state(2.0, 0.2, 0.05)});
  }
  out.push_back({"asymmetric stick-slip", with(asym, {.transverse = 0.002, .friction = 0.4}),
                 make_state(0.1, 0.6, 0.0, 0.6, 0.5)});
  return out;
}

Trajectory run(const Body& b, const InitialState& s, const std::vector<double>& times, bool taylor,
               TaylorSummary* summary = nullptr) {
  return taylor ? simulate_taylor(b, s, times, tolerance(1e-12), summary)
                : simulate_nonlinear(b, s, times, tolerance(1e-12));
}

// tol = 1e-12 both, 1001 samples over 10 s: the axis direction (rad) and w3 = L_3 / C (relative
// to the initial |w|) agree within 1e-9, and so do the three integrals of what the torques took
// away (relative to E's scale) and the motor's torque. Measured: axis 2.4e-12 to 3.0e-11 rad
// (the friction stops the largest), w3 below 3.9e-12, the integrals below 5.3e-12.
TEST(TaylorDamped, AgreesWithDopri5OnEveryTorque) {
  const std::vector<double> times = sample_times(10.0, 1001);
  std::string record;
  for (const Case& c : cases()) {
    TaylorSummary summary;
    const Trajectory ty = run(c.body, c.start, times, true, &summary);
    const Trajectory dp = run(c.body, c.start, times, false);
    ASSERT_EQ(ty.size(), dp.size());
    ASSERT_EQ(ty.extra.size(), dp.extra.size()) << c.name;  // the same damping columns
    for (std::size_t k = 0; k < ty.extra.size(); ++k) EXPECT_EQ(ty.extra[k].first, dp.extra[k].first);
    EXPECT_TRUE(summary.damped);
    EXPECT_EQ(summary.variables, c.body.A == c.body.B ? TaylorVariables::SpinFactored : TaylorVariables::Plain);
    const double w_scale = std::hypot(c.start.spin, 0.5 + std::abs(c.start.theta_rate0) + std::abs(c.start.phi_rate0));
    const double e_scale = std::abs(column(dp, "energy")[0]) + std::abs(c.body.mgR());
    double axis = 0.0, spin = 0.0, losses = 0.0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      axis = std::max(axis, angle_between(axis_of(ty.theta[i], ty.phi[i]), axis_of(dp.theta[i], dp.phi[i])));
      spin = std::max(spin, std::abs(column(ty, "axial_momentum")[i] - column(dp, "axial_momentum")[i]) /
                                (c.body.C * w_scale));
      for (const char* name : {"dissipated_work", "vertical_momentum_loss", "axial_momentum_loss"})
        losses = std::max(losses, std::abs(column(ty, name)[i] - column(dp, name)[i]) / e_scale);
      if (c.body.damping.driven)
        losses = std::max(losses, std::abs(column(ty, "motor_torque")[i] - column(dp, "motor_torque")[i]));
    }
    EXPECT_LT(axis, 1e-9) << c.name;
    EXPECT_LT(spin, 1e-9) << c.name;
    EXPECT_LT(losses, 1e-9) << c.name;
    if (c.name.ends_with("friction stop")) {
      EXPECT_GE(summary.friction_events, 1u) << c.name;  // the spin did stop
      EXPECT_EQ(column(ty, "axial_momentum")[980], 0.0) << c.name;  // t = 9.8 s: stopped, exactly 0
    }
    if (c.name == "asymmetric stick-slip") {  // w3 > 0, stuck, < 0, stuck, > 0, stuck (measured)
      EXPECT_GE(summary.friction_events, 5u);
      const auto& axial = column(ty, "axial_momentum");
      EXPECT_GE(std::count(axial.begin(), axial.end(), 0.0), 100);  // held exactly 0 while stuck
    }
    record += c.name + " " + sci(axis) + "/" + sci(spin) + "/" + sci(losses) + " (" +
              std::to_string(summary.friction_events) + " events); ";
  }
  RecordProperty("axis_spin_losses", record);
}

// E + dissipated work and L_zeta + its loss stay their initial values within 1e-11 of E's
// scale (and of the momentum scale sqrt(2 max(I) E)) over 100 s, for every case, and for
// A = B so does C w3 + its loss; and something was dissipated: the work is 1e6 times the
// residual.
TEST(TaylorDamped, TheEnergyAndMomentumBalancesHold) {
  const std::vector<double> times = sample_times(100.0, 201);
  std::string record;
  for (const Case& c : cases()) {
    const Trajectory tr = run(c.body, c.start, times, true);
    const double e_scale = std::abs(column(tr, "energy")[0]) + std::abs(c.body.mgR());
    const double l_scale = std::sqrt(2.0 * std::max({c.body.A, c.body.B, c.body.C}) * e_scale);
    const auto &e = column(tr, "energy_drift"), &w = column(tr, "dissipated_work");
    const auto &l = column(tr, "vertical_momentum_drift"), &ll = column(tr, "vertical_momentum_loss");
    const auto &a = column(tr, "axial_momentum_drift"), &al = column(tr, "axial_momentum_loss");
    double worst_e = 0.0, worst_l = 0.0, worst_a = 0.0;
    for (std::size_t i = 0; i < tr.size(); ++i) {
      worst_e = std::max(worst_e, std::abs(e[i] + w[i]) / e_scale);
      worst_l = std::max(worst_l, std::abs(l[i] + ll[i]) / l_scale);
      worst_a = std::max(worst_a, std::abs(a[i] + al[i]) / l_scale);
    }
    EXPECT_LT(worst_e, 1e-11) << c.name;
    EXPECT_LT(worst_l, 1e-11) << c.name;
    if (c.body.A == c.body.B) {  // else (A - B) w1 w2 changes C w3 too
      EXPECT_LT(worst_a, 1e-11) << c.name;
    }
    EXPECT_GT(std::abs(w.back()) / e_scale, 1e6 * worst_e) << c.name;
    record += c.name + " " + sci(worst_e) + "/" + sci(worst_l) + "/" + (c.body.A == c.body.B ? sci(worst_a) : "-") + "; ";
  }
  RecordProperty("energy_vertical_axial", record);
}

// For A = B the spin obeys C w' = -d_a w - tau0 sign(w) exactly whatever the transverse motion
// and gravity (SPEC 6): w3(t) follows SpinDecayLaw within 1e-11 of w0 over 40 s, free (m g R = 0)
// and heavy, and dry friction stops it within 1e-9 s of the law's stop time: w3 > 0 1e-9 s
// before, exactly 0 1e-9 s after.
TEST(TaylorDamped, TheSymmetricSpinFollowsTheClosedFormLawAndStopsOnTime) {
  std::string record;
  for (double mgR : {0.0, 1.0}) {
    for (auto [da, tau] : {std::pair{0.05, 0.0}, std::pair{0.0, 0.2}, std::pair{0.05, 0.2}}) {
      const Body b = with(make_body(1.0, 1.0, 1.5, mgR), {.transverse = 0.003, .axial = da, .friction = tau});
      const InitialState s = make_state(5.0, 0.1, 0.0, 0.3);
      const SpinDecayLaw law{b.C, da, tau};
      std::vector<double> times = sample_times(40.0, 401);
      const auto stop = law.stop_time(s.spin);
      if (stop) {
        times.push_back(*stop - 1e-9);
        times.push_back(*stop + 1e-9);
        std::sort(times.begin(), times.end());
      }
      const Trajectory tr = simulate_taylor(b, s, times, tolerance(1e-12));
      const auto& axial = column(tr, "axial_momentum");
      double worst = 0.0;
      for (std::size_t i = 0; i < tr.size(); ++i)
        worst = std::max(worst, std::abs(axial[i] / b.C - law.spin(s.spin, tr.t[i])) / s.spin);
      EXPECT_LT(worst, 1e-11) << "m g R " << mgR << " d_a " << da << " tau0 " << tau;
      if (stop) {
        const auto at = [&](double t) { return axial[std::find(tr.t.begin(), tr.t.end(), t) - tr.t.begin()]; };
        EXPECT_GT(at(*stop - 1e-9), 0.0) << "stopped early: d_a " << da;
        EXPECT_EQ(at(*stop + 1e-9), 0.0) << "not stopped: d_a " << da;
        EXPECT_EQ(axial.back(), 0.0);  // and it stays stopped
      }
      record += sci(worst) + " ";
    }
  }
  RecordProperty("worst_relative_spin_error", record);
}

// A motor holds w3 exactly (w3' = 0 in the recurrence) and, for A = B, pays d_a w0 + tau0.
TEST(TaylorDamped, ADrivenBodyKeepsItsSpinExactlyAndTheMotorPaysTheLoads) {
  const Body b = with(make_body(1.0, 1.0, 1.5, 1.0), {.transverse = 0.01, .axial = 0.02, .friction = 0.03, .driven = true});
  const InitialState s = make_state(6.0, 0.1);
  const Trajectory tr = simulate_taylor(b, s, sample_times(50.0, 51), tolerance(1e-12));
  for (std::size_t i = 0; i < tr.size(); ++i) {
    EXPECT_EQ(column(tr, "axial_momentum")[i], column(tr, "axial_momentum")[0]);
    EXPECT_NEAR(column(tr, "motor_torque")[i], 0.02 * 6.0 + 0.03, 1e-15);
  }
}

// simulate() and the tilt scan take a damped body with Integrator::Taylor: the solver says
// so, and the scan's extremes and end spin are dopri5's (tilt_extremes) within 1e-8 rad and
// 1e-8 rad/s (its extrema are located to ~1e-12 of a step there, the tilt to its square),
// for A != B and A = B (a top whose spin decays below its critical spin and falls past 1 rad).
TEST(TaylorDamped, SimulateAndTheTiltScanTakeIt) {
  struct Scan { Body body; InitialState start; const char* solver; bool falls; };
  const Scan scans[] = {
      {with(make_body(1.0, 1.5, 2.0, 1.0), {.transverse = 0.02, .axial = 0.05, .friction = 0.01}),
       make_state(8.0, 0.2, 0.05), ", plain variables, damped", false},
      {with(make_body(1.0, 1.0, 1.5, 1.0), {.transverse = 0.01, .axial = 0.1}), make_state(2.0, 0.1),
       ", spin-factored variables, damped", true},
  };
  std::string record;
  for (const Scan& c : scans) {
    SimulateOptions o;
    o.integrator = Integrator::Taylor;
    o.adaptive = tolerance(1e-12);
    const Simulation sim = simulate(Model::Nonlinear, c.body, c.start, sample_times(5.0, 11), o);
    ASSERT_TRUE(sim.summary.ok()) << sim.summary.message;
    // "Taylor, order p, ... variables, damped" (p from taylor_order(), not asserted here).
    EXPECT_TRUE(sim.summary.solver.starts_with("Taylor, order ")) << sim.summary.solver;
    EXPECT_TRUE(sim.summary.solver.ends_with(c.solver)) << sim.summary.solver;

    const TiltExtremes ty = taylor_tilt_extremes(c.body, c.start, 30.0, 1.0, tolerance(1e-12));
    const TiltExtremes dp = tilt_extremes(c.body, c.start, 30.0, 1.0, tolerance(1e-12));
    EXPECT_EQ(ty.exceeded, c.falls) << c.solver;
    EXPECT_EQ(dp.exceeded, c.falls) << c.solver;
    if (c.falls) {  // the crossing's time; max_tilt is the crossing's tilt on either side
      EXPECT_NEAR(ty.t_end, dp.t_end, 1e-8) << c.solver;
    } else {
      EXPECT_NEAR(ty.max_tilt, dp.max_tilt, 1e-8) << c.solver;
    }
    EXPECT_NEAR(ty.min_tilt, dp.min_tilt, 1e-8) << c.solver;
    EXPECT_NEAR(ty.spin_at_end, dp.spin_at_end, 1e-8) << c.solver;
    EXPECT_LT(ty.spin_at_end, 0.9 * c.start.spin) << c.solver;  // the spin did decay: not a trivial agreement
    record += sci(std::abs(ty.max_tilt - dp.max_tilt)) + "/" + sci(std::abs(ty.t_end - dp.t_end)) + "/" +
              sci(std::abs(ty.spin_at_end - dp.spin_at_end)) + " ";
  }
  RecordProperty("max_tilt_t_end_spin_differences", record);
}

// Viscous axial drag without friction has no modes: an asymmetric body falling from rest
// (w3 = 0, (A - B) w1 w2 = 0 at t = 0) gains spin from (A - B) w1 w2 at once. (dopri5 used to
// start such a body "stuck" and hold w3 = 0 for good; detail::initial_friction_mode.) Both
// integrators give the same w3 within 1e-10 rad/s, and it is not small.
TEST(TaylorDamped, AxialDragWithoutFrictionNeverHoldsTheSpin) {
  const Body b = with(make_body(1.0, 1.5, 2.0, 1.0), {.transverse = 0.01, .axial = 0.05});
  const InitialState s = make_state(0.0, 0.3, 0.2);
  const std::vector<double> times = sample_times(3.0, 31);
  const Trajectory ty = run(b, s, times, true), dp = run(b, s, times, false);
  const auto &a = column(ty, "axial_momentum"), &d = column(dp, "axial_momentum");
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    worst = std::max(worst, std::abs(a[i] - d[i]) / b.C);
    largest = std::max(largest, std::abs(d[i]) / b.C);
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(largest, 1e-3);
  RecordProperty("largest_spin", sci(largest));
}

}  // namespace
}  // namespace heavytop

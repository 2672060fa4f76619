// Damping and friction (SPEC section 6; paper-notes E6): the damped linear verdicts against an
// independent eigen-solve, the Kelvin-Tait-Chetaev instability, the spin-decay law.
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "heavytop/damping.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/stability.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;

Body damped(Body b, double transverse) {
  b.damping.transverse = transverse;
  return b;
}

double growth(LinearModelKind kind, const Body& b, double spin) {
  return linear_stability(linear_model(kind, b), spin).growth_rate;
}

constexpr auto kFirst = LinearModelKind::FirstOrder;
constexpr auto kFixed = LinearModelKind::BodyFixed;
constexpr auto kLinear = LinearModelKind::Linearized;

// The damped system matrices written out from the equations themselves, not through
// LinearModel: the paper's models in the axis frame (drag -d q'), the linearisation as
// Euler-Poisson in body axes on x = (p, q, gamma_x, gamma_y) with the drag -d (p, q).
Eigen::Matrix4d independent_matrix(LinearModelKind kind, const Body& b, double w0) {
  const double A = b.A, B = b.B, C = b.C, k = b.mgR(), d = b.damping.transverse;
  Eigen::Matrix4d j = Eigen::Matrix4d::Zero();
  if (kind == kLinear) {
    j.row(0) << -d / A, (B - C) * w0 / A, 0.0, k / A;   // A p' = (B - C) w0 q + k gy - d p
    j.row(1) << (C - A) * w0 / B, -d / B, -k / B, 0.0;  // B q' = (C - A) w0 p - k gx - d q
    j.row(2) << 0.0, -1.0, 0.0, w0;                      // gx' = w0 gy - q
    j.row(3) << 1.0, 0.0, -w0, 0.0;                      // gy' = p - w0 gx
    return j;
  }
  // (phi, theta, phi', theta'): A phi'' + g12 w0 theta' + d phi' = k phi, B theta'' + g21 w0 phi' + d theta' = k theta
  const double g12 = kind == kFirst ? C : C - B, g21 = kind == kFirst ? -C : -(C - A);
  j(0, 2) = j(1, 3) = 1.0;
  j.row(2) << k / A, 0.0, -d / A, -g12 * w0 / A;
  j.row(3) << 0.0, k / B, -g21 * w0 / B, -d / B;
  return j;
}

std::vector<std::complex<double>> sorted_eigenvalues(const Eigen::Matrix4d& j) {
  const Eigen::EigenSolver<Eigen::Matrix4d> solver(j, false);
  std::vector<std::complex<double>> v(solver.eigenvalues().begin(), solver.eigenvalues().end());
  std::sort(v.begin(), v.end(), [](auto x, auto y) {
    return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag();
  });
  return v;
}

TEST(DampedEigenvalues, EqualAnIndependentEigenSolveOfTheDampedSystemMatrices) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0.2, 3.0), spin(0.0, 8.0), drag(1e-3, 1.0);
  int compared = 0;
  for (int n = 0; n < 200; ++n) {
    double A = u(rng), B = u(rng), C = u(rng);
    if (A + B < C || B + C < A || C + A < B) continue;
    const Body b = damped(make_body(A, B, C, u(rng) - 1.5), drag(rng));
    const double w0 = spin(rng);
    for (auto kind : kLinearModels) {
      const auto ours = linear_stability(linear_model(kind, b), w0).eigenvalues;
      const auto theirs = sorted_eigenvalues(independent_matrix(kind, b, w0));
      ASSERT_EQ(ours.size(), 4u);
      double scale = 0.0;
      for (auto l : theirs) scale = std::max(scale, std::abs(l));
      // Match each eigenvalue to the nearest independent one (sorting can split conjugates).
      for (auto l : ours) {
        double best = INFINITY;
        for (auto r : theirs) best = std::min(best, std::abs(l - r));
        EXPECT_LE(best, 1e-10 * scale) << name(kind) << " A=" << A << " B=" << B << " C=" << C;
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);
}

// E6: A = B = 1, C = 2, m g R = 1, d = 0.01 (body-frame linearisation).
TEST(KelvinTaitChetaev, TheGrowthRatesOfE6) {
  const Body sym = damped(make_body(1.0, 1.0, 2.0, 1.0), 0.01);
  EXPECT_NEAR(growth(kLinear, sym, 1.5), 1.7e-3, 0.05e-3);
  EXPECT_NEAR(growth(kLinear, sym, 3.0), 3.0e-4, 0.05e-4);
  EXPECT_NEAR(growth(kLinear, sym, 10.0), 2.5e-5, 0.05e-5);
  const Body asym = damped(make_body(1.0, 1.5, 2.0, 1.0), 0.01);
  EXPECT_NEAR(growth(kLinear, asym, 1.5), 1.4e-3, 0.05e-3);
  EXPECT_NEAR(growth(kLinear, asym, 3.0), 2.9e-4, 0.05e-4);
  const Body hanging = damped(make_body(1.0, 1.0, 2.0, -1.0), 0.01);
  EXPECT_NEAR(growth(kLinear, hanging, 0.5), -2.8e-3, 0.05e-3);
}

TEST(KelvinTaitChetaev, EverySymmetricTopAboveItsPivotIsUnstableAtEverySpinUnderDrag) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 3.0), drag(1e-4, 1.0);
  for (int n = 0; n < 100; ++n) {
    const double A = u(rng), C = std::min(u(rng), 2.0 * A);
    const Body b = damped(make_body(A, A, C, u(rng)), drag(rng));
    for (auto kind : {kFirst, kLinear}) {
      const LinearModel model = linear_model(kind, b);
      EXPECT_TRUE(stable_spin_intervals(model).empty()) << name(kind);
      for (double w0 : {0.0, 0.5, 2.0, 10.0, 100.0}) {
        const auto v = linear_stability(model, w0);
        EXPECT_FALSE(v.stable);
        EXPECT_GT(v.growth_rate, 0.0) << name(kind) << " at " << w0;
      }
    }
  }
}

TEST(KelvinTaitChetaev, AHangingBodyWithCAboveAAndBIsAsymptoticallyStableAtEverySpin) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.2, 3.0), drag(1e-3, 1.0);
  for (int n = 0; n < 100; ++n) {
    const double A = u(rng), B = u(rng), C = std::max(A, B) * 1.2;
    if (A + B < C) continue;
    const Body b = damped(make_body(A, B, C, -u(rng)), drag(rng));
    const LinearModel model = linear_model(kLinear, b);
    const auto intervals = stable_spin_intervals(model);
    ASSERT_EQ(intervals.size(), 1u);
    EXPECT_EQ(intervals[0].lo, 0.0);
    EXPECT_FALSE(intervals[0].hi);
    for (double w0 : {0.0, 0.3, 1.0, 5.0, 50.0}) EXPECT_LT(linear_stability(model, w0).growth_rate, 0.0);
  }
}

// E6: a superfast asymmetric body that drag leaves asymptotically stable, and its window of
// spins found exactly: the interval ends are where the growth rate crosses zero.
TEST(KelvinTaitChetaev, AnAsymmetricBodysWindowOfAsymptoticStability) {
  const Body b = damped(make_body(2.549, 1.265, 3.615, 2.94), 0.5445);
  const LinearModel model = linear_model(kLinear, b);
  EXPECT_NEAR(growth(kLinear, b, 2.136), -7.79e-3, 0.005e-3);
  const auto intervals = stable_spin_intervals(model);
  ASSERT_FALSE(intervals.empty());
  bool inside = false;
  for (const auto& i : intervals) {
    if (i.lo <= 2.136 && (!i.hi || 2.136 <= *i.hi)) inside = true;
    // Each finite end is a zero of the growth rate, with the sign changing across it.
    for (auto end : {std::optional<double>(i.lo), i.hi}) {
      if (!end || *end == 0.0) continue;
      const double below = growth(kLinear, b, *end * (1.0 - 1e-7)), above = growth(kLinear, b, *end * (1.0 + 1e-7));
      EXPECT_LT(below * above, 0.0) << "end " << *end;
      EXPECT_LE(std::abs(growth(kLinear, b, *end)), 1e-9);
    }
  }
  EXPECT_TRUE(inside);
}

TEST(Damping, WithoutDragTheVerdictIsTheConservativeOneAndTheGrowthRateIsZeroWhenStable) {
  const Body b = make_body(1.0, 1.5, 2.0, 1.0);
  for (auto kind : kLinearModels)
    for (double w0 : {0.5, 2.0, 5.0}) {
      const auto v = linear_stability(linear_model(kind, b), w0);
      if (v.stable) { EXPECT_EQ(v.growth_rate, 0.0); }
      else { EXPECT_GT(v.growth_rate, 0.0); }
    }
}

// ---- The spin-decay law C w' = -d_a w - tau0 sign(w) ------------------------------------------

TEST(SpinDecayLaw, SolvesItsDifferentialEquationAndStopsWhereFrictionStopsIt) {
  for (auto [da, tau] : {std::pair{0.3, 0.0}, std::pair{0.0, 0.2}, std::pair{0.3, 0.2}}) {
    const SpinDecayLaw law{2.0, da, tau};
    const double w0 = 5.0;
    for (double t : {0.1, 1.0, 3.0}) {
      const double w = law.spin(w0, t);
      if (w == 0.0) continue;
      const double h = 1e-5;  // central difference: C w' + d_a w + tau0 = 0
      const double rate = (law.spin(w0, t + h) - law.spin(w0, t - h)) / (2.0 * h);
      EXPECT_NEAR(2.0 * rate + da * w + tau, 0.0, 1e-8);
      // time_to inverts spin.
      EXPECT_NEAR(*law.time_to(w0, w), t, 1e-12 * t + 1e-14);
    }
    if (tau > 0.0) {
      const double stop = *law.stop_time(w0);
      EXPECT_EQ(law.spin(w0, stop * (1 + 1e-12)), 0.0);
      EXPECT_GT(law.spin(w0, stop * (1 - 1e-6)), 0.0);
      EXPECT_NEAR(*law.time_to(w0, 0.0), stop, 1e-12 * stop);
      if (da == 0.0) { EXPECT_NEAR(stop, 2.0 * w0 / tau, 1e-12); }  // t = C w0 / tau0
    } else {
      EXPECT_FALSE(law.time_to(w0, 0.0));
      EXPECT_FALSE(law.stop_time(w0));
    }
    EXPECT_NEAR(law.spin(-w0, 1.0), -law.spin(w0, 1.0), 1e-15);
  }
}

TEST(Damping, ValidationNamesTheKey) {
  Body b = make_body(1.0, 1.0, 1.5, 1.0);
  b.damping.axial = -1.0;
  try {
    validate(b);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "damping.axial");
  }
  b.damping.axial = 0.0;
  b.damping.friction = NAN;
  EXPECT_THROW(validate(b), InvalidInput);
}

// ---- The nonlinear body with the torques --------------------------------------------------------

using test_support::column;
using test_support::make_state;

// dopri5's damped equations (auto now picks the Taylor integrator for most damped bodies;
// tests/test_taylor_damped.cpp holds it to the same laws and to dopri5).
Trajectory run_nonlinear(const Body& b, const InitialState& s, double t_end, std::size_t n, double tol = 1e-12) {
  SimulateOptions o;
  o.integrator = Integrator::Adaptive;
  o.adaptive.rtol = o.adaptive.atol = tol;
  const Simulation sim = simulate(Model::Nonlinear, b, s, sample_times(t_end, n), o);
  EXPECT_TRUE(sim.summary.ok()) << sim.summary.message;
  return sim.trajectory;
}

// For A = B the spin obeys C w' = -d_a w - tau0 sign(w) exactly (SPEC 6): compare with the law.
TEST(DampedNonlinear, TheSymmetricSpinFollowsTheClosedFormDecay) {
  for (auto [da, tau] : {std::pair{0.01, 0.0}, std::pair{0.0, 0.02}, std::pair{0.01, 0.02}}) {
    Body b = make_body(1.0, 1.0, 1.5, 1.0);
    b.damping = {.transverse = 0.003, .axial = da, .friction = tau};
    const InitialState s = make_state(10.0, 0.1);
    const Trajectory tr = run_nonlinear(b, s, 100.0, 201);
    const SpinDecayLaw law{b.C, da, tau};
    const auto& axial = column(tr, "axial_momentum");
    double worst = 0.0;
    for (std::size_t i = 0; i < tr.size(); ++i)
      worst = std::max(worst, std::abs(axial[i] / b.C - law.spin(s.spin, tr.t[i])) / s.spin);
    EXPECT_LT(worst, 1e-10) << "d_a " << da << " tau0 " << tau;
  }
}

// E(t) - E(0) = -(dissipated work), and likewise the vertical and axial momenta, for every
// kind of body and torque: a checked identity, not a drift.
TEST(DampedNonlinear, TheEnergyAndMomentumBalancesHold) {
  struct Case { Body body; Damping damping; };
  const Case cases[] = {
      {make_body(1.0, 1.0, 1.5, 1.0), {.transverse = 0.01, .axial = 0.01, .friction = 0.0}},
      {make_body(1.0, 1.5, 2.0, 1.0), {.transverse = 0.01, .axial = 0.005, .friction = 0.01}},
      {make_body(1.0, 1.5, 2.0, -1.0), {.transverse = 0.02, .axial = 0.0, .friction = 0.0}},
      {make_body(1.0, 1.5, 2.0, 1.0), {.transverse = 0.01, .axial = 0.01, .friction = 0.01, .driven = true}},
  };
  for (const auto& c : cases) {
    Body b = c.body;
    b.damping = c.damping;
    const Trajectory tr = run_nonlinear(b, make_state(8.0, 0.2, 0.05), 100.0, 101);
    const auto& e = column(tr, "energy_drift");
    const auto& w = column(tr, "dissipated_work");
    const auto& l = column(tr, "vertical_momentum_drift");
    const auto& ll = column(tr, "vertical_momentum_loss");
    const double e_scale = column(tr, "energy")[0] + std::abs(b.mgR());
    const double l_scale = std::sqrt(2.0 * 2.0 * e_scale);
    double worst_e = 0.0, worst_l = 0.0;
    for (std::size_t i = 0; i < tr.size(); ++i) {
      worst_e = std::max(worst_e, std::abs(e[i] + w[i]) / e_scale);
      worst_l = std::max(worst_l, std::abs(l[i] + ll[i]) / l_scale);
    }
    EXPECT_LT(worst_e, 1e-10);
    EXPECT_LT(worst_l, 1e-10);
    // Something was dissipated, so the identity is not 0 = 0: a million times its residual.
    EXPECT_GT(std::abs(w.back()) / e_scale, 1e6 * worst_e);
  }
}

// Dry friction alone stops a symmetric top's spin at t = C w0 / tau0, and it stays stopped.
TEST(DampedNonlinear, DryFrictionStopsTheSpinAtCw0OverTau0AndHoldsIt) {
  Body b = make_body(1.0, 1.0, 1.5, 1.0);
  b.damping.friction = 0.5;
  const InitialState s = make_state(4.0, 0.05);
  const double stop = b.C * s.spin / b.damping.friction;  // 12 s
  const Trajectory tr = run_nonlinear(b, s, 30.0, 301);
  const auto& axial = column(tr, "axial_momentum");
  for (std::size_t i = 0; i < tr.size(); ++i) {
    const double t = tr.t[i];
    if (t > stop * (1.0 + 1e-12)) { EXPECT_EQ(axial[i], 0.0) << t; }  // exactly: it sticks
    else if (t >= stop) { EXPECT_NEAR(axial[i], 0.0, 1e-10 * b.C * s.spin) << t; }
    else { EXPECT_NEAR(axial[i] / b.C, s.spin - b.damping.friction * t / b.C, 1e-10 * s.spin) << t; }
  }
}

TEST(DampedNonlinear, ADrivenBodyKeepsItsSpinAndTheMotorPaysTheLoads) {
  Body b = make_body(1.0, 1.0, 1.5, 1.0);
  b.damping = {.transverse = 0.01, .axial = 0.02, .friction = 0.03, .driven = true};
  const InitialState s = make_state(6.0, 0.1);
  const Trajectory tr = run_nonlinear(b, s, 50.0, 51);
  for (std::size_t i = 0; i < tr.size(); ++i) {
    EXPECT_NEAR(column(tr, "axial_momentum")[i], b.C * s.spin, 1e-12);
    EXPECT_NEAR(column(tr, "motor_torque")[i], 0.02 * 6.0 + 0.03, 1e-12);  // A = B: d_a w0 + tau0
  }
}

// Linear against nonlinear at small amplitude: the damped linearisation (matrix exponential)
// and the damped nonlinear body agree to 1e-4 of the tilt over 400 s, in which the top's
// tilt grows (Kelvin-Tait-Chetaev, E6) and the hanging body's decays.
TEST(DampedNonlinear, SmallTiltsFollowTheDampedLinearisation) {
  for (double mgR : {1.0, -1.0}) {
    const Body b = damped(make_body(1.0, 1.5, 2.0, mgR), 0.05);
    const InitialState s = make_state(3.0, 1e-6, 0.5e-6, 1e-6);
    const auto times = sample_times(400.0, 4001);
    const Trajectory nl = run_nonlinear(b, s, 400.0, 4001);
    SimulateOptions o;
    o.method = LinearMethod::Numeric;
    const Trajectory lin = simulate(Model::Linearized, b, s, times, o).trajectory;
    double worst = 0.0, size = 0.0;
    for (std::size_t i = 0; i < nl.size(); ++i) {
      worst = std::max({worst, std::abs(nl.theta[i] - lin.theta[i]), std::abs(nl.phi[i] - lin.phi[i])});
      size = std::max({size, std::abs(nl.theta[i]), std::abs(nl.phi[i])});
    }
    EXPECT_LT(worst, 1e-4 * size) << "m g R = " << mgR;
    const double rate = growth(kLinear, b, 3.0);
    EXPECT_TRUE(mgR > 0 ? rate > 0.0 : rate < 0.0);
  }
}

// Strong drag makes the motion stiff: dopri5's step is held at its stability boundary on the
// negative real axis, h |lambda| = 3.31 with |lambda| = d_t / A, however slowly the body moves;
// a run that cannot reach its end within max_steps stops early (after a hundredth of them)
// saying so, instead of spending them all (d_t = 1e9 on the toy top: 80 s, now 1 s).
TEST(DampedNonlinear, StrongDragHoldsTheStepAtTheStabilityBoundaryAndAHopelessRunStopsEarly) {
  Body b = make_body(1.0, 1.0, 1.5, 1.0);
  b.damping.transverse = 1e4;  // |lambda| = 1e4 1/s against a motion of ~1 rad/s
  const InitialState s = make_state(10.0, 0.1);
  const double t_end = 100.0, boundary_steps = t_end * b.damping.transverse / b.A / 3.31;
  NonlinearSummary summary;
  simulate_nonlinear(b, s, sample_times(t_end, 11), {}, &summary);
  EXPECT_GT(double(summary.steps), 0.95 * boundary_steps);
  EXPECT_LT(double(summary.steps), 1.05 * boundary_steps);
  // With fewer steps allowed than half of that: stopped at a hundredth of max_steps, saying why.
  Tolerances few;
  few.max_steps = std::size_t(0.4 * boundary_steps);
  try {
    simulate_nonlinear(b, s, sample_times(t_end, 11), few);
    ADD_FAILURE() << "no failure";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the damping makes this motion stiff"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("after " + std::to_string(few.max_steps / 100) + " steps"), std::string::npos) << e.what();
  }
  // And a run that can finish within max_steps is not stopped.
  Tolerances enough;
  enough.max_steps = std::size_t(1.5 * boundary_steps);
  EXPECT_NO_THROW(simulate_nonlinear(b, s, sample_times(t_end, 11), enough));
}

TEST(DampedNonlinear, TheIntegratorsThatCannotIncludeDampingRefuseIt) {
  Body b = make_body(1.0, 1.0, 1.5, 1.0);
  b.damping.axial = 0.1;
  const auto times = sample_times(1.0, 3);
  auto key_of = [&](Model m, SimulateOptions o) {
    try {
      simulate(m, b, make_state(5.0, 0.1), times, o);
    } catch (const InvalidInput& e) {
      return e.key();
    }
    return std::string("accepted");
  };
  SimulateOptions splitting;
  splitting.integrator = Integrator::Splitting;
  EXPECT_EQ(key_of(Model::Nonlinear, splitting), "integrator");
  SimulateOptions o;
  o.integrator = Integrator::Dop853;  // its equations hold no torques
  EXPECT_EQ(key_of(Model::Nonlinear, o), "integrator");
  o.integrator = Integrator::Taylor;  // its damped variables do (test_taylor_damped.cpp)
  EXPECT_EQ(key_of(Model::Nonlinear, o), "accepted");
  EXPECT_EQ(key_of(Model::Nonlinear, {}), "accepted");
  // auto: the conservative body's rule (A = B here: dopri5 above min(rtol, atol) = 1e-2).
  EXPECT_EQ(choose_integrator(b, {}), Integrator::Taylor);
  Tolerances loose;
  loose.rtol = loose.atol = 0.05;
  EXPECT_EQ(choose_integrator(b, loose), Integrator::Adaptive);
  EXPECT_EQ(key_of(Model::LagrangeExact, {}), "model");
  b.damping = {.transverse = 0.1};
  EXPECT_EQ(key_of(Model::Linearized, {}), "method");  // the closed form is undamped
  SimulateOptions numeric;
  numeric.method = LinearMethod::Numeric;
  EXPECT_EQ(key_of(Model::Linearized, numeric), "accepted");
}

// ---- How long it stays up (SPEC section 8) ------------------------------------------------------

// The toy top at 200 rad/s with axial damping 2e-7 N m s, 0.01 rad off vertical (issue 18).
TEST(Lifetime, TheToyTopReachesItsCriticalSpinByTheLawAndFallsAfterIt) {
  Body top = example_toy_top();
  top.damping.axial = 2e-7;
  InitialState s = example_motion();
  s.theta0 = 0.01;
  const Lifetime life = lifetime(top, s);
  ASSERT_TRUE(life.critical_spin && life.time_to_critical && life.fall_time && life.fall_spin);
  // The critical spin of the symmetric top, C^2 w^2 = 4 A m g R, and the law's time to it.
  const double critical = 2.0 * std::sqrt(top.A * top.mgR()) / top.C;
  EXPECT_NEAR(*life.critical_spin, critical, 1e-9 * critical);
  const double expected = top.C / top.damping.axial * std::log(s.spin / *life.critical_spin);
  EXPECT_NEAR(*life.time_to_critical, expected, 1e-12 * expected);
  EXPECT_DOUBLE_EQ(life.horizon, 10.0 * *life.time_to_critical);
  // It falls after the spin has passed the critical spin, and below it.
  EXPECT_GT(*life.fall_time, *life.time_to_critical);
  EXPECT_LT(*life.fall_spin, *life.critical_spin);
  // The spin at the fall is the law's (A = B), and the fall is located on the dense output:
  // a run sampled at that time has the threshold tilt there.
  const SpinDecayLaw law{top.C, 2e-7, 0.0};
  EXPECT_NEAR(*life.fall_spin, law.spin(s.spin, *life.fall_time), 1e-9 * s.spin);
  const Trajectory tr = simulate(Model::Nonlinear, top, s, {0.0, *life.fall_time}).trajectory;
  const Eigen::Vector3d k = test_support::axis_of(tr.theta[1], tr.phi[1]);
  EXPECT_NEAR(std::acos(k.z()), life.max_tilt, 1e-9);
  // Refining the tolerance moves the fall by less than 1e-6 relative.
  LifetimeOptions finer;
  finer.integrator.rtol = finer.integrator.atol = 1e-13;
  LifetimeOptions coarser;
  coarser.integrator.rtol = coarser.integrator.atol = 1e-10;
  const double fine = *lifetime(top, s, finer).fall_time, coarse = *lifetime(top, s, coarser).fall_time;
  EXPECT_LT(std::abs(fine - *life.fall_time), 1e-6 * fine);
  EXPECT_LT(std::abs(coarse - fine), 1e-6 * fine);
  RecordProperty("fall_time_s", test_support::sci(fine));
}

TEST(Lifetime, TheSpecialCasesOfSection8) {
  Body top = example_toy_top();
  InitialState s = example_motion();
  top.damping.axial = 2e-7;
  s.spin = 100.0;  // already below the critical spin
  EXPECT_EQ(*spin_decay(top, s).time_to_critical, 0.0);
  EXPECT_EQ(spin_decay(top, s).horizon, kDefaultLifetimeHorizon);
  s.spin = 200.0;
  top.damping.driven = true;  // the motor holds it: never
  EXPECT_FALSE(spin_decay(top, s).time_to_critical);
  top.damping = {};
  top.length = -0.025;  // hanging: stable at every spin
  EXPECT_EQ(*spin_decay(top, s).critical_spin, 0.0);
  EXPECT_FALSE(spin_decay(top, s).time_to_critical);
  top.length = 0.025;  // no damping: the spin never decays
  EXPECT_FALSE(spin_decay(top, s).time_to_critical);
  LifetimeOptions bad;
  bad.max_tilt = 4.0;
  EXPECT_THROW(spin_decay(top, s, bad), InvalidInput);
}

}  // namespace
}  // namespace heavytop

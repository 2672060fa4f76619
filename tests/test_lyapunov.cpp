// The Lyapunov verdict beyond the linearisation (SPEC section 7; errata E2 as revised, E3, E5):
// the energy index, the certificates, the exact stable spins, the superfast spin and the
// largest tilt (the wander), each against a closed form or an independent route.
#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "heavytop/lagrange_exact.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/sweep.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;
using test_support::make_state;
using V = LyapunovVerdictKind;
using Cert = LyapunovCertificate;

/// rad/s: inside one of the intervals (ends as included).
bool inside(const std::vector<SpinInterval>& intervals, double w) {
  for (const auto& i : intervals) {
    const bool above = w > i.lo || (w == i.lo && i.lo_included);
    const bool below = !i.hi || w < *i.hi || (w == *i.hi && i.hi_included);
    if (above && below) return true;
  }
  return false;
}

/// Largest real part of the exact linearisation's eigenvalues (1/s).
double growth(const Body& b, double w) {
  double g = -INFINITY;
  for (auto l : linear_stability(linear_model(LinearModelKind::Linearized, b), w).eigenvalues)
    g = std::max(g, l.real());
  return g;
}

// ---- Energy index and superfast spin against their closed forms, 200 random bodies --------

TEST(Lyapunov, EnergyIndexAndSuperfastSpinOverRandomBodies) {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> unit(0.2, 2.0), signed_k(-2.0, 2.0), spin(0.0, 4.0);
  int counted[3] = {0, 0, 0}, superfast_bodies = 0, checked_points = 0;
  for (int n = 0; n < 200; ++n) {
    double A = unit(rng), B = n % 5 == 0 ? A : unit(rng), C = unit(rng);
    if (C > A + B) C = 0.9 * (A + B);
    if (A > B + C || B > A + C) { --n; continue; }
    const double k = signed_k(rng);
    const Body b = make_body(A, B, C, k);

    // superfast_spin: sqrt(max(0, k/(C-A), k/(C-B))) when C > A and C > B, else never.
    const auto sf = superfast_spin(b);
    if (C > A && C > B) {
      ASSERT_TRUE(sf.has_value()) << n;
      EXPECT_NEAR(*sf, std::sqrt(std::max({0.0, k / (C - A), k / (C - B)})), 1e-14 * (1.0 + *sf)) << n;
      ++superfast_bodies;
      // and it is the spin above which the index stays 0: just below it the index is not 0
      const double above = *sf * (1.0 + 1e-9) + 1e-300, far = 1e3 * (*sf + 1.0);
      EXPECT_EQ(lyapunov_stability(b, above).energy_index, 0) << n;
      EXPECT_EQ(lyapunov_stability(b, far).energy_index, 0) << n;
      if (*sf > 0.0) { EXPECT_GT(lyapunov_stability(b, *sf * (1.0 - 1e-9)).energy_index, 0) << n; }
    } else {
      EXPECT_FALSE(sf.has_value()) << n;
      EXPECT_GT(lyapunov_stability(b, 1e4).energy_index, 0) << n;  // (C - min) w0^2 < 0 wins
    }

    const auto intervals = lyapunov_stable_spin_intervals(b);
    for (int j = 0; j < 10; ++j) {
      const double w = spin(rng), s = w * w;
      const double s1 = (C - A) * s - k, s2 = (C - B) * s - k;
      if (std::abs(s1) < 1e-6 || std::abs(s2) < 1e-6) continue;  // keep clear of the boundaries
      const LyapunovVerdict v = lyapunov_stability(b, w);
      const int index = int(s1 < 0.0) + int(s2 < 0.0);
      ASSERT_EQ(v.energy_index, index) << n << " w0 " << w;
      EXPECT_NEAR(v.s1, s1, 1e-14 * (std::abs(C - A) * s + std::abs(k)));
      EXPECT_NEAR(v.s2, s2, 1e-14 * (std::abs(C - B) * s + std::abs(k)));
      ++counted[index];
      ++checked_points;
      // The closed-form intervals hold exactly the spins the verdict proves stable.
      EXPECT_EQ(inside(intervals, w), v.verdict == V::Stable) << n << " w0 " << w;
      // Independent route, the exact linearisation: proven stable -> no exponential growth;
      // index 1 -> a real positive eigenvalue; A != B at index 2: unstable iff it grows.
      const double g = growth(b, w);
      if (v.verdict == V::Stable) { EXPECT_LE(g, 1e-7) << n << " w0 " << w; }
      if (index == 1) {
        EXPECT_EQ(v.certificate, Cert::OddIndex);
        EXPECT_GT(g, 1e-6) << n << " w0 " << w;
      }
      if (index == 2 && !is_symmetric(b)) { EXPECT_EQ(v.verdict == V::Unstable, g > 1e-9) << n << " w0 " << w; }
      if (index == 0) { EXPECT_EQ(v.certificate, Cert::EnergyCasimir); }
      if (v.certificate == Cert::None) { EXPECT_EQ(v.verdict, V::Undecided); }
    }
  }
  RecordProperty("points_index_0_1_2", std::to_string(counted[0]) + "/" + std::to_string(counted[1]) + "/" +
                                           std::to_string(counted[2]));
  EXPECT_GT(counted[0], 50);
  EXPECT_GT(counted[1], 50);
  EXPECT_GT(counted[2], 50);
  EXPECT_GT(superfast_bodies, 20);
  EXPECT_GT(checked_points, 1500);
}

// ---- E3's asymmetric example: A = 1, B = 1.5, C = 2, m g R = 1 ------------------------------

TEST(Lyapunov, AsymmetricExampleIsIndexOneBetweenOneAndRootTwo) {
  const Body b = make_body(1.0, 1.5, 2.0, 1.0);
  for (double w : {1.001, 1.1, 1.2, 1.3, 1.4, 1.414}) {
    const auto v = lyapunov_stability(b, w);
    EXPECT_EQ(v.energy_index, 1) << w;
    EXPECT_EQ(v.verdict, V::Unstable) << w;
    EXPECT_EQ(v.certificate, Cert::OddIndex) << w;
  }
  ASSERT_TRUE(superfast_spin(b));
  EXPECT_NEAR(*superfast_spin(b), std::sqrt(2.0), 1e-15);
  for (double w : {1.4143, 1.45, 3.0, 100.0}) {
    const auto v = lyapunov_stability(b, w);
    EXPECT_EQ(v.energy_index, 0) << w;
    EXPECT_EQ(v.certificate, Cert::EnergyCasimir) << w;
  }
  // Below w0 = 1 both stiffnesses are negative and the linearisation grows: unstable.
  const auto low = lyapunov_stability(b, 0.9);
  EXPECT_EQ(low.energy_index, 2);
  EXPECT_EQ(low.verdict, V::Unstable);
  EXPECT_EQ(low.certificate, Cert::LinearInstability);
  // At sqrt 2 itself s2 = 0 (degenerate): not proven, so the interval is open there.
  const auto intervals = lyapunov_stable_spin_intervals(b);
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_NEAR(intervals[0].lo, std::sqrt(2.0), 1e-15);
  EXPECT_FALSE(intervals[0].lo_included);
  EXPECT_FALSE(intervals[0].hi);
  EXPECT_NE(lyapunov_stability(b, intervals[0].lo).verdict, V::Stable);
  // The nonlinear body agrees (E3): 1e-4 rad off vertical it falls at 1.3, stays at 1.45.
  EXPECT_GT(tilt_extremes(b, make_state(1.3, 1e-4), 100.0, 2.0).max_tilt, 2.0);
  EXPECT_LT(tilt_extremes(b, make_state(1.45, 1e-4), 100.0).max_tilt, 4e-4);
}

// ---- The toy top: never superfast, Chetaev above 133.344 rad/s -------------------------------

TEST(Lyapunov, ToyTopIsNeverSuperfastAndChetaevAboveCriticalSpin) {
  const Body top = example_toy_top();
  EXPECT_FALSE(superfast_spin(top));
  const double critical = std::sqrt(4.0 * top.A * top.mgR()) / top.C;
  EXPECT_NEAR(critical, 133.344, 5e-4);
  const auto intervals = lyapunov_stable_spin_intervals(top);
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_NEAR(intervals[0].lo, critical, 1e-12 * critical);
  EXPECT_TRUE(intervals[0].lo_included);  // the critical case itself is proven (quartic)
  EXPECT_FALSE(intervals[0].hi);
  EXPECT_EQ(lyapunov_stability(top, intervals[0].lo).certificate, Cert::CriticalQuartic);
  for (double w : {133.345, 200.0, 1e4}) {
    const auto v = lyapunov_stability(top, w);
    EXPECT_EQ(v.verdict, V::Stable) << w;
    EXPECT_EQ(v.certificate, Cert::Chetaev) << w;
    EXPECT_EQ(v.energy_index, 2) << w;  // C < A: never the energy-Casimir
  }
  const auto below = lyapunov_stability(top, 133.343);
  EXPECT_EQ(below.verdict, V::Unstable);
  EXPECT_EQ(below.certificate, Cert::LinearInstability);
}

// ---- The boundary of (9) for A = B: critical-quartic, the sqrt(2 delta) plateau -------------

/// rad, 2 asin(sqrt(x / 2)): the tilt whose 1 - cos is x, without cancellation.
double tilt_of(double one_minus_cos) { return 2.0 * std::asin(std::sqrt(0.5 * one_minus_cos)); }

/// rad, the largest tilt of a symmetric top started at tilt delta with no transverse rate, from
/// the Lagrange cubic by hand: f(u) = (u0 - u)[beta (1 - u^2) - b^2 (u0 - u)], whose other
/// roots in x = 1 - u solve beta x^2 + (b^2 - 2 beta) x - b^2 (1 - u0) = 0 (beta != 0).
double cubic_max_tilt(double A, double C, double mgR, double w0, double delta) {
  const double b2 = (C * w0 / A) * (C * w0 / A), beta = 2.0 * mgR / A;
  const double x0 = 2.0 * std::sin(0.5 * delta) * std::sin(0.5 * delta);  // 1 - u0
  const double p = b2 - 2.0 * beta, q = -b2 * x0;                         // beta x^2 + p x + q
  const double root = std::sqrt(p * p - 4.0 * beta * q);
  // The smaller positive root, each form free of cancellation.
  const double r1 = p > 0.0 ? -2.0 * q / (p + root) : (-p + root) / (2.0 * beta);
  const double r2 = p > 0.0 ? -(p + root) / (2.0 * beta) : 2.0 * q / (-p + root);
  double x = INFINITY;
  for (double r : {r1, r2})
    if (r > 0.0) x = std::min(x, r);
  return tilt_of(std::max(x, x0));
}

TEST(Lyapunov, BoundaryOfNineIsStableByTheQuarticTerm) {
  const Body b = make_body(1.0, 1.0, 2.0, 1.0);  // C^2 w0^2 = 4 A m g R at w0 = 1
  const auto v = lyapunov_stability(b, 1.0);
  EXPECT_EQ(v.verdict, V::Stable);
  EXPECT_EQ(v.certificate, Cert::CriticalQuartic);
  EXPECT_FALSE(linear_stability(linear_model(LinearModelKind::FirstOrder, b), 1.0).stable);  // E2
  const auto intervals = lyapunov_stable_spin_intervals(b);
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_EQ(intervals[0].lo, 1.0);
  EXPECT_TRUE(intervals[0].lo_included);

  const double delta = 1e-3, plateau = std::sqrt(2.0 * delta);
  // Exact: sin(tilt/2) = sqrt(sin(delta/2)) at the boundary (docs/lyapunov.md).
  const double exact = 2.0 * std::asin(std::sqrt(std::sin(0.5 * delta)));
  const Wander w = axis_wander(b, make_state(1.0, delta), 100.0);
  ASSERT_TRUE(w.max_tilt);
  EXPECT_TRUE(w.closed_form);
  EXPECT_NEAR(*w.max_tilt, exact, 1e-12);
  EXPECT_NEAR(*w.max_tilt, plateau, 0.03 * plateau);
  RecordProperty("closed_form_max_tilt", test_support::sci(*w.max_tilt));

  // A long nonlinear run (2000 s, the number) stays on the plateau.
  const TiltExtremes run = tilt_extremes(b, make_state(1.0, delta), 2000.0);
  RecordProperty("nonlinear_max_tilt_2000s", test_support::sci(run.max_tilt));
  EXPECT_NEAR(run.max_tilt, plateau, 0.03 * plateau);
  EXPECT_NEAR(run.max_tilt, exact, 1e-8);

  // Just below (0.99 of the boundary) it swings out to about 0.28 rad, whatever delta is.
  for (double d : {1e-3, 1e-2}) {
    const Wander below = axis_wander(b, make_state(0.99, d), 100.0);
    ASSERT_TRUE(below.max_tilt);
    EXPECT_GT(*below.max_tilt, 0.2) << d;
    EXPECT_NEAR(*below.max_tilt, cubic_max_tilt(1.0, 2.0, 1.0, 0.99, d), 1e-12) << d;
    EXPECT_TRUE(tilt_extremes(b, make_state(0.99, d), 2000.0, 0.2).exceeded) << d;
  }
}

// ---- The largest tilt for A = B: the cubic's root (1e-12), the integration (1e-8) ----------

TEST(Lyapunov, WanderOfSymmetricTopIsTheCubicsRoot) {
  struct Case { double A, C, mgR, w0, delta; };
  const Body toy = example_toy_top();
  const Case cases[] = {{1.0, 2.0, 1.0, 1.0, 1e-2}, {1.0, 2.0, 1.0, 0.99, 1e-3}, {1.0, 2.0, 1.0, 1.5, 0.05},
                        {1.0, 2.0, 1.0, 3.0, 0.3},  {1.0, 0.5, -1.0, 0.5, 0.3},  {1.0, 1.2, 1.0, 0.5, 0.2},
                        {toy.A, toy.C, toy.mgR(), 200.0, 0.05}};
  double worst_root = 0.0, worst_run = 0.0;
  for (const auto& c : cases) {
    const Body b = make_body(c.A, c.A, c.C, c.mgR);
    const InitialState s = make_state(c.w0, c.delta);
    const Wander w = axis_wander(b, s, 100.0);
    ASSERT_TRUE(w.max_tilt) << w.note;
    EXPECT_TRUE(w.closed_form);
    const double root = cubic_max_tilt(c.A, c.C, c.mgR, c.w0, c.delta);
    EXPECT_NEAR(*w.max_tilt, root, 1e-12) << c.w0;
    worst_root = std::max(worst_root, std::abs(*w.max_tilt - root));
    // The integrated maximum over one and a half nutation periods.
    const double period = nutation_period(lagrange_top(b, s));
    ASSERT_TRUE(std::isfinite(period));
    const double run = tilt_extremes(b, s, 1.5 * period).max_tilt;
    EXPECT_NEAR(run, *w.max_tilt, 1e-8) << c.w0;
    worst_run = std::max(worst_run, std::abs(run - *w.max_tilt));
  }
  RecordProperty("worst_vs_cubic_root", test_support::sci(worst_root));
  RecordProperty("worst_vs_integration", test_support::sci(worst_run));
  // The upright start never tilts; an asymmetric body's wander is integrated over the horizon.
  const Wander up = axis_wander(make_body(1.0, 1.5, 2.0, 1.0), make_state(1.45, 0.0), 50.0);
  EXPECT_EQ(up.max_tilt, 0.0);
  const Wander asym = axis_wander(make_body(1.0, 1.5, 2.0, 1.0), make_state(1.45, 1e-4), 50.0);
  ASSERT_TRUE(asym.max_tilt);
  EXPECT_FALSE(asym.closed_form);
  EXPECT_EQ(asym.horizon, 50.0);
  EXPECT_EQ(*asym.max_tilt, tilt_extremes(make_body(1.0, 1.5, 2.0, 1.0), make_state(1.45, 1e-4), 50.0).max_tilt);
  EXPECT_LT(*asym.max_tilt, 4e-4);
}

// ---- Hanging bodies, the free body, degenerate cases -----------------------------------------

TEST(Lyapunov, HangingBodies) {
  const Body sym = make_body(1.0, 1.0, 2.0, -1.0);
  for (double w : {0.0, 0.5, 10.0}) {
    EXPECT_EQ(lyapunov_stability(sym, w).certificate, Cert::EnergyCasimir) << w;
  }
  auto all = lyapunov_stable_spin_intervals(sym);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].lo, 0.0);
  EXPECT_TRUE(all[0].lo_included);
  EXPECT_FALSE(all[0].hi);
  EXPECT_EQ(superfast_spin(sym), 0.0);
  // C < A: index 2 at high spin, Chetaev still proves it (C^2 w0^2 > 4 A m g R for m g R < 0).
  const Body slender = make_body(1.0, 1.0, 0.5, -1.0);
  const auto fast = lyapunov_stability(slender, 10.0);
  EXPECT_EQ(fast.energy_index, 2);
  EXPECT_EQ(fast.certificate, Cert::Chetaev);
  ASSERT_EQ(lyapunov_stable_spin_intervals(slender).size(), 1u);
  EXPECT_EQ(lyapunov_stable_spin_intervals(slender)[0].lo, 0.0);
  EXPECT_FALSE(lyapunov_stable_spin_intervals(slender)[0].hi);
  // E3's asymmetric hanging body: index 1 exactly between sqrt 2 and sqrt(1/0.3) = 1.826.
  const Body asym = make_body(1.0, 1.2, 0.7, -1.0);
  EXPECT_EQ(lyapunov_stability(asym, 1.2).certificate, Cert::EnergyCasimir);
  EXPECT_EQ(lyapunov_stability(asym, 1.6).certificate, Cert::OddIndex);
  const auto high = lyapunov_stability(asym, 2.0);  // index 2, linearly stable: Arnold's theorem
  EXPECT_EQ(high.energy_index, 2);
  EXPECT_EQ(high.verdict, V::Stable);
  EXPECT_EQ(high.certificate, Cert::Kam);
  ASSERT_TRUE(high.normal_form.has_value());
  EXPECT_NE(high.normal_form->D, 0.0);
  const auto window = lyapunov_stable_spin_intervals(asym);
  ASSERT_EQ(window.size(), 2u);  // the energy-Casimir window, then the KAM spins above index 1
  EXPECT_NEAR(window[1].lo, std::sqrt(1.0 / 0.3), 1e-12);
  EXPECT_FALSE(window[1].lo_included);
  EXPECT_FALSE(window[1].hi);
  EXPECT_EQ(window[0].lo, 0.0);
  EXPECT_TRUE(window[0].lo_included);
  ASSERT_TRUE(window[0].hi);
  EXPECT_NEAR(*window[0].hi, std::sqrt(2.0), 1e-15);
  EXPECT_FALSE(window[0].hi_included);
  EXPECT_FALSE(superfast_spin(asym));
}

TEST(Lyapunov, FreeBody) {
  Body sym = make_body(1.0, 1.0, 2.0, 0.0);
  sym.gravity = 0.0;
  sym.length = 1.0;
  const auto rest = lyapunov_stability(sym, 0.0);  // a neutral drift: not stable
  EXPECT_EQ(rest.verdict, V::Unstable);
  EXPECT_EQ(rest.certificate, Cert::LinearInstability);
  EXPECT_EQ(lyapunov_stability(sym, 1.0).verdict, V::Stable);
  auto spins = lyapunov_stable_spin_intervals(sym);
  ASSERT_EQ(spins.size(), 1u);
  EXPECT_EQ(spins[0].lo, 0.0);
  EXPECT_FALSE(spins[0].lo_included);
  // Asymmetric: about the axis of least moment stable (energy-Casimir with |L|^2), about the
  // intermediate one index 1, with C equal to A it tumbles.
  const Body least = make_body(1.0, 1.5, 0.8, 0.0), middle = make_body(1.0, 2.0, 1.5, 0.0),
             equal = make_body(1.0, 1.5, 1.0, 0.0);
  EXPECT_EQ(lyapunov_stability(least, 1.0).verdict, V::Stable);
  EXPECT_EQ(lyapunov_stability(least, 1.0).energy_index, 2);
  EXPECT_EQ(lyapunov_stability(middle, 1.0).certificate, Cert::OddIndex);
  EXPECT_EQ(lyapunov_stability(equal, 1.0).verdict, V::Unstable);
  EXPECT_TRUE(lyapunov_stable_spin_intervals(middle).empty());
  EXPECT_TRUE(lyapunov_stable_spin_intervals(equal).empty());
  ASSERT_EQ(lyapunov_stable_spin_intervals(least).size(), 1u);
  // The independent route for the two: a nonlinear run with a small transverse rate.
  EXPECT_LT(tilt_extremes(least, make_state(1.0, 0.0, 0.0, 1e-2), 300.0).max_tilt, 0.05);
  EXPECT_TRUE(tilt_extremes(equal, make_state(1.0, 0.0, 0.0, 1e-2), 1000.0, 1.0).exceeded);
}

// ---- The sweep's column ----------------------------------------------------------------------

TEST(Lyapunov, SweepColumnIsTheProvenVerdict) {
  const Body b = make_body(1.0, 1.5, 2.0, 1.0);
  const std::vector<SweepAxis> axes{{"spin", 0.0, 3.0, 301}};
  const auto verdicts = sweep_verdicts(b, InitialState{}, axes, SweepOptions{}, 0, grid_size(axes));
  int stable = 0;
  for (std::size_t i = 0; i < verdicts.size(); ++i) {
    const double w = axes[0].value(i);
    EXPECT_EQ(verdicts[i].lyapunov, w > std::sqrt(2.0)) << w;
    stable += verdicts[i].lyapunov;
  }
  EXPECT_EQ(stable, 159);  // w0 = 1.42, 1.43, ..., 3.00
}

}  // namespace
}  // namespace heavytop

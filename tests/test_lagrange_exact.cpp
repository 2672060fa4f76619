// lagrange-exact: agreement with the adaptive nonlinear integrator for every degenerate motion
// and for random symmetric bodies, the nutation bounds against the cubic solved here, the
// periodicity that makes a sample's cost independent of t, the attitude and angular velocity,
// and input checking.

#include "heavytop/lagrange_exact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <Eigen/Geometry>

#include "heavytop/nonlinear.hpp"
#include "models/lagrange_evaluator.hpp"  // white-box: the poles, the Landen route
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::angle_between;
using test_support::axis_of;
using test_support::make_state;
using test_support::sci;

constexpr double kPi = 3.141592653589793;

// A symmetric body with mass 1, gravity 1 and length m g R (B = A unless given).
Body make_body(double A, double C, double mgR, double B = -1.0) {
  return test_support::make_body(A, B > 0.0 ? B : A, C, mgR);
}

struct Case {
  std::string name;
  Body body;
  InitialState state;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// The steady precession at tilt th: phi' about the vertical Omega solves
// 2 u Omega^2 - 2 b Omega + beta = 0 (slow root); SPEC's phi_rate0 = -Omega sin(th).
InitialState steady_precession(double A, double C, double mgR, double spin, double th) {
  const double b = C * spin / A, beta = 2.0 * mgR / A, u = std::cos(th);
  const double omega = (b - std::sqrt(b * b - 2.0 * beta * u)) / (2.0 * u);
  return make_state(spin, th, 0.0, 0.0, -omega * std::sin(th));
}

// L_zeta = L_3 from a tilted start: (k x k')_zeta = b (1 - cos th) with k' = (0, -phi_rate0, 0).
InitialState vertical_passage_from_tilt(double A, double C, double spin, double th) {
  const double b = C * spin / A;
  return make_state(spin, th, 0.0, 0.0, -b * (1.0 - std::cos(th)) / std::sin(th));
}

std::vector<Case> degenerate_cases() {
  return {
      {"generic_top", make_body(1.0, 0.5, 1.0), make_state(4.0, 0.3, 0.1, 0.2, -0.3)},
      {"fast_top", make_body(1.0, 0.5, 1.0), make_state(20.0, 0.2, 0.0, 0.1, 0.0)},
      {"sleeping_top", make_body(1.0, 0.5, 1.0), make_state(5.0, 0.0)},
      {"steady_precession", make_body(1.0, 0.5, 1.0), steady_precession(1.0, 0.5, 1.0, 5.0, 0.4)},
      {"through_vertical_from_vertical", make_body(1.0, 0.5, 1.0), make_state(5.0, 0.0, 0.0, 0.4)},
      {"through_vertical_from_tilt", make_body(1.0, 0.5, 1.0),
       vertical_passage_from_tilt(1.0, 0.5, 5.0, 0.5)},
      {"near_vertical_passage", make_body(1.0, 0.5, 1.0),
       [] { InitialState s = vertical_passage_from_tilt(1.0, 0.5, 5.0, 0.5); s.phi_rate0 *= 1.0 + 1e-6; return s; }()},
      // Passes 2.7e-3 rad from the downward vertical. Closer, the integrator's rounding
      // (amplified like 1/distance at each passage) exceeds 1e-9 rad over 100 passages.
      {"near_bottom_passage", make_body(1.0, 0.5, 1.0), make_state(1e-2, 2.0)},
      {"hanging_body", make_body(1.0, 0.7, -1.0), make_state(3.0, 0.5, 0.0, 0.0, 0.4)},
      {"hanging_large_swing", make_body(1.0, 0.7, -1.0), make_state(1.0, 2.0, 0.0, 2.5, 0.0)},
      {"pendulum_through_bottom", make_body(1.0, 0.5, 1.0), make_state(0.0, 2.0)},
      {"hanging_pendulum_through_bottom", make_body(1.0, 0.5, -1.0), make_state(0.0, 0.5, 0.0, 0.5)},
      {"hanging_pendulum_full_turns", make_body(1.0, 0.5, -1.0), make_state(0.0, 0.5, 0.0, 3.0)},
      {"free_body_R0", make_body(1.0, 0.6, 0.0), make_state(2.0, 0.4, 0.1, 0.3, 0.2)},
      {"no_gravity", [] { Body b = make_body(1.0, 0.6, 0.7); b.gravity = 0.0; return b; }(),
       make_state(2.0, 0.4, 0.1, 0.3, 0.2)},
      {"large_swing", make_body(1.0, 0.5, 1.0), make_state(1.0, 1.0, 0.0, 2.0, 0.0)},
      {"oblate_disc", make_body(1.0, 1.9, 0.5), make_state(3.0, 0.6, 0.2, 0.5, -0.4)},
  };
}

// Random symmetric bodies and states; a draw is kept when its nutation period is at most 8 s
// (100 periods at rtol 1e-14 then run in well under a second).
std::vector<Case> random_cases() {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Case> cases;
  while (cases.size() < 10) {
    const double A = 0.5 + 1.5 * U(rng);
    const double C = (0.2 + 1.7 * U(rng)) * A;
    const double mgR = -2.0 + 4.0 * U(rng);
    const InitialState s = make_state(-8.0 + 16.0 * U(rng), kPi * U(rng), -1.0 + 2.0 * U(rng),
                                      -2.0 + 4.0 * U(rng), -2.0 + 4.0 * U(rng));
    const Body body = make_body(A, C, mgR);
    const double period = nutation_period(lagrange_top(body, s));
    if (!(period <= 8.0)) continue;
    cases.push_back({"random_" + std::to_string(cases.size()), body, s});
  }
  return cases;
}

// ---- Agreement with the adaptive integrator ------------------------------------------------

class AgreesWithNonlinear : public ::testing::TestWithParam<Case> {};

TEST_P(AgreesWithNonlinear, Over100NutationPeriods) {
  const Case& c = GetParam();
  LagrangeExactOptions direct;
  direct.fourier_series = false;
  const LagrangeTop top = lagrange_top(c.body, c.state);
  const LagrangeTop top_direct = lagrange_top(c.body, c.state, direct);
  // 100 nutation periods; for a constant tilt 100 periods of the precession (or 100 s).
  double horizon = 100.0 * top.nutation_period;
  const double phi_rate = detail::evaluator_of(top).phi_rate;
  if (!std::isfinite(horizon)) horizon = std::abs(phi_rate) > 0.0 ? 100.0 * 2.0 * kPi / std::abs(phi_rate) : 100.0;
  horizon = std::min(horizon, 3000.0);
  const std::vector<double> times = sample_times(horizon, 4001);
  Tolerances tight;
  tight.rtol = tight.atol = 1e-14;
  const Trajectory reference = simulate_nonlinear(c.body, c.state, times, tight);
  const Trajectory exact = simulate_lagrange_exact(c.body, c.state, times);

  double axis_error = 0.0, angle_error = 0.0, max_eta = 0.0, series_vs_direct = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Vector3d k_ref = axis_of(reference.theta[i], reference.phi[i]);
    axis_error = std::max(axis_error, angle_between(axis_of(exact.theta[i], exact.phi[i]), k_ref));
    // theta = atan2(k_xi, k_zeta) jumps by 2 pi where the axis crosses below the vertical.
    angle_error = std::max({angle_error, std::abs(std::remainder(exact.theta[i] - reference.theta[i], 2 * kPi)),
                            std::abs(exact.phi[i] - reference.phi[i])});
    max_eta = std::max(max_eta, std::abs(k_ref.y()));
    series_vs_direct = std::max(series_vs_direct, angle_between(lagrange_axis(top, times[i]).k,
                                                                lagrange_axis(top_direct, times[i]).k));
  }
  RecordProperty("axis_error_rad", sci(axis_error));
  RecordProperty("angle_error_rad", sci(angle_error));
  RecordProperty("series_vs_direct_rad", sci(series_vs_direct));
  RecordProperty("periods", sci(horizon / top.nutation_period));
  EXPECT_LT(axis_error, 1e-9) << c.name;
  // theta, phi themselves where SPEC's angles are well conditioned (|phi| < 1.1 rad); near
  // |k_eta| = 1 they amplify any error by 1/cos(phi).
  if (max_eta < 0.9) {
    EXPECT_LT(angle_error, 1e-9) << c.name;
  }
  EXPECT_LT(series_vs_direct, 1e-12) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Degenerate, AgreesWithNonlinear, ::testing::ValuesIn(degenerate_cases()),
                         [](const auto& info) { return info.param.name; });
INSTANTIATE_TEST_SUITE_P(RandomSymmetric, AgreesWithNonlinear, ::testing::ValuesIn(random_cases()),
                         [](const auto& info) { return info.param.name; });

TEST(LagrangeExact, DegenerateCasesAreRecognised) {
  const auto cases = degenerate_cases();
  auto top_of = [&](const std::string& name) {
    for (const Case& c : cases)
      if (c.name == name) return lagrange_top(c.body, c.state);
    throw std::out_of_range(name);
  };
  EXPECT_TRUE(top_of("sleeping_top").constant_tilt);
  EXPECT_EQ(top_of("sleeping_top").u_min, 1.0);
  const LagrangeTop steady = top_of("steady_precession");
  EXPECT_NEAR(steady.u_max - steady.u_min, 0.0, 1e-14);
  EXPECT_TRUE(top_of("through_vertical_from_vertical").through_vertical);
  EXPECT_EQ(top_of("through_vertical_from_vertical").u_max, 1.0);
  EXPECT_NEAR(top_of("through_vertical_from_tilt").u_max, 1.0, 1e-15);
  EXPECT_TRUE(top_of("pendulum_through_bottom").through_downward);
  EXPECT_TRUE(top_of("hanging_pendulum_through_bottom").through_vertical);
  EXPECT_TRUE(top_of("hanging_pendulum_full_turns").through_vertical);
  EXPECT_TRUE(top_of("hanging_pendulum_full_turns").through_downward);
  EXPECT_TRUE(std::isinf(top_of("free_body_R0").u_third));
}

// Near the separatrix (an unstable sleeping top started 1e-3 rad off the vertical; k' ~ 1e-3,
// Landen's descent instead of theta series) the period depends on the energy like log(1/dE),
// so the integrator's error is amplified; it must shrink tenfold per decade of tolerance,
// towards the closed form.
TEST(LagrangeExact, NearSeparatrixTheIntegratorConvergesToIt) {
  const Body body = make_body(1.0, 0.5, 1.0);
  const InitialState s = make_state(3.0, 1e-3);  // critical spin 4 rad/s
  const LagrangeTop top = lagrange_top(body, s);
  ASSERT_LT(detail::evaluator_of(top).jacobi.kc2, 1e-5);
  ASSERT_EQ(detail::evaluator_of(top).jacobi.theta_terms, 0);  // Landen's descent
  const std::vector<double> times = sample_times(20.0 * top.nutation_period, 201);
  std::vector<double> errors;
  for (double tol : {1e-12, 1e-13, 1e-14}) {
    Tolerances o;
    o.rtol = o.atol = tol;
    const Trajectory nl = simulate_nonlinear(body, s, times, o);
    double e = 0.0;
    for (std::size_t i = 0; i < times.size(); ++i)
      e = std::max(e, angle_between(lagrange_axis(top, times[i]).k, axis_of(nl.theta[i], nl.phi[i])));
    errors.push_back(e);
  }
  RecordProperty("errors_at_1e-12_1e-13_1e-14", sci(errors[0]) + " " + sci(errors[1]) + " " + sci(errors[2]));
  EXPECT_GT(errors[0] / errors[1], 5.0);
  EXPECT_GT(errors[1] / errors[2], 5.0);
  EXPECT_LT(errors[2], 1e-5);
}

// The azimuth of a vertical passage jumps by pi: just before and after, the axis sits on
// opposite sides of the vertical.
TEST(LagrangeExact, AzimuthJumpsByPiThroughTheVertical) {
  const LagrangeTop top = lagrange_top(make_body(1.0, 0.5, 1.0), make_state(5.0, 0.0, 0.0, 0.4));
  ASSERT_TRUE(top.through_vertical);
  const double T = top.nutation_period;
  const double dt = 1e-4 * T;
  const AxisMotion before = lagrange_axis(top, T - dt), after = lagrange_axis(top, T + dt);
  const double az_before = std::atan2(before.k.y(), before.k.x());
  const double az_after = std::atan2(after.k.y(), after.k.x());
  const double jump = std::remainder(az_after - az_before, 2.0 * kPi);
  RecordProperty("azimuth_jump_rad", sci(jump));
  EXPECT_NEAR(std::abs(jump), kPi, 1e-3);
  EXPECT_LT(1.0 - lagrange_axis(top, T).k.z(), 1e-15);  // at the vertical at t = T
}

// ---- Nutation bounds -------------------------------------------------------------------------

// The real roots of beta u^3 - (alpha + b^2) u^2 + (2 a b - beta) u + (alpha - a^2), the
// Lagrange top's cubic, from E, L_zeta and L_3 alone (companion matrix, then Newton).
std::vector<double> cubic_roots(const Body& body, const InitialState& s) {
  const ConservedQuantities q = conserved_quantities(body, initial_rigid_body_state(s));
  const double A = body.A, a = q.vertical_momentum / A, b = q.axial_momentum / A;
  const double alpha = (2.0 * q.energy - q.axial_momentum * q.axial_momentum / body.C) / A;
  const double beta = 2.0 * body.mgR() / A;
  const long double c[4] = {alpha - a * a, 2.0 * a * b - beta, -(alpha + b * b), beta};
  std::vector<double> roots;
  Eigen::Matrix3d companion = Eigen::Matrix3d::Zero();
  companion(1, 0) = companion(2, 1) = 1.0;
  for (int i = 0; i < 3; ++i) companion(i, 2) = static_cast<double>(-c[i] / c[3]);
  for (const auto& r : Eigen::EigenSolver<Eigen::Matrix3d>(companion).eigenvalues()) {
    if (std::abs(r.imag()) > 1e-6) continue;
    long double u = r.real();
    for (int it = 0; it < 8; ++it) {
      const long double f = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
      const long double df = (3 * c[3] * u + 2 * c[2]) * u + c[1];
      if (df != 0) u -= f / df;
    }
    roots.push_back(static_cast<double>(u));
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

class NutationBoundsTest : public ::testing::TestWithParam<Case> {};

TEST_P(NutationBoundsTest, AreRootsOfTheCubicAndAreReached) {
  const Case& c = GetParam();
  const LagrangeTop top = lagrange_top(c.body, c.state);
  const NutationBounds bounds = nutation_bounds(top);
  const std::vector<double> roots = cubic_roots(c.body, c.state);
  ASSERT_EQ(roots.size(), 3u);
  // m g R > 0: u_min, u_max are the two smaller roots; m g R < 0: the two larger.
  const double lo = c.body.mgR() > 0.0 ? roots[0] : roots[1];
  const double hi = c.body.mgR() > 0.0 ? roots[1] : roots[2];
  const double far = c.body.mgR() > 0.0 ? roots[2] : roots[0];
  // The roots from the expanded cubic are only as good as its conditioning: a near-double
  // root (steady precession, near a separatrix) moves by sqrt(df / f'') for a rounding df.
  const double A = c.body.A;
  const ConservedQuantities q = conserved_quantities(c.body, initial_rigid_body_state(c.state));
  auto tolerance = [&](double u) {
    const double a = q.vertical_momentum / A, b = q.axial_momentum / A, beta = 2.0 * c.body.mgR() / A;
    const double alpha = (2.0 * q.energy - q.axial_momentum * q.axial_momentum / c.body.C) / A;
    const double size = std::abs(alpha) + a * a + 2.0 * std::abs(a * b) + std::abs(beta) * 2.0 + b * b;
    const double df = 16.0 * 2.2e-16 * size;
    const double d1 = std::abs(3.0 * beta * u * u - 2.0 * (alpha + b * b) * u + 2.0 * a * b - beta);
    const double d2 = std::abs(6.0 * beta * u - 2.0 * (alpha + b * b));
    return 1e-13 + std::min(df / d1, std::sqrt(2.0 * df / d2));
  };
  RecordProperty("root_differences", sci(bounds.u_min - lo) + " " + sci(bounds.u_max - hi));
  EXPECT_NEAR(bounds.u_min, lo, tolerance(lo)) << c.name;
  EXPECT_NEAR(bounds.u_max, hi, tolerance(hi)) << c.name;
  EXPECT_NEAR(top.u_third, far, tolerance(far) * std::max(1.0, std::abs(far))) << c.name;
  EXPECT_NEAR(std::cos(bounds.max_tilt), bounds.u_min, 1e-15);
  EXPECT_NEAR(std::cos(bounds.min_tilt), bounds.u_max, 1e-15);

  // Sampled over two periods, u stays within the bounds and touches both: refine the
  // turning points (sign changes of u') by bisection on the samples.
  const double T = top.nutation_period;
  double u_lo_seen = 2.0, u_hi_seen = -2.0, outside = 0.0;
  double t_prev = 0.0, du_prev = lagrange_axis(top, 0.0).k_rate.z();
  for (int i = 1; i <= 2000; ++i) {
    const double t = 2.0 * T * i / 2000.0;
    const AxisMotion m = lagrange_axis(top, t);
    outside = std::max({outside, m.k.z() - bounds.u_max, bounds.u_min - m.k.z()});
    if ((du_prev > 0.0) != (m.k_rate.z() > 0.0)) {
      double a = t_prev, b = t;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (a + b);
        if ((lagrange_axis(top, mid).k_rate.z() > 0.0) == (du_prev > 0.0)) a = mid; else b = mid;
      }
      const double u = lagrange_axis(top, 0.5 * (a + b)).k.z();
      u_lo_seen = std::min(u_lo_seen, u);
      u_hi_seen = std::max(u_hi_seen, u);
    }
    t_prev = t;
    du_prev = m.k_rate.z();
  }
  RecordProperty("touch_differences", sci(u_lo_seen - bounds.u_min) + " " + sci(u_hi_seen - bounds.u_max));
  EXPECT_LT(outside, 1e-14);
  EXPECT_NEAR(u_lo_seen, bounds.u_min, 1e-13);
  EXPECT_NEAR(u_hi_seen, bounds.u_max, 1e-13);
}

std::vector<Case> bounded_cases() {
  std::vector<Case> out;
  for (const Case& c : degenerate_cases())
    if (std::isfinite(lagrange_top(c.body, c.state).nutation_period) && c.body.mgR() != 0.0 &&
        c.body.gravity != 0.0 && !lagrange_top(c.body, c.state).through_vertical &&
        !lagrange_top(c.body, c.state).through_downward)
      out.push_back(c);
  for (const Case& c : random_cases()) out.push_back(c);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Cases, NutationBoundsTest, ::testing::ValuesIn(bounded_cases()),
                         [](const auto& info) { return info.param.name; });

// The whole-period increments of the azimuth and the spin angle (elliptic integrals of the
// third kind) against a quadrature of phi' = P/(1 - u) + Q/(1 + u), psi' = w3 - b - P/(1 - u)
// + Q/(1 + u) over a period, u from Boost's Jacobi sn (not the library's own). Includes
// passages 3e-5 and 1e-10 rad from a vertical, where the integrand is a spike that narrow.
TEST(LagrangeExact, PeriodIncrementsMatchQuadrature) {
  std::vector<Case> cases = degenerate_cases();
  cases.push_back({"bottom_at_3e-5_rad", make_body(1.0, 0.5, 1.0), make_state(1e-4, 2.0)});
  cases.push_back({"top_within_1e-10_rad", make_body(1.0, 0.5, 1.0), [] {
                     InitialState s = vertical_passage_from_tilt(1.0, 0.5, 5.0, 0.5);
                     s.phi_rate0 *= 1.0 + 1e-10;
                     return s;
                   }()});
  std::string checked;
  double worst = 0.0;
  for (const Case& c : cases) {
    LagrangeExactOptions direct;
    direct.fourier_series = false;
    const LagrangeTop top = lagrange_top(c.body, c.state, direct);
    const detail::LagrangeEvaluator& d = detail::evaluator_of(top);
    if (!std::isfinite(top.nutation_period) || d.pole[0].signed_form || d.pole[1].signed_form) continue;
    const double P = d.pole[0].residue, Q = d.pole[1].residue;
    const double kc = std::sqrt(d.jacobi.kc2);
    // 1 - u and 1 + u at tau (near 0) or at K - tau (near K, by sn(K - e) = cn(e)/dn(e),
    // cn(K - e) = k' sn(e)/dn(e)): both ends of a half period without loss of digits.
    auto poles_rate = [&](double e, bool from_k, double sign_p) {
      double cn, dn;
      double sn = boost::math::jacobi_elliptic(d.jacobi.k, e, &cn, &dn);
      if (from_k) {
        const double s = cn / dn;
        cn = kc * sn / dn;
        sn = s;
      }
      const double om = d.d >= 0.0 ? d.one_minus_b + d.d * cn * cn : d.one_minus_a - d.d * sn * sn;
      const double op = d.d >= 0.0 ? d.one_plus_a + d.d * sn * sn : d.one_plus_b - d.d * cn * cn;
      return (sign_p * P / om + Q / op) / d.lambda;  // per unit tau
    };
    // sn^2 is even about 0 and K: twice the integral over [0, K], as two halves measured
    // from their ends, cut at points graded geometrically towards the ends, where the spike
    // of a near passage (width ~ its distance from the vertical) sits.
    boost::math::quadrature::tanh_sinh<double> quad;
    const std::vector<double> cuts = {0.0, 1e-18, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3, 0.5};
    double dphi = 0.0, dpsi = d.spin_rate_linear * top.nutation_period;
    for (bool from_k : {false, true})
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double a = cuts[i] * d.jacobi.K, b = cuts[i + 1] * d.jacobi.K;
        dphi += 2.0 * quad.integrate([&](double e) { return poles_rate(e, from_k, 1.0); }, a, b, 1e-14);
        dpsi += 2.0 * quad.integrate([&](double e) { return poles_rate(e, from_k, -1.0); }, a, b, 1e-14);
      }
    const double scale = 1.0 + std::abs(dphi);
    checked += c.name + " ";
    worst = std::max({worst, std::abs(top.precession_per_period - dphi) / scale,
                      std::abs(top.spin_per_period - dpsi) / (1.0 + std::abs(dpsi))});
    EXPECT_NEAR(top.precession_per_period, dphi, 1e-12 * scale) << c.name;
    EXPECT_NEAR(top.spin_per_period, dpsi, 1e-12 * (1.0 + std::abs(dpsi))) << c.name;
  }
  RecordProperty("checked", checked);
  RecordProperty("largest_relative_difference", sci(worst));
}

// ---- Periodicity: the cost of a sample does not depend on t ------------------------------

// k(t + n T) = R_zeta(n dphi) k(t) and R(t + n T) = R_zeta(n dphi) R(t) R_z(n dpsi): the sample
// at t = 1e6 s equals the sample at 1e6 - n T rotated by the whole-period increments.
TEST(LagrangeExact, FarSampleEqualsReducedSampleWithWholePeriodIncrements) {
  double worst = 0.0;
  for (const Case& c : degenerate_cases()) {
    const LagrangeTop top = lagrange_top(c.body, c.state);
    if (!std::isfinite(top.nutation_period)) continue;
    const double T = top.nutation_period, t = 1e6;
    const double n = std::floor(t / T);
    const double t_reduced = t - n * T;
    auto rz = [](double angle) {
      return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    };
    const double dphi = std::remainder(n * std::remainder(top.precession_per_period, 2 * kPi), 2 * kPi);
    const double dpsi = std::remainder(n * std::remainder(top.spin_per_period, 2 * kPi), 2 * kPi);
    const AxisMotion far = lagrange_axis(top, t), near = lagrange_axis(top, t_reduced);
    const RigidBodyState far_body = lagrange_rigid_body_state(top, t);
    const RigidBodyState near_body = lagrange_rigid_body_state(top, t_reduced);
    // The rounding of t itself (1.2e-10 s at 1e6 s) and of n dphi bound the agreement.
    worst = std::max({worst, (far.k - rz(dphi) * near.k).norm(),
                      (far_body.attitude - rz(dphi) * near_body.attitude * rz(dpsi)).norm()});
    EXPECT_LT((far.k - rz(dphi) * near.k).norm(), 1e-8) << c.name;
    EXPECT_LT((far_body.attitude - rz(dphi) * near_body.attitude * rz(dpsi)).norm(), 1e-8) << c.name;
    EXPECT_LT((far_body.omega - rz(dpsi).transpose() * near_body.omega).norm(), 1e-8) << c.name;
    // And the first integrals hold at t = 1 and t = 1e6.
    const Body& b = c.body;
    const ConservedQuantities q0 = conserved_quantities(b, initial_rigid_body_state(c.state));
    for (double tt : {1.0, 1e6}) {
      const ConservedQuantities q = conserved_quantities(b, lagrange_rigid_body_state(top, tt));
      const double scale = std::abs(q0.energy) + std::abs(b.mgR()) + 1.0;
      EXPECT_NEAR(q.energy, q0.energy, 1e-12 * scale) << c.name << " t=" << tt;
      EXPECT_NEAR(q.vertical_momentum, q0.vertical_momentum, 1e-12 * scale) << c.name;
      EXPECT_NEAR(q.axial_momentum, q0.axial_momentum, 1e-12 * scale) << c.name;
    }
  }
  RecordProperty("largest_difference", sci(worst));
}

// ---- The state at t = 0 and the rigid-body motion ------------------------------------------

TEST(LagrangeExact, ReproducesTheInitialState) {
  for (const Case& c : degenerate_cases()) {
    const Trajectory tr = simulate_lagrange_exact(c.body, c.state, {0.0});
    EXPECT_NEAR(tr.theta[0], c.state.theta0, 1e-14) << c.name;
    EXPECT_NEAR(tr.phi[0], c.state.phi0, 1e-14) << c.name;
    EXPECT_NEAR(tr.theta_rate[0], c.state.theta_rate0, 1e-13) << c.name;
    EXPECT_NEAR(tr.phi_rate[0], c.state.phi_rate0, 1e-13) << c.name;
    const RigidBodyState x0 = initial_rigid_body_state(c.state);
    const RigidBodyState x = lagrange_rigid_body_state(lagrange_top(c.body, c.state), 0.0);
    EXPECT_LT((x.attitude - x0.attitude).norm(), 1e-13) << c.name;
    EXPECT_LT((x.omega - x0.omega).norm(), 1e-13 * (1.0 + x0.omega.norm())) << c.name;
  }
}

// The attitude's derivative is R [w]x with the reported w (a check of the spin angle psi,
// which the axis alone does not show), by central differences.
TEST(LagrangeExact, AttitudeRateMatchesAngularVelocity) {
  for (const Case& c : degenerate_cases()) {
    const LagrangeTop top = lagrange_top(c.body, c.state);
    for (double t : {0.7, 13.1, 211.9}) {
      const double h = 1e-5;
      const RigidBodyState x = lagrange_rigid_body_state(top, t);
      const Eigen::Matrix3d rate = (lagrange_rigid_body_state(top, t + h).attitude -
                                    lagrange_rigid_body_state(top, t - h).attitude) / (2.0 * h);
      Eigen::Matrix3d wx;
      wx << 0.0, -x.omega.z(), x.omega.y(), x.omega.z(), 0.0, -x.omega.x(), -x.omega.y(),
          x.omega.x(), 0.0;
      const double scale = 1.0 + x.omega.squaredNorm();
      EXPECT_LT((rate - x.attitude * wx).norm(), 1e-7 * scale) << c.name << " t=" << t;
    }
  }
}

// ---- Input checking --------------------------------------------------------------------------

TEST(LagrangeExact, RefusesAnAsymmetricBody) {
  const InitialState s = make_state(4.0, 0.3);
  try {
    simulate_lagrange_exact(make_body(1.0, 0.5, 1.0, 1.01), s, {0.0, 1.0});
    FAIL() << "accepted A != B";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.B");
    EXPECT_NE(std::string(e.what()).find("symmetric"), std::string::npos);
  }
  // Within 1e-12 relative counts as symmetric.
  EXPECT_NO_THROW(simulate_lagrange_exact(make_body(1.0, 0.5, 1.0, 1.0 + 5e-13), s, {1.0}));
  EXPECT_THROW(simulate_lagrange_exact(make_body(1.0, 0.5, 1.0, 1.0 + 5e-12), s, {1.0}), InvalidInput);
}

TEST(LagrangeExact, RefusesBadInput) {
  const Body body = make_body(1.0, 0.5, 1.0);
  try {
    simulate_lagrange_exact(body, make_state(4.0, 0.3), {0.0, std::nan("")});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "times");
  }
  InitialState bad = make_state(4.0, 0.3);
  bad.theta_rate0 = std::nan("");
  EXPECT_THROW(simulate_lagrange_exact(body, bad, {0.0}), InvalidInput);
  Body heavy = body;
  heavy.mass = -1.0;
  EXPECT_THROW(simulate_lagrange_exact(heavy, make_state(4.0, 0.3), {0.0}), InvalidInput);
  // Any finite times, in any order, are fine for a closed form.
  const Trajectory tr = simulate_lagrange_exact(body, make_state(4.0, 0.3), {5.0, -1.0, 0.0});
  EXPECT_NEAR(tr.theta[2], 0.3, 1e-15);
}

}  // namespace
}  // namespace heavytop

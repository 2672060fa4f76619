// The nonlinear model: conservation, the Lagrange top's nutation bounds, convergence, the
// SPEC section 2 mapping, the small-motion limit (model (4)), erratum E3, an independent
// body-frame integration, and option checking.

#include "heavytop/nonlinear.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Geometry>
#include <boost/numeric/odeint.hpp>
#include <unsupported/Eigen/MatrixFunctions>

#include "heavytop/frames.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::axis_of;
using test_support::column;
using test_support::make_body;
using test_support::make_state;
using test_support::sci;

// Code written against heavytop 0.1 still compiles: NonlinearOptions is Tolerances (deprecated).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
static_assert(std::is_same_v<NonlinearOptions, Tolerances>);
#pragma GCC diagnostic pop

// The tilt acos(k_zeta) from SPEC's angles: k_zeta = cos(theta) cos(phi).
double tilt_from_angles(double theta, double phi) {
  const Eigen::Vector3d k = axis_of(theta, phi);
  return std::atan2(std::hypot(k.x(), k.y()), k.z());
}

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

double max_angle_difference(const Trajectory& a, const Trajectory& b) {
  return std::max(max_abs_difference(a.theta, b.theta), max_abs_difference(a.phi, b.phi));
}

// E, L_zeta and C w3 computed here from the rigid-body state (not with the library's helper).
struct Integrals {
  double E, L_zeta, L_z;
};
Integrals integrals(const Body& b, const RigidBodyState& x) {
  const Eigen::Vector3d gamma = x.attitude.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d L(b.A * x.omega.x(), b.B * x.omega.y(), b.C * x.omega.z());
  return {0.5 * x.omega.dot(L) + b.mgR() * gamma.z(), L.dot(gamma), L.z()};
}

// ---- Conservation ---------------------------------------------------------------------------

TEST(Nonlinear, SymmetricTopConservesEnergyAndMomentaOverThousandNutations) {
  // A = B = 1, C = 2, m g R = 1, spin 3, theta0 = 0.3: nutation period about 1 s.
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  const InitialState s = make_state(3.0, 0.3);
  const double horizon = 1200.0;
  NonlinearSummary summary;
  const Trajectory tr = simulate_nonlinear(body, s, sample_times(horizon, 120001), {}, &summary);

  // Count the nutation periods actually covered: maxima of the tilt between samples.
  std::vector<double> tilt(tr.size());
  for (std::size_t i = 0; i < tr.size(); ++i) tilt[i] = tilt_from_angles(tr.theta[i], tr.phi[i]);
  int maxima = 0;
  for (std::size_t i = 1; i + 1 < tilt.size(); ++i)
    if (tilt[i] > tilt[i - 1] && tilt[i] >= tilt[i + 1]) ++maxima;
  EXPECT_GE(maxima, 1000);

  const Integrals i0 = integrals(body, initial_rigid_body_state(s));
  EXPECT_NEAR(column(tr, "energy")[0], i0.E, 1e-15 * std::abs(i0.E));
  EXPECT_NEAR(column(tr, "vertical_momentum")[0], i0.L_zeta, 1e-15 * std::abs(i0.L_zeta));
  EXPECT_NEAR(column(tr, "axial_momentum")[0], i0.L_z, 1e-15 * std::abs(i0.L_z));
  double e = 0.0, l = 0.0, a = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    e = std::max(e, std::abs(column(tr, "energy_drift")[i]) / std::abs(i0.E));
    l = std::max(l, std::abs(column(tr, "vertical_momentum_drift")[i]) / std::abs(i0.L_zeta));
    a = std::max(a, std::abs(column(tr, "axial_momentum_drift")[i]) / std::abs(i0.L_z));
    // The drift columns are the value columns minus their first value.
    ASSERT_EQ(column(tr, "energy_drift")[i], column(tr, "energy")[i] - column(tr, "energy")[0]);
  }
  EXPECT_LT(e, 1e-10);
  EXPECT_LT(l, 1e-10);
  EXPECT_LT(a, 1e-10);
  // The summary watches every step, not just the samples.
  EXPECT_LT(summary.max_relative_energy_drift, 1e-10);
  EXPECT_LT(summary.max_relative_vertical_momentum_drift, 1e-10);
  EXPECT_LT(summary.max_relative_axial_momentum_drift, 1e-10);
  EXPECT_LT(summary.max_quaternion_norm_error, 1e-12);
  EXPECT_TRUE(summary.symmetric);
  EXPECT_EQ(summary.rhs_evaluations, 1 + 6 * (summary.steps + summary.rejected_steps));
  EXPECT_GE(summary.final_time, horizon);
  RecordProperty("nutation_periods", maxima);
  RecordProperty("energy_drift", sci(e));
}

TEST(Nonlinear, AsymmetricTumblingBodyConservesEnergyAndVerticalMomentum) {
  // A large, fast-changing motion of an asymmetric body: every term of Euler's equations works.
  const Body body = make_body(1.0, 1.5, 2.0, 1.0);
  const InitialState s = make_state(0.5, 1.2, -0.5, 0.7, -0.4);
  NonlinearSummary summary;
  const Trajectory tr = simulate_nonlinear(body, s, sample_times(100.0, 1001), {}, &summary);
  // Scales that cannot vanish: T + |m g R| for energy, sqrt(2 max(A, B, C) that) >= |I w|.
  const RigidBodyState x0 = initial_rigid_body_state(s);
  const double kinetic = integrals(body, x0).E - body.mgR() * x0.attitude(2, 2);
  const double energy_scale = kinetic + std::abs(body.mgR());
  const double momentum_scale = std::sqrt(2.0 * body.C * energy_scale);
  double e = 0.0, l = 0.0, axial_change = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    e = std::max(e, std::abs(column(tr, "energy_drift")[i]) / energy_scale);
    l = std::max(l, std::abs(column(tr, "vertical_momentum_drift")[i]) / momentum_scale);
    axial_change = std::max(axial_change, std::abs(column(tr, "axial_momentum_drift")[i]));
  }
  EXPECT_LT(e, 1e-10);
  EXPECT_LT(l, 1e-10);
  EXPECT_NEAR(summary.max_relative_energy_drift, e, 0.5 * e + 1e-13);  // same scales
  EXPECT_GT(axial_change, 1e-2);  // not an integral when A != B, and the column shows it
  EXPECT_FALSE(summary.symmetric);
  // The body really tumbles: its axis swings from near the top to near the bottom.
  const TiltExtremes range = tilt_extremes(body, s, 100.0);
  EXPECT_GT(range.max_tilt, 2.5);
  EXPECT_LT(range.min_tilt, 0.5);
  RecordProperty("energy_drift", sci(e));
  RecordProperty("vertical_momentum_drift", sci(l));
}

TEST(Nonlinear, SymmetricShortcutAgreesWithTheGeneralEquations) {
  // A == B takes a right-hand side without the spin angle; B = A (1 + 1e-13) takes the
  // general one. The bodies differ by far less than the tolerance, so must the motions.
  const InitialState s = make_state(3.0, 0.3, 0.1, 0.2, 0.1);
  const std::vector<double> times = sample_times(50.0, 501);
  NonlinearSummary symmetric, general;
  const Trajectory a = simulate_nonlinear(make_body(1.0, 1.0, 2.0, 1.0), s, times, {}, &symmetric);
  const Trajectory b =
      simulate_nonlinear(make_body(1.0, 1.0 + 1e-13, 2.0, 1.0), s, times, {}, &general);
  ASSERT_TRUE(symmetric.symmetric);
  ASSERT_FALSE(general.symmetric);
  const double angle = max_angle_difference(a, b);
  const double rate = std::max(max_abs_difference(a.theta_rate, b.theta_rate),
                               max_abs_difference(a.phi_rate, b.phi_rate));
  EXPECT_LT(angle, 1e-9);
  EXPECT_LT(rate, 1e-8);
  EXPECT_LT(general.max_relative_axial_momentum_drift, 1e-11);
  RecordProperty("angle_difference", sci(angle));
}

// ---- The Lagrange top's nutation bounds ----------------------------------------------------

// u = cos(tilt) of a symmetric top obeys u'^2 = f(u) with
//   f(u) = (2E' - 2 m g R u)(1 - u^2)/A - (b - a u)^2/A^2,  E' = E - a^2/(2C),
// a = L_z = C w3, b = L_zeta (A = B the transverse moment). f(+-1) <= 0 and f(u0) = u'(0)^2.
struct Cubic {
  double c3, c2, c1, c0;
  double operator()(double u) const { return ((c3 * u + c2) * u + c1) * u + c0; }
};
Cubic lagrange_cubic(const Body& b, const Integrals& in) {
  const double A = b.A, k = b.mgR(), a = in.L_z, bb = in.L_zeta;
  const double alpha = 2.0 * (in.E - a * a / (2.0 * b.C)) / A, beta = 2.0 * k / A;
  return {beta, -alpha - a * a / (A * A), -beta + 2.0 * a * bb / (A * A),
          alpha - bb * bb / (A * A)};
}

// The root of f in [lo, hi] where f changes sign, by bisection to the last bit.
double bisect(const Cubic& f, double lo, double hi) {
  const bool rising = f(lo) < f(hi);
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    ((f(mid) < 0.0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(Nonlinear, SymmetricTopTiltTouchesBothLagrangeNutationBounds) {
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  const InitialState s = make_state(3.0, 0.3, 0.1, 0.2, 0.1);  // neither bound is the start
  const RigidBodyState x0 = initial_rigid_body_state(s);
  const Cubic f = lagrange_cubic(body, integrals(body, x0));

  const Eigen::Vector3d k0 = x0.attitude.col(2);
  const Eigen::Vector3d k0_rate = x0.attitude * x0.omega.cross(Eigen::Vector3d::UnitZ());
  const double u0 = k0.z();
  ASSERT_NEAR(f(u0), k0_rate.z() * k0_rate.z(), 1e-12);  // the cubic is right at t = 0
  ASSERT_GT(f(u0), 1e-4);
  ASSERT_LT(f(-1.0), 0.0);
  ASSERT_LT(f(1.0), 0.0);
  const double tilt_low = std::acos(bisect(f, u0, 1.0));    // smallest tilt: larger root
  const double tilt_high = std::acos(bisect(f, -1.0, u0));  // largest tilt: smaller root
  ASSERT_GT(tilt_high - tilt_low, 0.05);

  // Refined extrema on the dense output over ~200 nutation periods.
  const TiltExtremes e = tilt_extremes(body, s, 200.0);
  EXPECT_NEAR(e.min_tilt, tilt_low, 1e-8);
  EXPECT_NEAR(e.max_tilt, tilt_high, 1e-8);
  EXPECT_FALSE(e.exceeded);
  EXPECT_EQ(e.t_end, 200.0);

  // Independently, from SPEC's angles at plain samples: never outside the bounds, and the
  // sampled extremes come within the sampling resolution of them.
  const Trajectory tr = simulate_nonlinear(body, s, sample_times(200.0, 200001));
  double lo = 10.0, hi = -10.0;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    const double tilt = tilt_from_angles(tr.theta[i], tr.phi[i]);
    lo = std::min(lo, tilt);
    hi = std::max(hi, tilt);
  }
  EXPECT_GE(lo, tilt_low - 1e-9);
  EXPECT_LE(hi, tilt_high + 1e-9);
  EXPECT_NEAR(lo, tilt_low, 1e-5);
  EXPECT_NEAR(hi, tilt_high, 1e-5);
  RecordProperty("bound_error_low", sci(std::abs(e.min_tilt - tilt_low)));
  RecordProperty("bound_error_high", sci(std::abs(e.max_tilt - tilt_high)));
}

// ---- Convergence ------------------------------------------------------------------------------

TEST(Nonlinear, ErrorShrinksWithTheTolerance) {
  const Body body = example_toy_top();
  const InitialState s = make_state(200.0, 0.05, 0.02, 0.5, -0.3);
  const std::vector<double> times = sample_times(5.0, 501);
  Tolerances reference;
  reference.rtol = reference.atol = 1e-14;
  const Trajectory ref = simulate_nonlinear(body, s, times, reference);
  double previous = 1.0;
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    Tolerances o;
    o.rtol = o.atol = tol;
    const double error = max_angle_difference(simulate_nonlinear(body, s, times, o), ref);
    EXPECT_LT(error, previous / 10.0) << "tol " << tol;  // 100x tighter: >= 10x smaller
    EXPECT_LT(error, 1e3 * tol) << "tol " << tol;
    RecordProperty("error_at_" + sci(tol), sci(error));
    previous = error;
  }
  EXPECT_LT(previous, 1e-10);  // the default tolerance, 1e-12
}

// ---- SPEC section 2 ---------------------------------------------------------------------------

TEST(Nonlinear, ReportsTheInputStateAtTimeZero) {
  const Body body = make_body(1.0, 1.5, 2.0, 1.0);
  double worst = 0.0;
  for (const InitialState& s :
       {make_state(3.0, 0.3), make_state(-2.0, -0.4, 0.7, 0.3, -0.25),
        make_state(0.0, 1.2, -0.9, -1.5, 2.0), make_state(200.0, 0.05, 0.01, 0.4, -0.6)}) {
    const Trajectory tr = simulate_nonlinear(body, s, {0.0, 0.5});
    EXPECT_NEAR(tr.theta[0], s.theta0, 1e-14);
    EXPECT_NEAR(tr.phi[0], s.phi0, 1e-14);
    EXPECT_NEAR(tr.theta_rate[0], s.theta_rate0, 1e-14);
    EXPECT_NEAR(tr.phi_rate[0], s.phi_rate0, 1e-14);
    worst = std::max({worst, std::abs(tr.theta[0] - s.theta0), std::abs(tr.phi[0] - s.phi0),
                      std::abs(tr.theta_rate[0] - s.theta_rate0),
                      std::abs(tr.phi_rate[0] - s.phi_rate0)});
    for (const auto& name : {"energy_drift", "vertical_momentum_drift", "axial_momentum_drift"})
      EXPECT_EQ(column(tr, name)[0], 0.0);
  }
  RecordProperty("worst_difference", sci(worst));
}

TEST(Nonlinear, RatesAreTheDerivativesOfTheAngles) {
  const Body body = make_body(1.0, 1.3, 2.0, 1.0);
  const InitialState s = make_state(4.0, 0.6, -0.3, 0.5, 0.8);
  const double h = 1e-4;
  std::vector<double> times;
  for (double t : {0.7, 3.1, 9.4}) times.insert(times.end(), {t - h, t, t + h});
  const Trajectory tr = simulate_nonlinear(body, s, times);
  for (std::size_t i = 1; i < times.size(); i += 3) {
    const double dtheta = (tr.theta[i + 1] - tr.theta[i - 1]) / (2.0 * h);
    const double dphi = (tr.phi[i + 1] - tr.phi[i - 1]) / (2.0 * h);
    EXPECT_NEAR(tr.theta_rate[i], dtheta, 1e-6 * (1.0 + std::abs(dtheta)));
    EXPECT_NEAR(tr.phi_rate[i], dphi, 1e-6 * (1.0 + std::abs(dphi)));
    EXPECT_GT(std::abs(tr.theta_rate[i]) + std::abs(tr.phi_rate[i]), 0.1);
  }
}

// ---- Against an independent integration in body axes ----------------------------------------

// The textbook form: attitude quaternion q (body to fixed) with q' = 1/2 q (x) (0, w), and
// Euler's equations in body axes; Bulirsch-Stoer at 1e-14, stepping to each output time.
TEST(Nonlinear, MatchesADirectBodyFrameIntegrationOfAnAsymmetricBody) {
  const Body b = make_body(1.0, 1.5, 2.0, 1.0);
  const InitialState s = make_state(5.0, 0.4, -0.2, 0.3, 0.6);
  using X = std::array<double, 7>;
  const double k = b.mgR();
  auto rhs = [&](const X& x, X& d, double) {
    const Eigen::Quaterniond q(x[0], x[1], x[2], x[3]);
    const Eigen::Vector3d w(x[4], x[5], x[6]);
    const Eigen::Vector3d gamma = q.normalized().toRotationMatrix().transpose().col(2);
    const Eigen::Quaterniond qd = q * Eigen::Quaterniond(0.0, w.x(), w.y(), w.z());
    d[0] = 0.5 * qd.w(), d[1] = 0.5 * qd.x(), d[2] = 0.5 * qd.y(), d[3] = 0.5 * qd.z();
    const Eigen::Vector3d inertia(b.A, b.B, b.C);
    const Eigen::Vector3d torque = k * gamma.cross(Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d wd =
        (torque - w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia);
    d[4] = wd.x(), d[5] = wd.y(), d[6] = wd.z();
  };
  const RigidBodyState x0 = initial_rigid_body_state(s);
  const Eigen::Quaterniond q0(x0.attitude);
  X x{q0.w(), q0.x(), q0.y(), q0.z(), x0.omega.x(), x0.omega.y(), x0.omega.z()};
  const std::vector<double> times = sample_times(20.0, 41);
  std::vector<AxisAngles> expected;
  boost::numeric::odeint::integrate_times(
      boost::numeric::odeint::bulirsch_stoer<X>(1e-14, 1e-14), rhs, x, times.begin(), times.end(),
      1e-3, [&](const X& y, double) {
        const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
        const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
        const Eigen::Vector3d w(y[4], y[5], y[6]);
        expected.push_back(axis_angles(r.col(2), r * w.cross(Eigen::Vector3d::UnitZ())));
      });
  const Trajectory tr = simulate_nonlinear(b, s, times);
  ASSERT_EQ(expected.size(), tr.size());
  double angle = 0.0, rate = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    angle = std::max({angle, std::abs(tr.theta[i] - expected[i].theta),
                      std::abs(tr.phi[i] - expected[i].phi)});
    rate = std::max({rate, std::abs(tr.theta_rate[i] - expected[i].theta_rate),
                     std::abs(tr.phi_rate[i] - expected[i].phi_rate)});
  }
  EXPECT_LT(angle, 1e-9);
  EXPECT_LT(rate, 1e-8);
  RecordProperty("angle_difference", sci(angle));
  RecordProperty("rate_difference", sci(rate));
}

// ---- The small-motion limit: model (4) --------------------------------------------------------

// Relative difference between the nonlinear motion and model (4)'s, for a symmetric body,
// started at amplitude eps: A phi'' + C w0 theta' = m g R phi, B theta'' - C w0 phi' = m g R theta.
double relative_difference_to_model_4(double eps) {
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  const double w0 = 3.0;
  const InitialState s = make_state(w0, eps, 0.5 * eps, 0.3 * eps, -0.2 * eps);
  const std::vector<double> times = sample_times(10.0, 201);
  const Trajectory tr = simulate_nonlinear(body, s, times);

  Eigen::Matrix4d J = Eigen::Matrix4d::Zero();  // x = (phi, theta, phi', theta')
  J(0, 2) = J(1, 3) = 1.0;
  J(2, 0) = body.mgR() / body.A;
  J(2, 3) = -body.C * w0 / body.A;
  J(3, 1) = body.mgR() / body.B;
  J(3, 2) = body.C * w0 / body.B;
  const Eigen::Vector4d x0(s.phi0, s.theta0, s.phi_rate0, s.theta_rate0);
  double difference = 0.0, size = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Matrix4d Jt = J * times[i];
    const Eigen::Vector4d x = Jt.exp() * x0;
    difference = std::max({difference, std::abs(tr.phi[i] - x(0)), std::abs(tr.theta[i] - x(1))});
    size = std::max({size, std::abs(x(0)), std::abs(x(1))});
  }
  return difference / size;
}

TEST(Nonlinear, DiffersFromModel4ByAmplitudeSquaredForASymmetricBody) {
  const double r1 = relative_difference_to_model_4(0.02);
  const double r2 = relative_difference_to_model_4(0.01);
  const double r3 = relative_difference_to_model_4(0.005);
  EXPECT_LT(r1, 1e-2);
  EXPECT_GT(r2 / r3, 3.0);
  EXPECT_LT(r2 / r3, 5.0);
  EXPECT_GT(r1 / r2, 3.0);
  EXPECT_LT(r1 / r2, 5.0);
  RecordProperty("relative_differences", sci(r1) + " " + sci(r2) + " " + sci(r3));
  RecordProperty("ratios", sci(r1 / r2) + " " + sci(r2 / r3));
}

// ---- Erratum E3 -------------------------------------------------------------------------------

TEST(Nonlinear, ErratumE3AsymmetricTopFallsBelowSqrt2AndStaysAbove) {
  // A = 1, B = 1.5, C = 2, m g R = 1: (9) promises stability above 1.112, the true
  // linearisation above sqrt(2). Started 1e-4 rad off vertical.
  const Body body = make_body(1.0, 1.5, 2.0, 1.0);
  const TiltExtremes falls = tilt_extremes(body, make_state(1.3, 1e-4), 300.0, 2.0);
  EXPECT_TRUE(falls.exceeded);
  EXPECT_GT(falls.max_tilt, 2.0);
  EXPECT_LT(falls.t_end, 300.0);
  const TiltExtremes stays = tilt_extremes(body, make_state(1.45, 1e-4), 300.0, 2.0);
  EXPECT_FALSE(stays.exceeded);
  EXPECT_LT(stays.max_tilt, 4e-4);
  EXPECT_GE(stays.max_tilt, 1e-4);
  EXPECT_EQ(stays.t_end, 300.0);
  // max_tilt is the same scan.
  EXPECT_GT(max_tilt(body, make_state(1.3, 1e-4), 300.0, 2.0), 2.0);
  RecordProperty("falls_at", std::to_string(falls.t_end));
  RecordProperty("stays_within", sci(stays.max_tilt));
}

TEST(Nonlinear, ErratumE3HangingAsymmetricBodySwingsOutOnlyInsideItsUnstableWindow) {
  // A = 1, B = 1.2, C = 0.7, m g R = -1: unstable for spins between sqrt 2 and 1.826 only.
  // R < 0: with the axis k up the centre of mass hangs below O. Started 1e-4 rad off vertical.
  const Body body = make_body(1.0, 1.2, 0.7, -1.0);
  auto swing = [&](double spin) { return max_tilt(body, make_state(spin, 1e-4), 300.0, 3.0); };
  const double unstable = swing(1.6), slow = swing(1.2), fast = swing(2.0);
  EXPECT_GT(unstable, 0.3);
  EXPECT_LT(slow, 1.5e-4);
  EXPECT_LT(fast, 1.5e-4);
  RecordProperty("swing", sci(slow) + " " + sci(unstable) + " " + sci(fast));
}

// ---- Options and failures ---------------------------------------------------------------------

TEST(Nonlinear, OptionsIsValidRejectsOutOfRangeSettings) {
  std::string why;
  EXPECT_TRUE(Tolerances{}.IsValid(&why));
  const double nan = std::nan("");
  const double inf = INFINITY;
  for (double rtol : {0.0, -1e-8, nan, inf, 1e-16, 2.0}) {
    Tolerances o;
    o.rtol = rtol;
    EXPECT_FALSE(o.IsValid(&why)) << rtol;
    EXPECT_EQ(why.rfind("rtol: ", 0), 0u) << why;
  }
  for (double atol : {0.0, -1.0, nan, inf}) {
    Tolerances o;
    o.atol = atol;
    EXPECT_FALSE(o.IsValid(&why)) << atol;
    EXPECT_EQ(why.rfind("atol: ", 0), 0u) << why;
  }
  Tolerances o;
  o.max_steps = 0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o.max_steps = 1;
  o.rtol = 1e-15;
  o.atol = 1e-300;
  EXPECT_TRUE(o.IsValid(nullptr));
}

TEST(Nonlinear, RefusesBadInputWithTheKey) {
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  const InitialState s = make_state(3.0, 0.3);
  Tolerances o;
  o.rtol = -1.0;
  try {
    simulate_nonlinear(body, s, {0.0, 1.0}, o);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "rtol");
  }
  try {
    simulate_nonlinear(body, s, {0.0, 2.0, 1.0});
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "times");
  }
  EXPECT_THROW(simulate_nonlinear(body, s, {-1.0}), InvalidInput);
  EXPECT_THROW(tilt_extremes(body, s, -1.0), InvalidInput);
  EXPECT_THROW(tilt_extremes(body, s, 1.0, std::nan("")), InvalidInput);
  Body bad = body;
  bad.C = 3.0;  // A + B < C
  EXPECT_THROW(simulate_nonlinear(bad, s, {1.0}), InvalidInput);
}

TEST(Nonlinear, FailsWithARuntimeErrorWhenMaxStepsIsExceeded) {
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  Tolerances o;
  o.max_steps = 50;
  try {
    simulate_nonlinear(body, make_state(3.0, 0.3), {100.0}, o);
    FAIL() << "no exception";
  } catch (const InvalidInput&) {
    FAIL() << "a numerical failure is not bad input";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("max_steps"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(Nonlinear, FailsWithARuntimeErrorWhenTheToleranceCannotBeMet) {
  // Pure relative accuracy 1e-15 on components that start at 0: rounding alone exceeds it.
  Tolerances o;
  o.rtol = 1e-15;
  o.atol = 1e-300;
  ASSERT_TRUE(o.IsValid(nullptr));
  NonlinearSummary summary;
  try {
    simulate_nonlinear(example_toy_top(), make_state(200.0, 0.05), {1.0}, o, &summary);
    FAIL() << "no exception";
  } catch (const InvalidInput&) {
    FAIL() << "a numerical failure is not bad input";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tolerance"), std::string::npos) << e.what();
  }
  EXPECT_GT(summary.rejected_steps, 0u);
}

TEST(Nonlinear, EmptyAndZeroTimesNeedNoStep) {
  const Body body = make_body(1.0, 1.0, 2.0, 1.0);
  NonlinearSummary summary;
  const Trajectory tr = simulate_nonlinear(body, make_state(3.0, 0.3), {0.0, 0.0}, {}, &summary);
  EXPECT_EQ(tr.size(), 2u);
  EXPECT_EQ(tr.extra.size(), 6u);
  EXPECT_EQ(summary.steps, 0u);
  EXPECT_EQ(simulate_nonlinear(body, make_state(3.0, 0.3), {}).size(), 0u);
}

}  // namespace
}  // namespace heavytop

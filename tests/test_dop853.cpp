// DOP853 (dop853.hpp) against independent routes: the symmetric top's closed form in elliptic
// functions (lagrange_exact.hpp) for the motion and its nutation bounds, the first integrals
// of the asymmetric body, and its refusals. The properties every integrator shares (first
// sample, streaming, steps, failures) are in test_integrator_conformance.cpp.

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "heavytop/dop853.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;
using test_support::make_state;

const Body kSymmetric = make_body(1.0, 1.0, 0.4, 0.5);
const Body kAsymmetric = make_body(1.0, 1.3, 1.6, 0.5);
const InitialState kStart = make_state(8.0, 0.2, -0.1, 0.3, 0.2);

Tolerances tolerance(double eps) {
  Tolerances o;
  o.rtol = o.atol = eps;
  return o;
}

// rad, the largest theta or phi difference between DOP853 and the closed form over 5 s.
double error_against_closed_form(double eps, NonlinearSummary* summary = nullptr) {
  const std::vector<double> times = sample_times(5.0, 501);
  const Trajectory exact = simulate_lagrange_exact(kSymmetric, kStart, times);
  const Trajectory got = simulate_dop853(kSymmetric, kStart, times, tolerance(eps), summary);
  double worst = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i)
    worst = std::max({worst, std::abs(got.theta[i] - exact.theta[i]), std::abs(got.phi[i] - exact.phi[i])});
  return worst;
}

// The symmetric top's motion is known in closed form: DOP853 at 1e-12 follows it to 1e-9 rad,
// and its error falls with the tolerance (an eighth-order method: fewer steps for the same
// error than dopri5 takes, checked by the step counts).
TEST(Dop853, FollowsTheClosedFormOfTheSymmetricTop) {
  NonlinearSummary tight;
  const double e12 = error_against_closed_form(1e-12, &tight);
  const double e9 = error_against_closed_form(1e-9);
  const double e6 = error_against_closed_form(1e-6);
  EXPECT_LT(e12, 1e-9);
  EXPECT_LT(e12, e9);
  EXPECT_LT(e9, e6);
  EXPECT_LT(e6, 1e-4);
  NonlinearSummary dopri5;
  simulate_nonlinear(kSymmetric, kStart, sample_times(5.0, 501), tolerance(1e-12), &dopri5);
  EXPECT_LT(3 * tight.steps, dopri5.steps) << tight.steps << " DOP853 steps, " << dopri5.steps << " dopri5";
}

// The tilt's extremes over several nutations are the closed form's nutation bounds.
TEST(Dop853, TiltExtremesAreTheNutationBounds) {
  const NutationBounds bounds = nutation_bounds(lagrange_top(kSymmetric, kStart));
  const TiltExtremes e = dop853_tilt_extremes(kSymmetric, kStart, 10.0, M_PI, tolerance(1e-12));
  EXPECT_FALSE(e.exceeded);
  EXPECT_NEAR(e.min_tilt, bounds.min_tilt, 1e-9);
  EXPECT_NEAR(e.max_tilt, bounds.max_tilt, 1e-9);
  // Stopped at a threshold between the bounds: the tilt there is the threshold.
  const double threshold = 0.5 * (bounds.min_tilt + bounds.max_tilt);
  const TiltExtremes stopped = dop853_tilt_extremes(kSymmetric, kStart, 10.0, threshold, tolerance(1e-12));
  ASSERT_TRUE(stopped.exceeded);
  const Trajectory at = simulate_lagrange_exact(kSymmetric, kStart, {stopped.t_end});
  const double tilt_there = std::acos(std::cos(at.theta[0]) * std::cos(at.phi[0]));
  EXPECT_NEAR(tilt_there, threshold, 1e-8);
}

// The asymmetric body: E and L_zeta are first integrals (kept to 1e-10 of their scale at
// 1e-12 over 20 s), C w3 is not one for A != B (it moves by more than 1e-5 of its scale).
TEST(Dop853, KeepsTheFirstIntegralsOfTheAsymmetricBody) {
  NonlinearSummary s;
  simulate_dop853(kAsymmetric, kStart, sample_times(20.0, 201), tolerance(1e-12), &s);
  EXPECT_LT(s.max_relative_energy_drift, 1e-10);
  EXPECT_LT(s.max_relative_vertical_momentum_drift, 1e-10);
  EXPECT_GT(s.max_relative_axial_momentum_drift, 1e-5);
  EXPECT_FALSE(s.symmetric);
}

// Its equations hold no torques and no products of inertia: a damped or general body is
// refused with the key that says so, not integrated as if it were the ordinary one.
TEST(Dop853, RefusesDampedAndGeneralBodies) {
  Body damped = kAsymmetric;
  damped.damping.axial = 1e-3;
  try {
    simulate_dop853(damped, kStart, {0.0, 1.0});
    FAIL() << "a damped body was integrated";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "integrator");
  }
  Body general = kAsymmetric;
  general.general.Ixy = 0.01;
  try {
    simulate_dop853(general, kStart, {0.0, 1.0});
    FAIL() << "a general body was integrated";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.Ixy");
  }
}

}  // namespace
}  // namespace heavytop

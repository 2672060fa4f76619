// The linear models against the full nonlinear body at small amplitude: the exact
// linearisation's error shrinks as the square of the amplitude; (4) does so only for A = B.
#include <cmath>

#include <gtest/gtest.h>

#include "heavytop/linear_motion.hpp"
#include "heavytop/nonlinear.hpp"

namespace heavytop {
namespace {

Body body_with(double A, double B, double C, double mgR) {
  return Body{.A = A, .B = B, .C = C, .mass = 1.0, .gravity = 1.0, .length = mgR};
}

/// max over the samples of |angle error| / max |angle|, both angles, linear model vs nonlinear.
double relative_error(LinearModelKind kind, const Body& b, const InitialState& s, double horizon) {
  const auto times = sample_times(horizon, 2001);
  Tolerances tight;
  tight.rtol = tight.atol = 1e-12;
  const Trajectory truth = simulate_nonlinear(b, s, times, tight);
  const Trajectory model = simulate_linear(linear_model(kind, b), s, times, LinearMethod::Analytic);
  double err = 0.0, size = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    err = std::max({err, std::abs(model.theta[i] - truth.theta[i]), std::abs(model.phi[i] - truth.phi[i])});
    size = std::max({size, std::abs(truth.theta[i]), std::abs(truth.phi[i])});
  }
  return err / size;
}

InitialState small(double amplitude, double spin) {
  return InitialState{.spin = spin, .theta0 = amplitude, .phi0 = -0.5 * amplitude,
                      .theta_rate0 = 0.3 * amplitude, .phi_rate0 = 0.2 * amplitude};
}

TEST(SmallMotion, LinearisationErrorShrinksAsAmplitudeSquared) {
  const Body b = body_with(1.0, 1.5, 2.0, 1.0);  // asymmetric, stable above sqrt 2
  const double e1 = relative_error(LinearModelKind::Linearized, b, small(1e-2, 2.0), 20.0);
  const double e2 = relative_error(LinearModelKind::Linearized, b, small(5e-3, 2.0), 20.0);
  EXPECT_LT(e1, 1e-2);
  EXPECT_GT(e1 / e2, 3.5);
  EXPECT_LT(e1 / e2, 4.5);
  // Model (4) of the same asymmetric body does not converge: its error stays O(1).
  const double paper = relative_error(LinearModelKind::FirstOrder, b, small(5e-3, 2.0), 20.0);
  EXPECT_GT(paper, 0.1);
  EXPECT_GT(paper, 100 * e2);
}

TEST(SmallMotion, ForASymmetricBodyModelFourConvergesToo) {
  const Body b = body_with(1.0, 1.0, 1.7, 1.0);
  for (auto kind : {LinearModelKind::FirstOrder, LinearModelKind::Linearized}) {
    const double e1 = relative_error(kind, b, small(1e-2, 2.5), 20.0);
    const double e2 = relative_error(kind, b, small(5e-3, 2.5), 20.0);
    EXPECT_LT(e1, 1e-2) << name(kind);
    EXPECT_GT(e1 / e2, 3.5) << name(kind);
    EXPECT_LT(e1 / e2, 4.5) << name(kind);
  }
  // The body-fixed model (5) misses even the symmetric top.
  EXPECT_GT(relative_error(LinearModelKind::BodyFixed, b, small(5e-3, 2.5), 20.0), 0.1);
}

}  // namespace
}  // namespace heavytop

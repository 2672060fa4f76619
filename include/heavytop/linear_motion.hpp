#pragma once
/// \file
/// Motion of the linear models: the closed-form solution for every input (erratum E1 mended),
/// an independent numerical route, and the trajectory in SPEC's theta, phi.

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "heavytop/linear_models.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// x = (q1, q2, q1', q2') of a linear model (rad, rad/s in the model's coordinates).
using LinearState = Eigen::Vector4d;

/// The closed-form solution x(t) = exp(J t) x0 of a linear model at one spin.
///
/// J's characteristic polynomial is a4 (l^2 - mu1)(l^2 - mu2), so J^2 satisfies
/// (J^2 - mu1)(J^2 - mu2) = 0 and exp(J t) = c(J^2) + J s(J^2) with the entire functions
/// c(mu) = cosh(sqrt(mu) t), s(mu) = sinh(sqrt(mu) t)/sqrt(mu). Interpolating them at mu1, mu2:
///   x(t) = c(mu1) x0 + s(mu1) J x0 + c[mu1,mu2] (J^2 - mu1) x0 + s[mu1,mu2] J (J^2 - mu1) x0,
/// with divided differences [.,.]. One formula covers stable, unstable and double roots: at
/// mu1 = mu2 the differences become derivatives, giving the secular t cos, t sin terms (E2).
struct LinearSolution {
  std::complex<double> mu1, mu2;  ///< 1/s^2, the roots of a4 mu^2 + a2 mu + a0 (mu = lambda^2)
  LinearState x0;                 ///< the initial state
  LinearState jx0, w2, w3;        ///< J x0, (J^2 - mu1) x0, J (J^2 - mu1) x0 (units of x / s^k)
  bool oscillatory = false;       ///< mu1, mu2 real, < 0 and distinct: the fast path applies
  double alpha1 = 0.0, alpha2 = 0.0;  ///< rad/s, sqrt(-mu1), sqrt(-mu2) when oscillatory
};

/// Precomputes the closed-form solution of `model` at spin w0 (rad/s) from x0.
LinearSolution closed_form_solution(const LinearModel& model, double spin, const LinearState& x0);

/// x(t) of the closed-form solution; t in s. Cost independent of t.
LinearState evaluate(const LinearSolution& solution, double t);

/// x(t) = exp(J t) x0 by Eigen's matrix exponential (Pade, scaling and squaring): the
/// independent numerical route the closed form is checked against.
LinearState matrix_exponential_solution(const LinearModel& model, double spin,
                                        const LinearState& x0, double t);

/// The model's initial x from the user's state (SPEC section 2). For first-order and
/// body-fixed, (phi0, theta0, phi_rate0, theta_rate0). For linearized, the body-frame tilt at
/// t = 0 (where the body axes are the axis frame's): z_b = z, z_b' = z' - i w0 z with
/// z = theta - i phi, so (phi_b, theta_b) = (phi0, theta0) and the rates shift by the spin.
LinearState initial_linear_state(const LinearModel& model, const InitialState& state);

/// How simulate_linear solves the model.
enum class LinearMethod {
  Analytic,  ///< the closed form (LinearSolution)
  Numeric,   ///< Eigen's matrix exponential at every sample
};

/// theta, phi and their rates (rad, rad/s) of `model` at the given times (s). For linearized,
/// the body-frame tilt is turned back through the spin: z(t) = exp(i w0 t) z_b(t).
Trajectory simulate_linear(const LinearModel& model, const InitialState& state,
                           const std::vector<double>& times, LinearMethod method);

/// The paper's printed section-8 "general solution" of model (4) (its formula after (14),
/// with A1 = A2 = B1 = B2 = 1), kept only to show erratum E1: it does not solve (4).
/// Returns (theta, phi) in rad at time t (s) for the stable case.
Eigen::Vector2d paper_section8_solution(const Body& body, const InitialState& state, double t);

}  // namespace heavytop

#pragma once
/// \file
/// The paper's routes to the equations of the axis's small motion, derived symbolically
/// (sections 3, 5, 6), and what follows from them: the characteristic polynomial (8) and the
/// stability condition (9) (section 7). docs/derivations.md describes each route.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <ginac/ginac.h>

#include "heavytop/symbolic/kinematics.hpp"

namespace heavytop::symbolic {

/// How the equations of motion are obtained.
enum class Method {
  EulerMoving,  ///< Euler's dynamic equations on the moving (Resal) axes: section 3, model (4)
  EulerFixed,   ///< the angular-momentum theorem on the fixed axes: section 5, model (6)
  EulerBody,    ///< Euler on axes attached to the body (psi' = omega0) with the small-angle
                ///< table kept: the step the paper calls an error, model (5)
  Lagrange,     ///< Lagrange's equations from T and V expanded to second order: section 6
};

/// Every method, in the order of the paper.
inline constexpr Method kMethods[] = {Method::EulerMoving, Method::EulerFixed, Method::EulerBody,
                                      Method::Lagrange};

/// CLI name: "euler-moving", "euler-fixed", "euler-body", "lagrange".
std::string_view name(Method method);

/// The method called `name` on the command line, or nullopt.
std::optional<Method> method_from_name(std::string_view name);

/// A requirement lhs > rhs (strict) or lhs >= rhs.
struct Inequality {
  GiNaC::ex lhs;       ///< left-hand side
  GiNaC::ex rhs;       ///< right-hand side
  bool strict = true;  ///< > rather than >=
};

/// When M q'' + G q' + K q = 0 is linearly stable (all roots on the imaginary axis, none
/// defective), for positive A, B, C, m, g, R, omega0 (a top).
struct StabilityCondition {
  std::vector<Inequality> all_of;  ///< every requirement must hold (empty: always, unless never)
  bool never = false;              ///< no parameter values make it stable
  std::vector<std::string> steps;  ///< how it follows from the polynomial, one step per line
};

/// One route's result at one order, as M q'' + G q' + K q = 0 with q = (phi, theta) and the
/// rows scaled so that M = diag(A, B).
struct Derivation {
  Method method = Method::EulerMoving;     ///< the route
  Sequence sequence = Sequence::PhiTheta;  ///< the rotation sequence
  int order = 1;                           ///< order of the kinematics (1 or 2)
  GiNaC::matrix omega;         ///< body angular velocity used, on the axes the route projects on
  GiNaC::ex T;                 ///< kinetic energy to second order (Lagrange only, else 0)
  GiNaC::ex V;                 ///< potential energy to second order (Lagrange only, else 0)
  GiNaC::ex psi_equation;      ///< the third (psi) equation, linear: C psi'' = 0, so psi = 0
  GiNaC::matrix M;             ///< 2x2, diag(A, B)
  GiNaC::matrix G;             ///< 2x2 gyroscopic matrix
  GiNaC::matrix K;             ///< 2x2 stiffness matrix
  GiNaC::ex characteristic_polynomial;  ///< det(M lambda^2 + G lambda + K), expanded
  StabilityCondition stability;         ///< derived from characteristic_polynomial
};

/// Derives the linear model of `method` for `sequence` with kinematics truncated at `order`
/// (1 or 2). Throws std::invalid_argument for another order.
Derivation derive(Method method, Sequence sequence, int order);

/// det(M lambda^2 + G lambda + K), expanded.
GiNaC::ex characteristic_polynomial(const GiNaC::matrix& M, const GiNaC::matrix& G,
                                    const GiNaC::matrix& K);

/// The stability condition of M q'' + G q' + K q = 0 from its (biquadratic) polynomial.
/// Throws std::domain_error if the polynomial has odd powers of lambda.
StabilityCondition stability_condition(const GiNaC::matrix& M, const GiNaC::matrix& G,
                                       const GiNaC::matrix& K);

/// The paper's published models, used only to name a derived result.
enum class PaperModel {
  Four,  ///< model (4) = (6): gyroscopic coefficients C omega0
  Five,  ///< model (5): (C - B) omega0 and (C - A) omega0
};

/// The paper's model (as printed) in the form M q'' + G q' + K q = 0, M = diag(A, B).
struct PaperMatrices {
  GiNaC::matrix M;  ///< diag(A, B)
  GiNaC::matrix G;  ///< gyroscopic matrix
  GiNaC::matrix K;  ///< diag(-m g R, -m g R)
};

/// The printed matrices of `model`.
PaperMatrices paper_model(PaperModel model);

/// Display name: "model (4)" or "model (5)".
std::string_view name(PaperModel model);

/// Which printed model `d` is, if any (entries compared with normal()).
std::optional<PaperModel> identify(const Derivation& d);

/// True if the two derivations have the same M, G and K.
bool same_model(const Derivation& a, const Derivation& b);

/// The paper's (8): lambda^4 + (C^2 omega0^2 - (A + B) m g R)/(A B) lambda^2 + (m g R)^2/(A B).
GiNaC::ex paper_polynomial_8();

/// The right-hand side of the paper's (9): (sqrt(A) + sqrt(B))^2 m g R / C^2.
GiNaC::ex paper_bound_9();

/// One line of the --check table.
struct CheckRow {
  Derivation derivation;                  ///< the route's result
  std::optional<PaperModel> model;        ///< what it equals, if a printed model
  std::optional<PaperModel> expected;     ///< what the paper says it gives (nullopt: neither)
  std::string why;                        ///< the paper's statement behind `expected`
  bool as_expected() const { return model == expected; }  ///< the paper's claim holds
};

/// Every method and sequence at each of `orders`, with the paper's expectation for each:
/// every route but euler-body gives (4), euler-body gives (5), and Lagrange at order 1 gives
/// neither (T and V need second-order kinematics, section 6).
std::vector<CheckRow> check(const std::vector<int>& orders = {1, 2});

}  // namespace heavytop::symbolic

#pragma once
/// \file
/// Expressions as text, as strings for a computer-algebra system, and as LaTeX, with factors
/// in the paper's order (A, B, C, m, g, R, omega0, then the variables) rather than GiNaC's.

#include <string>

#include <ginac/ginac.h>

namespace heavytop::symbolic {

/// How to print.
enum class Style {
  Text,   ///< for people: "(C - B) omega0 theta'"; juxtaposition is multiplication
  Cas,    ///< for programs: "(C-B)*omega0*theta", ^ for powers, sqrt(); sympy parses it after ^ -> **
  Latex,  ///< LaTeX math: "(C - B) \omega_0 \dot{\theta}"
};

/// `e` printed in `style`.
std::string to_string(const GiNaC::ex& e, Style style);

/// `e` tidied and printed for people: to_string(tidy(e), Style::Text).
std::string text(const GiNaC::ex& e);

/// `e` tidied for reading: polynomials in lambda collected by power, coefficients collected in
/// omega0 and factored; the value is unchanged.
GiNaC::ex tidy(const GiNaC::ex& e);

/// `e` with square roots of positive symbols made explicit and factored: writes each symbol X
/// under a root as x^2, factors numerator and denominator, and maps x back to sqrt(X).
/// E.g. A + B + 2 sqrt(A B) -> (sqrt(A) + sqrt(B))^2.
GiNaC::ex factor_radicals(const GiNaC::ex& e);

}  // namespace heavytop::symbolic

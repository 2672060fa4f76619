#pragma once
// Private to the library: the roots of a quadratic without cancellation, used for the
// characteristic polynomial in mu = lambda^2 (stability.cpp, linear_motion.cpp).

#include <cmath>
#include <complex>
#include <utility>

namespace heavytop::detail {

/// The roots of a x^2 + b x + c (a != 0) given its discriminant b^2 - 4 a c (computed by the
/// caller, who may know it more accurately): a conjugate pair when it is negative, else the
/// larger root q / a and c / q, q = -(b + sign(b) sqrt(disc)) / 2 (Numerical Recipes 5.6).
inline std::pair<std::complex<double>, std::complex<double>> quadratic_roots(double a, double b, double c,
                                                                             double disc) {
  if (disc < 0.0) {
    const std::complex<double> root(-b / (2.0 * a), std::sqrt(-disc) / (2.0 * a));
    return {root, std::conj(root)};
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  return {q / a, q != 0.0 ? c / q : 0.0};
}

}  // namespace heavytop::detail

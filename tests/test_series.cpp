// The Taylor integrator's series arithmetic (src/integrators/taylor/series.hpp, private) that
// the tilt scans stand on, against independent routes: polynomial_root (Newton in its bracket)
// against TOMS 748 (Boost.Math, series.hpp's root()) and against roots known in closed form,
// a triple root included; sum_of_squares (each square by its symmetry) against two full
// Cauchy products.

#include "integrators/taylor/series.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using heavytop::detail::taylor::Coefficients;
using heavytop::detail::taylor::cauchy;
using heavytop::detail::taylor::horner;
using heavytop::detail::taylor::polynomial_root;
using heavytop::detail::taylor::root;
using heavytop::detail::taylor::sum_of_squares;

// The coefficients of prod_k (tau - r_k) times (tau^2 + c), lowest order first.
Coefficients with_roots(std::initializer_list<double> roots, double c, int& p) {
  Coefficients s{};
  s[0] = c, s[2] = 1.0;
  p = 2;
  for (double r : roots) {  // multiply by (tau - r)
    for (int n = p + 1; n >= 0; --n) s[n] = (n > 0 ? s[n - 1] : 0.0) - r * s[n];
    ++p;
  }
  return s;
}

TEST(Series, PolynomialRootIsTheKnownRootAndTOMS748s) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double h = 0.01 + 5.0 * unit(random);  // the step, s
    const double a = h * unit(random) * 0.8, b = a + h / 8.0;
    const double r = a + (b - a) * (0.02 + 0.96 * unit(random));
    int p = 0;
    // one root in [a, b], four outside it and a complex pair: order 7
    const Coefficients s = with_roots({r, -0.7 * h, 2.0 * h + b, -3.0 * h, 4.5 * h}, 0.3 * h * h, p);
    const double fa = horner(s, p, a), fb = horner(s, p, b);
    ASSERT_LT(fa * fb, 0.0);
    const double newton = polynomial_root(s.data(), p, a, b, fa, fb, h);
    const double toms = root([&](double tau) { return horner(s, p, tau); }, a, b, fa, fb, h);
    EXPECT_NEAR(newton, r, 4e-15 * h) << "trial " << trial;
    EXPECT_NEAR(newton, toms, 4e-15 * h) << "trial " << trial;
  }
}

TEST(Series, PolynomialRootOfATripleRootStaysInItsBracket) {
  // (tau - r)^3 (tau^2 + 1): Newton converges linearly there; the value's rounding (~1e-16)
  // bounds the root's accuracy to about its cube root.
  const double h = 1.0, a = 0.1, b = 0.225, r = 0.17;
  int p = 0;
  const Coefficients s = with_roots({r, r, r}, 1.0, p);
  const double x = polynomial_root(s.data(), p, a, b, horner(s, p, a), horner(s, p, b), h);
  EXPECT_GE(x, a);
  EXPECT_LE(x, b);
  EXPECT_NEAR(x, r, 2e-5);
}

TEST(Series, SumOfSquaresIsTwoCauchyProducts) {
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  Coefficients a{}, b{};
  for (int n = 0; n <= heavytop::detail::taylor::kM; ++n) a[n] = normal(random) / (n + 1), b[n] = normal(random) / (n + 1);
  for (int n = 0; n <= heavytop::detail::taylor::kM; ++n) {
    const double full = cauchy(a, a, n) + cauchy(b, b, n);
    double scale = 0.0;  // the sum of the products' sizes: the rounding's scale
    for (int j = 0; j <= n; ++j) scale += std::abs(a[j] * a[n - j]) + std::abs(b[j] * b[n - j]);
    EXPECT_NEAR(sum_of_squares(a, b, n), full, 4e-16 * (n + 2) * scale) << "order " << n;
  }
}

}  // namespace

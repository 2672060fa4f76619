// Jacobi's elliptic functions of src/math/elliptic.hpp (the closed form's sn, cn, dn and K)
// against independent routes: Boost.Math's jacobi_elliptic and ellint_1, the identities
// sn^2 + cn^2 = 1 and dn^2 + k^2 sn^2 = 1, the values at the quarter period, the
// half-period antisymmetry, the limits k = 0 (circular) and k = 1 (hyperbolic), and
// d sn / du = cn dn by a central difference. Both routes (theta series for q <= 0.3, Landen's
// descent beyond) are covered: each test says which moduli take which.

#include "math/elliptic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

namespace {

using heavytop::detail::JacobiElliptic;
using heavytop::detail::JacobiValues;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.141592653589793;

// Moduli given by k'^2 (as lagrange_exact.cpp gives them, k' keeping its digits near k = 1).
struct Modulus {
  double k, kc2;
};
Modulus from_k(double k) { return {k, (1.0 - k) * (1.0 + k)}; }
Modulus from_kc2(double kc2) { return {std::sqrt(1.0 - kc2), kc2}; }

// Moduli a double k represents with its k'^2 = (1 - k)(1 + k) to rounding, so that Boost (which
// takes k) and JacobiElliptic (which takes k and k'^2) compute the same functions.
std::vector<Modulus> moduli() {
  return {from_k(0.0), from_k(1e-8), from_k(0.1),         from_k(0.5),         from_k(0.8),  from_k(0.9),
          from_k(0.99), from_k(0.995), from_k(0.999), from_k(1.0 - 1e-4), from_k(1.0 - 1e-6)};
}
// Closer to k = 1 a double k no longer carries k'^2 (Boost's K(k) at k = 1 - 1e-9 is off by
// ~2000 eps from the input's rounding alone): there the routes are A&S's expansions in k'^2.
std::vector<Modulus> near_one() { return {from_kc2(1e-9), from_kc2(1e-12), from_kc2(1e-14)}; }

// Arguments over two periods, both signs, off the grid of K's multiples.
std::vector<double> arguments(double K) {
  std::vector<double> r;
  for (int i = -40; i <= 40; ++i) r.push_back(K * (i / 10.0 + 0.0123));
  return r;
}

TEST(Elliptic, BothRoutesAreExercised) {
  // The theta series up to q = 0.3 (k between 0.995 and 0.999), Landen's descent beyond.
  for (double k : {0.0, 0.5, 0.99, 0.995}) EXPECT_GT(JacobiElliptic(k, from_k(k).kc2).theta_terms, 0) << k;
  for (double k : {0.999, 1.0 - 1e-6}) EXPECT_EQ(JacobiElliptic(k, from_k(k).kc2).theta_terms, 0) << k;
  EXPECT_EQ(JacobiElliptic(1.0, 0.0).theta_terms, 0);
}

TEST(Elliptic, QuarterPeriodIsBoostsCompleteIntegral) {
  for (const Modulus m : moduli()) {
    const JacobiElliptic f(m.k, m.kc2);
    ASSERT_TRUE(f.periodic);
    const double K = boost::math::ellint_1(m.k);
    EXPECT_NEAR(f.K, K, 4.0 * kEps * K) << "k = " << m.k;
  }
  // Near k = 1 (A&S 17.3.26): K = L + (k'^2/4)(L - 1) + (9 k'^4/64)(L - 7/6) + O(k'^6 L),
  // L = ln(4/k'); the terms left out are below 1e-27.
  for (const Modulus m : near_one()) {
    const double L = std::log(4.0 / std::sqrt(m.kc2));
    const double K = L + m.kc2 / 4.0 * (L - 1.0) + 9.0 * m.kc2 * m.kc2 / 64.0 * (L - 7.0 / 6.0);
    EXPECT_NEAR(JacobiElliptic(m.k, m.kc2).K, K, 4.0 * kEps * K) << "k'^2 = " << m.kc2;
  }
  EXPECT_FALSE(JacobiElliptic(1.0, 0.0).periodic);
  EXPECT_TRUE(std::isinf(JacobiElliptic(1.0, 0.0).K));
}

TEST(Elliptic, AgreesWithBoostsJacobiElliptic) {
  double worst = 0.0;
  for (const Modulus m : moduli()) {
    const JacobiElliptic f(m.k, m.kc2);
    for (double r : arguments(f.K)) {
      double cn = 0.0, dn = 0.0;
      const double sn = boost::math::jacobi_elliptic(m.k, r, &cn, &dn);
      const JacobiValues v = f(r);
      // Both carry the argument's rounding, eps |r| / K of a period, into the phase.
      const double tol = 8.0 * kEps * std::max(1.0, std::abs(r));
      EXPECT_NEAR(v.sn, sn, tol) << "k = " << m.k << ", r = " << r;
      EXPECT_NEAR(v.cn, cn, tol) << "k = " << m.k << ", r = " << r;
      EXPECT_NEAR(v.dn, dn, tol) << "k = " << m.k << ", r = " << r;
      worst = std::max({worst, std::abs(v.sn - sn), std::abs(v.cn - cn), std::abs(v.dn - dn)});
    }
  }
  RecordProperty("worst_difference", std::to_string(worst));
}

TEST(Elliptic, NearOneAgreesWithTheExpansionInKPrime) {
  // A&S 16.15: with m1 = k'^2, sn = tanh u + (m1/4)(sinh u cosh u - u) sech^2 u,
  // cn = sech u - (m1/4)(sinh u cosh u - u) tanh u sech u, dn = sech u + (m1/4)(sinh u cosh u
  // + u) tanh u sech u, up to O(m1^2 e^(4|u|)): below 1e-15 for |u| <= 1.5 and m1 <= 1e-9.
  for (const Modulus m : near_one()) {
    const JacobiElliptic f(m.k, m.kc2);
    for (double u : {-1.5, -1.0, -0.3, 0.1, 0.5, 1.0, 1.5}) {
      const double sh = std::sinh(u), ch = std::cosh(u), th = std::tanh(u), sech = 1.0 / ch;
      const double q = 0.25 * m.kc2;
      const JacobiValues v = f(u);
      EXPECT_NEAR(v.sn, th + q * (sh * ch - u) * sech * sech, 8.0 * kEps) << "k'^2 = " << m.kc2 << ", u = " << u;
      EXPECT_NEAR(v.cn, sech - q * (sh * ch - u) * th * sech, 8.0 * kEps) << "k'^2 = " << m.kc2 << ", u = " << u;
      EXPECT_NEAR(v.dn, sech + q * (sh * ch + u) * th * sech, 8.0 * kEps) << "k'^2 = " << m.kc2 << ", u = " << u;
    }
  }
}

TEST(Elliptic, SatisfiesThePythagoreanIdentities) {
  // sn, cn and dn come from separate theta sums (each a few eps off): 8 eps for the identities.
  std::vector<Modulus> all = moduli();
  for (const Modulus m : near_one()) all.push_back(m);
  for (const Modulus m : all) {
    const JacobiElliptic f(m.k, m.kc2);
    for (double r : arguments(f.K)) {
      const JacobiValues v = f(r);
      EXPECT_NEAR(v.sn * v.sn + v.cn * v.cn, 1.0, 8.0 * kEps) << "k = " << m.k << ", r = " << r;
      EXPECT_NEAR(v.dn * v.dn + m.k * m.k * v.sn * v.sn, 1.0, 8.0 * kEps) << "k = " << m.k << ", r = " << r;
    }
  }
}

TEST(Elliptic, QuarterAndHalfPeriods) {
  for (const Modulus m : moduli()) {
    const JacobiElliptic f(m.k, m.kc2);
    // sn(K) = 1, cn(K) = 0, dn(K) = k'.
    const JacobiValues q = f(f.K);
    EXPECT_NEAR(q.sn, 1.0, 4.0 * kEps) << "k = " << m.k;
    EXPECT_NEAR(q.cn, 0.0, 8.0 * kEps) << "k = " << m.k;
    EXPECT_NEAR(q.dn, std::sqrt(m.kc2), 8.0 * kEps) << "k = " << m.k;
    // sn(r + 2K) = -sn(r), cn(r + 2K) = -cn(r), dn(r + 2K) = dn(r).
    for (double r : {0.1 * f.K, 0.77 * f.K, -0.4 * f.K}) {
      const JacobiValues a = f(r), b = f(r + 2.0 * f.K);
      const double tol = 16.0 * kEps * std::max(1.0, f.K);
      EXPECT_NEAR(b.sn, -a.sn, tol) << "k = " << m.k << ", r = " << r;
      EXPECT_NEAR(b.cn, -a.cn, tol) << "k = " << m.k << ", r = " << r;
      EXPECT_NEAR(b.dn, a.dn, tol) << "k = " << m.k << ", r = " << r;
    }
  }
}

TEST(Elliptic, DerivativeOfSnIsCnDn) {
  // Central difference of step h: error h^2 |sn'''| / 6 plus rounding eps / h.
  const double h = 1e-5;
  for (const Modulus m : moduli()) {
    const JacobiElliptic f(m.k, m.kc2);
    for (double r : {0.13 * f.K, 0.5 * f.K, 1.4 * f.K, -0.9 * f.K}) {
      const double derivative = (f(r + h).sn - f(r - h).sn) / (2.0 * h);
      const JacobiValues v = f(r);
      EXPECT_NEAR(derivative, v.cn * v.dn, 1e-9) << "k = " << m.k << ", r = " << r;
    }
  }
}

TEST(Elliptic, CircularAndHyperbolicLimits) {
  const JacobiElliptic circular(0.0, 1.0), hyperbolic(1.0, 0.0);
  EXPECT_DOUBLE_EQ(circular.K, kPi / 2.0);
  for (double r : {-3.0, -0.5, 0.2, 1.0, 2.5, 7.0}) {
    const JacobiValues c = circular(r);
    EXPECT_NEAR(c.sn, std::sin(r), 4.0 * kEps * std::max(1.0, std::abs(r)));
    EXPECT_NEAR(c.cn, std::cos(r), 4.0 * kEps * std::max(1.0, std::abs(r)));
    EXPECT_NEAR(c.dn, 1.0, 4.0 * kEps);
    const JacobiValues h = hyperbolic(r);
    EXPECT_NEAR(h.sn, std::tanh(r), 2.0 * kEps);
    EXPECT_NEAR(h.cn, 1.0 / std::cosh(r), 2.0 * kEps);
    EXPECT_NEAR(h.dn, 1.0 / std::cosh(r), 2.0 * kEps);
  }
}

TEST(Elliptic, ThetaRouteGivesThePhaseOfTheFourierSeries) {
  // cos2v, sin2v = cos, sin of pi r / K on the theta route (lagrange_exact.cpp's series use them).
  for (double k : {0.1, 0.5, 0.9, 0.99}) {
    const Modulus m = from_k(k);
    const JacobiElliptic f(m.k, m.kc2);
    ASSERT_GT(f.theta_terms, 0);
    for (double r : arguments(f.K)) {
      const JacobiValues v = f(r);
      EXPECT_NEAR(v.cos2v, std::cos(kPi * r / f.K), 8.0 * kEps * std::max(1.0, std::abs(r))) << "k = " << k;
      EXPECT_NEAR(v.sin2v, std::sin(kPi * r / f.K), 8.0 * kEps * std::max(1.0, std::abs(r))) << "k = " << k;
    }
  }
}

}  // namespace

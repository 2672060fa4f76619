#pragma once
// Private to the library: Jacobi's elliptic functions sn, cn, dn of one modulus, prepared once
// and evaluated many times (the closed form of lagrange_exact.cpp evaluates them per sample),
// and the complete integral K(k) of the first kind from the same AGM. Tested against Boost.Math
// and the functions' identities in tests/test_elliptic.cpp.
//
// Two routes, chosen at preparation: the theta series in the nome q (DLMF 22.2.4) while
// q <= 0.3 (k up to about 0.9997), a handful of terms without cancellation; the descending
// Landen transformation (A&S 16.4) on the AGM of (1, k') beyond, which stays accurate as
// k -> 1. k and k'^2 = 1 - k^2 are given separately, so that k' keeps its digits near k = 1.

#include <cmath>
#include <complex>

namespace heavytop::detail {

/// sn, cn, dn at one argument; on the theta route also cos and sin of 2 v = pi r / K, which
/// lagrange_exact.cpp's Fourier series reuse (1 and 0 on the Landen route).
struct JacobiValues {
  double sn, cn, dn;
  double cos2v = 1.0, sin2v = 0.0;
};

/// Jacobi's elliptic functions of the modulus k, arguments r in units of the integral's
/// variable (dimensionless). k = 1 (k'^2 = 0): sn = tanh, cn = dn = sech, K infinite.
struct JacobiElliptic {
  double k = 0.0, kc2 = 1.0;  // modulus k and k'^2 = 1 - k^2, kept separately
  double K = 0.0;             // the quarter period K(k) (complete integral of the first kind)
  bool periodic = false;      // K finite (k < 1)
  int theta_terms = 0;            // 0: the Landen descent
  double theta_odd[8] = {};       // q^(n(n+1)), n = 0.. (theta_1, theta_2 without 2 q^(1/4))
  double theta_even[8] = {};      // 2 q^(n^2), n = 1.. (theta_3, theta_4)
  double sn_scale = 0.0, cn_scale = 0.0, dn_scale = 0.0, theta_freq = 0.0;
  int landen_levels = 0;
  double landen_ratio[16] = {};   // c_n / a_n of the AGM of (1, k'), n = 1..levels
  double landen_scale = 0.0;      // 2^N a_N

  JacobiElliptic() = default;
  /// Prepared for modulus k in [0, 1] with kc2 = 1 - k^2 (both given: see the file comment).
  JacobiElliptic(double k, double kc2);

  JacobiValues operator()(double r) const { return theta_terms > 0 ? theta(r) : landen(r); }

  // Theta series (DLMF 22.2.4) with the common factor 2 q^(1/4) of theta_1, theta_2 divided
  // out: a handful of terms for q <= 0.3, no cancellation since theta_4 >= 1 - 2q > 0.
  JacobiValues theta(double r) const {
    using Complex = std::complex<double>;
    const double v = theta_freq * r;
    const Complex z1(std::cos(v), std::sin(v));
    const Complex w = z1 * z1;
    Complex odd = z1, even = w;
    double t1 = 0.0, t2 = 0.0, t3 = 1.0, t4 = 1.0, sign = 1.0;
    for (int n = 0; n < theta_terms; ++n) {
      t1 += sign * theta_odd[n] * odd.imag();
      t2 += theta_odd[n] * odd.real();
      t3 += theta_even[n] * even.real();
      t4 -= sign * theta_even[n] * even.real();
      sign = -sign;
      odd *= w;
      even *= w;
    }
    const double inv4 = 1.0 / t4;
    return {sn_scale * t1 * inv4, cn_scale * t2 * inv4, dn_scale * t3 * inv4, w.real(), w.imag()};
  }

  // Descending Landen transformation (A&S 16.4) on the AGM of (1, k') precomputed from k'^2,
  // which stays accurate as k -> 1 where q -> 1 and the theta series would need many terms.
  JacobiValues landen(double r) const {
    if (kc2 == 0.0) {  // k = 1: the separatrix
      const double sech = 1.0 / std::cosh(r);
      return {std::tanh(r), sech, sech, 1.0, 0.0};
    }
    double phi = landen_scale * r;
    for (int n = landen_levels; n >= 1; --n) phi = 0.5 * (phi + std::asin(landen_ratio[n - 1] * std::sin(phi)));
    const double sn = std::sin(phi), cn = std::cos(phi);
    return {sn, cn, std::sqrt(cn * cn + kc2 * sn * sn), 1.0, 0.0};
  }
};

}  // namespace heavytop::detail

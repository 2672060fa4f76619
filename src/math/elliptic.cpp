#include "math/elliptic.hpp"

#include <cmath>
#include <limits>

namespace heavytop::detail {

// K(k) from the AGM of (1, k') (and the Landen table), K'(k), and the theta coefficients.
JacobiElliptic::JacobiElliptic(double modulus, double complement2) : k(modulus), kc2(complement2) {
  constexpr double kPi = 3.141592653589793;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // AGM of (1, k'), with c_{n+1} = c_n^2 / (4 a_{n+1}) to avoid the cancellation in a - b.
  double a = 1.0, b = std::sqrt(kc2), c = k;
  int levels = 0;
  while (c > kEps * a && levels < 16 && b > 0.0) {
    const double a1 = 0.5 * (a + b);
    b = std::sqrt(a * b);
    c = c * c / (4.0 * a1);
    a = a1;
    landen_ratio[levels++] = c / a;
  }
  landen_levels = levels;
  landen_scale = std::ldexp(a, levels);
  periodic = kc2 > 0.0;
  K = periodic ? kPi / (2.0 * a) : kInf;

  theta_terms = 0;
  if (!periodic) return;
  // Nome q = exp(-pi K'/K), K' from the AGM of (1, k).
  double a2 = 1.0, b2 = k;
  for (int i = 0; i < 64 && std::abs(a2 - b2) > kEps * a2; ++i) {
    const double a1 = 0.5 * (a2 + b2);
    b2 = std::sqrt(a2 * b2);
    a2 = a1;
  }
  const double q = b2 > 0.0 ? std::exp(-kPi * (kPi / (2.0 * a2)) / K) : 0.0;
  if (q > 0.3) return;  // Landen descent instead
  // Terms n = 0..M; the first left out, q^((M+1)(M+2)), is below 2^-60.
  int m = 0;
  while (m < 7 && q > 0.0 && std::pow(q, (m + 1) * (m + 2)) > 0x1p-60) ++m;
  theta_terms = m + 1;
  double t2_0 = 0.0, t3_0 = 1.0, t4_0 = 1.0;
  for (int n = 0; n <= m; ++n) {
    theta_odd[n] = q > 0.0 ? std::pow(q, n * (n + 1)) : (n == 0 ? 1.0 : 0.0);
    theta_even[n] = q > 0.0 ? 2.0 * std::pow(q, (n + 1) * (n + 1)) : 0.0;
    t2_0 += theta_odd[n];
    t3_0 += theta_even[n];
    t4_0 += ((n % 2 == 0) ? -1.0 : 1.0) * theta_even[n];
  }
  sn_scale = t3_0 / t2_0;
  cn_scale = t4_0 / t2_0;
  dn_scale = t4_0 / t3_0;
  theta_freq = kPi / (2.0 * K);
}

}  // namespace heavytop::detail

#pragma once
// Private to the Taylor integrator (src/integrators/taylor/): the arithmetic of truncated
// power series. A jet (every variable's coefficients, order by order), Cauchy products,
// Horner's rule, and the root of a function of the step's series. No physics here.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <boost/math/tools/toms748_solve.hpp>

#include "heavytop/taylor.hpp"

namespace heavytop::detail::taylor {

// ---- Series ---------------------------------------------------------------------------------------
//
// A truncated power series in tau = t - t0: s(tau) = sum_n s[n] tau^n (normalised Taylor
// coefficients, s[n] = s^(n)(t0) / n!). The solution's coefficients follow from x' = f(x):
// x[n+1] = f[n] / (n + 1), f[n] the n-th coefficient of f(x(tau)), which for a polynomial f
// is a sum of Cauchy products sum_{j=0..n} a[j] b[n-j] of the coefficients up to order n.
constexpr int kM = kTaylorMaxOrder;
using Coefficients = std::array<double, kM + 1>;  // one series

// The state's series, order by order: c[n][i] is coefficient n of variable i (conservative
// sets: 7 used, the 8th pads a row to two cache-line halves; the damped set: 10). A row per
// order lets one loop over j form every Cauchy product of order n in SIMD pairs (SSE2, the
// x86-64 baseline) and Horner's rule run on all variables at once. W is even.
template <int W>
struct alignas(64) JetOf {
  double c[kM + 1][W];
};
using Jet = JetOf<8>;

using v2d = double __attribute__((vector_size(16)));
inline v2d load2(const double* p) {
  v2d v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline v2d splat(double a) { return v2d{a, a}; }

// x = m 2^e with m in [0.5, 1) for a normal x > 0: frexp's m and e from the bits (no call).
inline bool split_normal(double x, double& m, int& e) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>(bits >> 52) & 0x7ff;
  if (biased == 0 || biased == 0x7ff) return false;  // zero, subnormal, infinity, NaN
  bits = (bits & 0x000fffffffffffffULL) | (std::uint64_t{1022} << 52);
  std::memcpy(&m, &bits, sizeof m);
  e = biased - 1022;
  return true;
}

// 2^k, |k| <= 1022 (from the bits: exact).
inline double power_of_two(int k) {
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// min(x^(-1/(p-1)), y^(-1/p)) as std::min of the two std::pow, bit for bit, with one pow
// wherever the smaller is clear: a < b exactly when x^p > y^(p-1), compared from the mantissas
// and exponents of x and y (r 2^d with r = mx^p / my^(p-1) against 1 +- 1e-10, as r against
// (1 +- 1e-10) 2^-d: scaling by a power of two is exact, so the comparison is ldexp(r, d)'s);
// a margin of 1e-10 on that ratio is a relative gap of at least 1.8e-13 between a and b, far
// beyond pow's error (< 1 ulp), so the one pow computed is the smaller of the two. Near a tie,
// and for zeros, subnormals, infinities and NaN, both (the batch's kernel does the same,
// integrators/batch/batch_kernel.hpp).
inline double step_from_norms(double x, double y, int p) {
  const double ea = -1.0 / (p - 1), eb = -1.0 / p;
  double mx, my;
  int ex, ey;
  if (x > 0.0 && y > 0.0 && split_normal(x, mx, ex) && split_normal(y, my, ey)) {
    double px = 1.0, py = 1.0;  // mx^p, my^(p-1), in [2^-24, 1]
    for (int n = p; n > 0; n >>= 1, mx *= mx)
      if (n & 1) px *= mx;
    for (int n = p - 1; n > 0; n >>= 1, my *= my)
      if (n & 1) py *= my;
    const long d = static_cast<long>(p) * ex - static_cast<long>(p - 1) * ey;
    if (d > 60) return std::pow(x, ea);  // the ratio r 2^d > 2^36
    if (d < -60) return std::pow(y, eb);
    const double r = px / py, scale = power_of_two(static_cast<int>(-d));
    if (r > (1.0 + 1e-10) * scale) return std::pow(x, ea);
    if (r < (1.0 - 1e-10) * scale) return std::pow(y, eb);
  }
  return std::min(std::pow(x, ea), std::pow(y, eb));
}

// The n-th coefficient of the product of two series.
inline double cauchy(const Coefficients& a, const Coefficients& b, int n) {
  double s = 0.0;
  for (int j = 0; j <= n; ++j) s += a[j] * b[n - j];
  return s;
}

// The n-th coefficient of a^2 + b^2, each square by its symmetry: a[j] a[n - j] once for
// j < n - j and doubled, the middle term a[n/2]^2 once (half the products of cauchy(a, a, n)).
// The batch's kernel forms it in the same order (integrators/batch/batch_kernel.hpp).
inline double sum_of_squares(const Coefficients& a, const Coefficients& b, int n) {
  double sa = 0.0, sb = 0.0;
  for (int j = 0; 2 * j < n; ++j) sa += a[j] * a[n - j], sb += b[j] * b[n - j];
  double s = (sa + sb) * 2.0;
  if (n % 2 == 0) s += a[n / 2] * a[n / 2] + b[n / 2] * b[n / 2];
  return s;
}

// s(tau) by Horner's rule.
inline double horner(const Coefficients& s, int p, double tau) {
  double v = s[p];
  for (int n = p - 1; n >= 0; --n) v = v * tau + s[n];
  return v;
}

// Every variable of the jet at tau (Horner, W / 2 pairs at a time).
template <int W>
inline void horner(const JetOf<W>& x, int p, double tau, double* out) {
  constexpr int kPairs = W / 2;
  v2d v[kPairs];
  for (int i = 0; i < kPairs; ++i) v[i] = load2(&x.c[p][2 * i]);
  const v2d t = splat(tau);
  for (int n = p - 1; n >= 0; --n)
    for (int i = 0; i < kPairs; ++i) v[i] = v[i] * t + load2(&x.c[n][2 * i]);
  for (int i = 0; i < kPairs; ++i) std::memcpy(out + 2 * i, &v[i], sizeof v[i]);
}

// Every variable of the jet at two points at once, tau_a and tau_b: horner()'s two passes with
// their chains interleaved, so that each hides the latency of the other's multiply-adds. The
// same operations in the same order per point: the same bits as two horner() calls.
template <int W>
inline void horner_pair(const JetOf<W>& x, int p, double tau_a, double tau_b, double* out_a, double* out_b) {
  constexpr int kPairs = W / 2;
  v2d a[kPairs], b[kPairs];
  for (int i = 0; i < kPairs; ++i) a[i] = b[i] = load2(&x.c[p][2 * i]);
  const v2d ta = splat(tau_a), tb = splat(tau_b);
  for (int n = p - 1; n >= 0; --n)
    for (int i = 0; i < kPairs; ++i) {
      const v2d c = load2(&x.c[n][2 * i]);
      a[i] = a[i] * ta + c, b[i] = b[i] * tb + c;
    }
  for (int i = 0; i < kPairs; ++i) {
    std::memcpy(out_a + 2 * i, &a[i], sizeof a[i]);
    std::memcpy(out_b + 2 * i, &b[i], sizeof b[i]);
  }
}

// Variable i of the jet at tau (Horner).
template <int W>
inline double horner(const JetOf<W>& x, int i, int p, double tau) {
  double v = x.c[p][i];
  for (int n = p - 1; n >= 0; --n) v = v * tau + x.c[n][i];
  return v;
}

// One variable's series out of the jet.
template <int W>
inline Coefficients series_of(const JetOf<W>& x, int i, int p) {
  Coefficients s{};
  for (int n = 0; n <= p; ++n) s[n] = x.c[n][i];
  return s;
}

// A root of f on [a, b] where f(a), f(b) have opposite signs, to ~1e-15 of the step h
// (TOMS 748; f is a function of the step's series, cheap, so it is solved to rounding).
template <class F>
double root(F f, double a, double b, double fa, double fb, double h) {
  std::uintmax_t iterations = 100;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, fa, fb, [h](double lo, double hi) { return std::abs(hi - lo) <= 1e-15 * h; }, iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// A root of the polynomial s[0..p] on [a, b] where s(a), s(b) have opposite signs, to ~1e-15
// of the step h: Newton's method from the secant's point, the value and the slope in one Horner
// pass, each iterate kept inside the bracket that the signs shrink (bisection where Newton's
// step would leave it). A simple root takes 3-4 passes, where TOMS 748 (root()) took about 10
// values; a multiple one converges linearly, still inside the bracket. The scan's events
// (taylor.cpp) and the batch's (integrators/batch/) both solve here: the same roots.
inline double polynomial_root(const double* s, int p, double a, double b, double fa, double fb, double h) {
  const double tolerance = 1e-15 * h;
  const bool negative_at_a = fa < 0.0;
  double x = a + (b - a) * (fa / (fa - fb));
  if (!(x > a && x < b)) x = 0.5 * (a + b);
  for (int pass = 0; pass < 200; ++pass) {
    double f = s[p], slope = 0.0;
    for (int n = p - 1; n >= 0; --n) slope = slope * x + f, f = f * x + s[n];
    if (f == 0.0) return x;
    ((f < 0.0) == negative_at_a ? a : b) = x;
    const double step = f / slope;
    if (std::abs(step) <= tolerance) return x - step;
    double next = x - step;
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (!(b - a > tolerance)) return next;
    x = next;
  }
  return x;
}

}  // namespace heavytop::detail::taylor

// The outer-product recurrences (recurrence_kernels.hpp), included once by each of
// recurrence_sse2.cpp, recurrence_avx2.cpp and recurrence_avx512.cpp, which define
// HEAVYTOP_RECURRENCE_SUFFIX (the entry points' suffix), HEAVYTOP_RECURRENCE_PAIRS (1: the
// products in SSE2 pairs instead) and HEAVYTOP_RECURRENCE_WIDE (1 where 8-wide registers pair
// two 4-wide products). No include guard: once per translation unit.

#include "integrators/taylor/recurrence_kernels.hpp"

#define HEAVYTOP_CAT2(a, b) a##b
#define HEAVYTOP_CAT(a, b) HEAVYTOP_CAT2(a, b)

#if HEAVYTOP_RECURRENCE_PAIRS
// SSE2 (the x86-64 baseline, and WebAssembly): the products in pairs, as recurrence.hpp formed
// them before the outer-product form (4-wide products lowered to pairs measured 1.4x slower).
namespace heavytop::detail::taylor {
namespace {
typedef double v2d __attribute__((vector_size(16)));
inline v2d load2(const double* p) {
  v2d v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline v2d splat(double a) { return v2d{a, a}; }
}  // namespace

void HEAVYTOP_CAT(plain_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                  const PlainConstants& k) {
  for (int n = 0; n < p; ++n) {
    v2d qw_w{}, qx_w{}, qy_w{}, qz_w{}, wx_w3{}, yz_w3{};  // q_i (w1, w2); (qw, qx) w3, (qy, qz) w3
    v2d xz_yz = {}, wy_wx = {}, w23_w31 = {};
    double w12 = 0.0;
    auto term = [&](int j) {
      const double *a = c[j], *b = c[n - j];
      const v2d w = load2(b + 4), w3 = splat(b[6]);
      qw_w += splat(a[0]) * w, qx_w += splat(a[1]) * w, qy_w += splat(a[2]) * w, qz_w += splat(a[3]) * w;
      wx_w3 += load2(a) * w3, yz_w3 += load2(a + 2) * w3;
      xz_yz += load2(a + 1) * splat(b[3]);
      wy_wx += splat(a[0]) * v2d{b[2], b[1]};
      w23_w31 += load2(a + 5) * v2d{b[6], b[4]};
      w12 += a[4] * b[5];
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
    g1[n] = 2.0 * (xz_yz[0] - wy_wx[0]);
    g2[n] = 2.0 * (xz_yz[1] + wy_wx[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    double* next = c[n + 1];
    next[0] = -half * (qx_w[0] + qy_w[1] + yz_w3[1]);
    next[1] = half * (qw_w[0] + yz_w3[0] - qz_w[1]);
    next[2] = half * (qw_w[1] + qz_w[0] - wx_w3[1]);
    next[3] = half * (wx_w3[0] + qx_w[1] - qy_w[0]);
    next[4] = inv * (k.e1 * w23_w31[0] + k.ka * g2[n]);
    next[5] = inv * (k.e2 * w23_w31[1] - k.kb * g1[n]);
    next[6] = inv * (k.e3 * w12);
    next[7] = 0.0;
  }
}

void HEAVYTOP_CAT(factored_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                     const FactoredConstants& k) {
  const double nutation = k.c_over_a * c[0][6];  // rad/s, C w3 / A
  for (int n = 0; n < p; ++n) {
    v2d pw_v{}, px_v{}, py_v{}, pz_v{}, xz_yz = {}, wy_wx = {};  // p_i (v1, v2); gamma
    auto term = [&](int j) {
      const double *a = c[j], *b = c[n - j];
      const v2d v = load2(b + 4);
      pw_v += splat(a[0]) * v, px_v += splat(a[1]) * v, py_v += splat(a[2]) * v, pz_v += splat(a[3]) * v;
      xz_yz += load2(a + 1) * splat(b[3]);
      wy_wx += splat(a[0]) * v2d{b[2], b[1]};
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
    g1[n] = 2.0 * (xz_yz[0] - wy_wx[0]);
    g2[n] = 2.0 * (xz_yz[1] + wy_wx[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    const double* row = c[n];
    double* next = c[n + 1];
    next[0] = -half * (px_v[0] + py_v[1]);
    next[1] = half * (pw_v[0] - pz_v[1]);
    next[2] = half * (pw_v[1] + pz_v[0]);
    next[3] = half * (px_v[1] - py_v[0]);
    next[4] = inv * (-nutation * row[5] + k.ka * g2[n]);
    next[5] = inv * (nutation * row[4] - k.ka * g1[n]);
    next[6] = 0.0;
    next[7] = 0.0;
  }
}
}  // namespace heavytop::detail::taylor

#else  // the outer-product form
namespace heavytop::detail::taylor {
namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX) {
namespace {

constexpr int kM = 24;  // kTaylorMaxOrder (taylor.hpp; recurrence_dispatch.cpp checks)
typedef double V4 __attribute__((vector_size(32)));
typedef double V8 __attribute__((vector_size(64)));

// 0.5 / (n + 1) and 1 / (n + 1): the same values recurrence.hpp divides out each time
// (a division is correctly rounded at compile time as at run time). constexpr, so that no
// code of this file runs before the dispatch has chosen it: a constructor here was compiled
// with this file's instruction set and ran at start-up on every processor (SIGILL without
// AVX-512; tests/valgrind_start.sh runs the command where AVX-512 is absent).
struct Reciprocals {
  double half[kM], inv[kM];
  constexpr Reciprocals() : half{}, inv{} {
    for (int n = 0; n < kM; ++n) half[n] = 0.5 / (n + 1), inv[n] = 1.0 / (n + 1);
  }
};
constexpr Reciprocals reciprocals;

// Row n of the jet rearranged for the products of order >= n: the quaternion q, and the
// vertical's and the gyroscopic products' factors in lane order,
//   gamma: (qx, qy, qw, qw) x (qz, qz, qy, qx) -> (qx qz, qy qz, qw qy, qw qx)
//   gyro:  (w2, w3, w1, 0) x (w3, w1, w2, 0)   -> (w2 w3, w3 w1, w1 w2, 0)
struct alignas(64) Rows {
#if HEAVYTOP_RECURRENCE_WIDE
  V8 qq[kM + 1];   // (q, q)
  V8 w12[kM + 1];  // (w1 x4, w2 x4)
  V8 qa[kM + 1];   // (q, gamma's left factors)
  V8 w3b[kM + 1];  // (w3 x4, gamma's right factors)
#else
  V4 q[kM + 1], ga[kM + 1], gb[kM + 1];
#endif
  V4 wa[kM + 1], wb[kM + 1];
};

inline void arrange(Rows& r, const double* c, int n, bool gyro) {
  const V4 q = {c[0], c[1], c[2], c[3]}, ga = {c[1], c[2], c[0], c[0]}, gb = {c[3], c[3], c[2], c[1]};
#if HEAVYTOP_RECURRENCE_WIDE
  r.qq[n] = V8{q[0], q[1], q[2], q[3], q[0], q[1], q[2], q[3]};
  r.w12[n] = V8{c[4], c[4], c[4], c[4], c[5], c[5], c[5], c[5]};
  r.qa[n] = V8{q[0], q[1], q[2], q[3], ga[0], ga[1], ga[2], ga[3]};
  r.w3b[n] = V8{c[6], c[6], c[6], c[6], gb[0], gb[1], gb[2], gb[3]};
#else
  r.q[n] = q, r.ga[n] = ga, r.gb[n] = gb;
#endif
  if (gyro) r.wa[n] = V4{c[5], c[6], c[4], 0.0}, r.wb[n] = V4{c[6], c[4], c[5], 0.0};
}

}  // namespace
}  // namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX)

void HEAVYTOP_CAT(plain_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                  const PlainConstants& k) {
  using namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX);
  Rows r;
  for (int n = 0; n < p; ++n) {
    arrange(r, c[n], n, true);
    // a1 = q w1, a2 = q w2, a3 = q w3 (lanes qw, qx, qy, qz); ag = gamma's; aw = gyro's.
    V4 a1 = {}, a2 = {}, a3 = {}, ag = {}, aw = {};
#if HEAVYTOP_RECURRENCE_WIDE
    V8 a12 = {}, a3g = {};
    auto term = [&](int j) {
      a12 += r.qq[j] * r.w12[n - j];
      a3g += r.qa[j] * r.w3b[n - j];
      aw += r.wa[j] * r.wb[n - j];
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
    a1 = V4{a12[0], a12[1], a12[2], a12[3]}, a2 = V4{a12[4], a12[5], a12[6], a12[7]};
    a3 = V4{a3g[0], a3g[1], a3g[2], a3g[3]}, ag = V4{a3g[4], a3g[5], a3g[6], a3g[7]};
#else
    auto term = [&](int j) {
      const double* b = c[n - j];
      a1 += r.q[j] * V4{b[4], b[4], b[4], b[4]};
      a2 += r.q[j] * V4{b[5], b[5], b[5], b[5]};
      a3 += r.q[j] * V4{b[6], b[6], b[6], b[6]};
      ag += r.ga[j] * r.gb[n - j];
      aw += r.wa[j] * r.wb[n - j];
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
#endif
    g1[n] = 2.0 * (ag[0] - ag[2]);
    g2[n] = 2.0 * (ag[1] + ag[3]);
    const double half = reciprocals.half[n], inv = reciprocals.inv[n];
    double* next = c[n + 1];
    // q' = q (x) (0, w) / 2, as AttitudeTerms::rate
    next[0] = -half * (a1[1] + a2[2] + a3[3]);
    next[1] = half * (a1[0] + a3[2] - a2[3]);
    next[2] = half * (a2[0] + a1[3] - a3[1]);
    next[3] = half * (a3[0] + a2[1] - a1[2]);
    // Euler: I w' = (I w) x w + m g R (gamma x e3)
    next[4] = inv * (k.e1 * aw[0] + k.ka * g2[n]);
    next[5] = inv * (k.e2 * aw[1] - k.kb * g1[n]);
    next[6] = inv * (k.e3 * aw[2]);
    next[7] = 0.0;
  }
}

void HEAVYTOP_CAT(factored_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                     const FactoredConstants& k) {
  using namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX);
  Rows r;
  const double nutation = k.c_over_a * c[0][6];  // rad/s, C w3 / A
  for (int n = 0; n < p; ++n) {
    arrange(r, c[n], n, false);
    V4 a1 = {}, a2 = {}, ag = {};  // p v1, p v2 (lanes pw, px, py, pz); gamma's
#if HEAVYTOP_RECURRENCE_WIDE
    V8 a12 = {}, a3g = {};  // a3g's lower half (p w3) is not used: w3 is no variable here
    auto term = [&](int j) {
      a12 += r.qq[j] * r.w12[n - j];
      a3g += r.qa[j] * r.w3b[n - j];
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
    a1 = V4{a12[0], a12[1], a12[2], a12[3]}, a2 = V4{a12[4], a12[5], a12[6], a12[7]};
    ag = V4{a3g[4], a3g[5], a3g[6], a3g[7]};
#else
    auto term = [&](int j) {
      const double* b = c[n - j];
      a1 += r.q[j] * V4{b[4], b[4], b[4], b[4]};
      a2 += r.q[j] * V4{b[5], b[5], b[5], b[5]};
      ag += r.ga[j] * r.gb[n - j];
    };
    for (int j = 1; j < n; ++j) term(j);  // the products' order (recurrence_kernels.hpp)
    term(0);
    if (n > 0) term(n);
#endif
    g1[n] = 2.0 * (ag[0] - ag[2]);
    g2[n] = 2.0 * (ag[1] + ag[3]);
    const double half = reciprocals.half[n], inv = reciprocals.inv[n];
    const double* row = c[n];
    double* next = c[n + 1];
    // p' = p (x) (0, v1, v2, 0) / 2, as FactoredAttitudeTerms::rate
    next[0] = -half * (a1[1] + a2[2]);
    next[1] = half * (a1[0] - a2[3]);
    next[2] = half * (a2[0] + a1[3]);
    next[3] = half * (a2[1] - a1[2]);
    next[4] = inv * (-nutation * row[5] + k.ka * g2[n]);
    next[5] = inv * (nutation * row[4] - k.ka * g1[n]);
    next[6] = 0.0;
    next[7] = 0.0;
  }
}

}  // namespace heavytop::detail::taylor

#endif  // HEAVYTOP_RECURRENCE_PAIRS

#undef HEAVYTOP_CAT
#undef HEAVYTOP_CAT2

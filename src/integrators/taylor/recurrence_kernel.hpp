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
    const double g1n = 2.0 * (xz_yz[0] - wy_wx[0]), g2n = 2.0 * (xz_yz[1] + wy_wx[1]);
    g1[n] = g1n, g2[n] = g2n;  // stored, and used from registers (g1 and g2 may alias c)
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    double* next = c[n + 1];
    next[0] = -half * (qx_w[0] + qy_w[1] + yz_w3[1]);
    next[1] = half * (qw_w[0] + yz_w3[0] - qz_w[1]);
    next[2] = half * (qw_w[1] + qz_w[0] - wx_w3[1]);
    next[3] = half * (wx_w3[0] + qx_w[1] - qy_w[0]);
    next[4] = inv * (k.e1 * w23_w31[0] + k.ka * g2n);
    next[5] = inv * (k.e2 * w23_w31[1] - k.kb * g1n);
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
    const double g1n = 2.0 * (xz_yz[0] - wy_wx[0]), g2n = 2.0 * (xz_yz[1] + wy_wx[1]);
    g1[n] = g1n, g2[n] = g2n;
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    const double* row = c[n];
    double* next = c[n + 1];
    next[0] = -half * (px_v[0] + py_v[1]);
    next[1] = half * (pw_v[0] - pz_v[1]);
    next[2] = half * (pw_v[1] + pz_v[0]);
    next[3] = half * (px_v[1] - py_v[0]);
    next[4] = inv * (-nutation * row[5] + k.ka * g2n);
    next[5] = inv * (nutation * row[4] - k.ka * g1n);
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
typedef long long V4i __attribute__((vector_size(32)));
typedef double V8 __attribute__((vector_size(64)));

// 0.5 / (n + 1) and 1 / (n + 1): the same values recurrence.hpp divides out each time
// (a division is correctly rounded at compile time as at run time). constexpr, so that no
// code of this file runs before the dispatch has chosen it: a constructor here was compiled
// with this file's instruction set and ran at start-up on every processor (SIGILL without
// AVX-512; tests/other_processors.sh runs the command where AVX-512 is absent).
struct Reciprocals {
  double half[kM][4], inv[kM];  // half as (-half, half, half, half), the attitude's signs: one load
  constexpr Reciprocals() : half{}, inv{} {
    for (int n = 0; n < kM; ++n) {
      const double h = 0.5 / (n + 1);
      half[n][0] = -h, half[n][1] = h, half[n][2] = h, half[n][3] = h, inv[n] = 1.0 / (n + 1);
    }
  }
};
constexpr Reciprocals reciprocals;

// Row n of the jet rearranged for the products of order >= n: the quaternion q, and the
// vertical's and the gyroscopic products' factors in lane order,
//   gamma: (qx, qy, qw, qw) x (qz, qz, qy, qx) -> (qx qz, qy qz, qw qy, qw qx) (the 4-wide
//          form's differ, with the attitude's: factors())
//   gyro:  (w2, w3, w1, 0) x (w3, w1, w2, 0)   -> (w2 w3, w3 w1, w1 w2, 0)
struct alignas(64) Rows {
#if HEAVYTOP_RECURRENCE_WIDE
  V8 qq[kM + 1];   // (q, q)
  V8 w12[kM + 1];  // (w1 x4, w2 x4)
  V8 qa[kM + 1];   // (q, gamma's left factors)
  V8 w3b[kM + 1];  // (w3 x4, gamma's right factors)
#else
  V4 ga[kM + 1], gb[kM + 1];
  V4 la[kM + 1], lb[kM + 1], lc[kM + 1];  // the attitude's factors as row j
  V4 ra[kM + 1], rb[kM + 1], rc[kM + 1];  // and as row n - j (factors())
#endif
  V4 wa[kM + 1], wb[kM + 1];
};

// One row of the jet in two registers: (qw, qx, qy, qz) and (w1, w2, w3, 0). Each order's row
// stays in them for the next order's arrange(): read back from the jet, the shortest chain of
// the recurrence (row n -> its products with row 0 -> row n + 1) would also wait on the store
// and rebuild the vectors lane by lane.
struct Row {
  V4 q, w;
};
inline Row load_row(const double* c) { return {V4{c[0], c[1], c[2], c[3]}, V4{c[4], c[5], c[6], 0.0}}; }
inline void store_row(const Row& row, double* c) {
  __builtin_memcpy(c, &row.q, sizeof row.q);
  __builtin_memcpy(c + 4, &row.w, sizeof row.w);
}

// The sign flipped in the lanes where `mask` has the sign bit: x - y is x + (-y), bit for bit
// (signed zeros too), so a row's sums keep the scalar expressions' bits.
constexpr long long kSign = static_cast<long long>(0x8000000000000000ULL);
inline V4 flip(V4 v, V4i mask) { return reinterpret_cast<V4>(reinterpret_cast<V4i>(v) ^ mask); }

#if HEAVYTOP_RECURRENCE_WIDE
// Row n + 1's attitude, half (x) the sums of the products a1 = q w1, a2 = q w2, a3 = q w3 in
// lanes (the scalar form: -half (a1[1] + a2[2] + a3[3]), half (a1[0] + a3[2] - a2[3]),
// half (a2[0] + a1[3] - a3[1]), half (a3[0] + a2[1] - a1[2]); AttitudeTerms::rate), formed in
// the registers rather than lane by lane.
inline V4 attitude_rate(V4 a1, V4 a2, V4 a3, V4 half) {
  const V4 x = __builtin_shufflevector(__builtin_shufflevector(a1, a2, 1, 0, 4, 4), a3, 0, 1, 2, 4);
  const V4 y = __builtin_shufflevector(__builtin_shufflevector(a2, a3, 2, 6, 1, 1), a1, 0, 1, 7, 2);
  const V4 z = __builtin_shufflevector(__builtin_shufflevector(a3, a2, 3, 7, 1, 1), a1, 0, 1, 2, 6);
  return half * ((x + y) + flip(z, V4i{0, kSign, kSign, kSign}));
}
// The spin-factored attitude's: -half (a1[1] + a2[2]), half (a1[0] - a2[3]), half (a2[0] + a1[3]),
// half (a2[1] - a1[2]) (FactoredAttitudeTerms::rate).
inline V4 factored_attitude_rate(V4 a1, V4 a2, V4 half) {
  const V4 x = __builtin_shufflevector(a1, a2, 1, 0, 4, 5), y = __builtin_shufflevector(a2, a1, 2, 3, 7, 6);
  return half * (x + flip(y, V4i{0, kSign, 0, kSign}));
}
// gamma's products ag summed as (ag[1] + ag[3], ag[0] - ag[2], the same again): g2 / 2, g1 / 2.
inline V4 half_gamma(V4 ag) {
  return __builtin_shufflevector(ag, ag, 1, 0, 1, 0) +
         flip(__builtin_shufflevector(ag, ag, 3, 2, 3, 2), V4i{0, kSign, 0, kSign});
}
#else
// Row n + 1's attitude from the sums already in its lanes (factors()): half (x + y + z), the
// scalar form's sums in its order (x + y commutes), z's sign flipped where the scalar form
// subtracts. No shuffle between the last sum and the row: this is the chain from row n to n + 1.
inline V4 attitude_rate(V4 x, V4 y, V4 z, V4 half) {
  return half * ((x + y) + flip(z, V4i{0, kSign, kSign, kSign}));
}
inline V4 factored_attitude_rate(V4 x, V4 y, V4 half) {
  return half * (x + flip(y, V4i{0, kSign, 0, kSign}));
}
// ... and gamma's (factors()): (ag[2] + ag[0], ag[3] - ag[1], +0, +0), g2 / 2, g1 / 2: the
// high half brought down (a 128-bit extraction, which zeroes the rest) while the low half's sign
// is flipped, and the zeros let the gravity term add -0 (no term) in lanes 2 and 3 with no blend.
inline V4 half_gamma(V4 ag) {
  return __builtin_shufflevector(ag, V4{}, 2, 3, 4, 5) +
         flip(__builtin_shufflevector(ag, V4{}, 0, 1, 4, 5), V4i{0, kSign, 0, 0});
}
#endif

#if HEAVYTOP_RECURRENCE_WIDE
inline void arrange(Rows& r, const Row& row, int n, bool gyro) {
  const V4 q = row.q, w = row.w;
  r.qq[n] = __builtin_shufflevector(q, q, 0, 1, 2, 3, 0, 1, 2, 3);
  r.w12[n] = __builtin_shufflevector(w, w, 0, 0, 0, 0, 1, 1, 1, 1);
  r.qa[n] = __builtin_shufflevector(q, q, 0, 1, 2, 3, 1, 2, 0, 0);
  r.w3b[n] = __builtin_shufflevector(w, q, 2, 2, 2, 2, 7, 7, 6, 5);
  // (w2, w3, w1, 0) and (w3, w1, w2, 0): the pad is lane 3
  if (gyro) r.wa[n] = __builtin_shufflevector(w, w, 1, 2, 0, 3), r.wb[n] = __builtin_shufflevector(w, w, 2, 0, 1, 3);
}
#else
// One row's factors, each in the lanes of the sum it goes into: the left ones (la, lb, lc, ga,
// wa) as row j, the right ones (ra, rb, rc, gb, wb) as row n - j. The attitude's sums x = la ra,
// y = lb rb, z = lc rc are attitude_rate()'s operands lane for lane (the scalar form's three
// products of each component, in its order), so no shuffle follows the sums:
//   plain:  x = (qx w1, qy w3, qw w2, qw w3), y = (qy w2, qw w1, qz w1, qx w2),
//           z = (qz w3, qz w2, qx w3, qy w1)
//   spin-factored: x = (qx v1, qw v1, qw v2, qx v2), y = (qy v2, qz v2, qz v1, qy v1)
// and gamma's ag = ga gb = (qw qx, qw qy, qy qz, qx qz): half_gamma() adds the halves.
struct Factors {
  V4 la, lb, lc, ga, wa, ra, rb, rc, gb, wb;
};
inline Factors factors(const Row& row, bool gyro) {
  const V4 q = row.q, w = row.w;
  Factors f{};
  f.ga = __builtin_shufflevector(q, q, 0, 0, 2, 1), f.gb = __builtin_shufflevector(q, q, 1, 2, 3, 3);
  if (gyro) {
    f.la = __builtin_shufflevector(q, q, 1, 2, 0, 0), f.lb = __builtin_shufflevector(q, q, 2, 0, 3, 1);
    f.lc = __builtin_shufflevector(q, q, 3, 3, 1, 2);
    f.ra = __builtin_shufflevector(w, w, 0, 2, 1, 2), f.rb = __builtin_shufflevector(w, w, 1, 0, 0, 1);
    f.rc = __builtin_shufflevector(w, w, 2, 1, 2, 0);
    // (w2, w3, w1, 0) and (w3, w1, w2, 0): the pad is lane 3
    f.wa = __builtin_shufflevector(w, w, 1, 2, 0, 3), f.wb = __builtin_shufflevector(w, w, 2, 0, 1, 3);
  } else {
    f.la = __builtin_shufflevector(q, q, 1, 0, 0, 1), f.lb = __builtin_shufflevector(q, q, 2, 3, 3, 2);
    f.ra = __builtin_shufflevector(w, w, 0, 0, 1, 1), f.rb = __builtin_shufflevector(w, w, 1, 1, 0, 0);
  }
  return f;
}
inline void arrange(Rows& r, const Row& row, int n, bool gyro) {
  const Factors f = factors(row, gyro);
  r.ga[n] = f.ga, r.gb[n] = f.gb, r.la[n] = f.la, r.lb[n] = f.lb, r.ra[n] = f.ra, r.rb[n] = f.rb;
  if (gyro) r.lc[n] = f.lc, r.rc[n] = f.rc, r.wa[n] = f.wa, r.wb[n] = f.wb;
}
#endif

// One order's sums of products: a1 = q w1, a2 = q w2, a3 = q w3 (lanes qw, qx, qy, qz; in the
// 4-wide form x, y, z instead, factors()), ag = gamma's, aw = the gyroscopic ones (Plain only),
// each the sum over j of row j's factor times row n - j's, in the order of
// recurrence_kernels.hpp: j = 1..n-1, then j = 0 and j = n.
struct Sums {
  V4 a1, a2, a3, ag, aw;
};
template <bool Gyro>
inline Sums sums_of(const Rows& r, [[maybe_unused]] const Row& now, int n) {
  V4 a1 = {}, a2 = {}, a3 = {}, ag = {}, aw = {};
#if HEAVYTOP_RECURRENCE_WIDE
  V8 a12 = {}, a3g = {};
  auto term = [&](int j) {
    a12 += r.qq[j] * r.w12[n - j];
    a3g += r.qa[j] * r.w3b[n - j];
    if constexpr (Gyro) aw += r.wa[j] * r.wb[n - j];
  };
  for (int j = 1; j < n; ++j) term(j);
  term(0);
  if (n > 0) term(n);
  a1 = __builtin_shufflevector(a12, a12, 0, 1, 2, 3), a2 = __builtin_shufflevector(a12, a12, 4, 5, 6, 7);
  a3 = __builtin_shufflevector(a3g, a3g, 0, 1, 2, 3), ag = __builtin_shufflevector(a3g, a3g, 4, 5, 6, 7);
#else
  // x, y, z (factors()) in a1, a2, a3: a's factors from row j, b's from row n - j
  auto add = [&](const Factors& a, const Factors& b) {
    a1 += a.la * b.ra;
    a2 += a.lb * b.rb;
    if constexpr (Gyro) a3 += a.lc * b.rc;  // the spin-factored set has no z
    ag += a.ga * b.gb;
    if constexpr (Gyro) aw += a.wa * b.wb;
  };
  // row j's stored factors (the spin-factored kernel reads none it never formed)
  auto row = [&](int j) {
    Factors f{};
    f.ga = r.ga[j], f.gb = r.gb[j], f.la = r.la[j], f.lb = r.lb[j], f.ra = r.ra[j], f.rb = r.rb[j];
    if constexpr (Gyro) f.lc = r.lc[j], f.rc = r.rc[j], f.wa = r.wa[j], f.wb = r.wb[j];
    return f;
  };
  for (int j = 1; j < n; ++j) add(row(j), row(n - j));
  // j = 0 and j = n: row n's factors from its registers (`now`), not from the stores just made
  const Factors f = factors(now, Gyro);
  add(row(0), f);
  if (n > 0) add(f, row(0));
#endif
  return {a1, a2, a3, ag, aw};
}

}  // namespace
}  // namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX)

void HEAVYTOP_CAT(plain_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                  const PlainConstants& k) {
  using namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX);
  Rows r;
  Row row = load_row(c[0]);
  // the constants in registers (k might alias the jet, for all the compiler knows, and would be
  // read again each order); lanes 2 and 3 of the gravity term: below
  const V4 e = V4{k.e1, k.e2, k.e3, 0.0}, kg = V4{2.0 * k.ka, -2.0 * k.kb, -0.0, -0.0};
  for (int n = 0; n < p; ++n) {
    arrange(r, row, n, true);
    const Sums sums = sums_of<true>(r, row, n);
    const V4 s = half_gamma(sums.ag), gamma = s + s;  // (g2, g1): 2 s, exactly
    g2[n] = gamma[0], g1[n] = gamma[1];
    V4 half;  // (-half, half, half, half)
    __builtin_memcpy(&half, reciprocals.half[n], sizeof half);
    const double inv = reciprocals.inv[n];
    // Euler: I w' = (I w) x w + m g R (gamma x e3), lane by lane inv (e1 aw[0] + ka g2),
    // inv (e2 aw[1] - kb g1), inv (e3 aw[2]), 0. ka g2 = (2 ka) s: 2 ka and 2 s are exact, so
    // it is the same real product and the same rounding (a finite run never nears overflow),
    // one multiplication less on the way to the next row; lanes 2 and 3
    // have no gravity term (x + 0 could turn a -0 into +0; x + -0 is x: the 4-wide form's s has
    // +0 there, so (-0) s = -0 and no blend waits on the chain).
    const V4 gyro = e * sums.aw;
#if HEAVYTOP_RECURRENCE_WIDE
    const V4 euler = __builtin_shufflevector(gyro + kg * s, gyro, 0, 1, 6, 7);
#else
    const V4 euler = gyro + kg * s;
#endif
    row = {attitude_rate(sums.a1, sums.a2, sums.a3, half),  // q' = q (x) (0, w) / 2
           V4{inv, inv, inv, inv} * euler};
    store_row(row, c[n + 1]);
  }
}

void HEAVYTOP_CAT(factored_coefficients_, HEAVYTOP_RECURRENCE_SUFFIX)(double (*c)[8], double* g1, double* g2, int p,
                                                                     const FactoredConstants& k) {
  using namespace HEAVYTOP_CAT(ns_, HEAVYTOP_RECURRENCE_SUFFIX);
  Rows r;
  const double nutation = k.c_over_a * c[0][6];  // rad/s, C w3 / A
  const V4 kn = V4{-nutation, nutation, 0.0, 0.0}, kg = V4{2.0 * k.ka, -2.0 * k.ka, 0.0, 0.0};  // in registers
  Row row = load_row(c[0]);
  for (int n = 0; n < p; ++n) {
    arrange(r, row, n, false);
    const Sums sums = sums_of<false>(r, row, n);  // p v1, p v2 (lanes pw, px, py, pz); gamma's
    const V4 s = half_gamma(sums.ag), gamma = s + s;  // (g2, g1)
    g2[n] = gamma[0], g1[n] = gamma[1];
    V4 half;  // (-half, half, half, half)
    __builtin_memcpy(&half, reciprocals.half[n], sizeof half);
    const double inv = reciprocals.inv[n];
    // inv (-nutation v2 + ka g2), inv (nutation v1 - ka g1), 0, 0 (ka g2 as (2 ka) s, above)
#if HEAVYTOP_RECURRENCE_WIDE
    const V4 v = kn * __builtin_shufflevector(row.w, row.w, 1, 0, 2, 3) + kg * s;
    row = {factored_attitude_rate(sums.a1, sums.a2, half),  // p' = p (x) (0, v1, v2, 0) / 2
           V4{inv, inv, 0.0, 0.0} * __builtin_shufflevector(v, V4{}, 0, 1, 4, 5)};
#else
    // lanes 2 and 3 (row 0's w3 among them) zeroed on the way in, off the chain through gamma,
    // with s's zeros there (half_gamma) v's are +0 + +0 = +0
    const V4 v = kn * __builtin_shufflevector(row.w, V4{}, 1, 0, 4, 5) + kg * s;
    row = {factored_attitude_rate(sums.a1, sums.a2, half),  // p' = p (x) (0, v1, v2, 0) / 2
           V4{inv, inv, 0.0, 0.0} * v};
#endif
    store_row(row, c[n + 1]);
  }
}

}  // namespace heavytop::detail::taylor

#endif  // HEAVYTOP_RECURRENCE_PAIRS

#undef HEAVYTOP_CAT
#undef HEAVYTOP_CAT2

// The batched Taylor tilt scan, included once by each of batch.cpp (SSE2), batch_avx2.cpp and
// batch_avx512.cpp, which define HEAVYTOP_BATCH_NS (the namespace, unique per instruction
// set), HEAVYTOP_BATCH_LANES (doubles per vector) and HEAVYTOP_BATCH_ENTRY (the entry point's
// name). No include guard: one inclusion per translation unit.
//
// It is taylor/integrator.hpp's TaylorIntegrator::step() and taylor.cpp's scan_tilt() with every double of one body
// widened to a vector of W bodies (structure of arrays: c[n][i][lane]). Every expression keeps
// the unbatched one's operations and their order, so each lane computes exactly what the
// unbatched integrator computes for its body (see batch.hpp); what is not elementwise (the
// step size's pow, the events' sign tests and roots, the tilt's atan2) is done lane by lane in
// scalar code. Builtins instead of <cmath>'s inline wrappers, and no templates from outside
// this namespace: see integrators/batch/batch.hpp.

#include "integrators/batch/batch.hpp"  // the kernel interface: nothing else, see there

namespace heavytop::detail::HEAVYTOP_BATCH_NS {
namespace {

constexpr int W = HEAVYTOP_BATCH_LANES;
typedef double V __attribute__((vector_size(8 * HEAVYTOP_BATCH_LANES)));
constexpr int kM = kBatchMaxOrder;
constexpr int kPieces = 8;  // taylor.cpp's split of a step to isolate the events' roots

inline V broadcast(double a) {
  V v;
  for (int l = 0; l < W; ++l) v[l] = a;
  return v;
}
inline V vabs(V a) {
  for (int l = 0; l < W; ++l) a[l] = __builtin_fabs(a[l]);
  return a;
}
// std::max(a, b) and std::min(a, b), lane by lane (their exact semantics: (a < b) ? b : a).
inline V vmax(V a, V b) {
  V r;
  for (int l = 0; l < W; ++l) r[l] = (a[l] < b[l]) ? b[l] : a[l];
  return r;
}

// x^n for 1 <= n <= kBatchMaxOrder (repeated squaring; used only to compare, see step_size).
inline double integer_power(double x, int n) {
  double r = 1.0;
  for (; n > 0; n >>= 1, x *= x)
    if (n & 1) r *= x;
  return r;
}

// x = m 2^e with m in [0.5, 1) for a normal x > 0 (taylor/series.hpp's split_normal).
inline bool split_normal(double x, double& m, int& e) {
  unsigned long long bits;
  __builtin_memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>(bits >> 52) & 0x7ff;
  if (biased == 0 || biased == 0x7ff) return false;
  bits = (bits & 0x000fffffffffffffULL) | (1022ULL << 52);
  __builtin_memcpy(&m, &bits, sizeof m);
  e = biased - 1022;
  return true;
}
inline double power_of_two(int k) {  // 2^k, |k| <= 1022
  const unsigned long long bits = static_cast<unsigned long long>(k + 1023) << 52;
  double v;
  __builtin_memcpy(&v, &bits, sizeof v);
  return v;
}

// min(pow(x, -1/(p-1)), pow(y, -1/p)) (taylor/integrator.hpp's step: std::min(a, b) = (b < a) ? b : a)
// with one pow instead of two wherever the order of the two is clear, as
// taylor/series.hpp's step_from_norms: a < b exactly when x^p > y^(p-1), compared from the
// mantissas and exponents (no overflow). The margin 1e-10 on that ratio is a relative gap of
// >= 1e-10 / (p (p - 1)) >= 1.8e-13 between a and b, far beyond pow's error (< 1 ulp): where
// it is met the pow computed is the smaller of the two pows, so the result is the two-pow
// result bit for bit; elsewhere (near ties, zeros, subnormals, infinities, NaN) both are
// computed.
inline double step_size(double x, double y, int p, double inv_pm1, double inv_p) {
  double mx, my;
  int ex, ey;
  if (x > 0.0 && y > 0.0 && split_normal(x, mx, ex) && split_normal(y, my, ey)) {
    const long d = static_cast<long>(p) * ex - static_cast<long>(p - 1) * ey;
    if (d > 60) return __builtin_pow(x, inv_pm1);  // x^p / y^(p-1) = r 2^d, r in [2^-24, 2^23]
    if (d < -60) return __builtin_pow(y, inv_p);
    const double r = integer_power(mx, p) / integer_power(my, p - 1), scale = power_of_two(static_cast<int>(-d));
    if (r > (1.0 + 1e-10) * scale) return __builtin_pow(x, inv_pm1);
    if (r < (1.0 - 1e-10) * scale) return __builtin_pow(y, inv_p);
  }
  const double a = __builtin_pow(x, inv_pm1), b = __builtin_pow(y, inv_p);
  return (b < a) ? b : a;
}

// Everything of one batch: the jet of the W bodies, the events' series, the parameters.
struct Work {
  V c[kM + 1][7];          // c[n][i]: coefficient n of variable i (q w, x, y, z; w or v 1, 2, 3)
  V g1[kM + 1], g2[kM + 1];  // the vertical's gamma_1, gamma_2 in body (or N) axes
  V rate[kM + 1], kz[kM + 1];  // d(k_zeta)/dt and k_zeta - cos(stop_above)
  V x[7];                  // the state at the lanes' times
  V e1, e2, e3, ka, kb, c_over_a;
};

// 0.5 / (n + 1) and 1 / (n + 1), n = 0..kM - 1: the recurrence's divisions, each once (the
// same values, so the same bits).
struct Reciprocals {
  double half[kM], inv[kM];
  Reciprocals() {
    for (int n = 0; n < kM; ++n) half[n] = 0.5 / (n + 1), inv[n] = 1.0 / (n + 1);
  }
};

// taylor/recurrence.hpp's Plain::coefficients / SpinFactored::coefficients, on W lanes.
template <bool Symmetric>
inline void coefficients(Work& w, int p, const Reciprocals& r) {
  if constexpr (Symmetric) {
    const V nutation = w.c_over_a * w.c[0][6];  // rad/s, C w3 / A
    for (int n = 0; n < p; ++n) {
      V pw1 = {}, pw2 = {}, px1 = {}, px2 = {}, py1 = {}, py2 = {}, pz1 = {}, pz2 = {};
      V xz = {}, yz = {}, wy = {}, wx = {};
      auto term = [&](int j) {
        const V *a = w.c[j], *b = w.c[n - j];
        pw1 += a[0] * b[4], pw2 += a[0] * b[5], px1 += a[1] * b[4], px2 += a[1] * b[5];
        py1 += a[2] * b[4], py2 += a[2] * b[5], pz1 += a[3] * b[4], pz2 += a[3] * b[5];
        xz += a[1] * b[3], yz += a[2] * b[3], wy += a[0] * b[2], wx += a[0] * b[1];
      };
      for (int j = 1; j < n; ++j) term(j);  // the recurrence's order of the products
      term(0);
      if (n > 0) term(n);
      w.g1[n] = 2.0 * (xz - wy);
      w.g2[n] = 2.0 * (yz + wx);
      const double half = r.half[n], inv = r.inv[n];
      const V* row = w.c[n];
      V* next = w.c[n + 1];
      next[0] = -half * (px1 + py2);
      next[1] = half * (pw1 - pz2);
      next[2] = half * (pw2 + pz1);
      next[3] = half * (px2 - py1);
      next[4] = inv * (-nutation * row[5] + w.ka * w.g2[n]);
      next[5] = inv * (nutation * row[4] - w.ka * w.g1[n]);
      next[6] = V{};
    }
  } else {
    for (int n = 0; n < p; ++n) {
      V qw1 = {}, qw2 = {}, qx1 = {}, qx2 = {}, qy1 = {}, qy2 = {}, qz1 = {}, qz2 = {};
      V qw3 = {}, qx3 = {}, qy3 = {}, qz3 = {};  // q_i w3
      V xz = {}, yz = {}, wy = {}, wx = {};
      V w23 = {}, w31 = {}, w12 = {};
      auto term = [&](int j) {
        const V *a = w.c[j], *b = w.c[n - j];
        qw1 += a[0] * b[4], qw2 += a[0] * b[5], qx1 += a[1] * b[4], qx2 += a[1] * b[5];
        qy1 += a[2] * b[4], qy2 += a[2] * b[5], qz1 += a[3] * b[4], qz2 += a[3] * b[5];
        qw3 += a[0] * b[6], qx3 += a[1] * b[6], qy3 += a[2] * b[6], qz3 += a[3] * b[6];
        xz += a[1] * b[3], yz += a[2] * b[3], wy += a[0] * b[2], wx += a[0] * b[1];
        w23 += a[5] * b[6], w31 += a[6] * b[4], w12 += a[4] * b[5];
      };
      for (int j = 1; j < n; ++j) term(j);  // the recurrence's order of the products
      term(0);
      if (n > 0) term(n);
      w.g1[n] = 2.0 * (xz - wy);
      w.g2[n] = 2.0 * (yz + wx);
      const double half = r.half[n], inv = r.inv[n];
      V* next = w.c[n + 1];
      next[0] = -half * (qx1 + qy2 + qz3);
      next[1] = half * (qw1 + qy3 - qz2);
      next[2] = half * (qw2 + qz1 - qx3);
      next[3] = half * (qw3 + qx2 - qy1);
      next[4] = inv * (w.e1 * w23 + w.ka * w.g2[n]);
      next[5] = inv * (w.e2 * w31 - w.kb * w.g1[n]);
      next[6] = inv * (w.e3 * w12);
    }
  }
}

// Coefficient n of the product of the series a and b (a[j], b[j] every `stride` V apart).
inline V cauchy(const V* a, const V* b, int stride, int n) {
  V s = {};
  for (int j = 0; j <= n; ++j) s += a[j * stride] * b[(n - j) * stride];
  return s;
}

// A series (stride V apart) at tau, lane by lane, by Horner's rule.
inline V horner(const V* s, int stride, int p, V tau) {
  V v = s[p * stride];
  for (int n = p - 1; n >= 0; --n) v = v * tau + s[n * stride];
  return v;
}

// One series (stride V apart) at the pieces' points at[0..kPieces], their Horner chains
// interleaved (each chain's operations as horner()'s, so the same bits; one chain alone waits
// on each multiply-add in turn).
inline void horner_pieces(const V* s, int stride, int p, const V* at, V* out) {
  V v[kPieces + 1];
  for (int k = 0; k <= kPieces; ++k) v[k] = s[p * stride];
  for (int n = p - 1; n >= 0; --n)
    for (int k = 0; k <= kPieces; ++k) v[k] = v[k] * at[k] + s[n * stride];
  for (int k = 0; k <= kPieces; ++k) out[k] = v[k];
}

// taylor.cpp's tilt_of: frames.hpp's tilt_of_axis (here again: no heavytop header in this
// file) of the axis of a (not normalised) quaternion.
inline double tilt_of(double qw, double qx, double qy, double qz) {
  const double g1 = 2.0 * (qx * qz - qw * qy), g2 = 2.0 * (qy * qz + qw * qx);
  const double g3 = qw * qw - qx * qx - qy * qy + qz * qz;
  const double h = g1 * g1 + g2 * g2, v = g3 * g3;
  if (g3 > 0.0 && h < v && h > 1e-280) return __builtin_asin(__builtin_sqrt(h / (h + v)));
  return __builtin_atan2(__builtin_hypot(g1, g2), g3);
}

// Extremes false: the verdict only (exceeded and t_end, the same bits), without the tilt's
// extrema: no series of d(k_zeta)/dt, no roots but the crossing's, no tilt at the crossing or
// at the step ends.
template <bool Symmetric, bool Extremes>
void scan(const BatchPoint* points, std::size_t count, const BatchSettings& s, BatchResult* out) {
  const int p = s.order;
  const double horizon = s.horizon, stop_above = s.stop_above;
  const bool threshold = stop_above < 3.141592653589793;  // a tilt above pi cannot be reached
  const double cos_stop = __builtin_cos(stop_above);
  const double half_stop = __builtin_sin(0.5 * stop_above);
  const double one_minus_cos_stop = 2.0 * half_stop * half_stop;  // taylor.cpp's, without cancellation
  const double inv_pm1 = -1.0 / (p - 1), inv_p = -1.0 / p;
  const Reciprocals reciprocals;
  // The band (batch_tilt_bands): k_zeta - cos(stop_above) below this means a tilt above band_low.
  const bool banded = !Extremes && s.band_low > 0.0;
  const double low_kz = banded ? __builtin_cos(s.band_low) - cos_stop : 0.0;

  Work w;
  std::size_t point[W];   // the point each lane integrates
  bool active[W];
  double t[W], t_old[W];  // s
  std::size_t steps[W];
  double last_largest[W];  // banded: the largest tilt's chord in the lane's previous step
  BatchResult e[W];
  std::size_t next_point = 0;

  // Lane l takes the next point that needs integrating (those decided by their start are
  // written out at once); an idle lane integrates the body at rest, all zeros, harmlessly.
  auto fill = [&](int l) {
    active[l] = false;
    while (next_point < count) {
      const BatchPoint& b = points[next_point++];
      BatchResult& r = e[l];
      r = BatchResult{0.0, 0.0, 0.0, 0.0, 0.0, false};
      r.peak_cos = __builtin_cos(b.tilt0);
      r.touched_low = banded && b.tilt0 > s.band_low;
      r.min_tilt = r.max_tilt = b.tilt0;
      r.exceeded = b.tilt0 > stop_above;
      if (r.exceeded || horizon == 0.0) {
        out[b.index] = r;
        continue;
      }
      point[l] = b.index;
      for (int i = 0; i < 7; ++i) w.x[i][l] = b.x0[i];
      w.e1[l] = b.e1, w.e2[l] = b.e2, w.e3[l] = b.e3, w.ka[l] = b.ka, w.kb[l] = b.kb;
      w.c_over_a[l] = b.c_over_a;
      t[l] = t_old[l] = 0.0;
      steps[l] = 0;
      last_largest[l] = 0.0;
      active[l] = true;
      return;
    }
    for (int i = 0; i < 7; ++i) w.x[i][l] = i == 0 ? 1.0 : 0.0;
    w.e1[l] = w.e2[l] = w.e3[l] = w.ka[l] = w.kb[l] = w.c_over_a[l] = 0.0;
    t[l] = t_old[l] = 0.0;
  };
  auto finish = [&](int l) {
    e[l].steps = steps[l];
    out[point[l]] = e[l];
    fill(l);
  };
  auto note = [&](int l, double time, double tilt) {
    BatchResult& r = e[l];
    if (tilt < r.min_tilt) r.min_tilt = tilt, r.t_min = time;
    if (tilt > r.max_tilt) r.max_tilt = tilt, r.t_max = time;
  };
  // The state of lane l at `time` in [t_old, t] (TaylorIntegrator::interpolate) and its tilt.
  auto tilt_at = [&](int l, double time) {
    if (time == t[l]) return tilt_of(w.x[0][l], w.x[1][l], w.x[2][l], w.x[3][l]);
    const double tau = time - t_old[l];
    double q[4];
    for (int i = 0; i < 4; ++i) {
      double v = w.c[p][i][l];
      for (int n = p - 1; n >= 0; --n) v = v * tau + w.c[n][i][l];
      q[i] = v;
    }
    return tilt_of(q[0], q[1], q[2], q[3]);
  };
  auto root = [&](const V* series, int l, double a, double b, double fa, double fb, double h) {
    double c[kM + 1];
    for (int n = 0; n <= p; ++n) c[n] = series[n][l];
    return series_root(c, p, a, b, fa, fb, h);
  };

  for (int l = 0; l < W; ++l) fill(l);
  for (;;) {
    bool any = false;
    for (int l = 0; l < W; ++l) any = any || active[l];
    if (!any) return;

    // ---- TaylorIntegrator::step() ----
    for (int l = 0; l < W; ++l)
      if (active[l] && steps[l] >= s.max_steps) fail_max_steps(s.max_steps, t[l]);
    {  // |q| = 1 before each step
      const V sum = w.x[0] * w.x[0] + w.x[1] * w.x[1] + w.x[2] * w.x[2] + w.x[3] * w.x[3];
      V norm;
      for (int l = 0; l < W; ++l) norm[l] = __builtin_sqrt(sum[l]);
      for (int i = 0; i < 4; ++i) w.x[i] /= norm;
    }
    for (int i = 0; i < 7; ++i) w.c[0][i] = w.x[i];
    coefficients<Symmetric>(w, p, reciprocals);
    V norm_pm1 = {}, norm_p = {};
    for (int i = 0; i < 7; ++i) {
      const V weight = 1.0 / (s.atol + s.rtol * vabs(w.x[i]));
      norm_pm1 = vmax(norm_pm1, vabs(w.c[p - 1][i]) * weight);
      norm_p = vmax(norm_p, vabs(w.c[p][i]) * weight);
    }
    V tau = {};
    double t_new[W] = {};
    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      double h = step_size(norm_pm1[l], norm_p[l], p, inv_pm1, inv_p);
      const double left = horizon - t[l];
      if (left > 0.0 && !(h < left)) h = left;
      if (!(t[l] + h > t[l]) || !__builtin_isfinite(h)) fail_underflow(t[l]);
      t_old[l] = t[l];
      tau[l] = h;
      t_new[l] = (h == left) ? horizon : t_old[l] + h;
      ++steps[l];
    }
    {  // the seven variables' Horner chains interleaved (each as horner(): the same bits)
      V v[7];
      for (int i = 0; i < 7; ++i) v[i] = w.c[p][i];
      for (int n = p - 1; n >= 0; --n)
        for (int i = 0; i < 7; ++i) v[i] = v[i] * tau + w.c[n][i];
      for (int i = 0; i < 7; ++i) w.x[i] = v[i];
    }
    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      t[l] = t_new[l];
      for (int i = 0; i < 7; ++i)
        if (!__builtin_isfinite(w.x[i][l])) fail_not_finite(t_old[l]);
    }

    // ---- scan_tilt(): the series of d(k_zeta)/dt and of k_zeta - cos(stop_above) ----
    const V* q0 = &w.c[0][0];
    const V *q1 = q0 + 1, *q2 = q0 + 2, *q3 = q0 + 3;
    if constexpr (Extremes) {
      const V *u1 = q0 + 4, *u2 = q0 + 5;
      w.g1[p] = 2.0 * (cauchy(q1, q3, 7, p) - cauchy(q0, q2, 7, p));
      w.g2[p] = 2.0 * (cauchy(q2, q3, 7, p) + cauchy(q0, q1, 7, p));
      for (int n = 0; n <= p; ++n) {
        V r1 = {}, r2 = {};
        for (int j = 0; j <= n; ++j) r1 += w.g1[j] * u2[(n - j) * 7], r2 += w.g2[j] * u1[(n - j) * 7];
        w.rate[n] = r1 - r2;
      }
    }
    // k_zeta as 1 - 2 (qx^2 + qy^2) (|q|^2's series is 1), each square by its symmetry: taylor.cpp's
    // -2 sum_of_squares(qx, qy, n) (taylor/series.hpp), its operations in its order.
    for (int n = 0; n <= p; ++n) {
      V sx = {}, sy = {};
      for (int j = 0; 2 * j < n; ++j) {
        const V *a = w.c[j], *b = w.c[n - j];
        sx += a[1] * b[1], sy += a[2] * b[2];
      }
      V sum = (sx + sy) * 2.0;
      if (n % 2 == 0) {
        const V* m = w.c[n / 2];
        sum += m[1] * m[1] + m[2] * m[2];
      }
      w.kz[n] = -2.0 * sum;
    }
    w.kz[0] += one_minus_cos_stop;

    V h = {};
    for (int l = 0; l < W; ++l) h[l] = active[l] ? t[l] - t_old[l] : 0.0;
    V at[kPieces + 1], rate_at[kPieces + 1], kz_at[kPieces + 1];
    at[0] = V{};
    for (int k = 1; k <= kPieces; ++k) at[k] = h * static_cast<double>(k) / static_cast<double>(kPieces);
    if constexpr (Extremes) horner_pieces(w.rate, 1, p, at, rate_at);
    horner_pieces(w.kz, 1, p, at, kz_at);

    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      const double t0 = t_old[l], hl = h[l];
      double a = 0.0, ra = Extremes ? rate_at[0][l] : 0.0, ka = kz_at[0][l];
      bool crossed = false;
      if (banded) {  // the band: the piece points up to the crossing (or the step's end)
        double least = ka;
        for (int k = 1; k <= kPieces && kz_at[k - 1][l] >= 0.0; ++k) least = kz_at[k][l] < least ? kz_at[k][l] : least;
        if (least < low_kz) e[l].touched_low = true;
        const double c = (least < 0.0 ? 0.0 : least) + cos_stop;  // past the crossing: stop_above's
        if (c < e[l].peak_cos) e[l].peak_cos = c;
        // The tilt's amplitude: its largest chord at the same points in this step and the one
        // before (kz = 1 - cos(stop_above) - 2 (qx^2 + qy^2), 2 (qx^2 + qy^2) = 2 sin^2(tilt / 2)).
        const double twice_s = one_minus_cos_stop - least;
        const double largest = __builtin_sqrt(twice_s > 0.0 ? 2.0 * twice_s : 0.0);
        const double amplitude = largest > last_largest[l] ? largest : last_largest[l];
        last_largest[l] = largest;
        e[l].inverse_tilt_sum += amplitude > 0.0 ? 1.0 / amplitude : __builtin_inf();
      }
      for (int k = 1; k <= kPieces && !crossed; ++k) {
        const double b = at[k][l], rb = Extremes ? rate_at[k][l] : 0.0, kb = kz_at[k][l];
        double crossing = -1.0;
        if (threshold && ka >= 0.0 && kb < 0.0) crossing = root(w.kz, l, a, b, ka, kb, hl);
        if (Extremes && ((ra < 0.0 && rb > 0.0) || (ra > 0.0 && rb < 0.0))) {
          const double extremum = root(w.rate, l, a, b, ra, rb, hl);
          if (crossing < 0.0 || extremum < crossing) note(l, t0 + extremum, tilt_at(l, t0 + extremum));
        }
        if (crossing >= 0.0) {
          if constexpr (Extremes) note(l, t0 + crossing, tilt_at(l, t0 + crossing));
          e[l].exceeded = true;
          e[l].t_end = t0 + crossing;
          crossed = true;
        }
        a = b, ra = rb, ka = kb;
      }
      if (crossed) {
        finish(l);
        continue;
      }
      if constexpr (Extremes) note(l, t[l], tilt_at(l, t[l]));
      if (!(t[l] < horizon)) {
        e[l].t_end = horizon;
        finish(l);
      }
    }
  }
}

}  // namespace
}  // namespace heavytop::detail::HEAVYTOP_BATCH_NS

void heavytop::detail::HEAVYTOP_BATCH_ENTRY(bool symmetric, const BatchPoint* points, std::size_t count,
                                            const BatchSettings& s, BatchResult* out) {
  using namespace HEAVYTOP_BATCH_NS;
  if (s.extremes) symmetric ? scan<true, true>(points, count, s, out) : scan<false, true>(points, count, s, out);
  else symmetric ? scan<true, false>(points, count, s, out) : scan<false, false>(points, count, s, out);
}

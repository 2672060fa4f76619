// The Taylor recurrence alone (one step's coefficients 1..p from a state), per instruction set
// (taylor/recurrence_kernels.hpp: the outer-product form) against the form it replaced (4ae2fee's
// recurrence.hpp: products in SIMD pairs, SSE2, copied below as it was), for the plain
// variables (an asymmetric body) and the spin-factored ones (a symmetric top), at the orders of
// rtol = 1e-6, 1e-9 and 1e-12. Counter ns_per_iteration: time / (p (p + 1) / 2), the inner
// loop's iterations (one j of one order). Checked before timing: every kernel's jet equals the
// old form's bit for bit. Run with --benchmark_repetitions=5 and read the medians.

#include <benchmark/benchmark.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "heavytop/heavytop.hpp"
#include "integrators/taylor/recurrence_kernels.hpp"

namespace {

using namespace heavytop;
using namespace heavytop::detail::taylor;

constexpr int kM = kTaylorMaxOrder;
struct alignas(64) Jet {
  double c[kM + 1][8];
};

// ---- 4ae2fee's recurrence.hpp for Plain and SpinFactored, verbatim but for the names and the
// products' order (j = 1..n-1, 0, n: recurrence_kernels.hpp) ----
using v2d = double __attribute__((vector_size(16)));
inline v2d load2(const double* p) {
  v2d v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline v2d splat(double a) { return v2d{a, a}; }

void old_plain(Jet& x, double* g1, double* g2, int p, const PlainConstants& k) {
  for (int n = 0; n < p; ++n) {
    v2d qw_w{}, qx_w{}, qy_w{}, qz_w{}, wx_w3{}, yz_w3{};
    v2d xz_yz = {}, wy_wx = {}, w23_w31 = {};
    double w12 = 0.0;
    auto term = [&](int j) {
      const double *a = x.c[j], *b = x.c[n - j];
      const v2d w = load2(b + 4), w3 = splat(b[6]);
      qw_w += splat(a[0]) * w, qx_w += splat(a[1]) * w, qy_w += splat(a[2]) * w, qz_w += splat(a[3]) * w;
      wx_w3 += load2(a) * w3, yz_w3 += load2(a + 2) * w3;
      xz_yz += load2(a + 1) * splat(b[3]);
      wy_wx += splat(a[0]) * v2d{b[2], b[1]};
      w23_w31 += load2(a + 5) * v2d{b[6], b[4]};
      w12 += a[4] * b[5];
    };
    for (int j = 1; j < n; ++j) term(j);
    term(0);
    if (n > 0) term(n);
    g1[n] = 2.0 * (xz_yz[0] - wy_wx[0]);
    g2[n] = 2.0 * (xz_yz[1] + wy_wx[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    double* next = x.c[n + 1];
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

void old_factored(Jet& x, double* g1, double* g2, int p, const FactoredConstants& k) {
  const double nutation = k.c_over_a * x.c[0][6];
  for (int n = 0; n < p; ++n) {
    v2d pw_v{}, px_v{}, py_v{}, pz_v{}, xz_yz = {}, wy_wx = {};
    auto term = [&](int j) {
      const double *a = x.c[j], *b = x.c[n - j];
      const v2d v = load2(b + 4);
      pw_v += splat(a[0]) * v, px_v += splat(a[1]) * v, py_v += splat(a[2]) * v, pz_v += splat(a[3]) * v;
      xz_yz += load2(a + 1) * splat(b[3]);
      wy_wx += splat(a[0]) * v2d{b[2], b[1]};
    };
    for (int j = 1; j < n; ++j) term(j);
    term(0);
    if (n > 0) term(n);
    g1[n] = 2.0 * (xz_yz[0] - wy_wx[0]);
    g2[n] = 2.0 * (xz_yz[1] + wy_wx[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    const double* row = x.c[n];
    double* next = x.c[n + 1];
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

// The asymmetric body of bench/peers (A = 1, B = 1.5, C = 2, m g R = 0.981 N m) at its start
// (tilt 0.2 rad, spin 10 rad/s), and the toy top at 200 rad/s.
Jet start(bool symmetric) {
  Jet x{};
  const double q[4] = {0.99500416527802582, 0.099833416646828155, 0.0, 0.0};
  for (int i = 0; i < 4; ++i) x.c[0][i] = q[i];
  x.c[0][4] = 0.3, x.c[0][5] = -0.2, x.c[0][6] = symmetric ? 200.0 : 10.0;
  return x;
}
const PlainConstants kPlain{(1.5 - 2.0) / 1.0, (2.0 - 1.0) / 1.5, (1.0 - 1.5) / 2.0, 0.981, 0.981 / 1.5};
const FactoredConstants kFactored{1.2e-5 / 4.35e-5, 0.060 * 9.81 * 0.025 / 4.35e-5};

// way: 0 the old form, 1 SSE2, 2 AVX2, 3 AVX-512F
void run(bool symmetric, int way, Jet& x, double* g1, double* g2, int p) {
  if (symmetric) {
    if (way == 0) old_factored(x, g1, g2, p, kFactored);
    else factored_kernel(way - 1)(x.c, g1, g2, p, kFactored);
  } else {
    if (way == 0) old_plain(x, g1, g2, p, kPlain);
    else plain_kernel(way - 1)(x.c, g1, g2, p, kPlain);
  }
}

void BM_Recurrence(benchmark::State& state) {
  const bool symmetric = state.range(0) == 1;
  const int way = static_cast<int>(state.range(1)), p = static_cast<int>(state.range(2));
  if (way > 0 && !recurrence_isa_supported(way - 1)) {
    state.SkipWithError("instruction set not supported here");
    return;
  }
  Jet reference = start(symmetric), x = start(symmetric);
  double rg1[kM + 1] = {}, rg2[kM + 1] = {}, g1[kM + 1] = {}, g2[kM + 1] = {};
  run(symmetric, 0, reference, rg1, rg2, p);
  run(symmetric, way, x, g1, g2, p);
  if (std::memcmp(&reference, &x, sizeof x) != 0 || std::memcmp(rg1, g1, sizeof g1) != 0 ||
      std::memcmp(rg2, g2, sizeof g2) != 0) {
    state.SkipWithError("not the old form's bits");
    return;
  }
  for (auto _ : state) {
    run(symmetric, way, x, g1, g2, p);
    benchmark::DoNotOptimize(x.c[p][0]);
    benchmark::ClobberMemory();
  }
  const double iterations = p * (p + 1) / 2.0;
  state.counters["ns_per_iteration"] =
      benchmark::Counter(iterations * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  static const char* names[] = {"old SSE2 pairs", "sse2", "avx2", "avx512"};
  state.SetLabel(std::string(symmetric ? "spin-factored " : "plain ") + names[way]);
}
// Orders: taylor_order() at 1e-6, 1e-9, 1e-12 (plain 12, 17, 22; spin-factored 15, 22, 24).
void Args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"symmetric", "way", "p"});
  for (int way = 0; way < 4; ++way) {
    for (int p : {12, 17, 22}) b->Args({0, way, p});
    for (int p : {15, 22, 24}) b->Args({1, way, p});
  }
}
BENCHMARK(BM_Recurrence)->Apply(Args);

}  // namespace

#pragma once
// Private to the Taylor integrator (src/integrators/taylor/): the recurrence, the hot loop.
// Each set of variables (variables.hpp) forms its coefficients 1..p from row 0 (x[n+1] =
// f[n] / (n + 1), f[n] from the Cauchy products of order n), with gamma's series along the
// way. The batched kernel (src/integrators/batch/batch_kernel.hpp) runs the same recurrence
// of Plain and SpinFactored on several bodies at once and must stay bit-identical to it.

#include <Eigen/Core>

#include "integrators/taylor/recurrence_kernels.hpp"
#include "integrators/taylor/series.hpp"
#include "integrators/taylor/variables.hpp"

namespace heavytop::detail::taylor {

// The gamma products of order n accumulated by the loops below, as pairs:
// (qx qz, qy qz) and (qw qy, qw qx).
inline void gamma_terms(const double* a, const double* b, v2d& xz_yz, v2d& wy_wx) {
  xz_yz += load2(a + 1) * splat(b[3]);
  wy_wx += splat(a[0]) * v2d{b[2], b[1]};
}
inline void store_gamma(Gamma& g, int n, v2d xz_yz, v2d wy_wx) {
  g.g1[n] = 2.0 * (xz_yz[0] - wy_wx[0]);
  g.g2[n] = 2.0 * (xz_yz[1] + wy_wx[1]);
}

// gamma_3 = qw^2 - qx^2 - qy^2 + qz^2 (the sets whose torque or integrals need it), from the
// pair sums (qw qw, qx qx), (qy qy, qz qz).
inline void gamma3_terms(const double* a, const double* b, v2d& ww_xx, v2d& yy_zz) {
  ww_xx += load2(a) * load2(b), yy_zz += load2(a + 2) * load2(b + 2);
}
inline double gamma3(v2d ww_xx, v2d yy_zz) { return (ww_xx[0] - ww_xx[1]) - (yy_zz[0] - yy_zz[1]); }

// The attitude's products of order n and its rate, q' = q (x) (0, w) / 2, for the plain
// state (q, body-axes w in slots 4..6): all 12 pairs q_i w_m.
struct AttitudeTerms {
  v2d qw_w{}, qx_w{}, qy_w{}, qz_w{};  // q_i (w1, w2)
  v2d wx_w3{}, yz_w3{};                // (qw, qx) w3, (qy, qz) w3
  void add(const double* a, const double* b) {
    const v2d w = load2(b + 4), w3 = splat(b[6]);
    qw_w += splat(a[0]) * w, qx_w += splat(a[1]) * w, qy_w += splat(a[2]) * w, qz_w += splat(a[3]) * w;
    wx_w3 += load2(a) * w3, yz_w3 += load2(a + 2) * w3;
  }
  void rate(double half, double* next) const {
    next[0] = -half * (qx_w[0] + qy_w[1] + yz_w3[1]);
    next[1] = half * (qw_w[0] + yz_w3[0] - qz_w[1]);
    next[2] = half * (qw_w[1] + qz_w[0] - wx_w3[1]);
    next[3] = half * (wx_w3[0] + qx_w[1] - qy_w[0]);
  }
};

// The same for the spin-factored state: p' = p (x) (0, v1, v2, 0) / 2, the 8 pairs p_i v_m.
struct FactoredAttitudeTerms {
  v2d pw_v{}, px_v{}, py_v{}, pz_v{};  // p_i (v1, v2)
  void add(const double* a, const double* b) {
    const v2d v = load2(b + 4);
    pw_v += splat(a[0]) * v, px_v += splat(a[1]) * v, py_v += splat(a[2]) * v, pz_v += splat(a[3]) * v;
  }
  void rate(double half, double* next) const {
    next[0] = -half * (px_v[0] + py_v[1]);
    next[1] = half * (pw_v[0] - pz_v[1]);
    next[2] = half * (pw_v[1] + pz_v[0]);
    next[3] = half * (px_v[1] - py_v[0]);
  }
};

// ---- Each set's coefficients --------------------------------------------------------------------

// Plain and SpinFactored: the outer-product kernels at the machine's width
// (recurrence_kernels.hpp; the same products and sums, so the same bits as the batch).
inline void Plain::coefficients(Jet& x, Gamma& g, int p) const {
  best_plain_kernel()(x.c, g.g1.data(), g.g2.data(), p, PlainConstants{e1, e2, e3, ka, kb});
}

inline void General::coefficients(Jet& x, Gamma& g, int p) const {
  for (int n = 0; n < p; ++n) {
    const double* row = x.c[n];
    for (int i = 0; i < 3; ++i)
      L[n][i] = inertia(i, 0) * row[4] + inertia(i, 1) * row[5] + inertia(i, 2) * row[6];
    AttitudeTerms q;
    v2d xz_yz = {}, wy_wx = {}, ww_xx = {}, yy_zz = {};                      // gamma
    v2d l2w3_l3w2 = {}, l3w1_l1w3 = {}, l1w2_l2w1 = {};                      // L x w
    for (int j = 0; j <= n; ++j) {
      const double *a = x.c[j], *b = x.c[n - j], *l = L[j];
      q.add(a, b);
      gamma_terms(a, b, xz_yz, wy_wx);
      gamma3_terms(a, b, ww_xx, yy_zz);
      l2w3_l3w2 += v2d{l[1], l[2]} * v2d{b[6], b[5]};
      l3w1_l1w3 += v2d{l[2], l[0]} * v2d{b[4], b[6]};
      l1w2_l2w1 += v2d{l[0], l[1]} * v2d{b[5], b[4]};
    }
    store_gamma(g, n, xz_yz, wy_wx);
    const double g3 = gamma3(ww_xx, yy_zz);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    double* next = x.c[n + 1];
    q.rate(half, next);
    // I w' = (I w) x w + gamma x (m g c)
    const double g1 = g.g1[n], g2 = g.g2[n];
    const Eigen::Vector3d torque(l2w3_l3w2[0] - l2w3_l3w2[1] + (g2 * weight[2] - g3 * weight[1]),
                                 l3w1_l1w3[0] - l3w1_l1w3[1] + (g3 * weight[0] - g1 * weight[2]),
                                 l1w2_l2w1[0] - l1w2_l2w1[1] + (g1 * weight[1] - g2 * weight[0]));
    const Eigen::Vector3d rate = inverse * torque;
    next[4] = inv * rate[0];
    next[5] = inv * rate[1];
    next[6] = inv * rate[2];
    next[7] = 0.0;
  }
}

inline void SpinFactored::coefficients(Jet& x, Gamma& g, int p) const {
  best_factored_kernel()(x.c, g.g1.data(), g.g2.data(), p, FactoredConstants{c_over_a, ka});
}

inline void DampedTerms::integrals(JetOf<kWidth>& x, const Gamma& g, int n, double gyroscopic, double perp2) {
  const double* row = x.c[n];
  tz[n] = held() ? -gyroscopic : -axial * row[6] - (n == 0 ? friction * mode : 0.0);
  // The products with gamma and tau_z of order n need their coefficient n just formed.
  double w_gamma = 0.0, tz_w3 = 0.0, tz_g3 = 0.0;
  for (int j = 0; j <= n; ++j) {
    const double* a = x.c[j];
    w_gamma += a[4] * g.g1[n - j] + a[5] * g.g2[n - j];
    tz_w3 += tz[n - j] * a[6];
    tz_g3 += tz[j] * g3[n - j];
  }
  const double inv = 1.0 / (n + 1);
  double* next = x.c[n + 1];
  // What the torques take away: -tau.w, -tau.zeta (gravity's torque has none), -tau_z.
  next[7] = inv * (drag * perp2 - tz_w3);
  next[8] = inv * (drag * w_gamma - tz_g3);
  next[9] = -inv * tz[n];
}

inline void DampedPlain::coefficients(JetOf<kWidth>& x, Gamma& g, int p) {
  const bool hold = held();
  for (int n = 0; n < p; ++n) {
    AttitudeTerms q;
    v2d xz_yz = {}, wy_wx = {}, ww_xx = {}, yy_zz = {};  // gamma
    v2d w23_w31 = {}, w11_w22 = {};                  // (w2 w3, w3 w1), (w1 w1, w2 w2)
    double w12 = 0.0;                                // w1 w2
    for (int j = 0; j <= n; ++j) {
      const double *a = x.c[j], *b = x.c[n - j];
      const v2d w = load2(b + 4);
      q.add(a, b);
      gamma_terms(a, b, xz_yz, wy_wx);
      gamma3_terms(a, b, ww_xx, yy_zz);
      w23_w31 += load2(a + 5) * v2d{b[6], b[4]};
      w11_w22 += load2(a + 4) * w;
      w12 += a[4] * b[5];
    }
    store_gamma(g, n, xz_yz, wy_wx);
    g3[n] = gamma3(ww_xx, yy_zz);
    integrals(x, g, n, a_minus_b * w12, w11_w22[0] + w11_w22[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    const double* row = x.c[n];
    double* next = x.c[n + 1];
    q.rate(half, next);
    // Euler: I w' = (I w) x w + m g R (gamma x e3) - d_t w_perp + tau_z e3
    next[4] = inv * (e1 * w23_w31[0] + ka * g.g2[n] - da * row[4]);
    next[5] = inv * (e2 * w23_w31[1] - kb * g.g1[n] - db * row[5]);
    next[6] = hold ? 0.0 : inv * (e3 * w12 + inv_c * tz[n]);
  }
}

inline void DampedSpinFactored::coefficients(JetOf<kWidth>& x, Gamma& g, int p) {
  const bool hold = held();
  for (int n = 0; n < p; ++n) {
    FactoredAttitudeTerms q;
    v2d xz_yz = {}, wy_wx = {}, ww_xx = {}, yy_zz = {};  // gamma
    v2d w3_v = {}, v11_v22 = {};                         // w3 (v1, v2), (v1 v1, v2 v2)
    for (int j = 0; j <= n; ++j) {
      const double *a = x.c[j], *b = x.c[n - j];
      const v2d v = load2(b + 4);
      q.add(a, b);
      gamma_terms(a, b, xz_yz, wy_wx);
      gamma3_terms(a, b, ww_xx, yy_zz);
      w3_v += splat(a[6]) * v;
      v11_v22 += load2(a + 4) * v;
    }
    store_gamma(g, n, xz_yz, wy_wx);
    g3[n] = gamma3(ww_xx, yy_zz);
    integrals(x, g, n, 0.0, v11_v22[0] + v11_v22[1]);
    const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
    const double* row = x.c[n];
    double* next = x.c[n + 1];
    q.rate(half, next);
    next[4] = inv * (-c_over_a * w3_v[1] + ka * g.g2[n] - da * row[4]);
    next[5] = inv * (c_over_a * w3_v[0] - ka * g.g1[n] - da * row[5]);
    next[6] = hold ? 0.0 : inv * inv_c * tz[n];
  }
}

}  // namespace heavytop::detail::taylor

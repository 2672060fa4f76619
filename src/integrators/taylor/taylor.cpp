#include "heavytop/taylor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <Eigen/Geometry>
#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "heavytop/general_body.hpp"
#include "heavytop/rigid_body.hpp"

#include "integrators/integration.hpp"
#include "integrators/sampling.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

namespace {

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

// The n-th coefficient of the product of two series.
inline double cauchy(const Coefficients& a, const Coefficients& b, int n) {
  double s = 0.0;
  for (int j = 0; j <= n; ++j) s += a[j] * b[n - j];
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

// ---- The sets of variables --------------------------------------------------------------------
//
// Both keep the attitude quaternion in slots 0..3 (w, x, y, z) and compute the series of the
// upward vertical's first two components gamma_1, gamma_2 along the way: the torque
// m g R (gamma x e3) = m g R (gamma_2, -gamma_1, 0) needs them, and so does the tilt's rate
// d(k_zeta)/dt = gamma_1 u_2 - gamma_2 u_1 (u = w, or v in the non-spinning frame).
// gamma = R(q)^T e_zeta is quadratic in q for |q| = 1, which the exact flow keeps and every
// step restores (normalise()), so the right-hand side is a quadratic polynomial.
//   gamma_1 = 2 (qx qz - qw qy),  gamma_2 = 2 (qy qz + qw qx).
//
// A damped body has its own two sets (DampedPlain, DampedSpinFactored, below), whose torques
// linear in w are linear terms in the w (or v, w3) rows: - d_t/A w1[n] etc.
struct Gamma {
  Coefficients g1{}, g2{};
};

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

// The conserved quantities and drift scales of a body on principal axes (every set but General).
struct OrdinaryBody {
  static ConservedQuantities conserved(const Body& body, const RigidBodyState& x) {
    return conserved_quantities(body, x);
  }
  static Scales scales(const Body& body, const RigidBodyState& x0) { return scales_of(body, x0); }
};

// The seven variables of the conservative sets: a quaternion in slots 0..3 (q, or SpinFactored's
// p) and an angular velocity in 4..6 (body-axes w, or v1, v2, w3), as to_vector/from_vector
// (rigid_body.hpp) hold them, the quaternion normalised on the way out. For SpinFactored
// psi = 0 at the start (p = q, v = (w1, w2)), and its state read as a body (attitude R_p,
// angular velocity (v1, v2, w3)) has the body's axis, the axis's rate (k' = v2 n1 - v1 n2) and
// E, L_zeta, C w3 (all Rz-invariant for A == B).
struct SevenVariables {
  static constexpr int kSize = 7, kWidth = 8;
  static constexpr bool kDamped = false;
  static constexpr int kU1 = 4, kU2 = 5;  // the velocity components in d(k_zeta)/dt
  static std::array<double, 7> state_of(const RigidBodyState& rb) { return to_vector(rb); }
  static RigidBodyState rigid_body(const std::array<double, 7>& x) { return from_vector(x); }
};

// The plain state of rigid_body.hpp: q (body to fixed), w in body axes. 19 Cauchy products
// per order: q (x) w (all 12 pairs q_i w_m), gamma (4), w x I w (3).
struct Plain : OrdinaryBody, SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::Plain;
  double e1, e2, e3, ka, kb;  // (B - C)/A, (C - A)/B, (A - B)/C (1), m g R / A, m g R / B (1/s^2)

  explicit Plain(const Body& b)
      : e1((b.B - b.C) / b.A), e2((b.C - b.A) / b.B), e3((b.A - b.B) / b.C), ka(b.mgR() / b.A),
        kb(b.mgR() / b.B) {}

  // Coefficients 1..p of every variable from row 0; gamma up to order p - 1.
  void coefficients(Jet& x, Gamma& g, int p) const {
    for (int n = 0; n < p; ++n) {
      AttitudeTerms q;
      v2d xz_yz = {}, wy_wx = {};                      // gamma
      v2d w23_w31 = {};                                // (w2 w3, w3 w1)
      double w12 = 0.0;                                // w1 w2
      for (int j = 0; j <= n; ++j) {
        const double *a = x.c[j], *b = x.c[n - j];
        q.add(a, b);
        gamma_terms(a, b, xz_yz, wy_wx);
        w23_w31 += load2(a + 5) * v2d{b[6], b[4]};
        w12 += a[4] * b[5];
      }
      store_gamma(g, n, xz_yz, wy_wx);
      const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
      double* next = x.c[n + 1];
      q.rate(half, next);
      // Euler: I w' = (I w) x w + m g R (gamma x e3)
      next[4] = inv * (e1 * w23_w31[0] + ka * g.g2[n]);
      next[5] = inv * (e2 * w23_w31[1] - kb * g.g1[n]);
      next[6] = inv * (e3 * w12);
      next[7] = 0.0;
    }
  }
};

// The general body of general_body.hpp (SPEC section 11) in the plain state: I w' = (I w) x w
// + gamma x (m g c), with the full inertia tensor I and the centre of mass c anywhere in body
// axes. 26 Cauchy products per order: q (x) w (12), gamma (all three components: 8), (I w) x w
// (6, the series of L = I w being linear in w's). w' = I^-1 (...) is linear.
struct General : SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::General;
  Eigen::Matrix3d inertia, inverse;  // kg m^2, I about O, and its inverse (body axes)
  Eigen::Vector3d weight;            // N m, m g c
  mutable double L[kM + 1][3] = {};  // the series of I w (kg m^2/s), filled order by order

  explicit General(const Body& b) {
    const GeneralRigidBodySystem system(b);
    inertia = system.inertia, inverse = system.inverse, weight = system.weight;
  }

  void coefficients(Jet& x, Gamma& g, int p) const {
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

  static ConservedQuantities conserved(const Body& body, const RigidBodyState& x) {
    return general_conserved_quantities(body, x);
  }
  static Scales scales(const Body& body, const RigidBodyState& x0) { return general_scales(body, x0); }
};

// The spin-factored state of nonlinear.hpp for A == B: q = p (x) exp(psi e3 / 2) with
// psi' = w3, p's frame N turns with the transverse angular velocity v = Rz(psi)(w1, w2) only.
// For A == B, w3 is constant and psi drops out: v' = (C w3 / A) J v + (m g R / A) J gamma.
// Slot 6 holds w3 (its series is the constant). 12 Cauchy products per order:
// p (x) v (the 8 pairs p_i v_m) and gamma (4).
struct SpinFactored : OrdinaryBody, SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::SpinFactored;
  double c_over_a, ka;  // C / A (1), m g R / A (1/s^2)

  explicit SpinFactored(const Body& b) : c_over_a(b.C / b.A), ka(b.mgR() / b.A) {}

  void coefficients(Jet& x, Gamma& g, int p) const {
    const double nutation = c_over_a * x.c[0][6];  // rad/s, C w3 / A
    for (int n = 0; n < p; ++n) {
      FactoredAttitudeTerms q;
      v2d xz_yz = {}, wy_wx = {};                      // gamma
      for (int j = 0; j <= n; ++j) {
        const double *a = x.c[j], *b = x.c[n - j];
        q.add(a, b);
        gamma_terms(a, b, xz_yz, wy_wx);
      }
      store_gamma(g, n, xz_yz, wy_wx);
      const double half = 0.5 / (n + 1), inv = 1.0 / (n + 1);
      const double* row = x.c[n];
      double* next = x.c[n + 1];
      q.rate(half, next);
      next[4] = inv * (-nutation * row[5] + ka * g.g2[n]);
      next[5] = inv * (nutation * row[4] - ka * g.g1[n]);
      next[6] = 0.0;
      next[7] = 0.0;
    }
  }
};

// ---- A damped body (SPEC section 6) ------------------------------------------------------------
//
// The state of the conservative sets, plus the integrals of what the torques take away, as in
// dopri5's damped state: the work [7] (J), the vertical [8] and the axial [9] angular momentum
// (kg m^2/s), so that E + work, L_zeta + loss and C w3 + loss are first integrals. Torques:
// -d_t w_perp, and the axial tau_z of the friction mode (detail::initial_friction_mode):
// sliding -d_a w3 - tau0 mode, held (stuck, or driven) -(A - B) w1 w2 with w3' = 0 exactly.
// Within a mode the right-hand side stays a quadratic polynomial: the linear torques are
// linear terms of the w (v) rows, at no extra product; the integrals' rates add |w_perp|^2
// (2 products), gamma_3 (4), w_perp.gamma (2), tau_z w3 and tau_z gamma_3 (2).
struct DampedTerms : OrdinaryBody {
  static constexpr int kSize = 10, kWidth = 10;
  static constexpr bool kDamped = true;
  static constexpr int kWork = 7, kVerticalLoss = 8, kAxialLoss = 9;
  using State = std::array<double, kSize>;
  double drag, axial, friction, inv_c;  // d_t (N m s), d_a (N m s), tau0 (N m), 1/C
  bool driven;
  double mode = 1.0;        // the friction mode: sign of w3 while sliding, 0 while held
  Coefficients g3{}, tz{};  // gamma_3 and tau_z (N m), order by order

  explicit DampedTerms(const Body& b)
      : drag(b.damping.transverse), axial(b.damping.axial), friction(b.damping.friction), inv_c(1.0 / b.C),
        driven(b.damping.driven) {}

  bool held() const { return driven || mode == 0.0; }

  // The integrals start at 0 (for A == B: psi = 0, p = q, v = (w1, w2)).
  static State state_of(const RigidBodyState& rb) {
    State x{};
    const RigidBodyVector v = to_vector(rb);
    std::copy(v.begin(), v.end(), x.begin());
    return x;
  }
  static RigidBodyState rigid_body(const State& x) {
    RigidBodyVector v;
    std::copy(x.begin(), x.begin() + 7, v.begin());
    return from_vector(v);
  }
  static constexpr int kU1 = 4, kU2 = 5;

  // Order n's tau_z (given (A - B) (w1 w2)[n]), then the rows n + 1 of the three integrals,
  // once gamma's coefficient n is stored and with (w_perp . w_perp)[n] = `perp2`.
  void integrals(JetOf<kWidth>& x, const Gamma& g, int n, double gyroscopic, double perp2) {
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
};

// A damped body with A != B: Plain's state (q, body-axes w) and the integrals. 29 Cauchy
// products per order.
struct DampedPlain : DampedTerms {
  static constexpr TaylorVariables kVariables = TaylorVariables::Plain;
  double e1, e2, e3, ka, kb;  // as Plain's
  double da, db;              // d_t / A, d_t / B (1/s)
  double a_minus_b;           // A - B (kg m^2)

  explicit DampedPlain(const Body& b)
      : DampedTerms(b), e1((b.B - b.C) / b.A), e2((b.C - b.A) / b.B), e3((b.A - b.B) / b.C), ka(b.mgR() / b.A),
        kb(b.mgR() / b.B), da(b.damping.transverse / b.A), db(b.damping.transverse / b.B), a_minus_b(b.A - b.B) {}

  void coefficients(JetOf<kWidth>& x, Gamma& g, int p) {
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
};

// A damped body with A == B: SpinFactored's state (p, v in N, w3) and the integrals. The
// transverse inertia and drag are isotropic, so psi still drops out:
// v' = (C w3 / A) J v + (m g R / A) J gamma - (d_t / A) v, C w3' = tau_z (no gyroscopic
// torque: a stopped spin stays stopped). w3 now has a series, so C w3 / A J v is a product
// (2): 24 Cauchy products per order. For A == B the outputs are Rz-invariant (SpinFactored).
struct DampedSpinFactored : DampedTerms {
  static constexpr TaylorVariables kVariables = TaylorVariables::SpinFactored;
  double c_over_a, ka, da;  // C / A (1), m g R / A (1/s^2), d_t / A (1/s)

  explicit DampedSpinFactored(const Body& b)
      : DampedTerms(b), c_over_a(b.C / b.A), ka(b.mgR() / b.A), da(b.damping.transverse / b.A) {}

  void coefficients(JetOf<kWidth>& x, Gamma& g, int p) {
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
};

// ---- The integrator -----------------------------------------------------------------------------------

template <class System>
class TaylorIntegrator {
 public:
  static constexpr int N = System::kSize, W = System::kWidth;
  using State = std::array<double, N>;
  using Jet = JetOf<W>;

  TaylorIntegrator(const Body& body, const System& system, const State& x0, double horizon,
                   const NonlinearOptions& options, TaylorSummary* summary)
      : body_(body),
        system_(system),
        order_(taylor_order(options, System::kVariables)),
        rtol_(options.rtol),
        atol_(options.atol),
        horizon_(horizon),
        max_steps_(options.max_steps),
        summary_(summary),
        x_(x0) {
    if constexpr (System::kDamped)
      system_.mode = initial_friction_mode(body.damping, x0[6], (body.A - body.B) * x0[4] * x0[5]);
    if (summary_) {
      *summary_ = TaylorSummary{};
      summary_->order = order_;
      summary_->variables = System::kVariables;
      summary_->damped = System::kDamped;
      summary_->work.symmetric = System::kVariables == TaylorVariables::SpinFactored;
      scales_ = System::scales(body, System::rigid_body(x0));
      initial_ = conserved(x0);
    }
  }

  int order() const { return order_; }
  double time() const { return t_; }
  double previous_time() const { return t_old_; }
  const Jet& series() const { return jet_; }
  const Gamma& gamma() const { return gamma_; }

  // One step from time(): the series at time(), its step, the state at its end. Afterwards
  // interpolate() covers [previous_time(), time()] from the same series.
  void step() {
    if (steps_ >= max_steps_) fail("taylor", StepOutcome::MaxSteps, t_, max_steps_);
    normalise();
    for (int i = 0; i < N; ++i) jet_.c[0][i] = x_[i];
    for (int i = N; i < W; ++i) jet_.c[0][i] = 0.0;
    system_.coefficients(jet_, gamma_, order_);

    // The step at which the last two terms reach the tolerance, componentwise:
    // |x_i[n]| h^n = eps_i = atol + rtol |x_i| for n = p - 1 and p (the estimate Jorba & Zou
    // start from; their rho / e^2 exp(-0.7/(p-1)) is its asymptotic simplification, and
    // measured at equal error it costs 10-30% more steps here: docs/integrators.md).
    double norm_pm1 = 0.0, norm_p = 0.0;
    for (int i = 0; i < N; ++i) {
      const double weight = 1.0 / (atol_ + rtol_ * std::abs(x_[i]));
      norm_pm1 = std::max(norm_pm1, std::abs(jet_.c[order_ - 1][i]) * weight);
      norm_p = std::max(norm_p, std::abs(jet_.c[order_][i]) * weight);
    }
    // +inf when the series ends below order p - 1 (a polynomial motion: the step is exact).
    double h = std::min(std::pow(norm_pm1, -1.0 / (order_ - 1)), std::pow(norm_p, -1.0 / order_));
    const double left = horizon_ - t_;
    if (left > 0.0 && !(h < left)) h = left;  // never beyond the horizon (dense output inside)
    if (!(t_ + h > t_) || !std::isfinite(h)) fail("taylor", StepOutcome::StepUnderflow, t_);

    // Dry friction: the step ends where its mode does (the series holds for that mode only).
    double event = -1.0;
    if constexpr (System::kDamped) {
      event = friction_event(h);
      if (event >= 0.0) h = event;
    }

    t_old_ = t_;
    h_ = h;
    double end[W];
    horner(jet_, order_, h, end);
    std::copy(end, end + N, x_.begin());
    t_ = (h == left) ? horizon_ : t_old_ + h;
    ++steps_;
    if constexpr (System::kDamped) {
      if (event >= 0.0) change_friction_mode();
    }
    if (!std::all_of(x_.begin(), x_.end(), [](double v) { return std::isfinite(v); }))
      fail("taylor", StepOutcome::NotFinite, t_old_);
    if (summary_) monitor();
  }

  // The state at t in [previous_time(), time()], from the series.
  void interpolate(double t, State& out) const {
    if (t == t_) {
      out = x_;
      return;
    }
    double at[W];
    horner(jet_, order_, t - t_old_, at);
    std::copy(at, at + N, out.begin());
  }

  double step_size() const { return h_; }

 private:
  // tau in [0, h] where the step's friction mode ends, or -1 if it lasts the step: while
  // sliding, the first root of w3 mode (the spin stops); while stuck, of tau0 - |(A - B) w1 w2|
  // (the gyroscopic torque outgrows static friction). The step is split into 8 pieces to find
  // the first sign change, which TOMS 748 solves on the series (nonlinear.cpp's events, which
  // look at the step's end only, on the dense output).
  double friction_event(double h) const {
    const Damping& d = body_.damping;
    const double mode = system_.mode, a_minus_b = body_.A - body_.B;
    if (!(d.friction > 0.0) || d.driven || (mode == 0.0 && a_minus_b == 0.0)) return -1.0;
    const int p = order_;
    auto event = [&](double tau) {
      if (mode != 0.0) return horner(jet_, 6, p, tau) * mode;
      return d.friction - std::abs(a_minus_b * horner(jet_, 4, p, tau) * horner(jet_, 5, p, tau));
    };
    constexpr int kPieces = 8;
    double a = 0.0, fa = event(0.0);
    for (int k = 1; k <= kPieces; ++k) {
      const double b = k == kPieces ? h : h * k / kPieces, fb = event(b);
      if (mode != 0.0 ? !(fb > 0.0) : fb < 0.0) return fb < 0.0 ? root(event, a, b, fa, fb, h) : b;
      a = b, fa = fb;
    }
    return -1.0;
  }

  // At the end of a mode (x_ there): a stopped spin is exactly 0 from here on, and the next
  // mode is nonlinear.cpp's (detail::next_friction_mode).
  void change_friction_mode() {
    const double mode = system_.mode;
    if (mode != 0.0) x_[6] = 0.0;
    system_.mode = next_friction_mode(body_.damping, mode, (body_.A - body_.B) * x_[4] * x_[5]);
    if (summary_) ++summary_->friction_events;
  }

  // |q| = 1 before each step: the vertical's formula is quadratic only on the unit sphere.
  void normalise() {
    const double norm = std::sqrt(x_[0] * x_[0] + x_[1] * x_[1] + x_[2] * x_[2] + x_[3] * x_[3]);
    if (summary_)
      summary_->work.max_quaternion_norm_error =
          std::max(summary_->work.max_quaternion_norm_error, std::abs(norm - 1.0));
    for (int i = 0; i < 4; ++i) x_[i] /= norm;
  }

  ConservedQuantities conserved(const State& x) const {
    if constexpr (System::kVariables == TaylorVariables::General) {
      return System::conserved(body_, System::rigid_body(x));
    } else {
      const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
      const double inv = 1.0 / (qw * qw + qx * qx + qy * qy + qz * qz);
      ConservedQuantities q =
          conserved_from(body_, x[4], x[5], x[6], 2.0 * (qx * qz - qw * qy) * inv, 2.0 * (qy * qz + qw * qx) * inv,
                         (qw * qw - qx * qx - qy * qy + qz * qz) * inv);
      if constexpr (System::kDamped) {  // plus what the torques took away
        q.energy += x[System::kWork];
        q.vertical_momentum += x[System::kVerticalLoss];
        q.axial_momentum += x[System::kAxialLoss];
      }
      return q;
    }
  }

  void monitor() {
    NonlinearSummary& w = summary_->work;
    ++w.steps;
    w.rhs_evaluations += static_cast<std::size_t>(order_);
    w.final_time = t_;
    note_drift(w, conserved(x_), initial_, scales_);
  }

  const Body& body_;
  System system_;
  int order_;
  double rtol_, atol_, horizon_;
  std::size_t max_steps_;
  TaylorSummary* summary_;
  std::size_t steps_ = 0;
  Scales scales_;
  ConservedQuantities initial_;
  Jet jet_{};
  Gamma gamma_;
  State x_;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0;
};


template <class System>
void simulate(const Body& body, const RigidBodyState& rb0, const SampleStream& samples,
              const NonlinearOptions& options, TaylorSummary* summary) {
  using State = typename TaylorIntegrator<System>::State;
  const double horizon = samples.horizon();
  TaylorIntegrator<System> integrator(body, System(body), System::state_of(rb0), horizon, options, summary);
  write_samples(integrator, body, rb0, System::conserved(body, rb0), System::kDamped, samples, options.progress,
                [&body](const State& x) {
                  const RigidBodyState rb = System::rigid_body(x);
                  SampleValues v = sample_of(rb, System::conserved(body, rb));
                  if constexpr (System::kDamped) v.taken = {x[System::kWork], x[System::kVerticalLoss], x[System::kAxialLoss]};
                  return v;
                });
}

// ---- Events on the series ---------------------------------------------------------------------------

// Tilt acos(k_zeta) of a state, as atan2(|k_horizontal|, k_zeta) (accurate near 0).
template <class State>
double tilt_of(const State& x) {
  const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
  const double g1 = 2.0 * (qx * qz - qw * qy), g2 = 2.0 * (qy * qz + qw * qx);
  return std::atan2(std::hypot(g1, g2), qw * qw - qx * qx - qy * qy + qz * qz);
}

// A root of the polynomial s on [a, b] where s(a), s(b) have opposite signs, to ~1e-15 of
// the step (TOMS 748; the polynomial is cheap, so it is solved to rounding).
double polynomial_root(const Coefficients& s, int p, double a, double b, double fa, double fb, double h) {
  return root([&](double tau) { return horner(s, p, tau); }, a, b, fa, fb, h);
}

template <class System>
TiltExtremes scan_tilt(const Body& body, const RigidBodyState& rb0, double horizon, double stop_above,
                       const NonlinearOptions& options, TaylorSummary* summary) {
  using Integrator = TaylorIntegrator<System>;
  TiltExtremes e;
  if (summary) *summary = TaylorSummary{};
  const auto x0 = System::state_of(rb0);
  const double tilt0 = tilt_of(x0);
  e.min_tilt = e.max_tilt = tilt0;
  e.exceeded = tilt0 > stop_above;
  if (e.exceeded || horizon == 0.0) return e;

  Integrator integrator(body, System(body), x0, horizon, options, summary);
  const int p = integrator.order();
  const bool threshold = stop_above < 3.141592653589793;  // a tilt above pi cannot be reached
  const double cos_stop = std::cos(stop_above);
  auto note = [&](double t, double tilt) {
    if (tilt < e.min_tilt) e.min_tilt = tilt, e.t_min = t;
    if (tilt > e.max_tilt) e.max_tilt = tilt, e.t_max = t;
  };

  Coefficients rate{}, kz{};
  Gamma g;
  typename Integrator::State y;
  constexpr int kPieces = 8;
  while (integrator.time() < horizon) {
    integrator.step();
    const double t0 = integrator.previous_time(), h = integrator.time() - t0;
    const auto& x = integrator.series();
    // The series of d(k_zeta)/dt = gamma_1 u_2 - gamma_2 u_1 and of k_zeta = qw^2 - qx^2 - qy^2 + qz^2,
    // to order p (gamma to order p first: the recurrence stopped at p - 1).
    g = integrator.gamma();
    std::array<Coefficients, 4> q;
    for (int i = 0; i < 4; ++i) q[i] = series_of(x, i, p);
    const Coefficients u1 = series_of(x, System::kU1, p), u2 = series_of(x, System::kU2, p);
    g.g1[p] = 2.0 * (cauchy(q[1], q[3], p) - cauchy(q[0], q[2], p));
    g.g2[p] = 2.0 * (cauchy(q[2], q[3], p) + cauchy(q[0], q[1], p));
    for (int n = 0; n <= p; ++n) {
      rate[n] = cauchy(g.g1, u2, n) - cauchy(g.g2, u1, n);
      kz[n] = cauchy(q[0], q[0], n) - cauchy(q[1], q[1], n) - cauchy(q[2], q[2], n) + cauchy(q[3], q[3], n);
    }
    kz[0] -= cos_stop;  // k_zeta - cos(stop): negative once the tilt passes stop_above

    double a = 0.0, ra = horner(rate, p, 0.0), ka = horner(kz, p, 0.0);
    for (int k = 1; k <= kPieces; ++k) {
      const double b = h * k / kPieces, rb = horner(rate, p, b), kb = horner(kz, p, b);
      double crossing = -1.0;
      if (threshold && ka >= 0.0 && kb < 0.0) crossing = polynomial_root(kz, p, a, b, ka, kb, h);
      if ((ra < 0.0 && rb > 0.0) || (ra > 0.0 && rb < 0.0)) {
        const double extremum = polynomial_root(rate, p, a, b, ra, rb, h);
        if (crossing < 0.0 || extremum < crossing) {
          integrator.interpolate(t0 + extremum, y);
          note(t0 + extremum, tilt_of(y));
        }
      }
      if (crossing >= 0.0) {
        integrator.interpolate(t0 + crossing, y);
        note(t0 + crossing, tilt_of(y));
        e.exceeded = true;
        e.t_end = t0 + crossing;
        if constexpr (System::kDamped) e.spin_at_end = y[6];
        return e;
      }
      a = b, ra = rb, ka = kb;
    }
    integrator.interpolate(integrator.time(), y);
    note(integrator.time(), tilt_of(y));
  }
  e.t_end = horizon;
  if constexpr (System::kDamped) e.spin_at_end = y[6];
  return e;
}

// The set of variables for a body; a damped general body is refused (SPEC section 11 is
// integrated undamped), naming its damping key.
enum class Set { SpinFactored, Plain, General, DampedSpinFactored, DampedPlain };
Set taylor_set(const Body& body) {
  const bool damped = !body.damping.conservative();
  switch (taylor_variables(body)) {
    case TaylorVariables::General: refuse_damped_general(body); return Set::General;
    case TaylorVariables::SpinFactored: return damped ? Set::DampedSpinFactored : Set::SpinFactored;
    case TaylorVariables::Plain: return damped ? Set::DampedPlain : Set::Plain;
  }
  return Set::Plain;
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------------

TaylorVariables taylor_variables(const Body& body) {
  if (is_general(body)) return TaylorVariables::General;
  return body.A == body.B ? TaylorVariables::SpinFactored : TaylorVariables::Plain;
}

int taylor_order(const NonlinearOptions& options, TaylorVariables variables) {
  // Jorba & Zou's ceil(-ln(eps)/2 + 1) is optimal for a series with a fixed radius of
  // convergence; here the coefficients fall faster (the steps grew about as the order did), and
  // at equal error on five bodies (docs/integrators.md, "Order and step") higher orders were
  // 1.4-1.6x faster for the spin-factored variables (twice Jorba-Zou's -ln(eps)/2) and up to
  // 1.45x for the plain ones (1.5 times it; neutral to 0.8x at some levels).
  const double eps = std::min(options.rtol, options.atol);
  const double factor = variables == TaylorVariables::SpinFactored ? 1.0 : 0.75;
  const int p = static_cast<int>(std::ceil(-factor * std::log(eps) + 1.0));
  return std::clamp(p, 2, kTaylorMaxOrder);
}

void detail::stream_taylor(const Body& body, const InitialState& initial, const SampleStream& samples,
                           const NonlinearOptions& options, TaylorSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  switch (taylor_set(body)) {
    case Set::SpinFactored: return simulate<SpinFactored>(body, rb0, samples, options, summary);
    case Set::Plain: return simulate<Plain>(body, rb0, samples, options, summary);
    case Set::General: return simulate<General>(body, rb0, samples, options, summary);
    case Set::DampedSpinFactored: return simulate<DampedSpinFactored>(body, rb0, samples, options, summary);
    case Set::DampedPlain: return simulate<DampedPlain>(body, rb0, samples, options, summary);
  }
}

Trajectory simulate_taylor(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const NonlinearOptions& options, TaylorSummary* summary) {
  return gathered(times, [&](const SampleStream& samples) {
    detail::stream_taylor(body, initial, samples, options, summary);
  });
}

TiltExtremes taylor_tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                                  double stop_above, const NonlinearOptions& options, TaylorSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  switch (taylor_set(body)) {
    case Set::SpinFactored: return scan_tilt<SpinFactored>(body, rb0, horizon, stop_above, options, summary);
    case Set::Plain: return scan_tilt<Plain>(body, rb0, horizon, stop_above, options, summary);
    case Set::General: return scan_tilt<General>(body, rb0, horizon, stop_above, options, summary);
    case Set::DampedSpinFactored: return scan_tilt<DampedSpinFactored>(body, rb0, horizon, stop_above, options, summary);
    case Set::DampedPlain: return scan_tilt<DampedPlain>(body, rb0, horizon, stop_above, options, summary);
  }
  return {};
}

}  // namespace heavytop

#include "heavytop/lagrange_exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>

#include <stdexcept>

#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>

#include "integrators/integration.hpp"
#include "math/elliptic.hpp"
#include "models/lagrange_evaluator.hpp"

namespace heavytop {

namespace {

// Double precision throughout: Boost.Math would otherwise evaluate in long double (x87),
// about ten times slower, for no accuracy the closed form needs.
using MathPolicy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 6.283185307179586;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Carlson's integrals are infinite exactly where the motion starts on the separatrix of an
// unstable equilibrium (modulus k = 1 with the start at its end: the phase tau0 is infinite).
// Boost then reports a domain error; we say what it means.
[[noreturn]] void separatrix() {
  throw std::runtime_error(
      "lagrange-exact: the motion starts on (or within rounding of) the separatrix of an unstable "
      "equilibrium, where the closed form's phase is infinite; the nonlinear model integrates it");
}
double rf(double x, double y, double z) {
  try {
    return boost::math::ellint_rf(x, y, z, MathPolicy());
  } catch (const std::domain_error&) {
    separatrix();
  }
}
double rj(double x, double y, double z, double p) {
  try {
    return boost::math::ellint_rj(x, y, z, p, MathPolicy());
  } catch (const std::domain_error&) {
    separatrix();
  }
}

using Detail = detail::LagrangeEvaluator;
using Pole = Detail::Pole;
using Jacobi = detail::JacobiValues;
using Complex = std::complex<double>;

// ---- Elliptic integrals of the third kind -----------------------------------------------------

// J(r) = int_0^r dtau / (1 - n sn^2(tau)) for |r| <= K, from sn, cn, dn of r.
// Direct (0 <= n < 1): Pi = F + (n/3) sn^3 R_J(cn^2, dn^2, 1, 1 - n sn^2) (DLMF 19.25.14) with
// F = r and 1 - n sn^2 = cn^2 + (1 - n) sn^2: no cancellation even as n -> 1.
// n < 0: A&S 17.7.15 maps it to N = (k^2 - n)/(1 - n) in (k^2, 1), where the three terms
// share the sign of r (no cancellation for large |n|, the near-vertical passages).
double third_kind(const Pole& p, double r, const Jacobi& j) {
  const double s2 = j.sn * j.sn, c2 = j.cn * j.cn, dn2 = j.dn * j.dn;
  if (p.mode == 1) {
    if (j.sn == 0.0) return r;
    return r + p.n * j.sn * s2 * rj(c2, dn2, 1.0, c2 + p.one_minus_n * s2) / 3.0;
  }
  double pi_n = 0.0;
  if (p.c1 != 0.0)
    pi_n = j.sn == 0.0 ? r : r + p.N * j.sn * s2 * rj(c2, dn2, 1.0, c2 + p.one_minus_N * s2) / 3.0;
  return p.c1 * pi_n + p.c2 * r + p.c3 * std::atan(p.p2 * j.sn * j.cn / j.dn);
}

// Sum_{j=1..n} b_j sin(j x) by Clenshaw's recurrence, from cos x and sin x.
double sine_series(const double* b, int n, double cos_x, double sin_x) {
  double b1 = 0.0, b2 = 0.0;
  const double two_c = 2.0 * cos_x;
  for (int j = n - 1; j >= 0; --j) {
    const double b0 = std::fma(two_c, b1, b[j] - b2);
    b2 = b1;
    b1 = b0;
  }
  return b1 * sin_x;
}

// 2 Pi(n, k), the increase of J over a period 2K.
double third_kind_complete2(const Pole& p, const Detail& d) {
  if (p.mode == 1) return 2.0 * (d.jacobi.K + p.n * rj(0.0, d.jacobi.kc2, 1.0, p.one_minus_n) / 3.0);
  const double pi_n = p.c1 != 0.0 ? d.jacobi.K + p.N * rj(0.0, d.jacobi.kc2, 1.0, p.one_minus_N) / 3.0 : 0.0;
  return 2.0 * (p.c1 * pi_n + p.c2 * d.jacobi.K);
}

// The pole of phi' at u = +-1: phi' = P/(1 - u) + Q/(1 + u). `one_a`, `one_b` are 1 -+ u at
// the two roots, `signed_d` the change of 1 -+ u from root a to root b (-d or +d).
void prepare_pole(Pole& p, double residue, double one_a, double one_b, double signed_d,
                  const Detail& d) {
  p = Pole{};
  p.residue = residue;
  if (one_a == 0.0) {  // the root a is the vertical itself: sqrt(1 -+ u) ~ sn
    p.signed_form = 1;
    return;
  }
  if (one_b == 0.0) {  // the root b is the vertical: sqrt(1 -+ u) ~ cn
    p.signed_form = 2;
    return;
  }
  if (residue == 0.0) return;
  // 1 -+ u = one_a (1 - n sn^2) with n = -signed_d / one_a, 1 - n = one_b / one_a.
  p.coefficient = residue / (one_a * d.lambda);
  p.n = -signed_d / one_a;
  p.one_minus_n = one_b / one_a;
  if (p.n == 0.0) return;
  if (p.n > 0.0) {
    p.mode = 1;
  } else {
    p.mode = 2;
    const double m = -p.n, k2 = d.jacobi.k * d.jacobi.k;
    p.N = (k2 + m) / (1.0 + m);
    p.one_minus_N = d.jacobi.kc2 / (1.0 + m);
    p.c1 = m * d.jacobi.kc2 / ((1.0 + m) * (m + k2));
    p.c2 = k2 / (k2 + m);
    p.c3 = std::sqrt(m / ((k2 + m) * (1.0 + m)));
    p.p2 = std::sqrt(m * p.N);
  }
  if (d.jacobi.periodic) p.complete2 = third_kind_complete2(p, d);
}

// ---- Roots of the cubic -----------------------------------------------------------------------

// p(x) = p[0] + p[1] x + p[2] x^2 + p[3] x^3.
struct Poly {
  double c[4] = {};
  double operator()(double x) const { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }
  double slope(double x) const { return (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1]; }
};

// The root of p in (lo, hi), p > 0 just above lo and < 0 just below hi when `positive_at_lo`
// (the reverse otherwise). Newton steps inside the bracket, bisection when Newton leaves it.
// The end values are never evaluated: their signs are known exactly, rounding may not be.
double bracketed_root(const Poly& p, double lo, double hi, bool positive_at_lo) {
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 400; ++it) {
    const double fx = p(x);
    if (fx == 0.0) return x;
    if ((fx > 0.0) == positive_at_lo) lo = x; else hi = x;
    const double dfx = p.slope(x);
    double next = dfx != 0.0 ? x - fx / dfx : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 0.5 * kEps * std::abs(x) || hi - lo <= 2.0 * kEps * std::max(std::abs(lo), std::abs(hi)))
      return next;
    x = next;
  }
  return x;
}

// The first root x >= 0 of g where the motion turns (g >= 0 on [0, x]), given g(0) >= 0 and
// g(e) <= 0 at the end e >= 0 (u = +-1). `end_is_root`: g(e) == 0 exactly (L_zeta = +-L_3);
// then e is the turning point if g decreases there (`slope_end` < 0), otherwise the third root.
double turning_root(const Poly& g, double e, bool end_is_root, double slope_end) {
  if (e <= 0.0) return 0.0;
  Poly q = g;
  if (g.c[0] == 0.0) {  // the state is at a root: x = 0, or the motion leaves it forwards
    if (g.c[1] <= 0.0) return 0.0;
    q.c[0] = g.c[1], q.c[1] = g.c[2], q.c[2] = g.c[3], q.c[3] = 0.0;
  }
  if (!end_is_root) return bracketed_root(q, 0.0, e, true);
  if (slope_end <= 0.0) return e;
  // e is the third root: divide it out; the quotient is < 0 at 0 and > 0 at e.
  Poly r;
  r.c[2] = q.c[3];
  r.c[1] = q.c[2] + e * r.c[2];
  r.c[0] = q.c[1] + e * r.c[1];
  return bracketed_root(r, 0.0, e, false);
}

// The pole integrands 1/(1 - n sn^2) sampled over a period and turned into sine series of
// their integrals: J_per(r) = sum_j B_j sin(j pi r / K). Kept only if the series reaches
// rounding level within kMaxSeries terms and matches the elliptic integrals off the grid.
void prepare_series(Detail& d) {
  d.series_terms = 0;
  if (!d.jacobi.periodic || d.jacobi.theta_terms == 0 || (!d.pole[0].mode && !d.pole[1].mode)) return;
  constexpr int kM = 4 * Detail::kMaxSeries;  // samples per period: aliasing from j >= 3 kMax
  constexpr int kJ = Detail::kMaxSeries;
  auto integrand = [&](const Pole& p, const Jacobi& j) {
    if (!p.mode) return 0.0;
    const double s2 = j.sn * j.sn;
    return 1.0 / (p.mode == 1 ? j.cn * j.cn + p.one_minus_n * s2 : 1.0 - p.n * s2);
  };
  static const auto cos_table = [] {
    std::array<double, kM> c{};
    for (int i = 0; i < kM; ++i) c[i] = std::cos(kTwoPi * i / kM);
    return c;
  }();
  std::array<double, kM> f_phi{}, f_psi{};
  for (int i = 0; i < kM; ++i) {
    const Jacobi j = d.jacobi(d.jacobi.K * (-1.0 + 2.0 * i / kM));
    const double g0 = d.pole[0].coefficient * integrand(d.pole[0], j);
    const double g1 = d.pole[1].coefficient * integrand(d.pole[1], j);
    f_phi[i] = g0 + g1;
    f_psi[i] = g1 - g0;
  }
  // cos(j pi r_i / K) = (-1)^j cos(2 pi j i / M) on the grid r_i = K (-1 + 2 i / M).
  double scale = 0.0;
  for (int j = 1; j <= kJ; ++j) {
    double a_phi = 0.0, a_psi = 0.0;
    for (int i = 0; i < kM; ++i) {
      const double c = cos_table[(static_cast<long>(j) * i) % kM];
      a_phi += f_phi[i] * c;
      a_psi += f_psi[i] * c;
    }
    const double sign = (j % 2 == 0) ? 1.0 : -1.0;
    const double to_sine = sign * (2.0 / kM) * d.jacobi.K / (j * kPi);
    d.phi_series[j - 1] = a_phi * to_sine;
    d.psi_series[j - 1] = a_psi * to_sine;
    scale = std::max({scale, std::abs(d.phi_series[j - 1]), std::abs(d.psi_series[j - 1])});
  }
  // Terms up to the last one above 1e-17 rad (and above rounding of the largest).
  const double floor = std::max(1e-17, 1e-16 * scale);
  int terms = kJ;
  while (terms > 0 && std::abs(d.phi_series[terms - 1]) <= floor &&
         std::abs(d.psi_series[terms - 1]) <= floor)
    --terms;
  if (terms >= kJ - 4) return;  // not converged: the elliptic integrals stay
  d.phi_slope = (d.pole[0].coefficient * d.pole[0].complete2 +
                 d.pole[1].coefficient * d.pole[1].complete2) / (2.0 * d.jacobi.K);
  d.psi_slope = (d.pole[1].coefficient * d.pole[1].complete2 -
                 d.pole[0].coefficient * d.pole[0].complete2) / (2.0 * d.jacobi.K);
  // Check against the integrals off the grid.
  for (int i = 0; i < 11; ++i) {
    const double r = d.jacobi.K * (-1.0 + (2.0 * i + 0.731) / 11.0);
    const Jacobi j = d.jacobi(r);
    const double a0 = d.pole[0].mode ? d.pole[0].coefficient * third_kind(d.pole[0], r, j) : 0.0;
    const double a1 = d.pole[1].mode ? d.pole[1].coefficient * third_kind(d.pole[1], r, j) : 0.0;
    const double phi = d.phi_slope * r + sine_series(d.phi_series, terms, j.cos2v, j.sin2v);
    const double psi = d.psi_slope * r + sine_series(d.psi_series, terms, j.cos2v, j.sin2v);
    if (!(std::abs(phi - (a0 + a1)) <= 1e-14 && std::abs(psi - (a1 - a0)) <= 1e-14)) return;
  }
  d.series_terms = terms;
}

double tilt_from(double one_minus, double one_plus) {
  return one_minus <= 1.0 ? 2.0 * std::asin(std::sqrt(0.5 * one_minus))
                          : kPi - 2.0 * std::asin(std::sqrt(0.5 * one_plus));
}

// ---- The canonical motion ---------------------------------------------------------------------

// The motion with the reference rotations about the vertical and the body axis left out:
// k = R_zeta(phi) (0, -sigma, u), sigma = sin(tilt) carried with a sign through a vertical.
struct Canonical {
  double u, du;            // k_zeta and its rate (1/s)
  double sigma, dsigma;    // signed sin(tilt) and its rate (1/s)
  double phi_rate_sigma;   // phi' sigma (rad/s)
  double phi, psi;         // rad, the Euler angles phi and psi, reduced to about [-3 pi, 3 pi]
};

template <bool WantPsi = true>
Canonical canonical(const Detail& d, double t) {
  Canonical c;
  if (!(d.lambda > 0.0)) {  // constant tilt
    c.u = d.u0;
    c.du = 0.0;
    c.sigma = d.sin_tilt0;
    c.dsigma = 0.0;
    c.phi_rate_sigma = d.phi_rate * d.sin_tilt0;
    c.phi = std::remainder(d.phi_rate * t, kTwoPi);
    c.psi = std::remainder(d.psi_rate * t, kTwoPi);
    return c;
  }
  // Whole periods out: tau = r + 2 K N with |r| <= K; the cost does not depend on t.
  const double tau = std::fma(d.lambda, t, d.tau0);
  double periods = 0.0, r = tau;
  if (d.jacobi.periodic) {
    periods = std::nearbyint(tau / (2.0 * d.jacobi.K));
    r = std::fma(-2.0 * d.jacobi.K, periods, tau);
  }
  const double parity = std::fmod(periods, 2.0) == 0.0 ? 1.0 : -1.0;  // sn, cn flip per period
  const Jacobi j = d.jacobi(r);
  const double s2 = j.sn * j.sn, c2 = j.cn * j.cn;
  c.u = d.u_a + d.d * s2;
  c.du = 2.0 * d.d * d.lambda * j.sn * j.cn * j.dn;
  // 1 - u and 1 + u as sums of like-signed terms (exact near the vertical).
  const double one_minus = d.d >= 0.0 ? d.one_minus_b + d.d * c2 : d.one_minus_a - d.d * s2;
  const double one_plus = d.d >= 0.0 ? d.one_plus_a + d.d * s2 : d.one_plus_b - d.d * c2;
  // sqrt(1 - u), sqrt(1 + u) and their rates; signed where the axis passes a vertical.
  auto factor = [&](const Pole& p, double one, double& s, double& ds) {
    if (p.signed_form == 1) {
      s = d.sqrt_abs_d * j.sn * parity;
      ds = d.sqrt_abs_d * d.lambda * j.cn * j.dn * parity;
    } else if (p.signed_form == 2) {
      s = d.sqrt_abs_d * j.cn * parity;
      ds = -d.sqrt_abs_d * d.lambda * j.sn * j.dn * parity;
    } else {
      s = std::sqrt(one);
      ds = 0.0;  // set below from du
    }
  };
  double sm, dsm, sp, dsp;
  factor(d.pole[0], one_minus, sm, dsm);
  factor(d.pole[1], one_plus, sp, dsp);
  if (d.pole[0].signed_form == 0) dsm = -c.du / (2.0 * sm);
  if (d.pole[1].signed_form == 0) dsp = c.du / (2.0 * sp);
  c.sigma = sm * sp;
  c.dsigma = dsm * sp + sm * dsp;
  // phi' sigma = P sqrt(1+u)/sqrt(1-u) + Q sqrt(1-u)/sqrt(1+u): finite through a vertical.
  c.phi_rate_sigma = 0.0;
  if (d.pole[0].signed_form == 0) c.phi_rate_sigma += d.pole[0].residue * sp / sm;
  if (d.pole[1].signed_form == 0) c.phi_rate_sigma += d.pole[1].residue * sm / sp;

  // The pole terms of phi (a0 + a1) and psi (a1 - a0) over the reduced tau.
  double phi_poles, psi_poles = 0.0;
  if (d.series_terms > 0) {
    phi_poles = d.phi_slope * r + sine_series(d.phi_series, d.series_terms, j.cos2v, j.sin2v);
    if constexpr (WantPsi)
      psi_poles = d.psi_slope * r + sine_series(d.psi_series, d.series_terms, j.cos2v, j.sin2v);
  } else {
    const double j0 = d.pole[0].mode ? third_kind(d.pole[0], r, j) : 0.0;
    const double j1 = d.pole[1].mode ? third_kind(d.pole[1], r, j) : 0.0;
    const double a0 = d.pole[0].coefficient * j0, a1 = d.pole[1].coefficient * j1;
    phi_poles = a0 + a1;
    psi_poles = a1 - a0;
  }
  c.phi = std::remainder(periods * d.phi_per_period_mod, kTwoPi) + phi_poles;
  c.psi = 0.0;
  if constexpr (WantPsi)
    c.psi = std::remainder(periods * d.psi_per_period_mod, kTwoPi) +
            d.spin_rate_linear * (r / d.lambda) + psi_poles;
  return c;
}

// The axis k, its rate, and e^{i phi} with the reference rotation included.
struct AxisFull {
  Eigen::Vector3d k, k_rate;
  Complex e_phi;
  Canonical c;
};

template <bool WantPsi = true>
AxisFull axis_full(const Detail& d, double t) {
  AxisFull a;
  a.c = canonical<WantPsi>(d, t);
  a.e_phi = Complex(d.phi_ref_cos, d.phi_ref_sin) * Complex(std::cos(a.c.phi), std::sin(a.c.phi));
  // h = k_xi + i k_eta = -i sigma e^{i phi};  h' = -i e^{i phi} (sigma' + i phi' sigma).
  const Complex minus_i_e = Complex(0.0, -1.0) * a.e_phi;
  const Complex h = a.c.sigma * minus_i_e;
  const Complex h_rate = minus_i_e * Complex(a.c.dsigma, a.c.phi_rate_sigma);
  a.k = Eigen::Vector3d(h.real(), h.imag(), a.c.u);
  a.k_rate = Eigen::Vector3d(h_rate.real(), h_rate.imag(), a.c.du);
  return a;
}

Eigen::Matrix3d rot_z(double c, double s) {
  Eigen::Matrix3d m;
  m << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return m;
}

// R = R_z(phi) R_x(tilt) R_z(psi), the tilt given by (sigma, u) = (sin, cos).
Eigen::Matrix3d euler_zxz(const Complex& e_phi, double sigma, double u, double psi) {
  Eigen::Matrix3d rx;
  rx << 1.0, 0.0, 0.0, 0.0, u, -sigma, 0.0, sigma, u;
  return rot_z(e_phi.real(), e_phi.imag()) * rx * rot_z(std::cos(psi), std::sin(psi));
}

void require_finite_state(const RigidBodyState& s) {
  if (!s.attitude.allFinite() || !s.omega.allFinite())
    throw InvalidInput("state", "attitude and angular velocity must be finite");
  if (!((s.attitude.transpose() * s.attitude - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <
            1e-9 &&
        s.attitude.determinant() > 0.0))
    throw InvalidInput("state", "the attitude must be a rotation matrix");
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------

void validate_symmetric(const Body& body) {
  validate(body);
  refuse_general(body, "lagrange-exact");
  if (!is_symmetric(body))
    throw InvalidInput("body.B",
                       "lagrange-exact needs a symmetric body: B must equal A (to 1e-12 relative)");
}

LagrangeTop lagrange_top(const Body& body, const InitialState& initial,
                         const LagrangeExactOptions& options) {
  validate_symmetric(body);
  validate(initial);
  return lagrange_top(body, initial_rigid_body_state(initial), options);
}

LagrangeTop lagrange_top(const Body& body, const RigidBodyState& state,
                         const LagrangeExactOptions& options) {
  validate_symmetric(body);
  require_finite_state(state);

  LagrangeTop top;
  const auto evaluator = std::make_shared<Detail>();
  Detail& d = *evaluator;
  top.A = 0.5 * (body.A + body.B);
  top.C = body.C;
  top.mgR = body.mgR();
  const double A = top.A, C = top.C;

  // Everything from the state in body axes: gamma = R^T e_zeta, w.
  const Eigen::Vector3d gamma = state.attitude.row(2).transpose();
  const Eigen::Vector3d& w = state.omega;
  double u0 = gamma.z();
  double s02 = gamma.x() * gamma.x() + gamma.y() * gamma.y();  // sin^2(tilt), exact near 0
  // An axis at a vertical to rounding with no transverse rate (theta0 = 3.141592653589793,
  // the double nearest pi, at the inverted rest of a hanging body) is at the vertical: an
  // equilibrium, which the closed form would otherwise start on the separatrix of.
  if (w.x() == 0.0 && w.y() == 0.0 && s02 <= 4.0 * kEps * kEps) {
    s02 = 0.0;
    u0 = std::copysign(1.0, u0);
  }
  const double om = u0 > 0.0 ? s02 / (1.0 + u0) : 1.0 - u0;          // 1 - u0
  const double op = u0 < 0.0 ? s02 / (1.0 - u0) : 1.0 + u0;          // 1 + u0
  top.w3 = w.z();
  const double b = C * top.w3 / A;
  const double beta = 2.0 * top.mgR / A;
  const double t_perp = w.x() * w.x() + w.y() * w.y();          // |k'|^2
  const double p0 = w.x() * gamma.x() + w.y() * gamma.y();      // (k x k')_zeta = a - b u0
  const double du0 = w.y() * gamma.x() - w.x() * gamma.y();     // k'_zeta = u0'
  top.energy = 0.5 * (A * t_perp + C * top.w3 * top.w3) + top.mgR * u0;
  top.vertical_momentum = A * p0 + C * top.w3 * u0;
  top.axial_momentum = C * top.w3;

  // f around u0, x = u - u0: g(x) = beta x^3 + c2 x^2 + c1 x + c0 with coefficients from the
  // state itself (c0 = u0'^2; c1 vanishes at a steady precession without cancellation of E).
  Poly g;
  g.c[0] = du0 * du0;
  g.c[1] = -s02 * beta - 2.0 * u0 * t_perp + 2.0 * p0 * b;
  g.c[2] = 2.0 * u0 * beta - t_perp - b * b;
  g.c[3] = beta;
  const double P = 0.5 * (p0 - b * om);  // (a - b)/2: f(1) = -4 P^2
  const double Q = 0.5 * (p0 + b * op);  // (a + b)/2: f(-1) = -4 Q^2
  const double x_hi = turning_root(g, om, P == 0.0, -2.0 * (t_perp - beta * om));
  Poly reflected = g;  // g(-y)
  reflected.c[1] = -g.c[1];
  reflected.c[3] = -g.c[3];
  const double x_lo = -turning_root(reflected, op, Q == 0.0, -2.0 * (t_perp + beta * op));

  // 1 - u_hi and 1 + u_lo: the difference om - x_hi loses digits near a vertical passage;
  // f(+-1) = -4 P^2, -4 Q^2 = beta prod(+-1 - u_i) gives them to rounding unless the third
  // root is near +-1 too (near a separatrix). Take whichever has the smaller error bound.
  const double one_minus_lo = om - x_lo, one_plus_hi = op + x_hi;
  const double bm = -g.c[2] - beta * (x_lo + x_hi + om);        // beta (u_third - 1) > 0
  const double bp = beta * op - g.c[2] - beta * (x_lo + x_hi);  // beta (u_third + 1) > 0
  const double b_size = std::abs(g.c[2]) + std::abs(beta) * (std::abs(x_lo) + std::abs(x_hi) + 2.0);
  auto closer_end = [&](double e, double x, double x_other, double one_other, double pq,
                        double pq_size, double bk, bool end_is_root) {
    if (end_is_root && std::abs(x) == e) return 0.0;  // the motion reaches the vertical exactly
    const double by_difference = e - std::abs(x);
    if (pq == 0.0 || !(bk > 0.0) || !(one_other > 0.0)) return by_difference;
    const double by_product = 4.0 * pq * pq / (bk * one_other);
    // Error bounds in units of eps: |x| for the difference; for the product the relative
    // errors of (2 P)^2, of bk and of 1 -+ u at the other root.
    const double err_difference = std::abs(x);
    const double err_product =
        by_product * (2.0 * pq_size / std::abs(2.0 * pq) + b_size / bk + std::abs(x_other) / one_other);
    return err_product < err_difference ? by_product : by_difference;
  };
  const double one_minus_hi =
      closer_end(om, x_hi, x_lo, one_minus_lo, P, std::abs(p0) + std::abs(b * om), bm, P == 0.0);
  const double one_plus_lo =
      closer_end(op, x_lo, x_hi, one_plus_hi, Q, std::abs(p0) + std::abs(b * op), bp, Q == 0.0);

  top.u_min = u0 + x_lo;
  top.u_max = u0 + x_hi;
  top.u_third = beta != 0.0 ? u0 + (-g.c[2] - beta * (x_lo + x_hi)) / beta
                            : kInf;  // f is a quadratic
  top.through_vertical = one_minus_hi == 0.0 && x_hi != x_lo;
  top.through_downward = one_plus_lo == 0.0 && x_hi != x_lo;
  d.u0 = u0;
  d.sin_tilt0 = std::sqrt(s02);

  // Root a: where tau = 0. beta >= 0: the lower root (u_far above), beta < 0: the upper.
  const bool a_is_lo = beta >= 0.0;
  const double x_a = a_is_lo ? x_lo : x_hi, x_b = a_is_lo ? x_hi : x_lo;
  d.u_a = u0 + x_a;
  d.d = x_b - x_a;
  d.one_minus_a = a_is_lo ? one_minus_lo : one_minus_hi;
  d.one_minus_b = a_is_lo ? one_minus_hi : one_minus_lo;
  d.one_plus_a = a_is_lo ? one_plus_lo : one_plus_hi;
  d.one_plus_b = a_is_lo ? one_plus_hi : one_plus_lo;
  d.sqrt_abs_d = std::sqrt(std::abs(d.d));
  d.spin_rate_linear = top.w3 - b;

  // 4 lambda^2 = beta (u_third - u_a); k^2 = (u_b - u_a)/(u_third - u_a), k'^2 likewise.
  const double four_lambda2 = -g.c[2] - beta * (2.0 * x_a + x_b);
  // u0 a double root of f (u0' = 0 and f'(u0) = 0): an equilibrium of the tilt, stable or not
  // (the rest at the inverted vertical, an unstable sleeping top): the tilt stays u0 exactly.
  const bool tilt_equilibrium = g.c[0] == 0.0 && g.c[1] == 0.0;
  top.constant_tilt = tilt_equilibrium || d.d == 0.0 || !(four_lambda2 > 0.0) || !std::isfinite(four_lambda2);
  if (top.constant_tilt) {
    // Sleeping top, steady precession or rest: u = u0, phi' and psi' constant.
    top.u_min = top.u_max = u0;
    top.through_vertical = top.through_downward = false;
    d.lambda = 0.0;
    d.d = 0.0;
    d.u_a = u0;
    if (s02 > 0.0) d.phi_rate = p0 / s02;
    else d.phi_rate = u0 > 0.0 ? Q / op : P / om;  // at the vertical only phi + -psi matters
    d.psi_rate = top.w3 - d.phi_rate * u0;
    top.nutation_period = kInf;
  } else {
    d.lambda = 0.5 * std::sqrt(four_lambda2);
    double k2 = beta * d.d / four_lambda2;
    double kc2 = (-g.c[2] - beta * (x_a + 2.0 * x_b)) / four_lambda2;
    k2 = std::clamp(k2, 0.0, 1.0);
    kc2 = std::clamp(kc2, 0.0, 1.0);
    if (k2 < kc2) kc2 = 1.0 - k2; else k2 = 1.0 - kc2;
    d.jacobi = detail::JacobiElliptic(std::sqrt(k2), kc2);

    // tau0: sn^2(tau0) = (u0 - u_a)/(u_b - u_a), with the sign of the motion of u.
    const double sa = std::sqrt(std::abs(x_a) / std::abs(d.d));
    const double ca = std::sqrt(std::abs(x_b) / std::abs(d.d));
    const double f0 = sa == 0.0 ? 0.0 : sa * rf(ca * ca, ca * ca + kc2 * sa * sa, 1.0);
    d.tau0 = du0 * d.d < 0.0 ? -f0 : f0;

    prepare_pole(d.pole[0], P, d.one_minus_a, d.one_minus_b, -d.d, d);
    prepare_pole(d.pole[1], Q, d.one_plus_a, d.one_plus_b, d.d, d);
    if (d.jacobi.periodic) {
      top.nutation_period = 2.0 * d.jacobi.K / d.lambda;
      top.precession_per_period = d.pole[0].coefficient * d.pole[0].complete2 +
                                  d.pole[1].coefficient * d.pole[1].complete2;
      top.spin_per_period = d.spin_rate_linear * top.nutation_period -
                            d.pole[0].coefficient * d.pole[0].complete2 +
                            d.pole[1].coefficient * d.pole[1].complete2;
      // A passage through a vertical turns the signed sin(tilt) over each period: that is
      // a further half turn of phi (and psi) per period for the axis in the fixed frame.
      d.phi_per_period_mod = std::remainder(top.precession_per_period, kTwoPi);
      d.psi_per_period_mod = std::remainder(top.spin_per_period, kTwoPi);
      const int flips = (d.pole[0].signed_form != 0) + (d.pole[1].signed_form != 0);
      if (flips % 2 == 1) {
        top.precession_per_period += kPi;
        top.spin_per_period += kPi;
      }
      if (options.fourier_series) prepare_series(d);
      top.fourier_series = d.series_terms > 0;
      top.series_terms = d.series_terms;
    } else {
      top.nutation_period = kInf;
    }
  }

  // The reference rotation about the vertical: h0 = e^{i phi_ref} H(0), h0' = e^{i phi_ref} H'(0),
  // fitted from both (either may vanish, e.g. at the vertical).
  d.phi_ref_cos = 1.0;
  d.phi_ref_sin = 0.0;
  d.psi_ref = 0.0;
  const AxisFull a0 = axis_full(d, 0.0);
  const Eigen::Vector3d k0 = state.attitude.col(2);
  const Eigen::Vector3d k0_rate = state.attitude * Eigen::Vector3d(w.y(), -w.x(), 0.0);
  const Complex h0(k0.x(), k0.y()), h0_rate(k0_rate.x(), k0_rate.y());
  const Complex H0(a0.k.x(), a0.k.y()), H0_rate(a0.k_rate.x(), a0.k_rate.y());
  const double scale2 = d.lambda * d.lambda + t_perp;
  const Complex fit = std::conj(H0) * h0 + (scale2 > 0.0 ? 1.0 / scale2 : 1.0) * std::conj(H0_rate) * h0_rate;
  if (std::abs(fit) > 0.0) {
    d.phi_ref_cos = fit.real() / std::abs(fit);
    d.phi_ref_sin = fit.imag() / std::abs(fit);
  }
  // The reference spin angle: R0 = R_z(phi_ref + Phi0) R_x R_z(Psi0 + psi_ref).
  const Complex e_phi0 = Complex(d.phi_ref_cos, d.phi_ref_sin) * Complex(std::cos(a0.c.phi), std::sin(a0.c.phi));
  const Eigen::Matrix3d m0 = euler_zxz(e_phi0, a0.c.sigma, a0.c.u, a0.c.psi);
  const Eigen::Matrix3d x = m0.transpose() * state.attitude;
  d.psi_ref = std::atan2(x(1, 0) - x(0, 1), x(0, 0) + x(1, 1));
  top.evaluator = evaluator;
  return top;
}

NutationBounds nutation_bounds(const LagrangeTop& top) {
  const Detail& d = detail::evaluator_of(top);
  NutationBounds n;
  n.u_min = top.u_min;
  n.u_max = top.u_max;
  if (top.constant_tilt) {
    n.min_tilt = n.max_tilt = std::atan2(d.sin_tilt0, d.u0);
    return n;
  }
  const bool a_is_lo = d.d > 0.0;
  const double om_lo = a_is_lo ? d.one_minus_a : d.one_minus_b;
  const double op_lo = a_is_lo ? d.one_plus_a : d.one_plus_b;
  const double om_hi = a_is_lo ? d.one_minus_b : d.one_minus_a;
  const double op_hi = a_is_lo ? d.one_plus_b : d.one_plus_a;
  n.min_tilt = tilt_from(om_hi, op_hi);
  n.max_tilt = tilt_from(om_lo, op_lo);
  return n;
}

double nutation_period(const LagrangeTop& top) { return top.nutation_period; }

AxisMotion lagrange_axis(const LagrangeTop& top, double t) {
  const AxisFull a = axis_full<false>(detail::evaluator_of(top), t);
  return {a.k, a.k_rate};
}

AxisAngles lagrange_axis_angles(const LagrangeTop& top, double t) {
  const AxisFull a = axis_full<false>(detail::evaluator_of(top), t);
  return axis_angles(a.k, a.k_rate);
}

RigidBodyState lagrange_rigid_body_state(const LagrangeTop& top, double t) {
  const Detail& d = detail::evaluator_of(top);
  const AxisFull a = axis_full(d, t);
  RigidBodyState s;
  s.attitude = euler_zxz(a.e_phi, a.c.sigma, a.c.u, a.c.psi + d.psi_ref);
  // w = k x k' + w3 k in the fixed frame (the transverse part is k x k' for any body).
  const Eigen::Vector3d w_fixed = a.k.cross(a.k_rate) + top.w3 * a.k;
  s.omega = s.attitude.transpose() * w_fixed;
  return s;
}

Trajectory simulate_lagrange_exact(const Body& body, const InitialState& initial,
                                   const std::vector<double>& times) {
  const LagrangeTop top = lagrange_top(body, initial);
  for (double t : times)
    if (!std::isfinite(t)) throw InvalidInput("times", "must be finite");
  Trajectory out;
  out.reserve(times.size());
  for (double t : times) {
    detail::push_angles(out, t, lagrange_axis_angles(top, t));
  }
  return out;
}

}  // namespace heavytop

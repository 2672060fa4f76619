#include "heavytop/stability.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "math/quadratic.hpp"

namespace heavytop {
namespace {

// The scale of every zero test: a quantity counts as zero when it is below this fraction of
// the sizes of the terms it was computed from (so the tests hold at every scale of the body
// and the spin). A computed boundary (a root of a condition, Newton-polished) lands within a
// few eps of it, and ~4500 eps leaves room for the products in between; two roots mu of the
// characteristic polynomial then count as one double root when they agree to about
// sqrt(1e-12) = 1e-6 relative, not 1e-5 as a fixed 1e-10 on the discriminant would allow.
constexpr double kCoincidence = 1e-12;
// A matrix polynomial that vanishes in exact arithmetic comes out ~1e-15 of the balanced
// system matrix's scale, and ~1e-6 for roots that are double only to kCoincidence; one that
// does not vanish (a Jordan block) is of order one.
constexpr double kSemisimple = 1e-4;
// The damped Routh-Hurwitz conditions' zero test: 256 eps of the size of their terms, the
// rounding of the products they are made of. kCoincidence (4500 eps) called the damped
// symmetric top of A = B = 1, C = 2, m g R = 1 at 100 rad/s with d_t = 0.01 "on the
// boundary": its h3 = -4 d^4 is 5e-13 of its terms (d^2 / (2 w0^4)), its eigenvalues' real
// part +2.5e-7 (Kelvin-Tait-Chetaev: unstable).
constexpr double kHurwitzZero = 256.0 * std::numeric_limits<double>::epsilon();

/// c0 + c1 s + c2 s^2 in s = w0^2, with m0, m1, m2 the sizes of the terms each coefficient was
/// computed from (>= |c_i|; larger where the coefficient is a cancellation), for zero tests.
struct SpinPolynomial {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  double operator()(double s) const { return c0 + s * (c1 + s * c2); }
  double magnitude(double s) const { return m0 + s * (m1 + s * m2); }
};

SpinPolynomial linear(double c0, double c1) { return {c0, c1, 0.0, std::abs(c0), std::abs(c1), 0.0}; }

SpinPolynomial product(const SpinPolynomial& p, const SpinPolynomial& q) {
  // Used only for products of two linear factors.
  return {p.c0 * q.c0, p.c0 * q.c1 + p.c1 * q.c0, p.c1 * q.c1,
          p.m0 * q.m0, p.m0 * q.m1 + p.m1 * q.m0, p.m1 * q.m1};
}

SpinPolynomial operator+(const SpinPolynomial& p, const SpinPolynomial& q) {
  return {p.c0 + q.c0, p.c1 + q.c1, p.c2 + q.c2, p.m0 + q.m0, p.m1 + q.m1, p.m2 + q.m2};
}

SpinPolynomial operator*(double a, const SpinPolynomial& p) {
  const double m = std::abs(a);
  return {a * p.c0, a * p.c1, a * p.c2, m * p.m0, m * p.m1, m * p.m2};
}

/// The damped quartic a4 l^4 + a3 l^3 + a2 l^2 + a1 l + a0 (characteristic_polynomial) in
/// s = w0^2, and its Hurwitz determinant h3 = a3 a2 a1 - a4 a1^2 - a3^2 a0: every root has a
/// negative real part iff a3, a2, a1, a0, h3 > 0 (a4 > 0). All are of degree <= 2 in s: the
/// gyroscopic and circulatory terms are both proportional to w0 and enter in pairs.
struct DampedCharacteristic {
  double a4 = 0.0, a3 = 0.0;
  SpinPolynomial a2, a1, a0, h3;
};

DampedCharacteristic damped_characteristic(const LinearModel& m) {
  DampedCharacteristic c;
  const double d = m.damping;
  const SpinPolynomial k11 = linear(m.K0(0, 0), m.K2(0, 0)), k22 = linear(m.K0(1, 1), m.K2(1, 1));
  c.a4 = m.M(0, 0) * m.M(1, 1);
  c.a3 = d * (m.M(0, 0) + m.M(1, 1));
  c.a2 = m.M(0, 0) * k22 + m.M(1, 1) * k11 + linear(d * d, -m.G1(0, 1) * m.G1(1, 0));
  c.a1 = d * (k11 + k22) + linear(0.0, -d * (m.G1(0, 1) * m.N1(1, 0) + m.G1(1, 0) * m.N1(0, 1)));
  c.a0 = product(k11, k22) + linear(0.0, -d * d * m.N1(0, 1) * m.N1(1, 0));
  c.h3 = (c.a3 * product(c.a2, c.a1) + (-c.a4) * product(c.a1, c.a1)) + (-c.a3 * c.a3) * c.a0;
  return c;
}

/// The characteristic polynomial's coefficients as functions of s = w0^2 (those of
/// characteristic_polynomial(model, spin), as polynomials in s).
struct SpinCharacteristic {
  double a4 = 0.0;
  SpinPolynomial k11, k22;  // the diagonal stiffnesses; a0 = k11 k22
  SpinPolynomial a2;
  SpinPolynomial a0;
  SpinPolynomial discriminant;  // a2^2 - 4 a4 a0
};

SpinCharacteristic spin_characteristic(const LinearModel& m) {
  SpinCharacteristic c;
  c.a4 = m.M(0, 0) * m.M(1, 1);
  c.k11 = linear(m.K0(0, 0), m.K2(0, 0));
  c.k22 = linear(m.K0(1, 1), m.K2(1, 1));
  const double gyro = m.G1(0, 1) * m.G1(1, 0);
  c.a2 = {m.M(0, 0) * c.k22.c0 + m.M(1, 1) * c.k11.c0,
          m.M(0, 0) * c.k22.c1 + m.M(1, 1) * c.k11.c1 - gyro, 0.0,
          m.M(0, 0) * c.k22.m0 + m.M(1, 1) * c.k11.m0,
          m.M(0, 0) * c.k22.m1 + m.M(1, 1) * c.k11.m1 + std::abs(gyro), 0.0};
  c.a0 = product(c.k11, c.k22);
  // a2 = (u + v) + (U + V + g^2) s and 4 a4 a0 = 4 (u + U s)(v + V s) with u = M11 k22(0),
  // v = M22 k11(0), U = M11 K2_22, V = M22 K2_11, so that a2^2 - 4 a4 a0 is, without the
  // cancellation of its expanded form (a slender body's double frequencies hinge on it):
  //   (u - v)^2 + 2 [(u - v)(U - V) + (u + v) g^2] s + [(U - V)^2 + g^2 W] s^2,
  // W = g^2 + 2 (U + V) given in closed form by the model (gyro_stiffness).
  const double u = m.M(0, 0) * c.k22.c0, v = m.M(1, 1) * c.k11.c0;
  const double U = m.M(0, 0) * c.k22.c1, V = m.M(1, 1) * c.k11.c1;
  const double g2 = -gyro, W = m.gyro_stiffness;
  c.discriminant = {(u - v) * (u - v),
                    2.0 * ((u - v) * (U - V) + (u + v) * g2),
                    (U - V) * (U - V) + g2 * W,
                    (u - v) * (u - v),
                    2.0 * (std::abs((u - v) * (U - V)) + std::abs((u + v) * g2)),
                    (U - V) * (U - V) + std::abs(g2 * W)};
  return c;
}

/// Real roots of p (degree <= 2), each polished by Newton's method; a double root once. A
/// coefficient counts as zero only when it is zero to rounding against its own terms (a
/// small leading coefficient is kept: it means a large root, such as a critical spin of 1e9).
std::vector<double> real_roots(const SpinPolynomial& p) {
  std::vector<double> roots;
  const double eps = std::numeric_limits<double>::epsilon();
  auto zero = [&](double c, double m) { return std::abs(c) <= 16.0 * eps * m; };
  if (zero(p.c2, p.m2)) {
    if (!zero(p.c1, p.m1)) roots.push_back(-p.c0 / p.c1);
  } else {
    const double d = p.c1 * p.c1 - 4.0 * p.c2 * p.c0;
    const double d_scale = p.c1 * p.c1 + 4.0 * std::abs(p.c2 * p.c0);
    if (std::abs(d) <= 64.0 * eps * d_scale) {
      roots.push_back(-p.c1 / (2.0 * p.c2));
      return roots;  // a double root: Newton would divide by a vanishing derivative
    }
    if (d < 0.0) return roots;
    const double q = -0.5 * (p.c1 + std::copysign(std::sqrt(d), p.c1));
    roots.push_back(q / p.c2);
    if (q != 0.0) roots.push_back(p.c0 / q);
  }
  for (double& s : roots) {
    for (int i = 0; i < 3; ++i) {
      const double slope = p.c1 + 2.0 * p.c2 * s;
      if (slope == 0.0) break;
      const double step = p(s) / slope;
      if (!std::isfinite(step)) break;
      s -= step;
    }
  }
  return roots;
}

bool is_zero(const SpinPolynomial& p, double s) {
  return std::abs(p(s)) <= kCoincidence * p.magnitude(s);
}

bool vanishes(const Eigen::Matrix4d& residual) {
  return residual.cwiseAbs().maxCoeff() <= kSemisimple;
}

/// Real part ascending, then imaginary part: the order every verdict reports.
void sort_eigenvalues(std::vector<std::complex<double>>& eigenvalues) {
  std::sort(eigenvalues.begin(), eigenvalues.end(), [](auto x, auto y) {
    return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag();
  });
}

/// rad/s, the distinct |Im| of `eigenvalues`, ascending (1e-12 relative counts as equal).
std::vector<double> distinct_frequencies(const std::vector<std::complex<double>>& eigenvalues) {
  std::vector<double> f;
  for (const auto& l : eigenvalues) f.push_back(std::abs(l.imag()));
  std::sort(f.begin(), f.end());
  f.erase(std::unique(f.begin(), f.end(), [](double x, double y) { return std::abs(x - y) <= 1e-12 * std::max(x, y); }),
          f.end());
  return f;
}

/// The eigenvalues of the damped model at `spin`, from the balanced system matrix (Eigen's
/// Hessenberg QR), each polished by Newton's method on the quartic; sorted like the undamped.
std::vector<std::complex<double>> damped_eigenvalues(const LinearModel& model, double spin,
                                                     double rate) {
  const CharacteristicPolynomial p = characteristic_polynomial(model, spin);
  const Eigen::Matrix4d j = state_matrix(model, spin, rate);
  const Eigen::EigenSolver<Eigen::Matrix4d> solver(j, false);
  const auto f = [&](std::complex<double> l) { return (((p.a4 * l + p.a3) * l + p.a2) * l + p.a1) * l + p.a0; };
  const auto df = [&](std::complex<double> l) { return ((4.0 * p.a4 * l + 3.0 * p.a3) * l + 2.0 * p.a2) * l + p.a1; };
  // The eigensolver's roots are accurate to ~eps of the largest: a strongly damped body's
  // slow roots (d_t = 1e5: |l| ~ 1e-9 of the fast ones) came out wrong by 180x or with the
  // wrong sign. Newton on the quartic, evaluated to rounding of its own terms at each root,
  // converges to each simple root from there; a start that does not converge (a multiple
  // root, where Newton is no better than the eigensolver) or that lands on a root another
  // start found keeps the eigensolver's value.
  std::array<std::complex<double>, 4> start, polished;
  std::array<bool, 4> converged{};
  for (int i = 0; i < 4; ++i) {
    std::complex<double> l = start[i] = solver.eigenvalues()[i] * rate;
    for (int it = 0; it < 100; ++it) {
      const auto slope = df(l);
      if (std::abs(slope) == 0.0) break;
      const auto next = l - f(l) / slope;
      if (!(std::isfinite(next.real()) && std::isfinite(next.imag()))) break;
      const double step = std::abs(next - l);
      l = next;
      if (step <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(l)) {
        converged[i] = true;
        break;
      }
    }
    polished[i] = l;
  }
  std::vector<std::complex<double>> roots;
  for (int i = 0; i < 4; ++i) {
    bool keep = converged[i] && std::abs(f(polished[i])) <= std::abs(f(start[i]));
    for (int j = 0; j < 4 && keep; ++j)
      if (j != i && std::abs(polished[j] - polished[i]) <= 1e-8 * std::abs(polished[i]) &&
          std::abs(start[j] - start[i]) > 1e-8 * std::abs(start[i]))
        keep = false;  // two starts on one root: a multiple root, or one lost
    roots.push_back((keep ? polished[i] : start[i]) + 0.0);
  }
  // Two slow roots far below two fast ones (a strongly damped body: |l| ~ m g R / d_t next to
  // d_t / A) that are nearly double (a complex pair 1e-10 of their size from the real axis):
  // Newton cannot separate them. The quartic divided by the fast pair's quadratic (its sum S and
  // product P, accurate) leaves l^2 - s l + q with q = a0 / (a4 P) and s = -(a1 / a4 + S q) / P,
  // each without cancellation: s / 2, the pair's real part, to rounding.
  std::sort(roots.begin(), roots.end(), [](auto x, auto y) { return std::abs(x) < std::abs(y); });
  if (std::abs(roots[1]) < 1e-3 * std::abs(roots[2])) {
    const double S = (roots[2] + roots[3]).real(), P = (roots[2] * roots[3]).real();
    const double q = p.a0 / (p.a4 * P);
    const double sum = -(p.a1 / p.a4 + S * q) / P;
    if (std::isfinite(q) && std::isfinite(sum)) {
      const auto [x1, x2] = detail::quadratic_roots(1.0, -sum, q, sum * sum - 4.0 * q);
      roots[0] = x1 + 0.0;
      roots[1] = x2 + 0.0;
    }
  }
  sort_eigenvalues(roots);
  return roots;
}

/// The frequency scale of the damped model at `spin`: the largest |a_k / a4|^(1 / (4 - k)), a
/// bound of the roots' size up to a factor 2 (Fujiwara), for balancing and zero tests.
double damped_rate(const LinearModel& model, double spin) {
  const CharacteristicPolynomial p = characteristic_polynomial(model, spin);
  double r = 0.0;
  r = std::max(r, std::abs(p.a3 / p.a4));
  r = std::max(r, std::sqrt(std::abs(p.a2 / p.a4)));
  r = std::max(r, std::cbrt(std::abs(p.a1 / p.a4)));
  r = std::max(r, std::sqrt(std::sqrt(std::abs(p.a0 / p.a4))));
  return r;
}

/// The InvalidInput for a characteristic polynomial that overflows a double at `spin`: the
/// spin's fault only when it does not at rest; otherwise the body's (or the damping's) term
/// farthest from 1 in magnitude, named by its key (a scaled body at 1e150, a subnormal
/// inertia, --length 1e200 and --transverse-damping 1e300 all blamed the spin).
InvalidInput overflow(const LinearModel& model, double spin, bool overflows_at_rest) {
  if (!overflows_at_rest)
    return InvalidInput("motion.spin", fmt::format("{:g} rad/s is too large for this body: its characteristic "
                                                   "polynomial overflows a double", spin));
  struct Term {
    const char* key;
    const char* what;
    double value;
  };
  const Term terms[] = {{"body.A", "A", model.M(0, 0)},
                        {"body.B", "B", model.M(1, 1)},
                        {"body.C", "the gyroscopic coefficient", std::abs(model.G1(0, 1))},
                        {"body.length", "m g R", std::abs(model.K0(0, 0))},
                        {"damping.transverse", "d_t", model.damping}};
  const Term* blamed = &terms[0];
  double worst = -1.0;
  for (const Term& t : terms) {
    if (t.value == 0.0 || !std::isfinite(t.value)) continue;
    const double far = std::abs(std::log10(t.value));
    if (far > worst) worst = far, blamed = &t;
  }
  const char* key = blamed->key;
  const char* what = blamed->what;
  const double value = blamed->value;
  return InvalidInput(key, fmt::format("{} = {:g} is out of the range the stability analysis computes in: the "
                                       "characteristic polynomial overflows or underflows a double at rest or at the spins "
                                       "where the verdict changes",
                                       what, value));
}

StabilityVerdict damped_stability(const LinearModel& model, double spin) {
  const DampedCharacteristic c = damped_characteristic(model);
  const double s = spin * spin;
  const double rate = damped_rate(model, spin);
  if (!std::isfinite(c.h3.magnitude(s)) || !std::isfinite(rate) || rate == 0.0)
    throw overflow(model, spin, !std::isfinite(c.h3.magnitude(0.0)) || !std::isfinite(damped_rate(model, 0.0)));
  StabilityVerdict v;
  v.eigenvalues = damped_eigenvalues(model, spin, rate);
  v.growth_rate = v.eigenvalues.back().real();
  for (const auto& l : v.eigenvalues) v.growth_rate = std::max(v.growth_rate, l.real());

  // Routh-Hurwitz, each condition's sign decided against the size of its terms.
  int negative = 0, zero = 0;
  for (const SpinPolynomial* q : {&c.a2, &c.a1, &c.a0, &c.h3}) {
    if (std::abs((*q)(s)) <= kHurwitzZero * q->magnitude(s)) ++zero;
    else if ((*q)(s) < 0.0) ++negative;
  }
  if (negative > 0) {  // a root in the open right half-plane (a closed-left one has all >= 0)
    v.reason = fmt::format("a mode grows under damping (e-folding time {:.4g} s)",
                           1.0 / std::max(v.growth_rate, std::numeric_limits<double>::min()));
    return v;
  }
  if (zero == 0) {
    v.stable = true;
    v.reason = fmt::format("asymptotically stable: every mode decays (the slowest e-folds in {:.4g} s)",
                           -1.0 / std::min(v.growth_rate, -std::numeric_limits<double>::min()));
  } else {
    // On the boundary: roots on the imaginary axis, stable iff each is semisimple.
    const Eigen::Matrix4cd j = state_matrix(model, spin, rate).cast<std::complex<double>>();
    const double axis = 1e-6 * rate;
    std::vector<std::complex<double>> on_axis;
    for (const auto& l : v.eigenvalues)
      if (std::abs(l.real()) <= axis) on_axis.push_back(std::complex<double>(0.0, l.imag()));
    // A root off the axis to the right that the conditions could not see (zero to rounding):
    // the mode grows, whatever the others do.
    // A root to the right of the axis by more than its own error (Newton's step there: a few
    // eps of |l| for a simple root, large at a multiple one) grows, however small it is next
    // to the fast roots (d_t = 1e7: 1e-18 of them, within `axis`).
    const CharacteristicPolynomial p = characteristic_polynomial(model, spin);
    const auto resolved_growth = [&](std::complex<double> l) {
      const auto f = (((p.a4 * l + p.a3) * l + p.a2) * l + p.a1) * l + p.a0;
      const auto df = ((4.0 * p.a4 * l + 3.0 * p.a3) * l + 2.0 * p.a2) * l + p.a1;
      const double error = std::abs(df) > 0.0 ? std::abs(f / df) : std::numeric_limits<double>::infinity();
      return l.real() > axis || (l.real() > 0.0 && l.real() > 1e3 * error + 64.0 * std::numeric_limits<double>::epsilon() * std::abs(l));
    };
    if (std::any_of(v.eigenvalues.begin(), v.eigenvalues.end(), resolved_growth)) {
      v.reason = fmt::format("a mode grows under damping (e-folding time {:.4g} s)", 1.0 / v.growth_rate);
      return v;
    }
    bool semisimple = true;
    for (const auto& l : on_axis) {
      const auto m = std::count_if(on_axis.begin(), on_axis.end(),
                                   [&](auto x) { return std::abs(x - l) <= axis; });
      if (m < 2) continue;
      const Eigen::JacobiSVD<Eigen::Matrix4cd> svd(j - (l / rate) * Eigen::Matrix4cd::Identity());
      if (svd.singularValues()(4 - m) > kSemisimple) semisimple = false;
    }
    v.stable = semisimple;
    v.reason = semisimple ? "on the damped stability boundary: a mode neither grows nor decays"
                          : "on the damped stability boundary with a Jordan block: the axis drifts";
    if (semisimple) v.growth_rate = std::min(v.growth_rate, 0.0);
  }
  if (v.stable) v.frequencies = distinct_frequencies(v.eigenvalues);
  return v;
}

}  // namespace

/// True when a term of the model, nonzero, has a fourth power below the smallest normal double:
/// the conditions' coefficients hold products of up to four terms (C^4 in the discriminant),
/// which then underflow and lose the verdict's ends (a body scaled by 1e-150 had no critical
/// spin, and a subnormal inertia no verdict). Refused as the overflow is, naming the term.
static bool underflows(const LinearModel& model) {
  for (double t : {model.M(0, 0), model.M(1, 1), model.G1(0, 1), model.K0(0, 0), model.K0(1, 1), model.damping}) {
    const double t2 = t * t;
    if (t != 0.0 && t2 * t2 < std::numeric_limits<double>::min()) return true;
  }
  return false;
}

StabilityVerdict linear_stability(const LinearModel& model, double spin) {
  if (underflows(model)) throw overflow(model, spin, true);
  if (model.damped()) return damped_stability(model, spin);
  const SpinCharacteristic c = spin_characteristic(model);
  const double s = spin * spin;
  const double a4 = c.a4, a2 = c.a2(s), a0 = c.a0(s), disc = c.discriminant(s);
  const bool a0_zero = is_zero(c.k11, s) || is_zero(c.k22, s);
  if (!std::isfinite(c.discriminant.magnitude(s)) || !std::isfinite(a4) || a4 == 0.0)
    throw overflow(model, spin, !std::isfinite(c.discriminant.magnitude(0.0)) || !std::isfinite(a4) || a4 == 0.0);
  const bool double_root = std::abs(disc) <= kCoincidence * c.discriminant.magnitude(s);

  // Roots mu = lambda^2 of a4 mu^2 + a2 mu + a0.
  std::complex<double> mu1, mu2;
  if (double_root) {
    mu1 = mu2 = -a2 / (2.0 * a4);
  } else {
    std::tie(mu1, mu2) = detail::quadratic_roots(a4, a2, a0, disc);
  }
  if (a0_zero) {  // exactly one root mu = 0 (or a double one when a2 vanishes too)
    if (double_root) mu1 = mu2 = 0.0;
    else { mu1 = 0.0; mu2 = -a2 / a4; }
  }

  StabilityVerdict v;
  for (auto mu : {mu1, mu2}) {
    const auto r = std::sqrt(mu);
    v.eigenvalues.push_back(-r + 0.0);  // + 0.0: no negative zeros in reports
    v.eigenvalues.push_back(r + 0.0);
  }
  sort_eigenvalues(v.eigenvalues);
  v.growth_rate = v.eigenvalues.back().real();

  const bool oscillatory = mu1.imag() == 0.0 && mu2.imag() == 0.0 && mu1.real() <= 0.0 &&
                           mu2.real() <= 0.0;
  if (!oscillatory) {
    v.reason = mu1.imag() != 0.0 ? "complex eigenvalues: an oscillation that grows"
                                 : "a real positive eigenvalue: the axis falls away";
    return v;
  }

  const double m1 = mu1.real(), m2 = mu2.real();
  const double rate = std::sqrt(std::max(std::abs(m1), std::abs(m2)));
  if (rate == 0.0) {  // every eigenvalue zero: the 4x4 matrix is nilpotent and not zero
    v.reason = "all eigenvalues zero (a Jordan block): the axis drifts";
    return v;
  }
  const Eigen::Matrix4d j = state_matrix(model, spin, rate);
  const Eigen::Matrix4d id = Eigen::Matrix4d::Identity();
  if (double_root) {
    // lambda = +-i sqrt(-mu) each double: semisimple iff J^2 = mu I.
    if (!vanishes(j * j - (m1 / (rate * rate)) * id)) {
      v.reason = fmt::format("double frequency {:.6g} rad/s is a Jordan block: the amplitude "
                             "grows linearly (erratum E2)", std::sqrt(-m1));
      return v;
    }
    v.reason = fmt::format("double frequency {:.6g} rad/s, semisimple", std::sqrt(-m1));
  } else if (a0_zero) {
    // lambda = 0 double, +-i sqrt(-mu2): semisimple iff J (J^2 - mu2 I) = 0.
    if (!vanishes(j * (j * j - (m2 / (rate * rate)) * id))) {
      v.reason = "zero eigenvalue is a Jordan block: the axis drifts";
      return v;
    }
    v.reason = "a neutral direction (zero frequency, semisimple) and one frequency";
  } else {
    v.reason = "two distinct frequencies";
  }
  v.stable = true;
  v.frequencies = distinct_frequencies(v.eigenvalues);
  return v;
}

std::vector<SpinInterval> stable_spin_intervals(const LinearModel& model) {
  // Every sign change of a condition happens at a root in s = w0^2 of one of these.
  std::vector<SpinPolynomial> conditions;
  if (model.damped()) {
    const DampedCharacteristic c = damped_characteristic(model);
    conditions = {c.a2, c.a1, c.a0, c.h3};
  } else {
    const SpinCharacteristic c = spin_characteristic(model);
    conditions = {c.k11, c.k22, c.a2, c.discriminant};
  }
  std::vector<double> ends{0.0};
  for (const SpinPolynomial& p : conditions)
    for (double s : real_roots(p))
      if (s > 0.0 && std::isfinite(s)) ends.push_back(s);
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end(),
                         [](double x, double y) { return y - x <= 1e-14 * y; }),
             ends.end());

  // Pieces in order: the point ends[0], the open gap after it, the point ends[1], ...,
  // the unbounded gap after the last end. Each piece's verdict is constant on it.
  struct Piece {
    double lo, hi;  // in s; hi = +inf for the last gap
    bool stable;
    bool point;     // the single spin lo == hi (an end), else the open gap between two ends
  };
  const double k_scale = std::max({std::abs(model.K0(0, 0)), std::abs(model.K0(1, 1))});
  const double m_scale = std::min({model.M(0, 0), model.M(1, 1)});
  const double s_beyond = std::max(4.0 * ends.back(), k_scale > 0.0 ? k_scale / m_scale : 1.0);
  auto stable_at = [&](double s) {
    // A spin of this analysis's own (an end, a gap's middle), not the user's: when the
    // polynomial overflows there, the body's scale is at fault (--length 1e200 put the
    // critical spin at 4e102 rad/s and blamed motion.spin).
    try {
      return linear_stability(model, std::sqrt(s)).stable;
    } catch (const InvalidInput& e) {
      if (e.key() != "motion.spin") throw;
      throw overflow(model, std::sqrt(s), true);
    }
  };

  std::vector<Piece> pieces;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    pieces.push_back({ends[i], ends[i], stable_at(ends[i]), true});
    const bool last = i + 1 == ends.size();
    const double hi = last ? std::numeric_limits<double>::infinity() : ends[i + 1];
    const double probe = last ? s_beyond : 0.5 * (ends[i] + ends[i + 1]);
    pieces.push_back({ends[i], hi, stable_at(probe), false});
  }

  std::vector<SpinInterval> intervals;
  for (std::size_t i = 0; i < pieces.size();) {
    if (!pieces[i].stable) { ++i; continue; }
    std::size_t j = i;
    while (j + 1 < pieces.size() && pieces[j + 1].stable) ++j;
    SpinInterval interval{std::sqrt(pieces[i].lo), std::nullopt, pieces[i].point, pieces[j].point};
    if (std::isfinite(pieces[j].hi)) interval.hi = std::sqrt(pieces[j].hi);
    intervals.push_back(interval);
    i = j + 1;
  }
  return intervals;
}

std::optional<double> critical_spin(const std::vector<SpinInterval>& intervals) {
  if (intervals.empty() || intervals.back().hi) return std::nullopt;
  return intervals.back().lo;
}

std::vector<ModelStability> analyse_stability(const Body& body, double spin) {
  std::vector<ModelStability> models;
  for (LinearModelKind kind : kLinearModels) {
    const LinearModel model = linear_model(kind, body);
    auto intervals = stable_spin_intervals(model);
    auto critical = critical_spin(intervals);
    models.push_back({kind, linear_stability(model, spin), std::move(intervals), critical});
  }
  return models;
}

}  // namespace heavytop

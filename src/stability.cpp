#include "heavytop/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "detail/quadratic.hpp"

namespace heavytop {
namespace {

// Roots closer than this (relative to the size of the terms that make the discriminant)
// are one double root; a float computation of an exact boundary lands within ~1e-15.
constexpr double kCoincidence = 1e-10;
// A matrix polynomial that vanishes in exact arithmetic comes out ~1e-15 of the balanced
// system matrix's scale; one that does not (a Jordan block) is of order one.
constexpr double kSemisimple = 1e-7;

/// c0 + c1 s + c2 s^2 in s = w0^2, with the sizes of its terms kept for zero tests.
struct SpinPolynomial {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;
  double operator()(double s) const { return c0 + s * (c1 + s * c2); }
  double magnitude(double s) const { return std::abs(c0) + s * (std::abs(c1) + s * std::abs(c2)); }
};

SpinPolynomial product(const SpinPolynomial& p, const SpinPolynomial& q) {
  // Used only for products of two linear factors.
  return {p.c0 * q.c0, p.c0 * q.c1 + p.c1 * q.c0, p.c1 * q.c1};
}

/// The characteristic polynomial's coefficients as functions of s = w0^2.
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
  c.k11 = {m.K0(0, 0), m.K2(0, 0), 0.0};
  c.k22 = {m.K0(1, 1), m.K2(1, 1), 0.0};
  c.a2 = {m.M(0, 0) * c.k22.c0 + m.M(1, 1) * c.k11.c0,
          m.M(0, 0) * c.k22.c1 + m.M(1, 1) * c.k11.c1 - m.G1(0, 1) * m.G1(1, 0), 0.0};
  c.a0 = product(c.k11, c.k22);
  c.discriminant = {c.a2.c0 * c.a2.c0 - 4.0 * c.a4 * c.a0.c0,
                    2.0 * c.a2.c0 * c.a2.c1 - 4.0 * c.a4 * c.a0.c1,
                    c.a2.c1 * c.a2.c1 - 4.0 * c.a4 * c.a0.c2};
  return c;
}

/// Real roots of p (degree <= 2), each polished by Newton's method; a double root once.
std::vector<double> real_roots(const SpinPolynomial& p) {
  std::vector<double> roots;
  const double scale = std::abs(p.c0) + std::abs(p.c1) + std::abs(p.c2);
  if (scale == 0.0) return roots;
  const double eps = std::numeric_limits<double>::epsilon();
  if (std::abs(p.c2) <= eps * scale) {
    if (std::abs(p.c1) > eps * scale) roots.push_back(-p.c0 / p.c1);
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

}  // namespace

StabilityVerdict linear_stability(const LinearModel& model, double spin) {
  const SpinCharacteristic c = spin_characteristic(model);
  const double s = spin * spin;
  const double a4 = c.a4, a2 = c.a2(s), a0 = c.a0(s), disc = c.discriminant(s);
  const bool a0_zero = is_zero(c.k11, s) || is_zero(c.k22, s);
  const double a2_terms = c.a2.magnitude(s);
  const bool double_root =
      std::abs(disc) <= kCoincidence * (a2_terms * a2_terms + 4.0 * a4 * std::abs(a0));

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
  std::sort(v.eigenvalues.begin(), v.eigenvalues.end(), [](auto x, auto y) {
    return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag();
  });

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
  for (const auto& l : v.eigenvalues) v.frequencies.push_back(std::abs(l.imag()));
  std::sort(v.frequencies.begin(), v.frequencies.end());
  v.frequencies.erase(std::unique(v.frequencies.begin(), v.frequencies.end(),
                                  [](double x, double y) {
                                    return std::abs(x - y) <= 1e-12 * std::max(x, y);
                                  }),
                      v.frequencies.end());
  return v;
}

std::vector<SpinInterval> stable_spin_intervals(const LinearModel& model) {
  const SpinCharacteristic c = spin_characteristic(model);

  // Every sign change of a condition happens at a root in s = w0^2 of one of these.
  std::vector<double> ends{0.0};
  for (const SpinPolynomial* p : {&c.k11, &c.k22, &c.a2, &c.discriminant})
    for (double s : real_roots(*p))
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
  };
  const double k_scale = std::max({std::abs(model.K0(0, 0)), std::abs(model.K0(1, 1))});
  const double m_scale = std::min({model.M(0, 0), model.M(1, 1)});
  const double s_beyond = std::max(4.0 * ends.back(), k_scale > 0.0 ? k_scale / m_scale : 1.0);
  auto stable_at = [&](double s) { return linear_stability(model, std::sqrt(s)).stable; };

  std::vector<Piece> pieces;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    pieces.push_back({ends[i], ends[i], stable_at(ends[i])});
    const bool last = i + 1 == ends.size();
    const double hi = last ? std::numeric_limits<double>::infinity() : ends[i + 1];
    const double probe = last ? s_beyond : 0.5 * (ends[i] + ends[i + 1]);
    pieces.push_back({ends[i], hi, stable_at(probe)});
  }

  std::vector<SpinInterval> intervals;
  for (std::size_t i = 0; i < pieces.size();) {
    if (!pieces[i].stable) { ++i; continue; }
    std::size_t j = i;
    while (j + 1 < pieces.size() && pieces[j + 1].stable) ++j;
    SpinInterval interval{std::sqrt(pieces[i].lo), std::nullopt};
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

#include "heavytop/lyapunov.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include <fmt/format.h>

#include "heavytop/lagrange_exact.hpp"
#include "heavytop/linear_models.hpp"

namespace heavytop {
namespace {

// A stiffness (or C^2 w0^2 - 4 A m g R) counts as zero below this fraction of its terms: the
// same relative slack as linear_stability's double roots, so that a computed boundary (a
// closed-form root, a few eps off) is recognised as the boundary.
constexpr double kZero = 1e-12;

/// C - A with the slack of is_symmetric: moments equal to rounding give exactly 0.
double difference(double C, double A) {
  return std::abs(C - A) <= kSymmetryTolerance * std::max(C, A) ? 0.0 : C - A;
}

struct Stiffness {
  double value = 0.0;  // N m
  bool zero = false;
  bool negative() const { return !zero && value < 0.0; }
  bool positive() const { return !zero && value > 0.0; }
};

Stiffness stiffness(double c, double s, double mgR) {
  const double value = c * s - mgR + 0.0;  // + 0.0: no negative zeros in reports
  const double scale = std::abs(c) * s + std::abs(mgR);
  return {value, std::abs(value) <= kZero * scale};
}

LyapunovVerdict verdict(LyapunovVerdict v, LyapunovVerdictKind kind, LyapunovCertificate certificate,
                        std::string reason) {
  v.verdict = kind;
  v.certificate = certificate;
  v.reason = std::move(reason);
  return v;
}

/// True if the exact linearisation at this spin has an eigenvalue of positive real part (an
/// exponential growth, which the full equations share by Lyapunov's first method).
bool grows_exponentially(const Body& body, double spin) {
  const StabilityVerdict lin = linear_stability(linear_model(LinearModelKind::Linearized, body), spin);
  if (lin.stable) return false;
  double largest = 0.0, size = 0.0;
  for (const auto& l : lin.eigenvalues) {
    largest = std::max(largest, l.real());
    size = std::max(size, std::abs(l));
  }
  return largest > 1e-9 * size;
}

}  // namespace

std::string_view name(LyapunovVerdictKind verdict) {
  switch (verdict) {
    case LyapunovVerdictKind::Stable: return "stable";
    case LyapunovVerdictKind::Unstable: return "unstable";
    case LyapunovVerdictKind::Undecided: return "undecided";
  }
  return "undecided";
}

std::string_view name(LyapunovCertificate certificate) {
  switch (certificate) {
    case LyapunovCertificate::EnergyCasimir: return "energy-casimir";
    case LyapunovCertificate::Chetaev: return "chetaev";
    case LyapunovCertificate::CriticalQuartic: return "critical-quartic";
    case LyapunovCertificate::OddIndex: return "odd-index";
    case LyapunovCertificate::LinearInstability: return "linear-instability";
    case LyapunovCertificate::None: return "none";
  }
  return "none";
}

LyapunovVerdict lyapunov_stability(const Body& body, double spin) {
  validate(body);
  refuse_general(body, "the Lyapunov analysis");
  if (!std::isfinite(spin)) throw InvalidInput("motion.spin", "must be a finite number");
  const double s = spin * spin, k = body.mgR();
  const double c1 = difference(body.C, body.A), c2 = difference(body.C, body.B);
  const Stiffness st1 = stiffness(c1, s, k), st2 = stiffness(c2, s, k);
  LyapunovVerdict v;
  v.s1 = st1.value;
  v.s2 = st2.value;
  v.energy_index = int(st1.negative()) + int(st2.negative());
  using K = LyapunovVerdictKind;
  using Cert = LyapunovCertificate;

  if (k == 0.0 && s == 0.0)
    return verdict(v, K::Unstable, Cert::LinearInstability,
                   "free body at rest: a neutral drift (any small angular velocity turns the axis "
                   "steadily away), not stable");
  if (v.energy_index == 0 && st1.positive() && st2.positive())
    return verdict(v, K::Stable, Cert::EnergyCasimir,
                   "proof: the energy-Casimir function is definite (energy index 0); stable also "
                   "under internal damping");

  if (is_symmetric(body)) {
    const double A = 0.5 * (body.A + body.B);
    const double d = body.C * body.C * s - 4.0 * A * k;
    const double scale = body.C * body.C * s + 4.0 * A * std::abs(k);
    if (k > 0.0 && std::abs(d) <= kZero * scale)
      return verdict(v, K::Stable, Cert::CriticalQuartic,
                     "proof: at C^2 w0^2 = 4 A m g R the quadratic term of the amended potential "
                     "vanishes and its quartic term (m g R / 8) tilt^4 is positive");
    if (d > 0.0)
      return verdict(v, K::Stable, Cert::Chetaev,
                     "proof: Chetaev's function (energy, vertical and axial momenta) is definite, "
                     "C^2 w0^2 > 4 A m g R");
    return verdict(v, K::Unstable, Cert::LinearInstability,
                   "C^2 w0^2 < 4 A m g R: the linearisation grows exponentially, and so does the "
                   "real top (Lyapunov's first method)");
  }

  if (v.energy_index == 1 && !st1.zero && !st2.zero)  // s1 s2 < 0: a real eigenvalue pair
    return verdict(v, K::Unstable, Cert::OddIndex,
                   "odd energy index: a real positive eigenvalue, the axis falls away");
  if (k == 0.0) {  // the free asymmetric body rotating about its principal axis z
    if (c1 < 0.0 && c2 < 0.0)
      return verdict(v, K::Stable, Cert::EnergyCasimir,
                     "proof: free body about its axis of least moment, the energy-Casimir function "
                     "with |L|^2 is definite (gyroscopic: destroyed by internal damping)");
    return verdict(v, K::Unstable, Cert::LinearInstability,
                   "free body with C equal to a transverse moment: it tumbles (the linearisation's "
                   "drift is an exact motion), not stable");
  }
  if (grows_exponentially(body, spin))
    return verdict(v, K::Unstable, Cert::LinearInstability,
                   "the linearisation grows exponentially, and so does the real body (Lyapunov's "
                   "first method)");
  if (st1.zero || st2.zero)
    return verdict(v, K::Undecided, Cert::None,
                   "a zero stiffness: degenerate, decided by higher-order terms that are not "
                   "analysed");
  return verdict(v, K::Undecided, Cert::None,
                 "index 2: gyroscopic stability only, destroyed by internal damping; the KAM "
                 "test is not built");
}

std::vector<SpinInterval> lyapunov_stable_spin_intervals(const Body& body) {
  validate(body);
  refuse_general(body, "the Lyapunov analysis");
  const double k = body.mgR();
  const double inf = std::numeric_limits<double>::infinity();
  // The candidate stable set in s = w0^2, as (lo, hi): open or closed is settled below by the
  // verdict at each end itself.
  double lo = 0.0, hi = inf;
  bool empty = false;
  if (is_symmetric(body)) {
    const double A = 0.5 * (body.A + body.B);
    if (k > 0.0) lo = 4.0 * A * k / (body.C * body.C);
  } else if (k == 0.0) {
    const double c1 = difference(body.C, body.A), c2 = difference(body.C, body.B);
    empty = !((c1 > 0.0 && c2 > 0.0) || (c1 < 0.0 && c2 < 0.0));
  } else {
    for (double c : {difference(body.C, body.A), difference(body.C, body.B)}) {
      // c s - k > 0
      if (c > 0.0) lo = std::max(lo, k / c);
      else if (c < 0.0) hi = std::min(hi, k / c);  // s < k / c, a positive bound only for k < 0
      else if (k >= 0.0) empty = true;
    }
    if (hi <= lo) empty = true;
  }
  if (empty) return {};
  SpinInterval interval;
  interval.lo = std::sqrt(lo);
  interval.lo_included = lyapunov_stability(body, interval.lo).verdict == LyapunovVerdictKind::Stable;
  if (hi < inf) {
    interval.hi = std::sqrt(hi);
    interval.hi_included = lyapunov_stability(body, *interval.hi).verdict == LyapunovVerdictKind::Stable;
  }
  return {interval};
}

std::optional<double> superfast_spin(const Body& body) {
  validate(body);
  refuse_general(body, "the Lyapunov analysis");
  const double k = body.mgR();
  double s = 0.0;
  for (double c : {difference(body.C, body.A), difference(body.C, body.B)}) {
    if (c < 0.0) return std::nullopt;     // (C - A) w0^2 - m g R < 0 for every large spin
    if (c == 0.0) {
      if (k > 0.0) return std::nullopt;   // the stiffness is -m g R < 0 at every spin
      continue;
    }
    s = std::max(s, k / c);
  }
  return std::sqrt(s);
}

LyapunovStability analyse_lyapunov(const Body& body, double spin) {
  return {lyapunov_stability(body, spin), lyapunov_stable_spin_intervals(body), superfast_spin(body)};
}

Wander axis_wander(const Body& body, const InitialState& initial, double horizon,
                   const NonlinearOptions& options) {
  Wander w;
  try {
    validate(body);
    refuse_general(body, "the Lyapunov analysis");
    validate(initial);
    if (initial.theta0 == 0.0 && initial.phi0 == 0.0 && initial.theta_rate0 == 0.0 &&
        initial.phi_rate0 == 0.0) {
      w.max_tilt = 0.0;  // the upright permanent rotation is an exact motion: it never tilts
      return w;
    }
    if (is_symmetric(body) && body.damping.conservative()) {
      w.max_tilt = nutation_bounds(lagrange_top(body, initial)).max_tilt;
      return w;
    }
    w.closed_form = false;
    w.horizon = horizon;
    if (!(std::isfinite(horizon) && horizon > 0.0)) throw InvalidInput("horizon", "must be a finite number > 0");
    NonlinearOptions capped = options;
    capped.max_steps = std::min(capped.max_steps, kWanderMaxSteps);
    w.max_tilt = tilt_extremes(body, initial, horizon, std::numeric_limits<double>::infinity(), capped).max_tilt;
  } catch (const InvalidInput& e) {
    w.max_tilt.reset();
    w.note = fmt::format("{}: {}", e.key(), e.rule());
  } catch (const std::exception& e) {
    w.max_tilt.reset();
    w.note = e.what();
  }
  return w;
}

}  // namespace heavytop

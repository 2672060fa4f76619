#include "heavytop/lyapunov.hpp"
#include "heavytop/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <exception>
#include <limits>
#include <utility>

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

/// Index 2, linearly stable, a principal asymmetric body: Arnold's theorem on the normal form,
/// Markeev's at 1:3 (SPEC section 7; docs/lyapunov.md).
LyapunovVerdict kam_verdict(const Body& body, double spin, LyapunovVerdict v) {
  using K = LyapunovVerdictKind;
  using Cert = LyapunovCertificate;
  // At the ends of the linearized model's stable spins two frequencies meet in a Jordan block
  // (a Krein collision): there the eigen-decomposition still splits them by ~sqrt(eps), so the
  // linear model's own verdict, not the frequencies, says that this is the 1:1 case.
  if (!linear_stability(linear_model(LinearModelKind::Linearized, body), spin).stable)
    return verdict(std::move(v), K::Undecided, Cert::None,
                   "index 2 at the boundary of linear stability (w1 = w2, a Jordan block): Arnold's "
                   "theorem does not apply, and higher orders are not analysed");
  v.normal_form = birkhoff_normal_form(body, spin);
  if (!v.normal_form)
    return verdict(std::move(v), K::Undecided, Cert::None,
                   "index 2 at the 1:1 resonance (w1 = w2): Arnold's theorem does not apply, and "
                   "higher orders are not analysed");
  const NormalForm& nf = *v.normal_form;
  if (std::abs(nf.D) <= kDegeneracyTolerance * nf.D_scale)
    return verdict(std::move(v), K::Undecided, Cert::None,
                   "index 2 with D = 0: the order-4 normal form is degenerate, order 6 would "
                   "decide and is not analysed");
  if (nf.resonance == 3) {
    const double bound = 3.0 * std::sqrt(3.0) * *nf.a13 * std::pow(std::min(nf.w1, nf.w2), 2);
    const double margin = std::abs(nf.D) - bound;
    if (std::abs(margin) <= kDegeneracyTolerance * (nf.D_scale + bound))
      return verdict(std::move(v), K::Undecided, Cert::None,
                     "index 2 at the 1:3 resonance with equality in Markeev's inequality: not "
                     "decided at order 4");
    if (margin > 0.0)
      return verdict(std::move(v), K::Stable, Cert::KamMarkeev,
                     fmt::format("proof (for perturbations small enough): at the 1:3 resonance "
                                 "|D| = {:.6g} > 3 sqrt(3) a13 min(w)^2 = {:.6g} (Markeev)",
                                 std::abs(nf.D), bound));
    return verdict(std::move(v), K::Unstable, Cert::Resonance,
                   fmt::format("at the 1:3 resonance |D| = {:.6g} < 3 sqrt(3) a13 min(w)^2 = {:.6g}: "
                               "the resonant exchange of the two modes grows (Markeev)",
                               std::abs(nf.D), bound));
  }
  return verdict(std::move(v), K::Stable, Cert::Kam,
                 fmt::format("proof (for perturbations small enough): Arnold's theorem, D = {:.6g} "
                             "!= 0 away from the 1:1 and 1:3 resonances (index 2: gyroscopic, "
                             "destroyed by internal damping)",
                             nf.D));
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
    case LyapunovCertificate::Kam: return "kam";
    case LyapunovCertificate::KamMarkeev: return "kam-markeev";
    case LyapunovCertificate::Resonance: return "resonance";
  }
  return "none";
}

bool proves_stability(LyapunovCertificate certificate) {
  using C = LyapunovCertificate;
  return certificate == C::EnergyCasimir || certificate == C::Chetaev || certificate == C::CriticalQuartic ||
         certificate == C::Kam || certificate == C::KamMarkeev;
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
  return kam_verdict(body, spin, std::move(v));
}

/// The closed-form part of lyapunov_stable_spin_intervals: energy-Casimir, Chetaev, the free body.
static std::vector<SpinInterval> closed_form_intervals(const Body& body) {
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

namespace {

/// The spins (rad/s) of index 2 at which the linearisation is stable, as open pieces (lo, hi)
/// (hi infinite when unbounded): where the KAM verdict applies.
std::vector<std::pair<double, double>> kam_pieces(const Body& body) {
  const double k = body.mgR(), inf = std::numeric_limits<double>::infinity();
  if (is_symmetric(body) || k == 0.0) return {};
  double lo = 0.0, hi = inf;  // in s = w0^2: c s - k < 0 for both stiffnesses
  for (double c : {difference(body.C, body.A), difference(body.C, body.B)}) {
    if (c > 0.0) {
      if (k <= 0.0) return {};
      hi = std::min(hi, k / c);
    } else if (c < 0.0) {
      lo = std::max(lo, k / c);
    } else if (k <= 0.0) {
      return {};
    }
  }
  std::vector<std::pair<double, double>> out;
  for (const SpinInterval& i : stable_spin_intervals(linear_model(LinearModelKind::Linearized, body))) {
    const double a = std::max(i.lo, std::sqrt(lo)), b = std::min(i.hi.value_or(inf), std::sqrt(hi));
    if (a < b) out.emplace_back(a, b);
  }
  return out;
}

/// The signed quantities whose zeros are KAM exceptions: D / D_scale, w1 - w2, w1 - 3 w2,
/// w2 - 3 w1 (relative to w1 + w2); nullopt where there is no normal form.
std::optional<std::array<double, 4>> kam_signs(const Body& body, double spin) {
  const auto nf = birkhoff_normal_form(body, spin);
  if (!nf) return std::nullopt;
  const double sum = nf->w1 + nf->w2;
  return std::array<double, 4>{nf->D / nf->D_scale, (nf->w1 - nf->w2) / sum, (nf->w1 - 3.0 * nf->w2) / sum,
                               (nf->w2 - 3.0 * nf->w1) / sum};
}

}  // namespace

std::vector<KamException> kam_exceptions(const Body& body) {
  validate(body);
  refuse_general(body, "the Lyapunov analysis");
  std::vector<KamException> out;
  const double natural = std::sqrt(std::abs(body.mgR()) / std::min({body.A, body.B, body.C}));
  constexpr std::string_view kWhat[] = {"D = 0", "1:1", "1:3", "1:3"};
  for (auto [a, b] : kam_pieces(body)) {
    // The grid: geometric from a to b (or to 1e4 max(a, natural) when unbounded), ends excluded.
    const double top = std::isfinite(b) ? b : 1e4 * std::max(a, natural);
    const double start = a > 0.0 ? a : 1e-4 * top;
    auto at = [&](int i) { return start * std::pow(top / start, (i + 0.5) / kKamScanPoints); };
    double w_prev = at(0);
    auto prev = kam_signs(body, w_prev);
    for (int i = 1; i < kKamScanPoints; ++i) {
      const double w = at(i);
      const auto cur = kam_signs(body, w);
      if (!cur) {
        out.push_back({w, "1:1"});  // no normal form inside a stable piece: a double frequency
      } else if (prev) {
        for (int f = 0; f < 4; ++f) {
          if (((*prev)[f] > 0.0) == ((*cur)[f] > 0.0)) continue;
          double l = w_prev, r = w, fl = (*prev)[f];
          for (int it = 0; it < 200 && l < r; ++it) {  // bisection to rounding
            const double m = 0.5 * (l + r);
            if (m <= l || m >= r) break;
            const auto sm = kam_signs(body, m);
            if (!sm) { l = r = m; break; }
            if (((*sm)[f] > 0.0) == (fl > 0.0)) l = m; else r = m;
          }
          const double root = 0.5 * (l + r);
          // At 1:3 Markeev's inequality may still hold: an exception only where it fails.
          if (f >= 2 && lyapunov_stability(body, root).verdict == LyapunovVerdictKind::Stable) continue;
          out.push_back({root, kWhat[f]});
        }
      }
      w_prev = w;
      prev = cur;
    }
  }
  std::sort(out.begin(), out.end(), [](const KamException& x, const KamException& y) { return x.spin < y.spin; });
  return out;
}

std::vector<SpinInterval> lyapunov_stable_spin_intervals(const Body& body) {
  validate(body);
  refuse_general(body, "the Lyapunov analysis");
  std::vector<SpinInterval> out = closed_form_intervals(body);
  const std::vector<KamException> exceptions = kam_exceptions(body);
  auto stable_at = [&](double w) { return lyapunov_stability(body, w).verdict == LyapunovVerdictKind::Stable; };
  for (auto [a, b] : kam_pieces(body)) {
    std::vector<double> cuts{a};
    for (const auto& e : exceptions)
      if (e.spin > a && e.spin < b) cuts.push_back(e.spin);
    cuts.push_back(b);
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (!(cuts[i] < cuts[i + 1])) continue;
      SpinInterval piece;
      piece.lo = cuts[i];
      piece.lo_included = stable_at(piece.lo);
      if (std::isfinite(cuts[i + 1])) {
        piece.hi = cuts[i + 1];
        piece.hi_included = stable_at(cuts[i + 1]);
      }
      out.push_back(piece);
    }
  }
  std::sort(out.begin(), out.end(), [](const SpinInterval& x, const SpinInterval& y) { return x.lo < y.lo; });
  // Pieces that touch at a spin proven stable are one interval.
  std::vector<SpinInterval> merged;
  for (const SpinInterval& i : out) {
    if (!merged.empty() && merged.back().hi && *merged.back().hi == i.lo &&
        (merged.back().hi_included || i.lo_included)) {
      merged.back().hi = i.hi;
      merged.back().hi_included = i.hi_included;
    } else {
      merged.push_back(i);
    }
  }
  return merged;
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
                   const Tolerances& options, const Progress& progress) {
  Wander w;
  try {
    validate(body);
    refuse_general(body, "the Lyapunov analysis");
    validate(initial);
    if (at_rest_upright(initial)) {
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
    Tolerances capped = options;
    capped.max_steps = std::min(capped.max_steps, kWanderMaxSteps);
    w.max_tilt = tilt_extremes(Integrator::Dopri5, body, initial, horizon, std::numeric_limits<double>::infinity(), capped,
                               nullptr, progress)
                    .max_tilt;
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

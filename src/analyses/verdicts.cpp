#include "heavytop/verdicts.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"

#include "integrators/integration.hpp"

namespace heavytop {
namespace {

// rad: a symmetric top whose exact largest tilt is this far below max_tilt stays up in the
// default pass too: the batch's largest tilt is the closed form's to 1e-11 rad at 1e-12 over 30
// nutation periods (tests/test_batch.cpp); the margin grows with a looser sweep tolerance
// (1e6 times it: 1e-3 rad at 1e-9), so that the default pass's own error stays far inside.
// The same number is the conserved quantities' barrier's relative allowance on E and L_zeta
// (1b): the default pass drifts them by at most 5.3e-12 relative over 50 s at 1e-12 (100 points of
// the plate's map, B/A x spin).
constexpr double kClosedFormMargin = 1e-6;
double closed_form_margin(const Tolerances& o) { return std::max(kClosedFormMargin, 1e6 * std::max(o.rtol, o.atol)); }
// rad: the loose pass's band is max_tilt -+ this (at most half of max_tilt).
constexpr double kBand = 0.05;
// The estimate's safety factor over the sum of the steps' errors.
constexpr double kSafety = 10.0;

struct Group {
  std::vector<Body> bodies;
  std::vector<InitialState> states;
  std::vector<std::size_t> index;  // where each goes in `out`
  void add(const Body& b, const InitialState& s, std::size_t i) {
    bodies.push_back(b), states.push_back(s), index.push_back(i);
  }
};

// Tilts between max_tilt and the start's at which the conserved quantities' barrier is sought.
constexpr int kBarrierPoints = 32;

}  // namespace

bool tilt_forbidden_by_conserved_quantities(const Body& body, const InitialState& initial, double max_tilt,
                                            double margin) {
  const RigidBodyState rb = initial_rigid_body_state(initial);
  const ConservedQuantities q = conserved_quantities(body, rb);
  const double u0 = rb.attitude(2, 2), u_max = std::cos(max_tilt);  // k_zeta at the start and at max_tilt
  if (!(u0 > u_max)) return false;
  const double mgr = body.mgR(), perp = std::max(body.A, body.B);
  const double l2 = q.vertical_momentum * q.vertical_momentum;
  const double allowance = margin * (std::abs(q.energy - mgr * u0) + std::abs(mgr));  // J
  for (int k = 0; k < kBarrierPoints; ++k) {
    const double u = u_max + (u0 - u_max) * k / kBarrierPoints;
    const double least_kinetic = 0.5 * l2 / (perp * (1.0 - u * u) + body.C * u * u);
    if (q.energy - mgr * u - least_kinetic < -allowance) return true;
  }
  return false;
}

void decided_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                           double max_tilt, const Tolerances& options, std::span<DecidedVerdict> out) {
  if (bodies.size() != initials.size() || bodies.size() != out.size())
    throw InvalidInput("bodies", "bodies, initial states and results must be as many");
  validate(options);
  if (!(std::isfinite(max_tilt) && max_tilt > 0.0 && max_tilt <= M_PI))
    throw InvalidInput("max_tilt", "must be in (0, pi] rad");
  const bool loose_pass = options.rtol < kLooseTolerance && options.atol < kLooseTolerance;
  const double margin = closed_form_margin(options);
  Group loose, tight;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    // 1. A symmetric top that stays up, in closed form (batch_tilt_verdicts validates the rest).
    if (b.A == b.B && batchable(b)) {
      validate(b);
      validate(initials[i]);
      LagrangeExactOptions closed;
      closed.fourier_series = false;  // the tilt's bounds only
      if (nutation_bounds(lagrange_top(b, initials[i], closed)).max_tilt < max_tilt - margin) {
        out[i] = DecidedVerdict{false, 0.0};
        continue;
      }
      tight.add(b, initials[i], i);  // near or above the threshold: a falling top's run is short
      continue;
    }
    // 1b. An asymmetric body that stays up by its energy and vertical momentum.
    if (batchable(b)) {
      validate(b);
      validate(initials[i]);
      if (tilt_forbidden_by_conserved_quantities(b, initials[i], max_tilt, margin)) {
        out[i] = DecidedVerdict{false, 0.0};
        continue;
      }
    }
    (loose_pass ? loose : tight).add(b, initials[i], i);
  }

  // 2. The loose pass with its band.
  if (!loose.bodies.empty()) {
    Tolerances o = options;
    o.rtol = o.atol = kLooseTolerance;
    const double band = std::min(kBand, 0.5 * max_tilt);
    std::vector<TiltBand> r(loose.bodies.size());
    try {
      batch_tilt_bands(loose.bodies, loose.states, horizon, max_tilt - band, max_tilt + band, o, r);
    } catch (const InvalidInput&) {
      throw;  // the default pass would refuse the same
    } catch (const std::runtime_error&) {
      // A failure of the loose run (its steps not finite, or max_steps) is not the sweep's:
      // every such point takes the default pass, whose failure is.
      for (std::size_t k = 0; k < loose.bodies.size(); ++k) tight.add(loose.bodies[k], loose.states[k], loose.index[k]);
      loose.bodies.clear();
      r.clear();
    }
    // Each step's error in the attitude's quaternion is at most atol + rtol per component
    // (|q_i| <= 1), 2 (atol + rtol) on the tilt's cosine and sine: 4 (atol + rtol) on the tilt.
    const double per_step = 4.0 * (o.atol + o.rtol);
    const double high = max_tilt + band;
    for (std::size_t k = 0; k < r.size(); ++k) {
      const TiltBand& b = r[k];
      const double tilt0 = std::max(tilt(loose.states[k].theta0, loose.states[k].phi0), 1e-6);
      const double sum = kSafety * per_step * static_cast<double>(b.steps);  // rad, the steps' errors
      bool decided = false;
      if (!b.exceeded) {
        // Stays below the band: the largest tilt's error, errors grown with the tilt, within
        // half the band.
        decided = !b.touched_low && sum * (1.0 + b.peak_tilt / tilt0) <= 0.5 * band;
      } else if (b.t_end == 0.0 || sum * (1.0 + b.peak_tilt / tilt0) <= 0.5 * band) {
        decided = true;  // above the band by more than the estimate (or tilted above it at the start)
      } else if (sum <= 10.0 * tilt0 && high > tilt0) {
        // A tilt that grew past the band from the start as an unstable rotation's does,
        // tilt0 e^(lambda t): an error of relative size rho = sum / tilt0 at the start moves its
        // crossing by ln(1 + rho) / lambda, lambda = ln(high / tilt0) / t_end. Falls if even
        // that late the crossing is within the horizon.
        const double shift = b.t_end * std::log1p(sum / tilt0) / std::log(high / tilt0);
        decided = b.t_end + shift < horizon;
      }
      if (decided) out[loose.index[k]] = DecidedVerdict{b.exceeded, o.rtol};
      else tight.add(loose.bodies[k], loose.states[k], loose.index[k]);
    }
  }

  // 3. The default pass: the sweep's own verdict.
  if (!tight.bodies.empty()) {
    std::vector<TiltVerdict> r(tight.bodies.size());
    batch_tilt_verdicts(tight.bodies, tight.states, horizon, max_tilt, options, r);
    for (std::size_t k = 0; k < r.size(); ++k) out[tight.index[k]] = DecidedVerdict{r[k].exceeded, options.rtol};
  }
}

}  // namespace heavytop

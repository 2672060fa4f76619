#include "heavytop/verdicts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"

#include "integrators/batch/points.hpp"
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
// rad: each loose step's error in the attitude's quaternion is at most atol + rtol per
// component (|q_i| <= 1), 2 (atol + rtol) on the tilt's cosine and sine: 4 (atol + rtol) on the
// tilt.
double tilt_error_per_step(const Tolerances& o) { return 4.0 * (o.atol + o.rtol); }

// Tilts between max_tilt and the start's at which the conserved quantities' barrier is sought.
constexpr int kBarrierPoints = 32;

}  // namespace

double crossing_delay_estimate(const TiltBand& band, double tilt0, double high, const Tolerances& loose) {
  // A tilt that grew past `high` from the start as an unstable rotation's does, its amplitude
  // tilt0 e^(lambda t): an error e made when the amplitude is a grows alike, as one of relative
  // size e / a at the start would, so the steps' errors add up to rho = sum of e / a
  // (TiltBand::inverse_tilt_sum), e the safety factor times the tilt's error per step. That
  // moves the crossing by ln(1 + rho) / lambda, lambda = ln(high / tilt0) / t_end. Beyond
  // rho = 10 the growth of errors is no longer the start's.
  const double rho = kSafety * tilt_error_per_step(loose) * band.inverse_tilt_sum;
  if (!band.exceeded || !(rho <= 10.0) || !(high > tilt0) || !(tilt0 > 0.0))
    return std::numeric_limits<double>::infinity();
  return band.t_end * std::log1p(rho) / std::log(high / tilt0);
}

namespace {

// tilt_forbidden_by_conserved_quantities from the initial rigid-body state.
bool forbidden(const Body& body, const RigidBodyState& rb, double max_tilt, double margin) {
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

}  // namespace

bool tilt_forbidden_by_conserved_quantities(const Body& body, const InitialState& initial, double max_tilt,
                                            double margin) {
  return forbidden(body, initial_rigid_body_state(initial), max_tilt, margin);
}

void decided_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                           double max_tilt, const Tolerances& options, std::span<DecidedVerdict> out) {
  if (bodies.size() != initials.size() || bodies.size() != out.size())
    throw InvalidInput("bodies", "bodies, initial states and results must be as many");
  validate(options);
  if (!(std::isfinite(max_tilt) && max_tilt > 0.0 && max_tilt <= M_PI))
    throw InvalidInput("max_tilt", "must be in (0, pi] rad");
  detail::check_run(horizon, max_tilt, options, best_batch_isa());
  const bool loose_pass = options.rtol < kLooseTolerance && options.atol < kLooseTolerance;
  const double margin = closed_form_margin(options);
  // Each point validated and prepared once; the passes hold its batch point (no copies of bodies).
  detail::BatchPoints loose, tight;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    validate(b);
    validate(initials[i]);
    // 1. A symmetric top that stays up, in closed form.
    if (b.A == b.B && batchable(b)) {
      LagrangeExactOptions closed;
      closed.fourier_series = false;  // the tilt's bounds only
      if (nutation_bounds(lagrange_top(b, initials[i], closed)).max_tilt < max_tilt - margin) {
        out[i] = DecidedVerdict{false, 0.0};
        continue;
      }
      // near or above the threshold: a falling top's run is short
      tight.add(detail::batch_point(b, initial_rigid_body_state(initials[i]), i));
      continue;
    }
    const RigidBodyState rb = initial_rigid_body_state(initials[i]);
    // 1b. An asymmetric body that stays up by its energy and vertical momentum.
    if (batchable(b) && forbidden(b, rb, max_tilt, margin)) {
      out[i] = DecidedVerdict{false, 0.0};
      continue;
    }
    (loose_pass ? loose : tight).add(detail::batch_point(b, rb, i));  // refuses a body the batch cannot run
  }
  std::vector<detail::BatchResult> results(bodies.size());

  // 2. The loose pass with its band (its points are all plain: symmetric tops go to 1 or 3).
  if (!loose.plain.empty()) {
    Tolerances o = options;
    o.rtol = o.atol = kLooseTolerance;
    const double band = std::min(kBand, 0.5 * max_tilt);
    try {
      detail::run_batch(loose, horizon, max_tilt + band, max_tilt - band, o, best_batch_isa(), false, results.data());
    } catch (const InvalidInput&) {
      throw;  // the default pass would refuse the same
    } catch (const std::runtime_error&) {
      // A failure of the loose run (its steps not finite, or max_steps) is not the sweep's:
      // every such point takes the default pass, whose failure is.
      for (const detail::BatchPoint& p : loose.plain) tight.add(p);
      loose.plain.clear();
    }
    const double per_step = tilt_error_per_step(o);
    const double high = max_tilt + band;
    for (const detail::BatchPoint& p : loose.plain) {
      const TiltBand b = detail::tilt_band(results[p.index]);
      const double tilt0 = std::max(p.tilt0, 1e-6);
      const double sum = kSafety * per_step * static_cast<double>(b.steps);  // rad, the steps' errors
      bool decided = false;
      if (!b.exceeded) {
        // Stays below the band: the largest tilt's error, errors grown with the tilt, within
        // half the band.
        decided = !b.touched_low && sum * (1.0 + b.peak_tilt / tilt0) <= 0.5 * band;
      } else if (b.t_end == 0.0 || sum * (1.0 + b.peak_tilt / tilt0) <= 0.5 * band) {
        decided = true;  // above the band by more than the estimate (or tilted above it at the start)
      } else {
        decided = b.t_end + crossing_delay_estimate(b, tilt0, high, o) < horizon;  // falls even that late
      }
      if (decided) out[p.index] = DecidedVerdict{b.exceeded, o.rtol};
      else tight.add(p);
    }
  }

  // 3. The default pass: the sweep's own verdict (batch_tilt_verdicts' bits).
  if (tight.size() > 0) {
    detail::run_batch(tight, horizon, max_tilt, 0.0, options, best_batch_isa(), false, results.data());
    for (const auto* set : {&tight.symmetric, &tight.plain})
      for (const detail::BatchPoint& p : *set) out[p.index] = DecidedVerdict{results[p.index].exceeded, options.rtol};
  }
}

}  // namespace heavytop

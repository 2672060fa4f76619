#pragma once
/// \file
/// A sweep's nonlinear verdicts ("does the tilt stay <= max_tilt over [0, horizon]?") each at
/// the tolerance that decides it (issue 31).
///
/// The verdict a sweep promises is batch_tilt_verdicts()' at the sweep's tolerance (the
/// "default pass", 1e-12 unless --rtol/--atol say otherwise). Most points of a map are far from
/// the threshold, where a much cheaper computation gives the same verdict (docs/performance.md,
/// "Verdicts at the tolerance that decides them"):
///   1. a symmetric top (A == B) whose largest tilt in closed form (lagrange-exact's nutation
///      bounds, exact for the motion the integrators approximate) lies more than 1e-6 rad
///      below max_tilt (1e6 times the sweep's tolerance if that is more) stays up: no
///      integration at all;
///   1b. an asymmetric conservative body whose energy E and vertical momentum L_zeta forbid its
///      axis from ever reaching max_tilt (tilt_forbidden_by_conserved_quantities below, a
///      proof for the exact motion, with the same margin) stays up: no integration either;
///   2. every other point is integrated once at a loose tolerance (kLooseTolerance) with a band
///      [max_tilt - band, max_tilt + band] around the threshold (batch_tilt_bands). The
///      tolerance bounds each step's error (the series' remainder: the last two terms are at
///      most atol + rtol |x| by the choice of the step), so the largest tilt's error is
///      estimated as safety x (steps x per-step error) x (1 + peak / initial tilt), the last
///      factor for errors that grow with the tilt (an unstable upright rotation). A point
///      whose run stays below the band, or passes above it, with that estimate below half the
///      band is decided there; so is a fall whose crossing, delayed by the errors' growth
///      (crossing_delay_estimate: each step's error weighed against the tilt's amplitude
///      then), still comes before the horizon;
///   3. the rest (within the band, or whose estimate is too large) take the default pass, and
///      their verdicts are batch_tilt_verdicts()' bits.
/// Verdicts equal the default pass's on every example map and on a map built with many points
/// near the threshold (tests/test_verdicts.cpp); the decision rule is an estimate, not a
/// proof, which those tests check.

#include <cstddef>
#include <span>

#include "heavytop/batch.hpp"
#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// rtol = atol of the loose pass (dimensionless); a sweep whose own tolerance is as loose or
/// looser has no loose pass.
inline constexpr double kLooseTolerance = 1e-6;

/// One point's nonlinear verdict and what decided it.
struct DecidedVerdict {
  bool exceeded = false;  ///< the tilt passed max_tilt within the horizon
  /// The rtol (dimensionless) of the integration that decided it: kLooseTolerance (the loose
  /// pass) or options.rtol (the default pass: batch_tilt_verdicts' verdict); 0 without
  /// integration (a body that stays up by the closed form or by the conserved quantities,
  /// steps 1 and 1b above).
  double tolerance = 0.0;
};

/// True when the conservative body's energy E and vertical momentum L_zeta from `initial`
/// forbid its axis from ever reaching the tilt `max_tilt` (rad): some tilt between the start's
/// and max_tilt is one no state with that E and L_zeta has, with a relative margin `margin`
/// (dimensionless, >= 0). Why (docs/performance.md, "The conserved quantities' barrier"): at
/// k_zeta = u the kinetic energy is E - m g R u, and the least kinetic energy with
/// (I w).gamma = L_zeta is L_zeta^2 / (2 gamma.I gamma) >= L_zeta^2 / (2 D(u)), D(u) =
/// max(A, B) (1 - u^2) + C u^2. So g(u) = E - m g R u - L_zeta^2 / (2 D(u)) >= 0 wherever the
/// axis can be, and the axis, moving continuously from the start, never passes a u with
/// g(u) < 0. Tested at 32 tilts from max_tilt to the start's; a u counts when g(u) < -margin
/// (|E - m g R u0| + |m g R|), which holds against any drift of E and L_zeta smaller than that.
/// For a fast spin about the axis of greatest moment this decides exactly the superfast spins
/// ((C - max(A, B)) w^2 > m g R, the energy-Casimir region), the bound on the tilt being about
/// tilt0 sqrt((C w^2 - m g R) / ((C - max(A, B)) w^2 - m g R)). Ignores damping and a general
/// body's terms: call it for a conservative batchable() body.
bool tilt_forbidden_by_conserved_quantities(const Body& body, const InitialState& initial, double max_tilt,
                                            double margin);

/// s: how much later than `band.t_end` the exact motion's tilt may cross `band`'s top `high`
/// (rad), estimated from a loose run's band (tolerances `loose`) whose tilt grew past it from
/// `tilt0` (rad, the start's) as an unstable rotation's does: the steps' errors, each weighed
/// against the tilt's amplitude when it was made (TiltBand::inverse_tilt_sum), grow with the
/// motion and delay or advance its crossing. +infinity where the estimate does not apply (the
/// band not exceeded, or errors of more than 10 times the amplitude). An estimate, not a bound:
/// tests/test_verdicts.cpp measures it against the crossing at 1e-12.
double crossing_delay_estimate(const TiltBand& band, double tilt0, double high, const Tolerances& loose);

/// The verdicts of batch_tilt_verdicts(bodies, initials, horizon, max_tilt, options) (its
/// `exceeded`), each computed as the file comment says, into out[i]. Every body must be
/// batchable(); same units, keys and failures as batch_tilt_verdicts. max_tilt rad in (0, pi].
void decided_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                           double max_tilt, const Tolerances& options, std::span<DecidedVerdict> out);

}  // namespace heavytop

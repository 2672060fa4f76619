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
///   2. every other point is integrated once at a loose tolerance (kLooseTolerance) with a band
///      [max_tilt - band, max_tilt + band] around the threshold (batch_tilt_bands). The
///      tolerance bounds each step's error (the series' remainder: the last two terms are at
///      most atol + rtol |x| by the choice of the step), so the largest tilt's error is
///      estimated as safety x (steps x per-step error) x (1 + peak / initial tilt), the last
///      factor for errors that grow with the tilt (an unstable upright rotation). A point
///      whose run stays below the band, or passes above it, with that estimate below half the
///      band is decided there;
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
  /// pass) or options.rtol (the default pass: batch_tilt_verdicts' verdict); 0 for the closed
  /// form (a symmetric top that stays up, step 1 above).
  double tolerance = 0.0;
};

/// The verdicts of batch_tilt_verdicts(bodies, initials, horizon, max_tilt, options) (its
/// `exceeded`), each computed as the file comment says, into out[i]. Every body must be
/// batchable(); same units, keys and failures as batch_tilt_verdicts. max_tilt rad in (0, pi].
void decided_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                           double max_tilt, const Tolerances& options, std::span<DecidedVerdict> out);

}  // namespace heavytop

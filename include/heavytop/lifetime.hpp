#pragma once
/// \file
/// How long a top stays up (SPEC section 8): its spin's decay to the critical spin (closed
/// form, damping.hpp) and the nonlinear run to the fall, with the torques of SPEC section 6.

#include <optional>
#include <string>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// Settings of lifetime().
struct LifetimeOptions {
  /// s, how long the nonlinear run may go (finite, > 0); nullopt: 10 times the time to the
  /// critical spin, or kDefaultLifetimeHorizon when that is null or 0.
  std::optional<double> horizon;
  /// rad, the tilt from the upward vertical past which the top has fallen (in (0, pi]).
  double max_tilt = 1.0;
  Tolerances integrator;  ///< the adaptive integrator's settings
  /// Which integrator runs the body (any but the splitting, through simulate.hpp's one
  /// dispatch); dopri5 by default, as the command line's `lifetime` has always run.
  Integrator method = Integrator::Dopri5;

  /// True if every setting is in range; else false and a one-line "key: rule" in `why`
  /// (key "horizon", "max_tilt", or the integrator's).
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput for the first setting out of range (LifetimeOptions::IsValid's keys).
void validate(const LifetimeOptions& options);

/// s, the horizon when neither the options nor the spin law give one (SPEC section 8).
inline constexpr double kDefaultLifetimeHorizon = 1000.0;

/// What lifetime() found.
struct Lifetime {
  /// rad/s, the critical spin of the `linearized` model of the body without damping (the lo
  /// of its unbounded interval of stable spins; 0: stable at every spin; nullopt: no spin).
  std::optional<double> critical_spin;
  /// s, when the spin law C w' = -d_a w - tau0 sign(w) brings |spin| down to the critical
  /// spin: 0 when it is there already; nullopt if never, for a driven body, or when the body
  /// is stable at every spin (critical 0) or at none. Exact for A = B; for A != B the law
  /// ignores the gyroscopic torque (A - B) w1 w2 (`law_exact` false).
  std::optional<double> time_to_critical;
  bool law_exact = true;
  /// s, the first time the nonlinear body's tilt passes max_tilt (located on the dense
  /// output); nullopt when it does not within the horizon.
  std::optional<double> fall_time;
  /// rad/s, the integrated w.k at the fall (nullopt with fall_time).
  std::optional<double> fall_spin;
  /// rad, the threshold used: LifetimeOptions::max_tilt, or past a start at or beyond it
  /// halfway from the start to upside down (fall_tilt(), nonlinear.hpp)
  double max_tilt = 1.0;
  double limit_given = 1.0;  ///< rad, LifetimeOptions::max_tilt
  double horizon = 0.0;   ///< s, the horizon used
  double largest_tilt = 0.0;  ///< rad, the largest tilt seen (the fall's threshold if it fell)
  NonlinearSummary summary;   ///< what the nonlinear run did
};

/// The closed-form part of lifetime(), no integration: critical_spin, time_to_critical,
/// law_exact, max_tilt and the horizon the run will use. Throws like lifetime().
Lifetime spin_decay(const Body& body, const InitialState& initial, const LifetimeOptions& options = {});

/// The lifetime of `body` (with its damping) started in `initial`. Throws InvalidInput for a
/// bad body, state or options; std::runtime_error if the integration fails; what `progress`
/// (the tilt scan's, progress.hpp) throws.
Lifetime lifetime(const Body& body, const InitialState& initial, const LifetimeOptions& options = {},
                  const Progress& progress = {});

}  // namespace heavytop

#pragma once
/// \file
/// The answer a person asks first (SPEC section 14): does the top stay up, and for how long?
/// One verdict from the analyses that decide it: the Lyapunov verdict for the conservative
/// body, the nonlinear motion from the given state when that verdict does not prove it, and the
/// lifetime (SPEC section 8) for a damped body. The numbers only; io/ puts them into words.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// SPEC section 14's three answers.
enum class AnswerVerdict {
  StaysUp,            ///< "stays up": proven (the Lyapunov verdict is stable)
  Falls,              ///< "falls": the computed nonlinear motion tilts past max_tilt
  StaysUpForHorizon,  ///< "stays up for the horizon": it did not fall in the run, not proven
  TurnsOver,          ///< "turns over": on a table, the tilt passes pi/2 (a tippe top; SPEC 16)
  LeavesTable,        ///< "leaves the table": on a table, the normal force reaches 0 (SPEC 16)
};
/// "stays up" | "falls" | "stays up for the horizon" | "turns over" | "leaves the table".
std::string_view name(AnswerVerdict verdict);

/// Why the answer is what it is (for the words; not part of the JSON).
enum class AnswerCase {
  ProvenStable,        ///< Lyapunov stable at the spin
  FallsConservative,   ///< not proven stable, and the nonlinear run falls
  BalancedUnstable,    ///< exactly upright and at rest transversely, but the upright is unstable
  NotFallen,           ///< not proven stable and it did not fall in the run
  FallsDamped,         ///< damped: the lifetime's run falls
  OutlivesHorizon,     ///< damped: it did not fall within the lifetime's horizon
  /// damped, exactly upright and at rest transversely: it never tilts in the computation, but its
  /// spin falls below the critical spin at Answer::time_to_critical, from when any push topples it
  BalancedDamped,
  RunStopped,          ///< its motion could not be computed to the horizon (Answer::stopped says why, Answer::horizon how far it got); nothing claimed
};

/// Settings of answer_question().
struct AnswerOptions {
  /// s, the conservative body's nonlinear run (finite, > 0): `stability --horizon`.
  double horizon = 100.0;
  /// rad, the tilt from the upward vertical past which the top has fallen (in (0, pi]).
  double max_tilt = 1.0;
  /// s, the damped body's run (lifetime()'s horizon); nullopt: lifetime()'s default.
  std::optional<double> damped_horizon;
  Tolerances integrator;  ///< the nonlinear run's tolerances
  /// True if every setting is in range; else false and "key: rule" in `why` (key "horizon",
  /// "max_tilt" or "lifetime_horizon").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput for the first setting out of range (AnswerOptions::IsValid's keys, then
/// the integrator's tolerances').
void validate(const AnswerOptions& options);

/// The answer (SPEC section 14's `answer` object, and what the words need).
struct Answer {
  AnswerVerdict verdict = AnswerVerdict::StaysUpForHorizon;
  AnswerCase why = AnswerCase::NotFallen;
  bool proven = false;  ///< true for a Lyapunov proof or a computed fall
  double spin = 0.0;    ///< rad/s, the spin asked about (w0)
  double start_tilt = 0.0;  ///< rad, the tilt at t = 0
  /// rad, the largest tilt: the wander (SPEC 7) when proven stable, else the run's largest
  /// tilt (at the fall, the threshold's crossing); nullopt when it could not be computed.
  std::optional<double> max_tilt;
  /// rad, the tilt past which it has fallen: fall_tilt(start_tilt, AnswerOptions::max_tilt),
  /// the limit given or, for a start at or beyond it, halfway from the start to upside down
  double fall_threshold = 1.0;
  double limit_given = 1.0;         ///< rad, AnswerOptions::max_tilt
  std::optional<double> falls_at;   ///< s, the first time the tilt passes fall_threshold
  std::optional<double> fall_spin;  ///< rad/s, w.k at falls_at
  double horizon = 0.0;             ///< s, the horizon of the run that decided (or would have)
  /// rad/s, the smallest of the spins proven stable (Lyapunov), nullopt when none.
  std::optional<double> min_spin;
  /// false when min_spin itself is not stable (the interval is open there: a body without
  /// gravity is stable at every spin > 0, but at rest any push turns its axis away)
  bool min_spin_included = true;
  /// true when every spin below min_spin is unstable (a symmetric top's sharp threshold C^2 w0^2
  /// = 4 A m g R: "below it, it would fall"); false when below it stability is only unproven.
  bool falls_below_min_spin = false;
  std::optional<double> lifetime;   ///< s, a damped body's fall time (= falls_at), else nullopt
  /// true when the proof holds for disturbances small enough only, with no size given (a KAM
  /// certificate, SPEC 7): the words say so.
  bool small_disturbances_only = false;
  bool damped = false;              ///< the damping (SPEC 6) was taken into account
  bool hanging = false;             ///< the centre of mass is below the pivot (length < 0)
  /// rad/s, for a damped body: the critical spin its spin decays to (lifetime's), nullopt else.
  std::optional<double> critical_spin;
  /// s, for a damped body: when its spin law brings the spin down to critical_spin (lifetime's
  /// time_to_critical), nullopt if never.
  std::optional<double> time_to_critical;
  /// Why the deciding run stopped before its horizon (AnswerCase::RunStopped; the integrator's
  /// one-line failure, e.g. too many steps for damping this strong), empty otherwise.
  std::string stopped;
};

/// The answer for `body` started in `initial`, from the Lyapunov analysis at the spin and the
/// wander (what `stability` computes, passed in so it is computed once) and, where they do not
/// decide, a nonlinear run: tilt_extremes over options.horizon for the conservative body,
/// lifetime() for a damped one. Throws InvalidInput for bad options (a horizon beyond
/// longest_meaningful_time() among them: key "horizon", or "lifetime_horizon" for the damped
/// body's); never throws for a run that cannot go on (RunFailure: the answer is then "stays up
/// for the horizon", AnswerCase::RunStopped, max_tilt empty and horizon the time it reached, its
/// words saying that nothing was decided and why).
/// `progress` (progress.hpp) is the deciding run's: it gets the simulated time (s) and may throw
/// to stop it (Python's Ctrl-C), the exception let through.
/// `life`, when given, gets the damped body's lifetime() run (left empty when it stops).
Answer answer_question(const Body& body, const InitialState& initial, const LyapunovStability& lyapunov,
                       const Wander& wander, const AnswerOptions& options = {}, const Progress& progress = {},
                       std::optional<Lifetime>* life = nullptr);

/// Everything `heavytop stability` says, computed once for the command line, the report and
/// Python alike: the linear models, the Lyapunov verdict, the wander and the answer.
struct TopAnalysis {
  double spin = 0.0;                     ///< rad/s, w0
  std::vector<ModelStability> models;    ///< analyse_stability(body, spin)
  LyapunovStability lyapunov;            ///< analyse_lyapunov(body, spin)
  Wander wander;                         ///< axis_wander(body, initial, options.horizon)
  Answer answer;                         ///< answer_question(...)
  /// A damped body's lifetime() run, the one the answer used (AnswerOptions' horizon, max_tilt
  /// and tolerances; the default options give lifetime()'s defaults); nullopt for a conservative
  /// body or when that run stopped (AnswerCase::RunStopped).
  std::optional<Lifetime> lifetime;
};
/// The analyses of `body` at the spin of `initial` and the answer; throws InvalidInput for a
/// bad body, state or options. `progress` is answer_question()'s.
TopAnalysis analyse_top(const Body& body, const InitialState& initial, const AnswerOptions& options = {},
                        const Progress& progress = {});

/// s, how long the run that decides the answer will be at most (the conservative body's
/// options.horizon, the damped body's lifetime horizon), for a progress bar; 0 when the options
/// or the body are refused (the analysis then says why).
double answer_run_length(const Body& body, const InitialState& initial, const AnswerOptions& options);

}  // namespace heavytop

#include "heavytop/answer.hpp"
#include "heavytop/simulate.hpp"

#include <cmath>
#include <exception>
#include <numbers>

#include "heavytop/frames.hpp"

#include "integrators/integration.hpp"

namespace heavytop {
namespace {

detail::Violation first_violation(const AnswerOptions& o) {
  if (!(std::isfinite(o.horizon) && o.horizon > 0.0)) return std::pair{"horizon", "must be a finite number > 0"};
  if (!(o.max_tilt > 0.0 && o.max_tilt <= std::numbers::pi)) return std::pair{"max_tilt", "must be in (0, pi]"};
  if (o.damped_horizon && !(std::isfinite(*o.damped_horizon) && *o.damped_horizon > 0.0))
    return std::pair{"lifetime_horizon", "must be a finite number > 0"};
  return std::nullopt;
}

/// The smallest spin proven stable, and whether every spin below it is unstable: proven for a
/// symmetric top, whose threshold C^2 w0^2 = 4 A m g R is sharp (below it the linearisation
/// grows at every spin); for A != B spins below may be stable without proof, so nothing is claimed.
void spin_threshold(const Body& body, const LyapunovStability& lyapunov, Answer& a) {
  if (lyapunov.intervals.empty()) return;
  a.min_spin = lyapunov.intervals.front().lo;
  a.min_spin_included = lyapunov.intervals.front().lo_included;
  if (*a.min_spin <= 0.0 || !is_symmetric(body) || !(body.mgR() > 0.0)) return;
  // Just below the end (a root of the closed form, exact to rounding), where the verdict is
  // no longer the boundary's.
  const double below = *a.min_spin * (1.0 - 1e-6);
  a.falls_below_min_spin = lyapunov_stability(body, below).verdict == LyapunovVerdictKind::Unstable;
}

/// The damped body's run (SPEC 14: the lifetime decides) with the answer's settings.
LifetimeOptions lifetime_options(const AnswerOptions& options) {
  LifetimeOptions life;
  life.horizon = options.damped_horizon;
  life.max_tilt = options.max_tilt;
  life.integrator = options.integrator;
  return life;
}

/// lifetime() for the answer: its horizon is the answer's "lifetime_horizon" (`stability
/// --lifetime-horizon`), so a refused one is named so, not "horizon" (the conservative run's).
Lifetime lifetime_named(const Body& body, const InitialState& initial, const LifetimeOptions& options,
                        const Progress& progress) {
  try {
    return lifetime(body, initial, options, progress);
  } catch (const InvalidInput& e) {
    if (e.key() == "horizon") throw InvalidInput("lifetime_horizon", e.rule());
    throw;
  }
}

/// The run that decides could not go on: nothing is claimed, the horizon is how far it got, and
/// the words say why (AnswerCase::RunStopped).
void stopped(const RunFailure& failure, Answer& a) {
  a.verdict = AnswerVerdict::StaysUpForHorizon;
  a.why = AnswerCase::RunStopped;
  a.horizon = failure.reached();
  a.max_tilt.reset();
  a.stopped = failure.what();
}

}  // namespace

std::string_view name(AnswerVerdict verdict) {
  switch (verdict) {
    case AnswerVerdict::StaysUp: return "stays up";
    case AnswerVerdict::Falls: return "falls";
    case AnswerVerdict::TurnsOver: return "turns over";
    case AnswerVerdict::LeavesTable: return "leaves the table";
    case AnswerVerdict::StaysUpForHorizon: break;
  }
  return "stays up for the horizon";
}

bool AnswerOptions::IsValid(std::string* why) const {
  return detail::is_valid(first_violation(*this), why) && integrator.IsValid(why);
}

void validate(const AnswerOptions& options) {
  detail::throw_if_invalid(first_violation(options));
  validate(options.integrator);
}

Answer answer_question(const Body& body, const InitialState& initial, const LyapunovStability& lyapunov,
                       const Wander& wander, const AnswerOptions& options, const Progress& progress,
                       std::optional<Lifetime>* life_out) {
  validate(options);
  Answer a;
  a.spin = initial.spin;
  a.start_tilt = tilt(initial.theta0, initial.phi0);
  a.fall_threshold = fall_tilt(a.start_tilt, options.max_tilt);
  a.limit_given = options.max_tilt;
  a.horizon = options.horizon;
  a.hanging = body.length < 0.0;
  a.damped = !body.damping.conservative();
  spin_threshold(body, lyapunov, a);

  if (a.damped) {  // SPEC 14: the lifetime (SPEC 8) decides
    const LifetimeOptions life_options = lifetime_options(options);
    try {
      const Lifetime life = lifetime_named(body, initial, life_options, progress);
      a.horizon = life.horizon;
      a.critical_spin = life.critical_spin;
      a.max_tilt = life.largest_tilt;
      if (life.fall_time) {
        a.verdict = AnswerVerdict::Falls;
        a.why = AnswerCase::FallsDamped;
        a.proven = true;
        a.falls_at = a.lifetime = life.fall_time;
        a.fall_spin = life.fall_spin;
      } else {
        a.verdict = AnswerVerdict::StaysUpForHorizon;
        a.why = AnswerCase::OutlivesHorizon;
        // Exactly upright it never tilts, however slowly it spins: an unstable equilibrium once
        // the spin is below the critical spin, which the words must say.
        if (at_rest_upright(initial) && life.time_to_critical && *life.time_to_critical < a.horizon)
          a.why = AnswerCase::BalancedDamped;
      }
      a.time_to_critical = life.time_to_critical;
      if (life_out) *life_out = life;
    } catch (const RunFailure& e) {
      stopped(e, a);
    }
    return a;
  }

  // The proof bounds the tilt by the wander: it proves no fall only where that bound is short
  // of the fall's tilt (a start upside down, or a slow stable spin that wanders past the limit,
  // is followed instead).
  if (lyapunov.verdict.verdict == LyapunovVerdictKind::Stable && (!wander.max_tilt || *wander.max_tilt < a.fall_threshold)) {
    a.verdict = AnswerVerdict::StaysUp;
    a.why = AnswerCase::ProvenStable;
    a.proven = true;
    a.max_tilt = wander.max_tilt;
    a.small_disturbances_only = lyapunov.verdict.certificate == LyapunovCertificate::Kam ||
                                lyapunov.verdict.certificate == LyapunovCertificate::KamMarkeev;
    return a;
  }
  a.verdict = AnswerVerdict::StaysUpForHorizon;
  if (at_rest_upright(initial)) {  // an exact permanent rotation: it never tilts, however unstable
    a.why = lyapunov.verdict.verdict == LyapunovVerdictKind::Unstable ? AnswerCase::BalancedUnstable
                                                                      : AnswerCase::NotFallen;
    a.max_tilt = 0.0;
    return a;
  }
  a.why = AnswerCase::NotFallen;
  // A horizon a double cannot resolve is refused before the run (1e300 s ran until max_steps
  // gave up), only here: where no run is needed it does no harm (a spin of 1e19 rad/s is proven).
  validate_horizon(body, initial, options.horizon, "horizon");
  try {
    const TiltExtremes run =
        tilt_extremes(Integrator::Dopri5, body, initial, options.horizon, a.fall_threshold, options.integrator,
                      nullptr, progress);
    a.max_tilt = run.max_tilt;
    if (run.exceeded) {
      a.verdict = AnswerVerdict::Falls;
      a.why = AnswerCase::FallsConservative;
      a.proven = true;
      a.falls_at = run.t_end;
      a.fall_spin = run.spin_at_end;
    }
  } catch (const RunFailure& e) {
    stopped(e, a);
  }
  return a;
}

TopAnalysis analyse_top(const Body& body, const InitialState& initial, const AnswerOptions& options,
                        const Progress& progress) {
  validate(initial);
  validate(options);
  TopAnalysis t;
  t.spin = initial.spin;
  t.models = analyse_stability(body, initial.spin);
  t.lyapunov = analyse_lyapunov(body, initial.spin);
  t.wander = axis_wander(body, initial, options.horizon, options.integrator, progress);
  t.answer = answer_question(body, initial, t.lyapunov, t.wander, options, progress, &t.lifetime);
  return t;
}

double answer_run_length(const Body& body, const InitialState& initial, const AnswerOptions& options) {
  if (body.damping.conservative()) return options.horizon;
  try {
    return spin_decay(body, initial, lifetime_options(options)).horizon;
  } catch (const InvalidInput&) {
    return 0.0;
  }
}

}  // namespace heavytop

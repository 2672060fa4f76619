// The answer (SPEC section 14) in plain words: the first thing `stability`, the report and
// Python's repr say. Spins in rad/s and rpm, angles in degrees and rad, times in seconds.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "heavytop/io/formats.hpp"
#include "heavytop/units.hpp"

namespace heavytop::io {
namespace {

std::string spin_words(double w) {
  const double rpm = rpm_from_rad_per_s(w);
  return fmt::format("{:.4g} rad/s ({} rpm)", w, std::abs(rpm) >= 100.0 ? fmt::format("{:.0f}", rpm)
                                                                          : fmt::format("{:.3g}", rpm));
}

std::string angle_words(double rad) {
  return fmt::format("{:.3g} degrees ({:.3g} rad)", rad * 180.0 / std::numbers::pi, rad);
}

/// rad, a start tilt past which the words describe the motion rather than the upright spin.
constexpr double kFarFromVertical = 0.5;

std::string time_words(double s) { return fmt::format("{:.4g} s", s); }

/// "this hanging body" with the centre of mass below the pivot, else "this top".
std::string noun(const Answer& a) { return a.hanging ? "this hanging body" : "this top"; }

std::string start_words(const Answer& a) {
  return a.start_tilt == 0.0 ? "started upright" : fmt::format("started {} off vertical", angle_words(a.start_tilt));
}

}  // namespace

namespace {

/// What a fall means for a start at or beyond the limit given (fall_tilt()), else "".
std::string limit_words(const Answer& a) {
  if (a.fall_threshold == a.limit_given) return "";
  if (a.start_tilt >= std::numbers::pi * (1.0 - 1e-12))
    return "It started upside down, below its pivot: it has no further to fall. ";
  return fmt::format("It started beyond the {} limit of a fall, so a fall here is a tilt past {}, halfway from its "
                     "start to upside down. ",
                     angle_words(a.limit_given), angle_words(a.fall_threshold));
}

std::string spin_advice(const Answer& a) {
  if (a.why == AnswerCase::RunStopped && a.damped) {  // no lifetime run: what the conservative analysis says
    if (!a.min_spin) return "Without damping no spin is proven to hold it up.";
    return a.falls_below_min_spin
               ? fmt::format("Without damping it needs at least {} to stay up (the critical spin).", spin_words(*a.min_spin))
               : fmt::format("Without damping it is proven stable from {} up.", spin_words(*a.min_spin));
  }
  if (a.damped) {
    if (a.critical_spin && *a.critical_spin > 0.0)
      return fmt::format("Without damping it needs at least {} to stay up (the critical spin).",
                         spin_words(*a.critical_spin));
    if (a.critical_spin) return "Without damping it would stay up at every spin.";
    return "No spin holds it up, even without damping.";
  }
  if (!a.min_spin) return "No spin is proven to hold it up.";
  if (*a.min_spin == 0.0 && !a.min_spin_included)
    return "It is stable at every spin above 0; at rest it is not (any push turns its axis away for good).";
  if (*a.min_spin == 0.0) return a.hanging ? "It hangs stably at every spin, even at rest." : "It is stable at every spin.";
  if (a.verdict == AnswerVerdict::StaysUp)
    return a.falls_below_min_spin ? fmt::format("Below {} it would fall.", spin_words(*a.min_spin))
                                  : fmt::format("Below {} its stability is not proven.", spin_words(*a.min_spin));
  return a.falls_below_min_spin ? fmt::format("It needs at least {} to stay up.", spin_words(*a.min_spin))
                                : fmt::format("From {} up it is proven stable.", spin_words(*a.min_spin));
}

}  // namespace

std::string answer_advice(const Answer& a) { return limit_words(a) + spin_advice(a); }

std::string answer_headline(const Answer& a) {
  switch (a.why) {
    case AnswerCase::ProvenStable: return a.hanging ? "Hangs steadily." : "Stays up.";
    case AnswerCase::FallsConservative: return "Falls.";
    case AnswerCase::FallsDamped: return fmt::format("Falls after {}.", time_words(a.falls_at.value_or(0.0)));
    case AnswerCase::BalancedUnstable:
    case AnswerCase::BalancedDamped:
      return fmt::format("Stays up for the {} computed, but only because it starts exactly upright.",
                         time_words(a.horizon));
    case AnswerCase::RunStopped: return "Not decided.";
    case AnswerCase::NotFallen:
    case AnswerCase::OutlivesHorizon: break;
  }
  return fmt::format("Stays up for the {} computed (not proven beyond).", time_words(a.horizon));
}

std::string answer_reason(const Answer& a) {
  const std::string body = noun(a);
  const std::string fall = fmt::format("{} from vertical", angle_words(a.fall_threshold));
  switch (a.why) {
    case AnswerCase::ProvenStable: {
      // Started far from the vertical (a classroom gyroscope, axle level), the proof is about the
      // upright spin; what the person sees is this motion's own largest tilt.
      if (a.start_tilt > kFarFromVertical && a.max_tilt)
        return fmt::format("Spinning at {} and {}, {} keeps its axis within {} of vertical; its upright spin is "
                           "proven stable.",
                           spin_words(a.spin), start_words(a), body, angle_words(*a.max_tilt));
      std::string s = fmt::format("Spinning at {} {} is proven stable{}", spin_words(a.spin), body,
                                  a.small_disturbances_only ? " against small enough disturbances (Arnold's theorem)"
                                                            : "");
      if (a.max_tilt) s += fmt::format("; its axis stays within {} of vertical", angle_words(*a.max_tilt));
      return s + ".";
    }
    case AnswerCase::FallsConservative:
      return fmt::format("Spinning at {}, {}, {} tilts past {} at t = {}.", spin_words(a.spin), start_words(a), body,
                         fall, time_words(a.falls_at.value_or(0.0)));
    case AnswerCase::BalancedUnstable:
      return fmt::format("Spinning at {} exactly upright, {} stays balanced in the computation, but its upright "
                         "spin is unstable: the slightest disturbance makes it fall.",
                         spin_words(a.spin), body);
    case AnswerCase::BalancedDamped:
      return fmt::format("With its damping, spinning at {} exactly upright, {} stays balanced in the computation, "
                         "but {}: from then on its upright spin is unstable and the slightest disturbance makes it "
                         "fall.",
                         spin_words(a.spin), body,
                         a.time_to_critical.value_or(0.0) > 0.0
                             ? fmt::format("its spin falls below the critical spin at t = {}",
                                           time_words(*a.time_to_critical))
                             : std::string("it spins below the critical spin from the start"));
    case AnswerCase::NotFallen: {
      std::string s = fmt::format("Spinning at {}, {}, {} ", spin_words(a.spin), start_words(a), body);
      s += a.max_tilt ? fmt::format("stayed within {} of vertical over the {} computed", angle_words(*a.max_tilt),
                                    time_words(a.horizon))
                      : fmt::format("could not be followed over the {} asked", time_words(a.horizon));
      return s + ", but its stability is not proven, so it may still fall later.";
    }
    case AnswerCase::FallsDamped:
      // "slows" only where the spin did slow (axial damping, friction); transverse damping alone
      // leaves it and makes the axis fall (Kelvin-Tait-Chetaev).
      return fmt::format("Damping {} its spin of {}; at t = {} its axis passes {}, spinning at {}.",
                         std::abs(a.fall_spin.value_or(a.spin)) < std::abs(a.spin) ? "slows" : "acts on",
                         spin_words(a.spin), time_words(a.falls_at.value_or(0.0)), fall,
                         spin_words(a.fall_spin.value_or(0.0)));
    case AnswerCase::RunStopped:
      return fmt::format("{}, spinning at {}, the motion of {} could be computed only to t = {}, not far enough to "
                         "say whether it falls ({}).",
                         a.damped ? "With its damping" : fmt::format("Started {} off vertical", angle_words(a.start_tilt)),
                         spin_words(a.spin), body, time_words(a.horizon), a.stopped);
    case AnswerCase::OutlivesHorizon: break;
  }
  std::string s = fmt::format("With its damping, spinning at {}, {} did not tilt past {} within the {} computed",
                              spin_words(a.spin), body, fall, time_words(a.horizon));
  if (a.max_tilt) s += fmt::format(" (largest tilt {})", angle_words(*a.max_tilt));
  return s + ".";
}

std::string answer_text(const Answer& a) {
  return answer_headline(a) + " " + answer_reason(a) + " " + answer_advice(a);
}

std::string uncertainty_sentence(const UncertaintyAnalysis& u) {
  // The probability to two decimals, as SPEC's sentence has it; 0 and 1 only when every draw
  // agreed, so a rounded 1.00 never hides a draw that did not stay up.
  const std::string p = u.p_stays_up == 1.0 ? "1" : u.p_stays_up == 0.0 ? "0"
                        : fmt::format("{:.2f}", std::clamp(u.p_stays_up, 0.01, 0.99));
  std::string critical = "no spin keeps it up in the linearized model";
  if (u.critical_spin) {
    // The expanded uncertainty U = 1.96 u to two significant digits, the value to the same place.
    const double value = rpm_from_rad_per_s(u.critical_spin->value);
    const double expanded = rpm_from_rad_per_s(1.96 * u.critical_spin->standard_uncertainty);
    const int decimals = expanded > 0.0 ? std::max(0, 1 - static_cast<int>(std::floor(std::log10(expanded)))) : 0;
    critical = expanded > 0.0 ? fmt::format("the critical spin is {:.{}f} +- {:.{}f} rpm (95 %)", value, decimals,
                                            expanded, decimals)
                              : fmt::format("the critical spin is {:.0f} rpm (no uncertain input moves it)", value);
  }
  return fmt::format("With these uncertainties it stays up with probability {}; {}.", p, critical);
}

// ---- on a table (SPEC section 16) --------------------------------------------------------------

std::string contact_words(const Table& t) {
  switch (t.contact) {
    case Contact::Frictionless: return "on a frictionless table";
    case Contact::Rolling: return "rolling on a table without slipping";
    case Contact::Sliding:
      return fmt::format("on a table with {} friction (mu = {:g}{})",
                         t.friction_law == FrictionLaw::Viscous   ? "viscous"
                         : t.friction_law == FrictionLaw::Coulomb ? "Coulomb"
                                                                  : "Coulomb-Contensou",
                         t.friction,
                         t.friction_law == FrictionLaw::Viscous ? fmt::format(", slip speed {:g} m/s", t.slip_speed)
                                                                : std::string());
    case Contact::Pivot: break;
  }
  return "on a pivot";
}

std::string table_answer_headline(const TableAnswer& a) {
  switch (a.verdict) {
    case AnswerVerdict::LeavesTable: return "Leaves the table.";
    case AnswerVerdict::Falls: return "Falls.";
    case AnswerVerdict::TurnsOver: return a.ends_upside_down ? "Turns over." : "Turns over part way.";
    case AnswerVerdict::StaysUp: return fmt::format("Rises to vertical in {} and sleeps.", time_words(*a.upright_at));
    case AnswerVerdict::StaysUpForHorizon: break;
  }
  if (!a.stopped.empty()) return "Not decided.";
  return "Stays up for the horizon.";
}

std::string table_answer_reason(const TableAnswer& a, const Table& table) {
  const std::string start = fmt::format(
      "Spinning at {} {}, {}", spin_words(a.spin), contact_words(table),
      a.start_tilt == 0.0 ? std::string("started upright") : fmt::format("started {} off vertical", angle_words(a.start_tilt)));
  switch (a.verdict) {
    case AnswerVerdict::LeavesTable:
      return fmt::format("{}, this body's normal force falls to zero at t = {}: it leaves the table (its flight "
                         "and landing are not modelled).",
                         start, time_words(*a.leaves_at));
    case AnswerVerdict::Falls:
      return fmt::format("{}, this top tilts past {} at t = {}{}.", start, angle_words(a.fall_threshold),
                         time_words(*a.falls_at), a.part_touches ? ", where another of its parts touches the table" : "");
    case AnswerVerdict::TurnsOver:
      return a.ends_upside_down
                 ? fmt::format("{}, this top passes a quarter turn at t = {} and ends spinning upside down on its "
                               "other side ({} from vertical at t = {}), at {} about its axis.",
                               start, time_words(*a.turns_over_at), angle_words(a.final_tilt),
                               time_words(a.end_time), spin_words(std::abs(a.final_spin)))
                 : fmt::format("{}, this top passes a quarter turn at t = {} and spins tilted part way, {} from "
                               "vertical at t = {}, at {} about its axis.",
                               start, time_words(*a.turns_over_at), angle_words(a.final_tilt),
                               time_words(a.end_time), spin_words(std::abs(a.final_spin)));
    case AnswerVerdict::StaysUp:
      return fmt::format("{}, this top rises: from t = {} its tilt stays below {} for the {} computed, spinning at {} "
                         "at the end; the upright spin {} there (the linearisation, Lyapunov's first method).",
                         start, time_words(*a.upright_at), angle_words(kSleepingTilt), time_words(a.horizon),
                         spin_words(a.final_spin),
                         a.upright_attracts ? "is asymptotically stable" : "is not asymptotically stable");
    case AnswerVerdict::StaysUpForHorizon: break;
  }
  if (!a.stopped.empty())
    return fmt::format("{}, the motion of this top could be computed only to t = {}, not far enough to say what it "
                       "does (largest tilt {} until then; {}).",
                       start, time_words(a.horizon), angle_words(a.max_tilt), a.stopped);
  return fmt::format("{}, this top did not fall, turn over or leave the table in the {} computed (largest tilt {}; "
                     "not proven beyond it).",
                     start, time_words(a.horizon), angle_words(a.max_tilt));
}

std::string table_spin_down_words(const TableSpinDown& d, const Table& table) {
  if (!d.critical_spin) return "";
  if (!d.time_to_critical)
    return fmt::format(" Asleep on this table, nothing of what is modelled slows its spin above the critical {}.",
                       spin_words(*d.critical_spin));
  if (*d.time_to_critical == 0.0)
    return fmt::format(" Its spin is already at or below the critical {} on this table.", spin_words(*d.critical_spin));
  const double total = d.losses.total();
  std::vector<std::string> shares;
  if (d.losses.drilling > 0.0)
    shares.push_back(fmt::format("{:.0f} % to the tip's drilling friction (Hertz's patch {:.2g} mm across)",
                                 100.0 * d.losses.drilling / total, 2e3 * d.patch_radius));
  if (d.losses.air > 0.0) shares.push_back(fmt::format("{:.0f} % to the air", 100.0 * d.losses.air / total));
  std::string said;
  for (std::size_t i = 0; i < shares.size(); ++i) said += (i == 0 ? "" : i + 1 == shares.size() ? " and " : ", ") + shares[i];
  return fmt::format(" Asleep on this table it spins about {} before its spin falls to the critical {}: its energy "
                     "goes {}{} (estimates from its shape and materials: docs/table.md).",
                     time_words(*d.time_to_critical), spin_words(*d.critical_spin), said,
                     table.rolling_resistance > 0.0 ? "; rolling resistance takes nothing while it sleeps" : "");
}

std::string table_answer_text(const TableAnswer& a, const Table& table) {
  std::string text = table_answer_headline(a) + " " + table_answer_reason(a, table);
  if (a.spin_down) text += table_spin_down_words(*a.spin_down, table);
  text += fmt::format(" Its contact point wandered up to {:.3g} m from where it started.", a.track);
  if (a.min_spin)
    text += fmt::format(" On this table the upright spin is stable from {} up.", spin_words(*a.min_spin));
  return text;
}

const char* const kStabilityGlossary =
    "Glossary\n"
    "  tilt: the angle of the spin axis from the upward vertical; azimuth: the direction it leans to.\n"
    "  first-order, body-fixed: the paper's approximate models (4) and (5); linearized: the exact "
    "linearisation, the one to trust.\n"
    "  critical spin: the slowest spin at which a model is stable (stable spins: all the spins where it is).\n"
    "  Lyapunov stable: every motion started close enough to the upright spin stays close, in the real "
    "(nonlinear) body, for ever.\n"
    "  certificate: the argument that proves the verdict (energy-casimir: the energy at fixed momentum is a "
    "minimum; chetaev: Chetaev's function for the symmetric top; critical-quartic: the quartic term at the "
    "boundary; odd-index: one stiffness negative, a real growth; linear-instability: the linearisation grows; kam, "
    "kam-markeev: Arnold's (Markeev's at 1:3) theorem on the order-4 normal form, for disturbances small enough; "
    "resonance: unstable at the 1:3 resonance).\n"
    "  energy index: how many of the two stiffnesses s1, s2 are negative (0: stable by energy alone).\n"
    "  Jordan block: a double eigenvalue whose motion grows like t (unstable in a linear model).\n"
    "  growth rate: the largest real part of the eigenvalues (1/s); > 0 means the motion grows.\n";

}  // namespace heavytop::io

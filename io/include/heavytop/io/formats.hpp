#pragma once
/// \file
/// The text, JSON and CSV forms of every result (SPEC section 5), one place for each, shared
/// by the command line, the report and the Python module so that every route prints the same.

#include <optional>
#include <string>
#include <vector>

#include "heavytop/answer.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/fit_decay.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/table.hpp"
#include "heavytop/uncertainty.hpp"

namespace heavytop::io {

/// Stable spins for people (rad/s): "[1.2, 3.4), above 5.6", "from 5.6" (5.6 itself stable),
/// "every spin", "every spin > 0" or "none"; brackets say whether an end is included.
std::string intervals_text(const std::vector<SpinInterval>& intervals);
/// `heavytop stability` (SPEC sections 5, 7, 14): the JSON is {"body", ["damping",] "spin",
/// "answer" {"verdict", "proven", "reason", "max_tilt" (rad), "falls_at" (s), "horizon" (s),
/// "min_spin" (rad/s), "lifetime" (s); null where absent}, "models", "lyapunov" {"verdict",
/// "certificate", "energy_index", "stable_spin_intervals" (rad/s), "superfast_spin" (rad/s or
/// null)}, "wander" {"max_tilt" (rad or null), "method" ("closed form" | "integrated"),
/// "horizon" (s or null), and "note" when max_tilt is null}}; the text opens with the answer in
/// words, then the details (the models' table, the real body's verdict) and a glossary.
/// With `uncertainty` (SPEC section 17), the JSON adds its "uncertainty" object (uncertainty_json())
/// and the answer's words its sentence (uncertainty_sentence()); without, both are as before.
std::string stability_json(const Body& body, const TopAnalysis& analysis,
                           const UncertaintyAnalysis* uncertainty = nullptr);
std::string stability_text(const Body& body, const TopAnalysis& analysis,
                           const UncertaintyAnalysis* uncertainty = nullptr);

/// SPEC section 17's "uncertainty" object as JSON text: {"method", "draws", "coverage",
/// "p_stays_up", "p_stays_up_interval", "critical_spin" {"value", "standard_uncertainty",
/// "interval"} (rad/s) or null, "falls_at" {..., "fraction"} (s) or null, "max_tilt" {...,
/// "fraction"} (rad) or null, "sensitivity" {KEY: (rad/s) per the key's unit}}.
std::string uncertainty_json(const UncertaintyAnalysis& uncertainty);

/// The answer's added sentence (SPEC section 17): "With these uncertainties it stays up with
/// probability 0.97; the critical spin is 1273 +- 48 rpm (95 %)." (the +- being 1.96 u, in rpm).
std::string uncertainty_sentence(const UncertaintyAnalysis& uncertainty);

/// The answer (SPEC section 14) in words, for people: answer_headline() ("Stays up.", "Falls.",
/// ...), answer_reason() (one sentence: the JSON's "reason"), and answer_text(), the
/// paragraph every person-facing output opens with (headline, reason, and answer_advice(): what
/// a fall means for a start beyond the limit given, then what the spin must be, or the critical
/// spin of a damped body).
/// Spins in rad/s and rpm, angles in degrees and rad, times in s.
std::string answer_headline(const Answer& answer);
std::string answer_reason(const Answer& answer);
std::string answer_advice(const Answer& answer);
std::string answer_text(const Answer& answer);

/// The answer on a table (SPEC section 16) in words: the headline ("Turns over.", "Rises to
/// vertical in 6.93 s and sleeps.", ...), the reason (the JSON's "reason"), and the paragraph
/// `stability` opens with on a table (the two, the track, the upright's critical spin).
std::string table_answer_headline(const TableAnswer& answer);
std::string table_answer_reason(const TableAnswer& answer, const Table& table);
std::string table_answer_text(const TableAnswer& answer, const Table& table);
/// The sentence on how long a top asleep on the table spins under its own losses and where its
/// energy goes (empty without a critical spin); starts with a space.
std::string table_spin_down_words(const TableSpinDown& spin_down, const Table& table);

/// `stability` on a table: the JSON (SPEC 14's keys with the table's "answer" and its "table"
/// keys; the linear models of the same body on a pivot; the "table" object of SPEC 16) and the
/// text (the answer, then each spinning state's verdict, critical spin and eigenvalues).
std::string table_stability_json(const Body& body, const Table& table, const TableAnalysis& analysis,
                                 const std::vector<ModelStability>& pivot_models);
std::string table_stability_text(const Body& body, const Table& table, const TableAnalysis& analysis);

/// The glossary of the terms the details of `stability` use (text, one term a line).
extern const char* const kStabilityGlossary;

/// `heavytop lifetime --format json` (SPEC section 8): {"spin_decay": {"critical_spin",
/// "time_to_critical"}, "fall": {"time", "spin", "max_tilt"}, "horizon"}.
std::string lifetime_json(const Lifetime& life);
/// The same for people: one line for the spin reaching the critical spin, one for the fall.
std::string lifetime_text(const Body& body, const InitialState& initial, const Lifetime& life);
/// `heavytop lifetime` on a table (docs/contract.md section 16): SPEC section 8's keys from the
/// spin-down asleep and the computed motion, and "table": {"verdict", "spin_down": {...}}.
std::string table_lifetime_json(const TableLifetime& life);
/// The same in words: how long it spins asleep and where its energy goes, then what the motion did.
std::string table_lifetime_text(const TableLifetime& life, const Table& table);

/// A number as JSON/CSV prints it: the shortest form that reads back to the same double.
std::string number(double value);

/// SPEC's simulate CSV: the header t,theta,phi,theta_rate,phi_rate (then any extra columns)
/// and one row per sample; trajectory_csv_rows() gives rows [begin, end) alone, for streaming.
std::string trajectory_csv_header(const Trajectory& trajectory);
std::string trajectory_csv_rows(const Trajectory& trajectory, std::size_t begin, std::size_t end);
std::string trajectory_csv(const Trajectory& trajectory);

/// `simulate --format json`: the model, body, motion, the columns by name, and the adaptive
/// integrator's summary when given.
std::string trajectory_json(Model model, const Body& body, const InitialState& state, const Trajectory& trajectory,
                            const NonlinearSummary* summary);

/// `simulate --format json` on a table (SPEC section 16): trajectory_json()'s keys with
/// "table" (the contact, its law) and the run's "summary" (steps, the drifts, how it ended).
std::string table_trajectory_json(const Body& body, const Table& table, const InitialState& state, const TableRun& run);

std::string comparison_json(const Comparison& comparison);
std::string comparison_csv(const Comparison& comparison);
std::string comparison_text(const Comparison& comparison, double t_end);

/// The sweep's CSV: the header (varied keys, a column per linear model, `lyapunov` (1: proven
/// Lyapunov stable, SPEC section 7) and `lyapunov_certificate` (its certificate's name),
/// `nonlinear` if asked, and after it `nonlinear_tolerance` with `tolerance` (`sweep
/// --tolerance-column`: the rtol that decided each nonlinear verdict, 0 for the closed form))
/// and the rows of grid points begin, begin + 1, ... with their verdicts.
std::string sweep_csv_header(const std::vector<SweepAxis>& axes, bool nonlinear, bool tolerance = false);
std::string sweep_csv_rows(const std::vector<SweepAxis>& axes, std::size_t begin,
                           const std::vector<SweepVerdict>& verdicts, bool tolerance = false);

/// `heavytop fit-decay --format json`: {"axial", "friction", "spin0": {"value", "uncertainty"
/// (null when not determined), "fitted", "at_bound"}, "rms_residual" (rad/s), "points",
/// "converged", "correlation" (of axial and friction, or null), "C" (kg m^2), "stop_time" (s or
/// null), "termination", "warnings": [...]}; units N m s, N m, rad/s (fit_decay.hpp).
std::string fit_decay_json(const DecayFit& fit);
/// The text for people: the values with their uncertainties, the warnings, what the fit
/// assumed, and the [damping] section to paste into a configuration (`transverse` as in
/// `configured`, axial and friction at full precision, so that the pasted file reproduces them).
std::string fit_decay_text(const DecayFit& fit, const Damping& configured);

/// A body with SPEC section 11's terms given by its keys (a [body] section, Python's Body), as
/// every command but `body` and `simulate --model nonlinear` refuses it: InvalidInput naming
/// the first nonzero key in the order body.Ixy, body.Ixz, body.Iyz, body.offset_x,
/// body.offset_y, with its value. Nothing for an ordinary body.
void refuse_general_keys(const Body& body);
/// The same for `command` (e.g. "simulate --model first-order"), the model named: InvalidInput
/// naming first_general_key(body).
void refuse_general_in(const Body& body, const std::string& command);

/// What `heavytop precession` (and Python's precession()) warns of a damped body.
inline constexpr const char* kPrecessionIgnoresDamping =
    "precession is the conservative body's: its damping, friction and motor are ignored (a damped body's steady "
    "motions decay; `heavytop lifetime` follows them)";

/// Why `heavytop explore` (and Python's explore()) has no page to write and how to build it:
/// the rule of InvalidInput("explore", ...).
inline constexpr const char* kExplorerPageMissing =
    "this heavytop was built without the explorer page, which needs Emscripten: run ./scripts/build.sh --web "
    "(or configure with -DHEAVYTOP_BUILD_WEB=ON and build the target heavytop_web), then run this again";

/// The explorer page (SPEC section 15) that `heavytop explore` writes: `built_page`, the text of
/// the page web/ builds (heavytop-explore.html), with its inputs starting at `body` and `state`
/// (window.HEAVYTOP_INITIAL: the configuration's sections as a JavaScript object; SI units).
/// nullopt when `built_page` is not the explorer page (it has no start mark).
std::optional<std::string> explorer_page(std::string built_page, const Body& body, const InitialState& state);

}  // namespace heavytop::io

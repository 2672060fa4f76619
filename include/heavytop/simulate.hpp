#pragma once
/// \file
/// One entry point for the motion of every model: simulate(model, body, state, times, options)
/// returns the trajectory and a summary of what the solver did (Ceres-style: a termination
/// status and a message instead of a half-filled result before a throw).

#include <array>
#include <initializer_list>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/linear_motion.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/splitting.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// Every model of the heavy top (SPEC section 3).
enum class Model {
  FirstOrder,     ///< the paper's model (4): linear, constant spin
  BodyFixed,      ///< the paper's model (5): linear, constant spin
  Linearized,     ///< the exact linearisation about the upright permanent rotation
  Nonlinear,      ///< the full rigid body, integrated numerically
  LagrangeExact,  ///< the symmetric body's (A = B) nonlinear motion in closed form
};

/// Every model, in SPEC order.
inline constexpr std::array<Model, 5> kModels = {Model::FirstOrder, Model::BodyFixed, Model::Linearized,
                                                 Model::Nonlinear, Model::LagrangeExact};

/// SPEC name of a model: "first-order", "body-fixed", "linearized", "nonlinear", "lagrange-exact".
std::string_view name(Model model);
/// The model called `name` in SPEC, or nullopt.
std::optional<Model> model_from_name(std::string_view name);
/// The SPEC names of every model joined by `separator` (for messages and help).
std::string model_names(std::string_view separator);
/// The linear model behind `model`, or nullopt for Nonlinear and LagrangeExact.
std::optional<LinearModelKind> linear_kind(Model model);
/// The Model of a linear model.
Model model_of(LinearModelKind kind);

/// How the `nonlinear` model is integrated. Each takes its tolerances from
/// SimulateOptions::adaptive; what each can integrate is kIntegratorSupport's;
/// docs/integrators.md compares them.
enum class Integrator {
  Dopri5,     ///< "dopri5": Dormand-Prince 5(4) with error control and dense output (nonlinear.hpp)
  Splitting,  ///< "splitting": fixed-step structure-preserving splitting (splitting.hpp)
  Taylor,     ///< "taylor": Taylor series, order and step from the tolerance (taylor.hpp)
  Dop853,     ///< "dop853": Dormand-Prince 8(5,3) with its 7th-order dense output (dop853.hpp)
  Auto,       ///< "auto": the fastest for the body and tolerance (choose_integrator; on a table, table.hpp)
  Rosenbrock4,  ///< "rosenbrock4": Boost.Odeint's L-stable Rosenbrock 4, for the stiff table (table.hpp)
  Adaptive = Dopri5,  ///< dopri5's old name (also accepted as "adaptive")
};
/// Every integrator, in the order the command line lists them: auto, taylor, dop853, dopri5,
/// splitting, rosenbrock4 (the one list behind name(), integrator_from_name() and integrator_names()).
inline constexpr std::array<Integrator, 6> kIntegrators = {Integrator::Auto,   Integrator::Taylor,
                                                           Integrator::Dop853, Integrator::Dopri5,
                                                           Integrator::Splitting, Integrator::Rosenbrock4};
/// "dopri5" | "splitting" | "taylor" | "dop853" | "auto" | "rosenbrock4".
std::string_view name(Integrator integrator);
/// The integrator called `name` ("adaptive" is dopri5's old name), or nullopt.
std::optional<Integrator> integrator_from_name(std::string_view name);

/// What a run asks of its integrator: one column of kIntegratorSupport each.
enum class IntegratorUse {
  Pivot,    ///< the body on a pivot (SPEC sections 2-15)
  Damped,   ///< with SPEC section 6's torques (damping, friction, a motor)
  General,  ///< SPEC section 11's general body
  Judging,  ///< a run that decides a verdict by its error control (the answer's, a sweep's, tilt extremes)
  Table,    ///< the body on a table (SPEC section 16)
};
/// What one integrator can integrate.
struct IntegratorSupport {
  Integrator integrator;
  bool pivot, damped, general, judging, table;  ///< IntegratorUse's columns, in its order
};
/// The one table every refusal of an integrator reads (integrator_refusal(), integrator_names()).
inline constexpr IntegratorSupport kIntegratorSupport[] = {
    //                        pivot  damped general judging table
    {Integrator::Auto,        true,  true,  true,   true,   true},
    {Integrator::Taylor,      true,  true,  true,   true,   false},
    {Integrator::Dop853,      true,  false, false,  true,   true},
    {Integrator::Dopri5,      true,  true,  true,   true,   false},
    {Integrator::Splitting,   true,  false, false,  false,  false},  // fixed step: conservative, ordinary
    {Integrator::Rosenbrock4, false, false, false,  true,   true},
};
/// True if kIntegratorSupport says `integrator` can do `use`.
bool supports(Integrator integrator, IntegratorUse use);
/// The names of kIntegrators in its order that can do every use of `uses`, joined by
/// `separator` and the last two by `last` (e.g. "auto, taylor, dop853, dopri5, splitting or
/// rosenbrock4" for no uses).
std::string integrator_names(std::string_view separator, std::string_view last,
                             std::initializer_list<IntegratorUse> uses = {});
/// The rule (for InvalidInput's key "integrator") that `integrator` breaks for a run of `body`
/// on a table (`on_table`) or a pivot, `judging` a verdict or not; nullopt if it can do it all.
std::optional<std::string> integrator_refusal(Integrator integrator, const Body& body, bool on_table, bool judging);
/// Throws InvalidInput("integrator", integrator_refusal(...)) if there is one.
void check_integrator(Integrator integrator, const Body& body, bool on_table, bool judging);
/// Auto picks the Taylor integrator when min(rtol, atol) is at most this (dimensionless), or
/// when A != B, or for a general body; dopri5 (Dopri5) for a symmetric body above it
/// (docs/integrators.md, "Choosing").
inline constexpr double kAutoTaylorBelow = 1e-2;
/// The integrator Auto stands for with these tolerances and this body (Taylor or Dopri5,
/// never Auto or Splitting); the rule and its measurements are in docs/integrators.md. A
/// damped body (SPEC section 6) follows the same rule (the Taylor integrator holds its
/// torques, taylor.hpp); a general body (SPEC section 11, general_body.hpp) gets Taylor, and a
/// damped general body Dopri5 (which refuses it: the general body is integrated undamped).
Integrator choose_integrator(const Body& body, const Tolerances& tolerances);

/// The one dispatch of the integrators: the integrator that runs for `asked` with this body and
/// these tolerances (Auto resolved by choose_integrator, every other one as asked).
Integrator resolve_integrator(Integrator asked, const Body& body, const Tolerances& tolerances);

/// tilt_extremes() (nonlinear.hpp) by any error-controlled integrator (`integrator` resolved
/// by resolve_integrator; the splitting is refused, key "integrator"): Dopri5's and Dop853's
/// scans on their dense output, Taylor's on its series (taylor_tilt_extremes, whose stop is
/// the crossing itself). `summary`, if set, receives the run's work (Dopri5 and Taylor).
TiltExtremes tilt_extremes(Integrator integrator, const Body& body, const InitialState& initial, double horizon,
                           double stop_above, const Tolerances& tolerances,
                           NonlinearSummary* summary = nullptr, const Progress& progress = {});

/// Settings of simulate(); each applies to the models named.
struct SimulateOptions {
  LinearMethod method = LinearMethod::Analytic;  ///< first-order, body-fixed, linearized
  Integrator integrator = Integrator::Auto;      ///< nonlinear
  Tolerances adaptive;                     ///< nonlinear with Dopri5, Taylor, Dop853, Auto
  SplittingOptions splitting;                    ///< nonlinear with Integrator::Splitting

  /// True if every setting is in range; else false with a one-line "key: rule" in `why`
  /// (key "rtol", "atol", "step", "order" or "max_steps").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput for the first setting out of range (SimulateOptions::IsValid's keys).
void validate(const SimulateOptions& options);

/// One option of a SimulateRequest: its value if the person gave one (on the command line or
/// in its configuration file; as a keyword argument in Python), and whether they asked for it
/// for this run (a flag or a keyword argument: the rules of what applies to which model check
/// these; a configuration file's [simulate] values are defaults, not asked).
template <class T>
struct Requested {
  std::optional<T> value;
  bool asked = false;
  /// The given value, asked for.
  static Requested of(std::optional<T> v) { return {v, v.has_value()}; }
};

/// A simulate() run as a person asks for it, every option by the core's key; resolve() turns
/// it into the options or refuses it. The command line and Python fill it and spell the keys
/// of its refusals their way (spelled()).
struct SimulateRequest {
  Requested<std::string> model;       ///< "model": a name of kModels; unset: "nonlinear"
  Requested<std::string> method;      ///< "method": "analytic" or "numeric" (the linear models)
  Requested<std::string> integrator;  ///< "integrator": a name of kIntegrators, or "adaptive"; unset: "auto"
  double t_end = 10.0;                ///< "t_end": s, the run's end (finite, > 0)
  long long samples = 1001;           ///< "samples": in [2, 100000000]
  Requested<double> rtol, atol;       ///< "rtol", "atol": Tolerances (the nonlinear model)
  Requested<double> step;             ///< "step": s, SplittingOptions::step (the splitting)
  Requested<int> order;               ///< "order": SplittingOptions::order (the splitting)
  Requested<long long> max_steps;     ///< "max_steps": both integrators' (< 1: refused by simulate())
};

/// What resolve() makes of a request.
struct ResolvedSimulate {
  Model model = Model::Nonlinear;
  double t_end = 10.0;      ///< s
  std::size_t samples = 0;  ///< at t_i = i t_end / (samples - 1)
  SimulateOptions options;
};

/// The options of `request` for `body`, or InvalidInput(key, rule) for the first rule it breaks,
/// in this order: "model" a known name; then `check_body(model)` if set (an adapter's refusal of
/// a general body, in its words) and, for lagrange-exact, validate_symmetric; "method" analytic
/// or numeric; "t_end" finite and > 0; "samples" in [2, 100000000]; "method" asked only for a
/// linear model; "integrator" a known name; "integrator", "step", "order", "max_steps", then
/// "rtol" and "atol" asked only for the nonlinear model; "step" and "order" asked only with the
/// splitting. Unasked, a damped linear model takes the numeric route (its closed form is the
/// undamped one). A rule naming another option writes it {key=value} and the integrators'
/// list {integrators}: spelled() writes them an adapter's way. The values' ranges (rtol, atol,
/// step, order, max_steps) are simulate()'s checks.
ResolvedSimulate resolve(const SimulateRequest& request, const Body& body,
                         const std::function<void(Model)>& check_body = {});

/// How an adapter writes the core's keys: an option's key ("t_end" -> "--t-end" or "t_end"),
/// a key with a value in a rule ("model", "nonlinear" -> "--model nonlinear" or
/// 'model="nonlinear"'), and the list of integrators.
struct Spelling {
  std::function<std::string(std::string_view key)> key;
  std::function<std::string(std::string_view key, std::string_view value)> option;
  std::string integrators;
};

/// `refusal` (from resolve()) with its key, if one of SimulateRequest's, and the {key=value} and
/// {integrators} of its rule written by `spelling`; any other key (e.g. "body.B") unchanged.
InvalidInput spelled(const InvalidInput& refusal, const Spelling& spelling);

/// How a simulation ended.
enum class Termination {
  Success,  ///< every sample computed
  Failure,  ///< a numerical failure (the solver could not go on); `message` says where and why
};

/// Throws InvalidInput unless `model` with `options` can integrate `body`'s damping (SPEC
/// section 6): lagrange-exact (key "model") and the splitting, Taylor and DOP853 integrators
/// ("integrator") are for the conservative body, and the linear models' closed form
/// ("method") for the undamped.
void validate_damping(Model model, const Body& body, const SimulateOptions& options);

/// The relative energy error of the splitting integrator above which simulate() warns that the
/// step is too large for the motion (the integrator itself bounds it only as O(h^order)).
inline constexpr double kSplittingEnergyWarning = 1e-3;

/// What simulate() did: the solver, its work, and the drift of the first integrals.
struct SimulationSummary {
  Model model = Model::Nonlinear;
  std::string solver;                ///< e.g. "closed form", "Dormand-Prince 5(4)", "splitting, order 4"
  Termination termination = Termination::Success;
  std::string message;               ///< one line: why it failed, or empty
  std::size_t samples = 0;           ///< samples computed
  std::size_t steps = 0;             ///< integrator steps (0 for closed forms)
  std::size_t rejected_steps = 0;    ///< steps rejected by the error control
  std::size_t rhs_evaluations = 0;   ///< evaluations of the equations of motion (kicks for the splitting)
  /// Relative drifts of E, L_zeta and C w3 over the run (nonlinear.hpp's Drifts); nullopt for
  /// models that do not monitor them.
  std::optional<Drifts> drifts;

  /// One line each: what a reader should know although the run succeeded (e.g. the
  /// splitting's energy error above kSplittingEnergyWarning).
  std::vector<std::string> warnings;

  bool ok() const noexcept { return termination == Termination::Success; }
  /// One line for people.
  std::string BriefReport() const;
};

/// A trajectory and how it was computed.
struct Simulation {
  Trajectory trajectory;      ///< every sample on Success; those computed before a Failure
  SimulationSummary summary;
  /// The error-controlled integrator's own summary (nonlinear with Dopri5, Taylor, Dop853
  /// or Auto), for the JSON `summary` object.
  std::optional<NonlinearSummary> adaptive;
};

/// s, the longest horizon over which a double still resolves the phase of the motion started
/// from `initial` to 1e-3 rad: 1e-3 / (eps * rate), rate the fastest of the spin, the initial
/// rates and the gravity frequency 1 / gravity_time(body). Beyond it every model's angles are
/// rounding noise, and simulate() refuses the times (InvalidInput key "t_end" or "times").
double longest_meaningful_time(const Body& body, const InitialState& initial);

/// Throws InvalidInput(key, "too long: ...") if `horizon` (s) is beyond
/// longest_meaningful_time(body, initial).
void validate_horizon(const Body& body, const InitialState& initial, double horizon, const std::string& key);

/// Receives consecutive pieces of a trajectory (same columns, at most `chunk` samples each).
using TrajectorySink = std::function<void(const Trajectory&)>;

/// simulate() at `grid`, streamed: `sink` gets the trajectory in pieces of at most `chunk`
/// samples as they are computed, so memory stays flat in the number of samples. On a
/// numerical failure the pieces already handed on stay valid and the summary says where.
/// `adaptive`, if not null, receives the adaptive integrator's own summary; `progress` is called
/// as the run proceeds (a throw from it stops the run and is its failure, as in simulate()).
SimulationSummary simulate_streaming(Model model, const Body& body, const InitialState& initial,
                                     const SampleGrid& grid, const SimulateOptions& options,
                                     const TrajectorySink& sink, std::size_t chunk = 4096,
                                     NonlinearSummary* adaptive = nullptr, const Progress& progress = {});

/// The motion of `model` for `body` from `initial` (SPEC section 2 mapping) at `times` (s;
/// finite, >= 0, non-decreasing). Columns theta, phi, theta_rate, phi_rate for every model;
/// the nonlinear integrators add the conserved quantities (nonlinear.hpp). A general body
/// (SPEC section 11, is_general()) is integrated by general_body.hpp's dopri5, for Nonlinear with
/// Integrator::Auto, Dopri5 or Taylor only (InvalidInput "integrator" otherwise, the body's key for
/// every other model, a "damping.*" key when damped). Throws
/// InvalidInput for bad input (the body, the state, the options; LagrangeExact needs A = B;
/// times beyond longest_meaningful_time()); a numerical failure, including a value that is
/// not finite (a linear model grown beyond a double), is reported in the summary
/// (Termination::Failure, with the column and the time), not thrown. `progress` (progress.hpp)
/// is called as the run proceeds; what it throws stops the run, its message the failure's, the
/// samples before it kept.
Simulation simulate(Model model, const Body& body, const InitialState& initial,
                    const std::vector<double>& times, const SimulateOptions& options = {},
                    const Progress& progress = {});

}  // namespace heavytop

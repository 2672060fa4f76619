#pragma once
/// \file
/// How sure is the answer (SPEC section 17, first part: uncertain inputs). The standard
/// uncertainties of body and motion keys propagated to the linearized model's critical spin by
/// JCGM 100's law of propagation (exact derivatives) and by JCGM 101's Monte Carlo (adaptive,
/// clause 7.9), the linear result reported only where JCGM 101 section 8's comparison passes;
/// and SPEC 14's answer over the Monte Carlo draws: the probability that the top stays up, when
/// it falls, how far it tilts. docs/uncertainty.md says what is claimed and what is not.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "heavytop/answer.hpp"
#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The keys that may carry an uncertainty, in SPEC order: "A", "B", "C", "mass", "gravity",
/// "length" (the body's, SPEC 1) and "spin", "theta0", "phi0", "theta_rate0", "phi_rate0" (the
/// motion's, SPEC 4; SI units).
const std::vector<std::string>& uncertain_keys();

/// How each input is distributed about its nominal value (SPEC 17: one for all keys).
enum class UncertaintyDistribution {
  Gaussian,  ///< normal, the given value its standard deviation
  Uniform,   ///< rectangular, the given value its half-width a (standard uncertainty a / sqrt(3))
};
/// "gaussian" | "uniform".
std::string_view name(UncertaintyDistribution distribution);
/// The distribution called `name`, or nullopt.
std::optional<UncertaintyDistribution> uncertainty_distribution_from_name(std::string_view name);

/// One input's uncertainty as given: absolute (in the key's SI unit: kg m^2, kg, m/s^2, m,
/// rad/s, rad) or relative (a fraction of |nominal|: 0.02 for "2%").
struct InputUncertainty {
  double value = 0.0;     ///< >= 0, finite: the standard uncertainty, or the half-width (uniform)
  bool relative = false;  ///< value is a fraction of the nominal value's magnitude
};

/// Settings of analyse_uncertainty().
struct UncertaintyOptions {
  /// The uncertain inputs, by uncertain_keys() name; a key absent is exact.
  std::map<std::string, InputUncertainty> inputs;
  UncertaintyDistribution distribution = UncertaintyDistribution::Gaussian;
  /// Monte Carlo draws of the answer: 0 adaptive (JCGM 101 7.9, two significant digits), else
  /// exactly this many (>= 0). The critical spin's comparison run is always adaptive.
  std::int64_t draws = 0;
  std::uint64_t seed = 1;  ///< the draws are a function of (seed, draw index) only
  unsigned threads = 2;    ///< worker threads (0: the hardware's); the result does not depend on it
  /// The most draws an adaptive run takes (>= 10^4): it stops there even if 7.9's rule has not
  /// passed (UncertaintyAnalysis::converged then says so).
  std::int64_t max_draws = 1000000;
  /// True if every setting is in range; else false and "key: rule" in `why` (keys
  /// "uncertainty.KEY", "uncertainty.draws", "uncertainty.max_draws").
  bool IsValid(std::string* why) const;
  /// True if some input is uncertain.
  bool any() const noexcept { return !inputs.empty(); }
};

/// Dimensionless: the largest relative standard uncertainty u(x) / |x| of the inputs of
/// `options` whose nominal value in `body`, `initial` is not 0 (SPEC 17: the chaos command's
/// default precision); nullopt when there is none.
std::optional<double> largest_relative_uncertainty(const UncertaintyOptions& options, const Body& body,
                                                   const InitialState& initial);

/// Throws InvalidInput for the first setting out of range (UncertaintyOptions::IsValid's keys),
/// and for a relative uncertainty of a key whose nominal value is 0 ("uncertainty.theta0").
void validate(const UncertaintyOptions& options, const Body& body, const InitialState& initial);

/// An output quantity's estimate: its value, standard uncertainty and 95 % coverage interval
/// (units of the quantity: rad/s, s, rad).
struct UncertainQuantity {
  double value = 0.0;
  double standard_uncertainty = 0.0;
  double lo = 0.0, hi = 0.0;  ///< the coverage interval
};

/// A Monte Carlo quantity defined on some of the draws: `fraction` of all draws have it.
struct UncertainOutcome : UncertainQuantity {
  double fraction = 0.0;  ///< dimensionless, in [0, 1]
};

/// Which result `critical_spin` reports (SPEC 17).
enum class UncertaintyMethod {
  Linear,      ///< JCGM 100's law of propagation, validated by JCGM 101 section 8
  MonteCarlo,  ///< JCGM 101's: mean, standard deviation, probabilistically symmetric interval
};
/// "linear" | "monte-carlo".
std::string_view name(UncertaintyMethod method);

/// SPEC 17's "uncertainty" object, and the validation behind its method.
struct UncertaintyAnalysis {
  UncertaintyMethod method = UncertaintyMethod::MonteCarlo;
  std::int64_t draws = 0;   ///< the answer's Monte Carlo draws
  double coverage = 0.95;   ///< the coverage probability of every interval
  /// Fraction of the answer's draws that are "stays up" and proven (SPEC 14), and its 95 %
  /// Clopper-Pearson (exact binomial) interval.
  double p_stays_up = 0.0;
  double p_stays_up_lo = 0.0, p_stays_up_hi = 1.0;
  /// rad/s, the linearized model's critical spin (linear or Monte Carlo, per `method`);
  /// nullopt when the nominal body has none (no spin stabilises it).
  std::optional<UncertainQuantity> critical_spin;
  /// s, over the draws that fall (fraction of all); nullopt when none falls.
  std::optional<UncertainOutcome> falls_at;
  /// rad, the answer's largest tilt over the draws that have one (fraction of all; a run that
  /// stopped has none); nullopt when no draw has one.
  std::optional<UncertainOutcome> max_tilt;
  /// (rad/s) per (the key's unit): d critical_spin / d KEY at the nominal inputs, exact (implicit
  /// differentiation of the condition whose root it is, by the complex step), for each uncertain
  /// key in uncertain_keys() order. For a symmetric body's A without B's own uncertainty, the
  /// derivative moves A and B together.
  std::vector<std::pair<std::string, double>> sensitivity;

  // The validation (JCGM 101 section 8), for the docs and tests.
  std::optional<UncertainQuantity> critical_linear;       ///< rad/s, JCGM 100, coverage factor 1.96
  std::optional<UncertainQuantity> critical_monte_carlo;  ///< rad/s, JCGM 101 7.9 adaptive
  std::int64_t critical_draws = 0;  ///< the adaptive comparison run's draws
  double tolerance = 0.0;           ///< rad/s, delta: half a unit of u_c's second significant digit
  double d_low = 0.0, d_high = 0.0; ///< rad/s, |y - U - y_low| and |y + U - y_high|
  bool converged = true;  ///< false when an adaptive run stopped at max_draws before 7.9's rule passed
};

/// Inputs of one Monte Carlo draw: `body` and `initial` with every uncertain key redrawn (a
/// draw outside SPEC 1's physical region is drawn again; `length` keeps its sign). A function
/// of (options.seed, index) only. Throws InvalidInput("uncertainty", ...) when 1000 draws in a
/// row fall outside the region.
std::pair<Body, InitialState> uncertain_draw(const Body& body, const InitialState& initial,
                                             const UncertaintyOptions& options, std::uint64_t index);

/// (rad/s) per (key's unit): d critical_spin / d KEY of the linearized model at `body`, for
/// `key` in uncertain_keys() (0 for the motion's keys); `with_b` moves B with A (a symmetric
/// body's A). Exact: the critical spin's square s_c is a root of one of the stability
/// conditions f(s; body), and ds_c/dp = -(df/dp)/(df/ds), both partials by the complex step
/// (h = 1e-30). nullopt when the body has no critical spin.
std::optional<double> critical_spin_derivative(const Body& body, const std::string& key, bool with_b = false);

/// rad/s, the linearized model's critical spin of `body` (SPEC 5), nullopt when none.
std::optional<double> linearized_critical_spin(const Body& body);

/// The uncertainty of the answer of `body` started in `initial` (SPEC 17): throws InvalidInput
/// for bad options or inputs. `answer` are the answer's settings (SPEC 14: horizon, max_tilt).
UncertaintyAnalysis analyse_uncertainty(const Body& body, const InitialState& initial,
                                        const UncertaintyOptions& options, const AnswerOptions& answer = {});

}  // namespace heavytop

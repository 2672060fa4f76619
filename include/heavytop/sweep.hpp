#pragma once
/// \file
/// Stability maps: each linear model's verdict, the real body's Lyapunov verdict (proven stable
/// or not, lyapunov.hpp), and optionally the nonlinear body's practical verdict, over a grid of
/// one, two or three parameters.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// One axis of a grid, KEY=START:STOP:COUNT: COUNT values from START to STOP inclusive.
struct SweepAxis {
  std::string key;  ///< a body key (A, B, C, mass, gravity, length), "spin", or "B/A", "C/A"
  double start = 0.0;
  double stop = 0.0;
  std::size_t count = 1;

  /// The i-th value, START + i (STOP - START) / (COUNT - 1), in the key's SI unit.
  double value(std::size_t i) const;
};

/// The most parameters a sweep may vary at once (a map of B/A, C/A and the spin, say).
inline constexpr std::size_t kMaxSweepAxes = 3;

/// The most grid points a sweep may have (a 10^4 x 10^4 map; about 3 GB of CSV).
inline constexpr std::size_t kMaxSweepPoints = 100'000'000;

/// Whether `key` is one a sweep varies: a body key (A, B, C, mass, gravity, length), spin,
/// spin_rpm, B/A or C/A. The one list: parse_sweep_axis() takes these, and a map file's
/// axes must be among them (io::read_map), so no other text becomes a map's key.
bool is_sweep_key(std::string_view key);

/// Those keys as a rule's words: "A, B, C, mass, gravity, length, spin, spin_rpm, B/A, C/A".
std::string sweep_keys_text();

/// Parses "KEY=START:STOP:COUNT". Throws InvalidInput (key "vary") naming the rule broken.
/// KEY "spin_rpm" gives the axis "spin" with START and STOP converted to rad/s (SPEC section 9).
SweepAxis parse_sweep_axis(std::string_view text);

/// The number of grid points: the product of the axes' counts.
std::size_t grid_size(const std::vector<SweepAxis>& axes);

/// The index along each axis of grid point `index` of a grid with these counts (row-major,
/// the first axis slowest).
std::vector<std::size_t> grid_indices(const std::vector<std::size_t>& counts, std::size_t index);

/// The value of each axis at grid point `index` (row-major, the first axis slowest).
std::vector<double> grid_values(const std::vector<SweepAxis>& axes, std::size_t index);

/// The values B/A takes for a real body with A and C held: |C - A| / A to (C + A) / A (the
/// triangle inequalities of the moments).
std::pair<double, double> realizable_ratio_range(const Body& body);

/// The body and state at grid point `index` (row-major, the first axis slowest). A ratio
/// B/A or C/A changes the numerator and holds the denominator at its base value.
void apply_grid_point(const std::vector<SweepAxis>& axes, std::size_t index, Body& body,
                      InitialState& state);

/// Settings of a sweep.
struct SweepOptions {
  bool nonlinear = false;       ///< also judge each point by a nonlinear simulation
  double horizon = 100.0;       ///< s, simulated time of each nonlinear run (> 0)
  double max_tilt = 0.5;        ///< rad, the nonlinear run is "stable" if its tilt stays <= this
  Tolerances integrator;  ///< tolerances of the nonlinear runs
  /// How the nonlinear runs are integrated (CLI --integrator): Auto and Taylor run the
  /// conservative principal-axes bodies through the batched Taylor integrator (batch.hpp,
  /// bit-identical to the unbatched one), Adaptive (dopri5) and Dop853 one point at a time;
  /// a damped or general body always takes choose_integrator()'s (dopri5) one point at a time
  /// under Auto (Taylor and Dop853 refuse it, key "integrator"). Splitting is refused.
  Integrator nonlinear_integrator = Integrator::Auto;
  unsigned threads = 0;         ///< worker threads; 0: one per core

  /// True if every setting is in range; else false with a one-line "key: rule" in `why`.
  bool IsValid(std::string* why) const;
};

/// The verdicts at one grid point.
struct SweepVerdict {
  std::array<bool, 3> linear{};   ///< stable? first-order, body-fixed, linearized (kLinearModels order)
  /// Proven Lyapunov stable (lyapunov_stability's verdict is Stable; undecided counts as false).
  bool lyapunov = false;
  /// The certificate behind that verdict (SPEC section 7's names; `none` when undecided).
  LyapunovCertificate lyapunov_certificate = LyapunovCertificate::None;
  std::optional<bool> nonlinear;  ///< tilt stayed <= max_tilt over the horizon (when asked)
  /// The rtol (dimensionless) of the run that decided `nonlinear` (verdicts.hpp's
  /// DecidedVerdict::tolerance: 0 when decided without integration); set with it.
  std::optional<double> nonlinear_tolerance;
};

/// One axis of a stability map: the key and its values (in the key's SI unit), as a sweep
/// computed them (SweepAxis::value) or as a map file holds them.
struct MapAxis {
  std::string key;
  std::vector<double> values;
};

/// A stability map: the verdicts at every point of a grid (what `heavytop sweep` writes).
struct StabilityMap {
  std::vector<MapAxis> axes;          ///< the grid, the first axis slowest
  bool nonlinear = false;             ///< true if the verdicts hold the nonlinear one
  std::vector<SweepVerdict> verdicts; ///< one per grid point, row-major (the product of the axes' sizes)
};

/// The map of a sweep over `axes` with these verdicts (one per grid point, in grid order).
StabilityMap stability_map(const std::vector<SweepAxis>& axes, bool nonlinear, std::vector<SweepVerdict> verdicts);

/// The index of the value in `values` (not empty) nearest `value` (the first of equals).
std::size_t nearest_index(const std::vector<double>& values, double value);

/// The map with axis `key` held at its grid value nearest `value` (in the key's SI unit): one
/// axis fewer (a three-parameter map's slice is a two-parameter map). Throws InvalidInput (key
/// "slice") if `key` is not an axis of the map or `value` is not finite.
StabilityMap slice(const StabilityMap& map, std::string_view key, double value);

/// Throws InvalidInput (key "vary", naming the grid point) unless at most kMaxSweepAxes distinct
/// keys are varied (none: the base point alone), the grid has at most kMaxSweepPoints points and every grid point gives a valid body and state (checked at the
/// grid's corners, which bound every rule), and, with options.nonlinear, the start is tilted
/// (else the upright body never moves) by less than max_tilt.
void validate_sweep(const Body& base, const InitialState& base_state,
                    const std::vector<SweepAxis>& axes, const SweepOptions& options);

/// The verdicts at grid points [begin, end), in grid order, computed in parallel on every
/// core; the result does not depend on the number of threads.
std::vector<SweepVerdict> sweep_verdicts(const Body& base, const InitialState& base_state,
                                         const std::vector<SweepAxis>& axes,
                                         const SweepOptions& options, std::size_t begin,
                                         std::size_t end);

}  // namespace heavytop

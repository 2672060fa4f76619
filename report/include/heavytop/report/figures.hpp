#pragma once
/// \file
/// Figures in PNG and SVG, drawn by gnuplot (a maintained plotting program from Debian's
/// packages; no plot rendering here): this file only writes the data and the gnuplot script.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "heavytop/compare.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/progress.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/table.hpp"

namespace heavytop::report {

/// `text` as a gnuplot string literal, quotes included: every string a figure's script holds
/// goes through it. Double quotes, with \" and \\, and ` as the octal escape \140: gnuplot
/// substitutes `command` on a command line even inside double quotes, so no backquote may be
/// there raw; a single-quoted string cannot hold a leading quote or two in a row (gnuplot 5.4
/// reads '''' as two empty strings: doubling is not enough). Neither @macros nor $0 are expanded
/// inside a string. Control characters are shown as io::printable() shows them (a newline would
/// end the command).
std::string gnuplot_string(std::string_view text);

/// Each function draws into `dir`, a private scratch folder (data files, gnuplot scripts,
/// NAME.png and NAME.svg): gnuplot runs inside it on relative names only.

/// The files a figure was written to: DIR/NAME.png and DIR/NAME.svg.
struct Figure {
  std::string name;     ///< e.g. "angles"; files name.png and name.svg
  std::string caption;  ///< one sentence for a reader
};

/// The most samples of a motion that the figures and the page draw: 1001 across a chart
/// 1000-odd pixels wide loses nothing a reader sees (display only: trajectories.csv keeps
/// every computed sample).
inline constexpr std::size_t kDisplaySamples = 1001;
/// The samples drawn of `n`: every stride-th (stride the smallest that keeps at most
/// kDisplaySamples), and the last.
std::vector<std::size_t> display_samples(std::size_t n);

/// How the report shows the axis's angles: in mrad when the true motion stays within 0.2 rad
/// (tick labels like 8.0e-02 rad read worse than 80 mrad), else in rad.
struct AngleUnit {
  double scale = 1.0;         ///< shown value = angle in rad * scale
  std::string name = "rad";   ///< "rad" or "mrad"
};
AngleUnit angle_unit(const Comparison& comparison);

/// rad, max(|d theta|, |d phi|) of `model` against `truth` at sample i (both at the same times).
double angle_error(const Trajectory& model, const Trajectory& truth, std::size_t i);

/// The nonlinear runs behind the stability diagram: one per grid point, started start_tilt
/// off vertical, "stays up" when the tilt stays <= max_tilt over horizon.
struct DiagramGrid {
  std::vector<SweepAxis> axes;         ///< B/A, then spin (rad/s)
  std::vector<SweepVerdict> verdicts;  ///< grid order (sweep_verdicts)
  double start_tilt = 0.0;             ///< rad
  double max_tilt = 0.0;               ///< rad
  double horizon = 0.0;                ///< s
};

/// How the diagram names the nonlinear verdicts: ("stays up", "falls") for a top, and for a
/// hanging body (R < 0), which does not stand up, ("axis stays near the vertical", "axis swings out").
std::pair<const char*, const char*> diagram_words(const Body& body);

/// The motion of every model, three figures from one set of data: "angles" (theta(t) and
/// phi(t) overlaid, two panels), "axis-path" (the tip seen from above, (k_xi, k_eta), to first
/// order (theta, -phi): loops and cusps), "errors" (each approximate model's angle error against time, log scale).
std::vector<Figure> plot_motion(const std::string& dir, const Comparison& comparison);
/// Stable spins against B/A for the three linear models, with nonlinear verdicts on a grid
/// and the body itself marked: erratum E3 at a glance. `grid`, if not null, receives the
/// nonlinear runs' grid and verdicts (the report's clickable explorer shows them).
Figure plot_stability_diagram(const std::string& dir, const Body& body, const InitialState& state,
                              DiagramGrid* grid = nullptr, const Progress& progress = {});
/// How far the axis wanders: the largest tilt against the spin for a start delta = 1e-3 and
/// 1e-2 rad off vertical (log scale), the exact linearisation's critical spin marked: the
/// sqrt(2 delta) plateau at the boundary of (9) and the jump below it (erratum E2). Exact
/// (the Lagrange top's cubic) for A = B, integrated for A != B.
Figure plot_wander(const std::string& dir, const Body& body, std::optional<double> critical_spin,
                   const Progress& progress = {});
/// A two-parameter map as a heat map, figure `name` (default "stability-map"): where the
/// paper's (4) and the exact linearisation agree or not; for a map with the nonlinear
/// verdict, where the linearisation and the real body do. `where` ends the title (a slice's
/// held value, e.g. "at C/A = 2").
Figure plot_sweep_map(const std::string& dir, const StabilityMap& map, const std::string& name = "stability-map",
                      const std::string& where = "");

/// How long a damped top stays up (SPEC section 8): its spin w.k and its tilt against time
/// from the damped nonlinear run of `life`, the critical spin as a line, the time the spin law
/// reaches it and the fall marked.
Figure plot_lifetime(const std::string& dir, const Body& body, const InitialState& state, const Lifetime& life,
                     const Progress& progress = {});

/// The body on a table (SPEC section 16), two figures from its run `run` (simulate_on_table's
/// columns) and its answer: "tilt" (the tilt from the upward vertical and the spin w.k against
/// time, the answer's events marked: the turn-over, the rise to sleep, a fall, leaving the
/// table) and "track" (the contact point P's path seen from above, x and y to the same scale).
std::vector<Figure> plot_table_motion(const std::string& dir, const TableRun& run, const TableAnswer& answer);

}  // namespace heavytop::report

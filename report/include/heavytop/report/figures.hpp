#pragma once
/// \file
/// Figures in PNG and SVG, drawn by gnuplot (a maintained plotting program from Debian's
/// packages; no plot rendering here): this file only writes the data and the gnuplot script.

#include <optional>
#include <string>
#include <vector>

#include "heavytop/compare.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::report {

/// Each function draws into `dir`, a private scratch folder (data files, gnuplot scripts,
/// NAME.png and NAME.svg): gnuplot runs inside it on relative names only.

/// The files a figure was written to: DIR/NAME.png and DIR/NAME.svg.
struct Figure {
  std::string name;     ///< e.g. "angles"; files name.png and name.svg
  std::string caption;  ///< one sentence for a reader
};

/// The motion of every model, three figures from one set of data: "angles" (theta(t) and
/// phi(t) overlaid, two panels), "axis-path" (theta against phi: nutation loops and cusps),
/// "errors" (each approximate model's angle error against time, log scale).
std::vector<Figure> plot_motion(const std::string& dir, const Comparison& comparison);
/// Stable spins against B/A for the three linear models, with nonlinear verdicts on a grid
/// and the body itself marked: erratum E3 at a glance.
Figure plot_stability_diagram(const std::string& dir, const Body& body, const InitialState& state);
/// How far the axis wanders: the largest tilt against the spin for a start delta = 1e-3 and
/// 1e-2 rad off vertical (log scale), the exact linearisation's critical spin marked: the
/// sqrt(2 delta) plateau at the boundary of (9) and the jump below it (erratum E2). Exact
/// (the Lagrange top's cubic) for A = B, integrated for A != B.
Figure plot_wander(const std::string& dir, const Body& body, std::optional<double> critical_spin);
/// A two-parameter sweep's map as a heat map: where (4) and the linearisation agree or not.
Figure plot_sweep_map(const std::string& dir, const std::vector<SweepAxis>& axes,
                      const std::vector<SweepVerdict>& verdicts);

}  // namespace heavytop::report

#pragma once
// Figures in PNG and SVG, drawn by gnuplot (a maintained plotting program from Debian's
// packages; no plot rendering here): this file only writes the data and the gnuplot script.

#include <string>
#include <vector>

#include "heavytop/compare.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::cli {

/// The files a figure was written to (both beside each other in the output folder).
struct Figure {
  std::string name;     ///< e.g. "angles"; files name.png and name.svg
  std::string caption;  ///< one sentence for a reader
};

/// theta(t) and phi(t) of every model overlaid, two panels.
Figure plot_angles(const std::string& dir, const Comparison& comparison);
/// The path of the axis tip (theta against phi): nutation loops and cusps.
Figure plot_axis_path(const std::string& dir, const Comparison& comparison);
/// Each approximate model's angle error against time (log scale).
Figure plot_errors(const std::string& dir, const Comparison& comparison);
/// Stable spins against B/A for the three linear models, with nonlinear verdicts on a grid
/// and the body itself marked: erratum E3 at a glance.
Figure plot_stability_diagram(const std::string& dir, const Body& body, const InitialState& state);
/// A two-parameter sweep's map as a heat map: where (4) and the linearisation agree or not.
Figure plot_sweep_map(const std::string& dir, const Body& body, const InitialState& state,
                      const std::vector<SweepAxis>& axes, const std::vector<SweepVerdict>& verdicts);

}  // namespace heavytop::cli

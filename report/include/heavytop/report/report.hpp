#pragma once
/// \file
/// The report: one folder a person can open from disk (report.html, its figures as PNG and
/// SVG drawn by gnuplot, the data behind them as CSV and JSON, and, when the build had npm,
/// the interactive page's script heavytop-report.js with its data report-data.js); nothing is
/// fetched from a network (SPEC section 5).

#include <optional>
#include <string>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::report {

/// Writes the report for `body` and `state` into folder `dir` (created if needed), the motion
/// over `t_end` (s; default natural_horizon()). Throws InvalidInput (key "--output") if the
/// folder cannot be made, io::Failure if a figure cannot be drawn.
void write_report(const std::string& dir, const Body& body, const InitialState& state, std::optional<double> t_end);

}  // namespace heavytop::report

#pragma once
/// \file
/// The report: one folder a person can open from disk (report.html, its figures as PNG and
/// SVG drawn by gnuplot, the data behind them as CSV and JSON, and, when the build had npm,
/// the interactive page's script heavytop-report.js with its data report-data.js); nothing is
/// fetched from a network (SPEC section 5).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::report {

/// A stability map (a sweep's file) for the report to draw: a map of two keys whole, a map of
/// three as heat maps at chosen values of one key.
struct ReportMap {
  std::string file;            ///< where it was read from, as the reader gave it (shown)
  StabilityMap map;            ///< two or three keys
  std::string held;            ///< three keys: the key each slice holds (default: the last)
  std::vector<double> values;  ///< ... at its grid values nearest these (default: first, middle, last)

  /// The maps to draw, each with its words ("at C/A = 2"): the map itself, or its slices.
  /// Throws InvalidInput (key "map" or "slice") if the map has one key, `held` is not a key of
  /// it, or slices are asked of a two-key map.
  std::vector<std::pair<std::string, StabilityMap>> heat_maps() const;
};

/// Writes the report for `body` and `state` into folder `dir` (created if needed): the answer
/// first (SPEC section 14, as `stability` gives it; for a damped body with its lifetime), then
/// the 3D view, the models, the motion over `t_end` (s; default: up to the fall and a fifth
/// more when the body falls, else natural_horizon()), and, if given, the heat maps of `map`.
/// `source` (the configuration file, "" for the built-in example) is named in the title. Throws
/// InvalidInput (key "map" or "slice", before anything is made: ReportMap::heat_maps()) for a
/// map it cannot draw, InvalidInput (key "--output") if the folder cannot be made, io::Failure
/// if a figure cannot be drawn.
void write_report(const std::string& dir, const Body& body, const InitialState& state, std::optional<double> t_end,
                  const std::optional<ReportMap>& map = std::nullopt, const std::string& source = "");

}  // namespace heavytop::report

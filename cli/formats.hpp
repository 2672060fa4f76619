#pragma once
// The text, JSON and CSV forms of each command's results, shared by the commands and the report.

#include <optional>
#include <string>
#include <vector>

#include "heavytop/compare.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::cli {

/// One linear model's stability at a spin, and its stable spins.
struct ModelReport {
  LinearModelKind kind;
  StabilityVerdict verdict;
  std::vector<SpinInterval> intervals;
  std::optional<double> critical;
};

/// Every linear model of `body` at spin w0 (rad/s).
std::vector<ModelReport> analyse(const Body& body, double spin);
/// Stable spins for people: "[1.2, 3.4], above 5.6", "every spin" or "none" (rad/s).
std::string intervals_text(const std::vector<SpinInterval>& intervals);
std::string stability_json(const Body& body, double spin, const std::vector<ModelReport>& reports);
std::string stability_text(const Body& body, double spin, const std::vector<ModelReport>& reports);

/// A number as JSON/CSV prints it: the shortest form that reads back to the same double.
std::string number(double value);

/// The names of a trajectory's columns (t, theta, phi, theta_rate, phi_rate, extras) and one by index.
std::vector<std::string> trajectory_columns(const Trajectory& trajectory);
const std::vector<double>& trajectory_column(const Trajectory& trajectory, std::size_t index);

/// SPEC's simulate CSV: t,theta,phi,theta_rate,phi_rate then any extra columns.
std::string trajectory_csv(const Trajectory& trajectory);

std::string comparison_json(const Comparison& comparison);
std::string comparison_csv(const Comparison& comparison);
std::string comparison_text(const Comparison& comparison, double t_end);

/// The sweep's CSV: the header (varied keys, a column per linear model, `nonlinear` if asked)
/// and the rows of grid points begin, begin + 1, ... with their verdicts.
std::string sweep_csv_header(const std::vector<SweepAxis>& axes, bool nonlinear);
std::string sweep_csv_rows(const std::vector<SweepAxis>& axes, std::size_t begin,
                           const std::vector<SweepVerdict>& verdicts);

}  // namespace heavytop::cli

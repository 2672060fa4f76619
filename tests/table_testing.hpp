#pragma once
// What the tests of the body on a table share: the toy top on a round tip, a start (SPEC
// section 2's state) and a run's column by name.
#include <stdexcept>
#include <string>
#include <vector>

#include "heavytop/table.hpp"

namespace heavytop::table_testing {

// The built-in wooden toy top's numbers (about its tip O): A_G = 6e-6, C = 1.2e-5 kg m^2.
inline Body toy_top(double tip_radius) {
  Body b;
  b.mass = 0.060;
  b.length = 0.025;
  b.C = 1.2e-5;
  b.A = b.B = 6.0e-6 + b.mass * b.length * b.length;
  b.tip_radius = tip_radius;
  return b;
}

inline InitialState start(double spin, double theta0, double phi0 = 0.0, double phi_rate0 = 0.0) {
  InitialState s;
  s.spin = spin;
  s.theta0 = theta0;
  s.phi0 = phi0;
  s.phi_rate0 = phi_rate0;
  return s;
}

// Integrator settings of a tight run (relative and absolute tolerances).
inline Tolerances tolerances(double rtol, double atol) {
  Tolerances t;
  t.rtol = rtol;
  t.atol = atol;
  return t;
}

// The column called `name` of a table run (kTableColumns, kLossColumns).
inline const std::vector<double>& column(const TableRun& run, const char* name) {
  for (const auto& [n, values] : run.trajectory.extra)
    if (n == name) return values;
  throw std::runtime_error(std::string("no column ") + name);
}

}  // namespace heavytop::table_testing

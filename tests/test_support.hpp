#pragma once
// Helpers shared by the model tests (test_nonlinear, test_splitting, test_lagrange_exact):
// bodies and initial states in few words, the extra columns by name, the axis from SPEC's
// angles, numbers for the test report.

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::test_support {

// A body with mass 1, gravity 1 and length m g R, so that m g R is given directly.
inline Body make_body(double A, double B, double C, double mgR) {
  Body b;
  b.A = A;
  b.B = B;
  b.C = C;
  b.mass = 1.0;
  b.gravity = 1.0;
  b.length = mgR;
  return b;
}

inline InitialState make_state(double spin, double theta0, double phi0 = 0.0,
                               double theta_rate0 = 0.0, double phi_rate0 = 0.0) {
  InitialState s;
  s.spin = spin;
  s.theta0 = theta0;
  s.phi0 = phi0;
  s.theta_rate0 = theta_rate0;
  s.phi_rate0 = phi_rate0;
  return s;
}

// A number for the test report (RecordProperty), in scientific notation.
inline std::string sci(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

// The Trajectory::extra column `name`.
inline const std::vector<double>& column(const Trajectory& tr, const std::string& name) {
  for (const auto& [key, values] : tr.extra)
    if (key == name) return values;
  throw std::out_of_range("no column " + name);
}

// The axis k from SPEC's angles: (sin theta cos phi, -sin phi, cos theta cos phi).
inline Eigen::Vector3d axis_of(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), -std::sin(phi), std::cos(theta) * std::cos(phi)};
}

// rad, the angle between two unit vectors (accurate for small angles too).
inline double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace heavytop::test_support

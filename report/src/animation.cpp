#include "heavytop/report/animation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace heavytop::report {

std::vector<double> spin_angles(const Body& body, const Trajectory& tr) {
  const auto column = std::find_if(tr.extra.begin(), tr.extra.end(), [](const auto& c) { return c.first == "axial_momentum"; });
  if (column == tr.extra.end() || column->second.size() != tr.size())
    throw InvalidInput("trajectory", "needs the nonlinear model's axial_momentum column (C w3)");
  const std::vector<double>& cw3 = column->second;
  auto rate = [&](std::size_t i) { return cw3[i] / body.C + tr.theta_rate[i] * std::sin(tr.phi[i]); };
  std::vector<double> psi(tr.size(), 0.0);
  for (std::size_t i = 1; i < tr.size(); ++i) psi[i] = psi[i - 1] + 0.5 * (tr.t[i] - tr.t[i - 1]) * (rate(i - 1) + rate(i));
  return psi;
}

EquivalentEllipsoid equivalent_ellipsoid(const Body& body) {
  const double m = body.mass, shift = m * body.length * body.length;
  const double a = body.A - shift, b = body.B - shift, c = body.C;  // central moments
  // Squares of the semi-axes from the three moment equations.
  const std::array<double, 3> squares{2.5 * (b + c - a) / m, 2.5 * (a + c - b) / m, 2.5 * (a + b - c) / m};
  EquivalentEllipsoid e;
  e.centre = body.length;
  double largest = 0.0;
  for (double s : squares) largest = std::max(largest, std::sqrt(std::max(s, 0.0)));
  if (!(largest > 0.0)) largest = std::max(std::abs(body.length), 1.0);
  const char* axis[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < 3; ++i) {
    e.semi_axes[i] = std::sqrt(std::max(squares[i], 0.0));
    if (e.semi_axes[i] < kMinThickness * largest) {
      // A flat body (a disc's moments, A_c + B_c = C) gives 0 up to rounding; clearly below
      // 0, the moments are those of no real body (SPEC section 1's warning).
      const bool impossible = squares[i] < -1e-9 * largest * largest;
      e.note += fmt::format("{}the {} semi-axis ({}) is drawn at {:g} of the largest", e.note.empty() ? "" : "; ", axis[i],
                            impossible ? std::string("no real body has these moments")
                            : e.semi_axes[i] < 1e-6 * largest ? std::string("0: a flat body")
                                                              : fmt::format("{:.3g} m", e.semi_axes[i]),
                            kMinThickness);
      e.semi_axes[i] = kMinThickness * largest;
    }
  }
  return e;
}

}  // namespace heavytop::report

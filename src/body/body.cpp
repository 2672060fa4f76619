#include "heavytop/body.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <limits>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

namespace heavytop {

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else out += fmt::format("\\x{:02x}", u);
  }
  return out;
}

InvalidInput::InvalidInput(std::string key, std::string rule)
    : std::invalid_argument(printable(key) + ": " + printable(rule)), key_(printable(key)), rule_(printable(rule)) {}

namespace {

void require_finite(double value, const char* key) {
  if (!std::isfinite(value)) throw InvalidInput(key, "must be a finite number");
}

void require_positive(double value, const char* key) {
  require_finite(value, key);
  if (!(value > 0.0)) throw InvalidInput(key, "must be > 0");
}

void require_triangle(double a, double b, double c, const char* key, const char* rule) {
  if (a + b < c * (1.0 - kSymmetryTolerance)) throw InvalidInput(key, rule);
}

}  // namespace

bool is_symmetric(const Body& body) noexcept {
  return std::abs(body.A - body.B) <= kSymmetryTolerance * std::max(body.A, body.B);
}

double gravity_time(const Body& body) noexcept {
  const double k = std::abs(body.mgR());
  return k > 0.0 ? std::sqrt(std::min(body.A, body.B) / k) : std::numeric_limits<double>::infinity();
}

bool is_planar(const Body& body) noexcept { return body.A + body.B <= body.C * (1.0 + kSymmetryTolerance); }

bool is_realizable(const Body& body) {
  const GeneralInertia& g = body.general;
  const Eigen::Vector3d r(g.offset_x, g.offset_y, body.length);
  Eigen::Matrix3d inertia;
  inertia << body.A, -g.Ixy, -g.Ixz, -g.Ixy, body.B, -g.Iyz, -g.Ixz, -g.Iyz, body.C;
  // Parallel axes: about the centre of mass, I_O - m (|r|^2 1 - r r^T).
  const Eigen::Matrix3d central =
      inertia - body.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  const double tolerance = 1e-9 * inertia.trace();
  if (g.is_zero()) {  // principal already: no eigensolver's rounding
    const double a = central(0, 0), b = central(1, 1), c = central(2, 2);
    return a + b - c >= -tolerance && b + c - a >= -tolerance && c + a - b >= -tolerance;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(central, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d e = eig.eigenvalues();  // ascending
  return e(0) >= -tolerance && e(0) + e(1) - e(2) >= -tolerance;
}

void validate(const Body& body) {
  require_positive(body.A, "body.A");
  require_positive(body.B, "body.B");
  require_positive(body.C, "body.C");
  require_positive(body.mass, "body.mass");
  require_finite(body.gravity, "body.gravity");
  if (!(body.gravity >= 0.0)) throw InvalidInput("body.gravity", "must be >= 0");
  require_finite(body.length, "body.length");
  if (!std::isfinite(body.mgR()))
    throw InvalidInput("body.mass", "m g R overflows a double: the product of mass, gravity and length must be finite");
  require_triangle(body.A, body.B, body.C, "body.C",
                   "a real body has A + B >= C (triangle inequality of the moments of inertia)");
  require_triangle(body.B, body.C, body.A, "body.A",
                   "a real body has B + C >= A (triangle inequality of the moments of inertia)");
  require_triangle(body.C, body.A, body.B, "body.B",
                   "a real body has C + A >= B (triangle inequality of the moments of inertia)");
  validate(body.damping);
  for (const auto& [radius, key] : {std::pair{body.tip_radius, "body.tip_radius"}, std::pair{body.rim_radius, "body.rim_radius"}}) {
    require_finite(radius, key);
    if (!(radius >= 0.0)) throw InvalidInput(key, "must be >= 0 (m)");
  }
  const GeneralInertia& g = body.general;
  require_finite(g.offset_x, "body.offset_x");
  require_finite(g.offset_y, "body.offset_y");
  require_finite(g.Ixy, "body.Ixy");
  require_finite(g.Ixz, "body.Ixz");
  require_finite(g.Iyz, "body.Iyz");
  if (g.Ixy == 0.0 && g.Ixz == 0.0 && g.Iyz == 0.0) return;  // diagonal: the checks above suffice
  const char* key = g.Ixy != 0.0 ? "body.Ixy" : g.Ixz != 0.0 ? "body.Ixz" : "body.Iyz";
  Eigen::Matrix3d I;
  I << body.A, -g.Ixy, -g.Ixz, -g.Ixy, body.B, -g.Iyz, -g.Ixz, -g.Iyz, body.C;
  const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(l[0] > 0.0))
    throw InvalidInput(key, fmt::format("the inertia tensor [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]] must "
                                        "be positive definite (its smallest principal moment is {:.6g})", l[0]));
  // Ascending: the one inequality that can fail is l0 + l1 >= l2.
  if (l[0] + l[1] < l[2] * (1.0 - kSymmetryTolerance))
    throw InvalidInput(key, fmt::format("the principal moments {:.6g}, {:.6g}, {:.6g} of the inertia tensor break "
                                        "the triangle inequality (a real body has I1 + I2 >= I3)", l[0], l[1], l[2]));
}

bool is_general(const Body& body) noexcept { return !body.general.is_zero(); }

const char* first_general_key(const Body& body) noexcept {
  const GeneralInertia& g = body.general;
  if (g.offset_x != 0.0) return "body.offset_x";
  if (g.offset_y != 0.0) return "body.offset_y";
  if (g.Ixy != 0.0) return "body.Ixy";
  if (g.Ixz != 0.0) return "body.Ixz";
  if (g.Iyz != 0.0) return "body.Iyz";
  return nullptr;
}

void refuse_general(const Body& body, const char* what) {
  if (const char* key = first_general_key(body))
    throw InvalidInput(key, fmt::format("is nonzero: the general body (SPEC section 11: the centre of mass off the z "
                                        "axis, products of inertia) is integrated by simulate --model nonlinear only, "
                                        "not by {}", what));
}

Body example_toy_top() {
  // A wooden toy top: a 40 mm disc (5 mm thick, ~60 g) on a steel spindle, the centre of
  // mass 25 mm above the tip. Moments about the tip (parallel-axis theorem included).
  Body top;
  top.mass = 0.060;
  top.length = 0.025;
  top.C = 1.2e-5;              // (1/2) m r^2 of the disc, r = 20 mm
  top.A = 6.0e-6 + 3.75e-5;    // (1/4) m r^2 + m R^2
  top.B = top.A;
  top.gravity = 9.81;
  return top;
}

}  // namespace heavytop

#include "heavytop/body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace heavytop {

InvalidInput::InvalidInput(std::string key, std::string rule)
    : std::invalid_argument(key + ": " + rule), key_(std::move(key)), rule_(std::move(rule)) {}

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

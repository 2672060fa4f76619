#include "heavytop/damping.hpp"

#include <cmath>

#include "heavytop/body.hpp"

namespace heavytop {

void validate(const Damping& d) {
  auto require = [](double value, const char* key) {
    if (!std::isfinite(value)) throw InvalidInput(key, "must be a finite number");
    if (!(value >= 0.0)) throw InvalidInput(key, "must be >= 0");
  };
  require(d.transverse, "damping.transverse");
  require(d.axial, "damping.axial");
  require(d.friction, "damping.friction");
}

// With u = |w| > 0: C u' = -d_a u - tau0. Viscous alone: u = u0 exp(-t/T), T = C/d_a; with
// friction: u + tau0/d_a = (u0 + tau0/d_a) exp(-t/T), zero at T ln(1 + d_a u0/tau0); Coulomb
// alone: u = u0 - tau0 t / C. expm1/log1p keep small d_a t / C and d_a u0 / tau0 exact.
double SpinDecayLaw::spin(double spin0, double t) const {
  const double u0 = std::abs(spin0);
  if (const auto stop = stop_time(spin0); stop && t >= *stop) return 0.0;
  double u = u0;
  if (axial > 0.0) {
    const double decay = std::expm1(-axial * t / C);  // exp(-t/T) - 1
    const double offset = friction / axial;
    u = u0 + (u0 + offset) * decay;
  } else if (friction > 0.0) {
    u = u0 - friction * t / C;
  }
  return std::copysign(std::max(u, 0.0), spin0);
}

std::optional<double> SpinDecayLaw::stop_time(double spin0) const {
  if (!(friction > 0.0)) return std::nullopt;
  const double u0 = std::abs(spin0);
  if (axial > 0.0) return C / axial * std::log1p(axial * u0 / friction);
  return C * u0 / friction;
}

std::optional<double> SpinDecayLaw::time_to(double spin0, double target) const {
  const double u0 = std::abs(spin0);
  if (u0 <= target) return 0.0;
  if (axial > 0.0) {
    const double offset = friction / axial;
    if (target + offset <= 0.0) return std::nullopt;  // viscous alone never reaches 0
    return C / axial * std::log1p((u0 - target) / (target + offset));
  }
  if (friction > 0.0) return C * (u0 - target) / friction;
  return std::nullopt;
}

}  // namespace heavytop

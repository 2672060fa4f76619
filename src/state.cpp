#include "heavytop/state.hpp"

#include <cmath>

#include "heavytop/body.hpp"

namespace heavytop {

InitialState example_motion() { return InitialState{.spin = 200.0, .theta0 = 0.05}; }

void validate(const InitialState& s) {
  const std::pair<double, const char*> fields[] = {{s.spin, "motion.spin"},
                                                   {s.theta0, "motion.theta0"},
                                                   {s.phi0, "motion.phi0"},
                                                   {s.theta_rate0, "motion.theta_rate0"},
                                                   {s.phi_rate0, "motion.phi_rate0"}};
  for (const auto& [value, key] : fields)
    if (!std::isfinite(value)) throw InvalidInput(key, "must be a finite number");
}

void Trajectory::reserve(std::size_t n) {
  for (auto* column : {&t, &theta, &phi, &theta_rate, &phi_rate}) column->reserve(n);
}

std::vector<double> sample_times(double t_end, std::size_t n) {
  std::vector<double> times(n);
  for (std::size_t i = 0; i < n; ++i)
    times[i] = n == 1 ? 0.0 : t_end * static_cast<double>(i) / static_cast<double>(n - 1);
  return times;
}

}  // namespace heavytop

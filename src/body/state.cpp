#include "heavytop/state.hpp"

#include <cmath>
#include <utility>

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

std::vector<std::string> Trajectory::column_names() const {
  std::vector<std::string> names(kTrajectoryColumns.begin(), kTrajectoryColumns.end());
  for (const auto& [name, values] : extra) names.push_back(name);
  return names;
}

const std::vector<double>& Trajectory::column(std::size_t index) const {
  const std::vector<double>* base[] = {&t, &theta, &phi, &theta_rate, &phi_rate};
  return index < kTrajectoryColumns.size() ? *base[index] : extra.at(index - kTrajectoryColumns.size()).second;
}

std::vector<double>& Trajectory::column(std::size_t index) {
  return const_cast<std::vector<double>&>(std::as_const(*this).column(index));
}

void Trajectory::append(const Trajectory& other) {
  if (extra.empty() && size() == 0)
    for (const auto& [name, values] : other.extra) extra.emplace_back(name, std::vector<double>{});
  for (std::size_t c = 0; c < kTrajectoryColumns.size() + other.extra.size(); ++c)
    column(c).insert(column(c).end(), other.column(c).begin(), other.column(c).end());
}

std::vector<double> sample_times(double t_end, std::size_t n) {
  const SampleGrid grid{t_end, n};
  std::vector<double> times(n);
  for (std::size_t i = 0; i < n; ++i) times[i] = grid.time(i);
  return times;
}

}  // namespace heavytop

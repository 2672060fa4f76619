#pragma once
/// \file
/// The user's initial state and the reported motion (SPEC section 2).

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace heavytop {

/// The initial state, as the user gives it (SPEC section 2). Angles in rad, rates in rad/s.
/// phi: about fixed xi; theta: about the intermediate axis; the spin w0 about the body axis z.
struct InitialState {
  double spin = 0.0;         ///< rad/s, w0: the spin about the body's z axis
  double theta0 = 0.0;       ///< rad, theta(0) = atan2(k_xi, k_zeta)
  double phi0 = 0.0;         ///< rad, phi(0) = -asin(k_eta)
  double theta_rate0 = 0.0;  ///< rad/s, theta'(0)
  double phi_rate0 = 0.0;    ///< rad/s, phi'(0)
};

/// The built-in example's motion: example_toy_top() spun at 200 rad/s, 0.05 rad off vertical.
InitialState example_motion();

/// Throws InvalidInput (key "motion.<name>") unless every field is finite.
void validate(const InitialState& state);

/// True if `state` is the upright permanent rotation exactly: no tilt and no tilt rates, a motion
/// that never tilts however unstable it is (the answer and lifetime's words say so).
inline bool at_rest_upright(const InitialState& state) noexcept {
  return state.theta0 == 0.0 && state.phi0 == 0.0 && state.theta_rate0 == 0.0 && state.phi_rate0 == 0.0;
}

/// The motion of the axis sampled at times t: theta(t), phi(t) and their rates (SPEC section 2),
/// column by column, plus optional further named columns (e.g. conserved quantities).
struct Trajectory {
  std::vector<double> t;           ///< s
  std::vector<double> theta;       ///< rad
  std::vector<double> phi;         ///< rad
  std::vector<double> theta_rate;  ///< rad/s
  std::vector<double> phi_rate;    ///< rad/s
  std::vector<std::pair<std::string, std::vector<double>>> extra;  ///< further columns, SI units

  std::size_t size() const noexcept { return t.size(); }
  void reserve(std::size_t n);
  /// The column names, SPEC's five (kTrajectoryColumns) then the extra ones, in order.
  std::vector<std::string> column_names() const;
  /// Column `index` in column_names() order (index < 5 + extra.size()).
  const std::vector<double>& column(std::size_t index) const;
  std::vector<double>& column(std::size_t index);
  /// Appends the samples of `other`, which has the same columns.
  void append(const Trajectory& other);
};

/// The five columns every trajectory has, in SPEC order (section 5, `simulate`).
inline constexpr std::array<std::string_view, 5> kTrajectoryColumns = {"t", "theta", "phi", "theta_rate",
                                                                        "phi_rate"};

/// Uniform sample times t_i = i t_end / (count - 1) (t = {0} when count == 1), not stored.
struct SampleGrid {
  double t_end = 0.0;     ///< s, finite and >= 0
  std::size_t count = 0;  ///< samples
  /// s, the i-th time.
  double time(std::size_t i) const noexcept {
    return count == 1 ? 0.0 : t_end * static_cast<double>(i) / static_cast<double>(count - 1);
  }
};

/// n sample times t_i = i t_end / (n - 1), i = 0..n-1 (t = {0} when n == 1), SampleGrid's. s.
std::vector<double> sample_times(double t_end, std::size_t n);

}  // namespace heavytop

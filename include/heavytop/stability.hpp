#pragma once
/// \file
/// Linear stability of the linear models (SPEC section 3): the verdict at one spin, and the
/// exact set of spins at which a model is stable, from the characteristic polynomial.

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "heavytop/linear_models.hpp"

namespace heavytop {

/// The linear-stability verdict of a model at one spin.
struct StabilityVerdict {
  /// Every eigenvalue has real part <= 0 and those on the imaginary axis are semisimple
  /// (without damping every real part is then zero; SPEC sections 3 and 6).
  bool stable = false;
  /// 1/s, the largest real part of the eigenvalues: > 0 means the motion grows like
  /// exp(growth_rate t) (e-folding time 1 / growth_rate); < 0 that it decays (damped).
  double growth_rate = 0.0;
  /// 1/s, the four eigenvalues (roots of the characteristic polynomial), real part ascending.
  std::vector<std::complex<double>> eigenvalues;
  /// rad/s, the distinct |Im| of the eigenvalues, ascending; empty unless stable.
  std::vector<double> frequencies;
  /// Why, in a few words for a person ("two distinct frequencies", "Jordan block at ...").
  std::string reason;
};

/// The verdict of `model` at spin w0 (rad/s). Roots closer than about 1e-10 relative are
/// treated as double, and a double root is stable only if it is semisimple (no Jordan block;
/// erratum E2), which is decided from the system matrix, not from the discriminant alone.
/// With damping (model.damped()) the verdict is Routh-Hurwitz's on the quartic, exact in the
/// signs of its coefficients and of a3 a2 a1 - a4 a1^2 - a3^2 a0; on its boundary (a condition
/// zero to rounding) the eigenvalues on the imaginary axis are tested for semisimplicity.
StabilityVerdict linear_stability(const LinearModel& model, double spin);

/// A range of spins from lo to hi (rad/s); hi = nullopt means "and above". The model is
/// stable inside; at an end it is stable exactly where the end is included (as
/// linear_stability says there: the boundary of (9) is a Jordan block, so excluded).
struct SpinInterval {
  double lo = 0.0;
  std::optional<double> hi;
  bool lo_included = true;  ///< stable at w0 = lo itself
  bool hi_included = true;  ///< stable at w0 = hi itself (meaningless when hi is nullopt)
};

/// The spins w0 >= 0 at which `model` is stable, ascending and disjoint. The ends are roots
/// of the conditions on the characteristic polynomial (each a polynomial of degree <= 2 in
/// w0^2, with damping too: the Hurwitz conditions), solved in closed form, so they are exact
/// to rounding; no grid is scanned. Under drag the set is often empty (Kelvin-Tait-Chetaev).
std::vector<SpinInterval> stable_spin_intervals(const LinearModel& model);

/// rad/s, the lo of the unbounded stable interval: 0 when stable at every spin > 0 (at 0 itself
/// too only when that interval's lo_included: m g R = 0 gives 0 with the rest excluded, a Jordan
/// block), nullopt when no spin stabilises the model.
std::optional<double> critical_spin(const std::vector<SpinInterval>& intervals);

/// One linear model's stability: its verdict at a spin and the spins at which it is stable.
struct ModelStability {
  LinearModelKind kind = LinearModelKind::FirstOrder;
  StabilityVerdict verdict;              ///< at the spin asked
  std::vector<SpinInterval> intervals;   ///< rad/s, stable_spin_intervals()
  std::optional<double> critical;        ///< rad/s, critical_spin(intervals)
};

/// Every linear model of `body` (kLinearModels order) at spin w0 (rad/s): what `heavytop
/// stability` reports.
std::vector<ModelStability> analyse_stability(const Body& body, double spin);

}  // namespace heavytop

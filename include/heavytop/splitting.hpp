#pragma once
/// \file
/// A structure-preserving fixed-step integrator for the `nonlinear` model, for long horizons
/// (docs/integrators.md compares it with the adaptive one of nonlinear.hpp).
///
/// State: the attitude as a unit quaternion (body-to-fixed) and the angular momentum L = I w
/// in body axes. The Hamiltonian H = T(L) + V(gamma), V = m g R gamma_3, gamma = R^T e_zeta,
/// is split into flows each solved exactly:
///   V:  the gravity kick L += s m g R (gamma x e3) (the attitude does not move);
///   T:  the free body, T = |L|^2/(2B) + (1/A - 1/B) L1^2/2 + (1/C - 1/B) L3^2/2: a rotation
///       about L (|L|^2 commutes with everything) and rotations about body x and z.
/// The Strang step V(h/2) T1(h/2) [T_L(h) T3(h)] T1(h/2) V(h/2) is symmetric, symplectic on the
/// Lie-Poisson manifold, second order, and keeps |q| = 1, L_zeta = L.gamma (to rounding, for
/// any body) and, for A == B, L_3 (T1 vanishes: the free flow is exact). Order 4 is Suzuki's
/// five-step symmetric composition of it. Its energy error stays bounded (O(h^order)) over
/// very long runs instead of drifting.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"  // Drifts
#include "heavytop/progress.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// Settings of the splitting integrator.
struct SplittingOptions {
  /// s, the fixed step h: finite and > 0. Sample times off the grid t_n = n h are reached
  /// by one shorter step from the last grid point, taken on a copy (the grid is not moved).
  double step = 1e-3;
  /// 2: Strang splitting; 4: Suzuki's composition of it (five Strang steps per step).
  int order = 2;
  /// Largest number of grid steps a run may take (> 0): refuses a step too small for the
  /// horizon rather than running for days.
  std::size_t max_steps = 1'000'000'000;

  /// True if every setting is in range; otherwise false, and `why` (if not null) receives a
  /// one-line "key: rule" message (key "step", "order" or "max_steps").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput (key "step", "order" or "max_steps") unless options.IsValid().
void validate(const SplittingOptions& options);

/// What one run of the splitting integrator did (and its Drifts, over the grid).
struct SplittingSummary : Drifts {
  std::size_t steps = 0;          ///< grid steps of size h
  std::size_t partial_steps = 0;  ///< shorter steps (on copies) to land on sample times
  std::size_t kicks = 0;          ///< gravity kicks (torque evaluations), the unit of work
  double final_time = 0.0;        ///< s, the last grid point reached
  bool symmetric = false;         ///< A == B exactly: the free flow is exact, L_3 conserved

  /// One line for people: steps, kicks, drifts.
  std::string BriefReport() const;
};

/// The nonlinear motion from `initial` (SPEC section 2 mapping) by the splitting integrator,
/// sampled at `times` (s; finite, >= 0, non-decreasing; InvalidInput key "times" otherwise).
/// Columns and extra columns exactly as simulate_nonlinear: theta, phi, theta_rate, phi_rate,
/// then "energy" (J), "vertical_momentum", "axial_momentum" (kg m^2/s), "energy_drift",
/// "vertical_momentum_drift", "axial_momentum_drift" (value minus its value at t = 0).
/// Throws InvalidInput for a bad body, state or options.
Trajectory simulate_splitting(const Body& body, const InitialState& initial,
                              const std::vector<double>& times, const SplittingOptions& options,
                              SplittingSummary* summary = nullptr, const Progress& progress = {});

}  // namespace heavytop

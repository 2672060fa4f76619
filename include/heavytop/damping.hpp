#pragma once
/// \file
/// Damping and friction (SPEC section 6): the torques a real top feels, and the closed-form
/// decay of its spin. All zero (the default) is the conservative body of every other file.
///
/// Torques on the body, k the body's spin axis (body z), w its angular velocity:
///   transverse  -d_t w_perp, w_perp = w - (w.k) k   (air drag on the axis's motion, a damped pivot)
///   axial       -d_a (w.k) k                          (viscous drag on the spin)
///   friction    -tau0 sign(w.k) k                     (dry friction at the tip; holds w.k = 0 once there)
/// `driven`: a motor holds w.k at its value at t = 0 (a gyroscope); the axial and friction
/// torques then load the motor, not the body.

#include <optional>

namespace heavytop {

/// The torques of SPEC section 6 on a body. Part of Body (body.hpp) as Pinocchio keeps joint
/// damping and friction in its model: they are properties of the mounted body.
struct Damping {
  double transverse = 0.0;  ///< d_t, N m s (>= 0)
  double axial = 0.0;       ///< d_a, N m s (>= 0)
  double friction = 0.0;    ///< tau0, N m (>= 0)
  bool driven = false;      ///< a motor holds w.k (SPEC key motion.driven)

  /// True if no torque acts and no motor drives: the conservative body.
  bool conservative() const noexcept {
    return transverse == 0.0 && axial == 0.0 && friction == 0.0 && !driven;
  }
  /// True if the spin w.k changes by the law below (some axial torque and no motor).
  bool spin_decays() const noexcept { return !driven && (axial > 0.0 || friction > 0.0); }
};

/// Throws InvalidInput (key "damping.transverse", "damping.axial" or "damping.friction")
/// unless each is finite and >= 0.
void validate(const Damping& damping);

/// The spin law of a free symmetric body, C w' = -d_a w - tau0 sign(w) (exact for A = B,
/// SPEC section 6), in closed form. C in kg m^2 (> 0), spins in rad/s, times in s. A spin
/// brought to zero by dry friction stays zero. The motor of a driven body is ignored here:
/// callers ask damping.spin_decays() first.
struct SpinDecayLaw {
  double C = 0.0;         ///< kg m^2, the axial moment of inertia
  double axial = 0.0;     ///< d_a, N m s
  double friction = 0.0;  ///< tau0, N m

  /// rad/s, the spin at time t >= 0 from `spin0` at t = 0.
  double spin(double spin0, double t) const;
  /// s, the first time the spin's magnitude reaches `spin` (0 <= spin; 0 when |spin0| <= spin
  /// already); nullopt when it never does (no axial torque, or viscous drag alone and spin = 0).
  std::optional<double> time_to(double spin0, double spin) const;
  /// s, when dry friction stops the spin (nullopt without friction): C/d_a ln(1 + d_a |w0|/tau0),
  /// or C |w0| / tau0 without viscous drag.
  std::optional<double> stop_time(double spin0) const;
};

}  // namespace heavytop

#pragma once
/// \file
/// The full equations of the heavy top as a system in Boost.Odeint's concept: a callable
/// rhs(x, dxdt, t) on a fixed-size state, so any stepper plugs in (the library's own
/// integrators use other, cheaper coordinates of the same motion: nonlinear.hpp, splitting.hpp).
///
/// State x = (q_w, q_x, q_y, q_z, w_1, w_2, w_3): the attitude as a unit quaternion (body to
/// fixed frame) and the angular velocity in body axes (rad/s). Equations:
///     q' = q (x) (0, w) / 2,     I w' = (I w) x w + m g R (gamma x e3),
/// gamma = R(q)^T e_zeta the upward vertical in body axes, I = diag(A, B, C).

#include <array>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"

namespace heavytop {

/// The state vector of RigidBodySystem (dimensionless quaternion, then rad/s).
using RigidBodyVector = std::array<double, 7>;

/// The equations of motion of `body` (a copy: the system owns its parameters).
struct RigidBodySystem {
  Body body;

  /// dxdt = f(x); t (s) is unused (the system is autonomous). The quaternion need not be
  /// normalised: its rate is that of the rotation it represents, scaled by its norm.
  void operator()(const RigidBodyVector& x, RigidBodyVector& dxdt, double t) const;
};

/// The state vector of a rigid-body state (attitude body-to-fixed, w in body axes).
RigidBodyVector to_vector(const RigidBodyState& state);
/// The rigid-body state of a state vector (the quaternion normalised).
RigidBodyState from_vector(const RigidBodyVector& x);

}  // namespace heavytop

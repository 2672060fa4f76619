#pragma once
/// \file
/// The general body in the `nonlinear` model (SPEC section 11): the centre of mass anywhere in
/// body axes, c = (offset_x, offset_y, length), and the full inertia tensor about O,
/// I = [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]]. docs/general-body.md derives the
/// equations and the integrals the tests check (Kovalevskaya, Goryachev-Chaplygin).
///
/// State: the plain one of rigid_body.hpp, x = (q_w, q_x, q_y, q_z, w_1, w_2, w_3): the attitude
/// as a unit quaternion (body to fixed frame) and w in body axes (rad/s). Equations:
///     q' = q (x) (0, w) / 2,     I w' = (I w) x w + m g (gamma x c),
/// gamma = R(q)^T e_zeta the upward vertical in body axes (the weight -m g gamma acts at c, so
/// its moment about O is c x (-m g gamma) = m g gamma x c; for c = R e3 this is
/// RigidBodySystem's m g R gamma x e3). Integrated by Dormand-Prince 5(4) (Boost.Odeint) with
/// error control and its dense output. An ordinary body (general terms zero) keeps the fast
/// paths of nonlinear.hpp, taylor.hpp and dop853.hpp; simulate() sends only a general one here.

#include <vector>

#include <Eigen/Core>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/rigid_body.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// kg m^2, the inertia tensor about O in body axes (SPEC section 11; diag(A, B, C) when the
/// products are zero).
Eigen::Matrix3d inertia_tensor(const Body& body);

/// m, the centre of mass from O in body axes: (offset_x, offset_y, length).
Eigen::Vector3d centre_of_mass(const Body& body);

/// The general body's equations of motion as an Odeint system on RigidBodyVector (the state
/// of rigid_body.hpp). Holds its parameters (no reference to the Body).
struct GeneralRigidBodySystem {
  Eigen::Matrix3d inertia;   ///< kg m^2, I about O, body axes
  Eigen::Matrix3d inverse;   ///< 1/(kg m^2), I^-1
  Eigen::Vector3d weight;    ///< N m, m g c (c the centre of mass, body axes)

  /// The system of a validated `body` (the general terms may be zero).
  explicit GeneralRigidBodySystem(const Body& body);

  /// dxdt = f(x); t (s) unused. The quaternion need not be normalised (as RigidBodySystem).
  void operator()(const RigidBodyVector& x, RigidBodyVector& dxdt, double t) const;
};

/// E = 1/2 w.I w + m g c.gamma (J), L_zeta = (I w).gamma (kg m^2/s) and, in the axial_momentum
/// field, (I w).e3, the angular momentum about body z (kg m^2/s; C w3 for an ordinary body;
/// conserved only for A = B with z principal and c on z) of `body` in the state `x`.
ConservedQuantities general_conserved_quantities(const Body& body, const RigidBodyState& x);

/// The general body's states (attitude body-to-fixed, w in body axes) at `times` (s; finite,
/// >= 0, non-decreasing; key "times"), started from `x0` at t = 0. Throws InvalidInput for a
/// bad body ("body.*"; a damped body: key "damping.*", not integrated here) or options ("rtol",
/// "atol", "max_steps"); std::runtime_error (one line) when the tolerance cannot be met,
/// max_steps is exceeded or the state stops being finite. The summary's drifts use
/// E_scale = T(0) + m g |c| and L_scale = sqrt(2 max eig(I) E_scale).
std::vector<RigidBodyState> integrate_general_body(const Body& body, const RigidBodyState& x0,
                                                   const std::vector<double>& times,
                                                   const Tolerances& options = {},
                                                   NonlinearSummary* summary = nullptr,
                                                   const Progress& progress = {});

/// simulate_nonlinear() for the general body: the body axes start on Q(phi0, theta0) (SPEC
/// section 2 and 11), k is body z; the same columns (angles by SPEC section 2, then energy,
/// vertical_momentum, axial_momentum = (I w).e3 and their drifts). Throws as
/// integrate_general_body().
Trajectory simulate_general_body(const Body& body, const InitialState& initial, const std::vector<double>& times,
                                 const Tolerances& options = {}, NonlinearSummary* summary = nullptr,
                                 const Progress& progress = {});

}  // namespace heavytop

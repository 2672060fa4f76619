#pragma once
/// \file
/// The three linear models of the axis's small motion (SPEC section 3), as data.
///
/// Each is a gyroscopic system in two angles q = (q1, q2):
///     M q'' + (w0 G1 + d_t I) q' + (K0 + w0^2 K2 + d_t w0 N1) q = 0,
/// with M, K0, K2 diagonal, G1 zero on its diagonal, d_t the transverse damping of SPEC
/// section 6 (0 for the conservative body) and N1 its circulatory part: zero in the axis-frame
/// models, where the drag -d_t w_perp is -d_t q', and [[0, -1], [1, 0]] in the body frame,
/// where w_perp = (phi_b' - w0 theta_b, theta_b' + w0 phi_b) also carries the spin. The coordinates are
///   first-order, body-fixed: q = (phi, theta), the paper's angles of the axis (Resal) frame;
///   linearized: q = (phi_b, theta_b), the same tilt measured in the spinning body frame,
///               where the vertical in body axes is gamma = (-theta_b, phi_b, 1) to first order.
/// docs/linearization.md derives all three.

#include <array>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "heavytop/body.hpp"

namespace heavytop {

enum class LinearModelKind {
  FirstOrder,  ///< the paper's model (4) = (6) = its Lagrange model
  BodyFixed,   ///< the paper's model (5): gyroscopic coefficients (C - B) w0 and (C - A) w0
  Linearized,  ///< the exact linearisation about the upright permanent rotation (body frame)
};

/// Every linear model, in the order SPEC lists them.
inline constexpr std::array<LinearModelKind, 3> kLinearModels = {
    LinearModelKind::FirstOrder, LinearModelKind::BodyFixed, LinearModelKind::Linearized};

/// SPEC name of a model: "first-order", "body-fixed", "linearized".
std::string_view name(LinearModelKind kind);

/// The model called `name` in SPEC, or nullopt.
std::optional<LinearModelKind> linear_model_from_name(std::string_view name);

/// A linear model's coefficients; see the file comment for the equation and coordinates.
struct LinearModel {
  LinearModelKind kind = LinearModelKind::FirstOrder;
  Eigen::Matrix2d M;   ///< kg m^2, inertia (diagonal)
  Eigen::Matrix2d G1;  ///< kg m^2, gyroscopic coefficients per unit spin (zero diagonal)
  Eigen::Matrix2d K0;  ///< N m, stiffness at zero spin (diagonal; -m g R for the paper's models)
  Eigen::Matrix2d K2;  ///< kg m^2, stiffness per unit spin squared (diagonal)
  /// kg^2 m^4, g^2 + 2 (M11 K2_22 + M22 K2_11) with g^2 = -G1_12 G1_21: the combination the
  /// discriminant's w0^4 coefficient needs, set by linear_model() in closed form ((C - A + B)(C + A - B)
  /// for `linearized`, where the sum of its terms cancels for a slender body, C << A).
  double gyro_stiffness = 0.0;
  /// N m s, d_t: the transverse damping (SPEC section 6; 0 for the conservative body).
  double damping = 0.0;
  /// Dimensionless, the circulatory matrix per unit d_t w0 (zero but in `linearized`).
  Eigen::Matrix2d N1 = Eigen::Matrix2d::Zero();

  /// kg m^2/s, gyroscopic matrix at spin w0 (rad/s).
  Eigen::Matrix2d G(double spin) const { return spin * G1; }
  /// N m, the conservative (diagonal) stiffness matrix at spin w0 (rad/s).
  Eigen::Matrix2d K(double spin) const { return K0 + spin * spin * K2; }
  /// N m s, the damping matrix d_t I.
  Eigen::Matrix2d D() const { return damping * Eigen::Matrix2d::Identity(); }
  /// N m, the circulatory (non-conservative positional) matrix d_t w0 N1 at spin w0 (rad/s).
  Eigen::Matrix2d circulatory(double spin) const { return damping * spin * N1; }
  /// True if d_t > 0: the damped analysis applies (odd powers in the polynomial).
  bool damped() const noexcept { return damping > 0.0; }
};

/// The model `kind` of `body` (which should satisfy validate()), with its transverse damping
/// body.damping.transverse (the linear models keep the spin constant, so only d_t enters).
LinearModel linear_model(LinearModelKind kind, const Body& body);

/// 1/s, the first-order system matrix J of x = (q1, q2, q1', q2'): x' = J x (rate = 1).
/// With a frequency `rate` (rad/s) it is the matrix of (q, q'/rate) in the time rate t, a
/// dimensionless similarity transform of J / rate (same Jordan structure, eigenvalues divided
/// by rate) whose entries are of order one when rate is the problem's frequency scale.
Eigen::Matrix4d state_matrix(const LinearModel& model, double spin, double rate = 1.0);

/// The characteristic polynomial det(M l^2 + (G + D) l + K + N) = a4 l^4 + a3 l^3 + a2 l^2
/// + a1 l + a0 (the odd powers vanish without damping). Units: a_k kg^2 m^4 / s^(4-k).
struct CharacteristicPolynomial {
  double a4 = 0.0;
  double a3 = 0.0;
  double a2 = 0.0;
  double a1 = 0.0;
  double a0 = 0.0;
};

/// The characteristic polynomial of `model` at spin w0 (rad/s).
CharacteristicPolynomial characteristic_polynomial(const LinearModel& model, double spin);

// ---- The paper's closed forms, kept under their own names for cross-checks ----------------

/// rad/s, the paper's condition (9) for model (4): w0^2 >= (sqrt A + sqrt B)^2 m g R / C^2.
/// Returns that bound for m g R > 0 and 0 for m g R <= 0 (stable at every spin by (4)).
/// The bound itself is not stable (erratum E2): stability needs strict inequality.
double paper_condition_9_spin(const Body& body);

/// rad/s, the analogue of (9) for the body-fixed model (5), for m g R > 0:
/// w0^2 > (sqrt A + sqrt B)^2 m g R / ((C - A)(C - B)); nullopt when (C - A)(C - B) <= 0
/// (no spin stabilises it; e.g. A = B = C). For A = B: 4 A m g R / (C - A)^2.
/// Throws std::domain_error for m g R <= 0, where (5) has no threshold of this form.
std::optional<double> paper_body_fixed_spin(const Body& body);

}  // namespace heavytop

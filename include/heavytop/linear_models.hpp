#pragma once
/// \file
/// The three linear models of the axis's small motion (SPEC section 3), as data.
///
/// Each is a gyroscopic system in two angles q = (q1, q2):
///     M q'' + w0 G1 q' + (K0 + w0^2 K2) q = 0,
/// with M, K0, K2 diagonal and G1 zero on its diagonal. The coordinates are
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

  /// kg m^2/s, gyroscopic matrix at spin w0 (rad/s).
  Eigen::Matrix2d G(double spin) const { return spin * G1; }
  /// N m, stiffness matrix at spin w0 (rad/s).
  Eigen::Matrix2d K(double spin) const { return K0 + spin * spin * K2; }
};

/// The model `kind` of `body` (which should satisfy validate()).
LinearModel linear_model(LinearModelKind kind, const Body& body);

/// 1/s, the first-order system matrix J of x = (q1, q2, q1', q2'): x' = J x (rate = 1).
/// With a frequency `rate` (rad/s) it is the matrix of (q, q'/rate) in the time rate t, a
/// dimensionless similarity transform of J / rate (same Jordan structure, eigenvalues divided
/// by rate) whose entries are of order one when rate is the problem's frequency scale.
Eigen::Matrix4d state_matrix(const LinearModel& model, double spin, double rate = 1.0);

/// The characteristic polynomial det(M l^2 + G l + K) = a4 l^4 + a2 l^2 + a0 (odd powers
/// vanish for every model here). Units: a4 kg^2 m^4, a2 kg^2 m^4/s^2, a0 kg^2 m^4/s^4.
struct CharacteristicPolynomial {
  double a4 = 0.0;
  double a2 = 0.0;
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

#include "heavytop/linear_models.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

namespace heavytop {

std::string_view name(LinearModelKind kind) {
  switch (kind) {
    case LinearModelKind::FirstOrder: return "first-order";
    case LinearModelKind::BodyFixed: return "body-fixed";
    case LinearModelKind::Linearized: return "linearized";
  }
  return "?";
}

std::optional<LinearModelKind> linear_model_from_name(std::string_view text) {
  for (LinearModelKind kind : kLinearModels)
    if (name(kind) == text) return kind;
  return std::nullopt;
}

LinearModel linear_model(LinearModelKind kind, const Body& body) {
  refuse_general(body, "the linear models");
  const double A = body.A, B = body.B, C = body.C, k = body.mgR();
  LinearModel m;
  m.kind = kind;
  m.M << A, 0.0, 0.0, B;
  m.K0 << -k, 0.0, 0.0, -k;
  m.K2.setZero();
  m.damping = body.damping.transverse;
  switch (kind) {
    case LinearModelKind::FirstOrder:  // A phi'' + C w0 theta' = k phi;  B theta'' - C w0 phi' = k theta
      m.G1 << 0.0, C, -C, 0.0;
      m.gyro_stiffness = C * C;
      break;
    case LinearModelKind::BodyFixed:  // (C - B) and (C - A) in place of C
      m.G1 << 0.0, C - B, -(C - A), 0.0;
      m.gyro_stiffness = (C - B) * (C - A);
      break;
    case LinearModelKind::Linearized:
      // Euler-Poisson in body axes about omega = w0 e3, gamma = e3 (docs/linearization.md):
      // A phi_b'' + (C - A - B) w0 theta_b' + ((C - B) w0^2 - k) phi_b = 0
      // B theta_b'' - (C - A - B) w0 phi_b' + ((C - A) w0^2 - k) theta_b = 0
      m.G1 << 0.0, C - A - B, -(C - A - B), 0.0;
      m.K2 << C - B, 0.0, 0.0, C - A;
      // (C - A - B)^2 + 2 (A (C - A) + B (C - B)) = C^2 - (A - B)^2, as a product whose
      // factors keep C whole when C << A = B (C - A + B would cancel to C's rounding error).
      m.gyro_stiffness = (C + (B - A)) * (C - (B - A));
      // The drag -d_t (p, q) on the body rates p = phi_b' - w0 theta_b, q = theta_b' + w0 phi_b.
      m.N1 << 0.0, -1.0, 1.0, 0.0;
      break;
  }
  return m;
}

Eigen::Matrix4d state_matrix(const LinearModel& model, double spin, double rate) {
  const Eigen::Matrix2d m_inv = model.M.inverse();
  Eigen::Matrix4d j;
  j << Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Identity(),
      -m_inv * (model.K(spin) + model.circulatory(spin)) / (rate * rate),
      -m_inv * (model.G(spin) + model.D()) / rate;
  return j;
}

CharacteristicPolynomial characteristic_polynomial(const LinearModel& model, double spin) {
  // det [[M11 l^2 + d l + K11, G12 l + N12], [G21 l + N21, M22 l^2 + d l + K22]] with M, K
  // diagonal, G and N zero-diagonal.
  const Eigen::Matrix2d g = model.G(spin), k = model.K(spin), n = model.circulatory(spin);
  const double d = model.damping;
  CharacteristicPolynomial p;
  p.a4 = model.M(0, 0) * model.M(1, 1);
  p.a3 = d * (model.M(0, 0) + model.M(1, 1));
  p.a2 = model.M(0, 0) * k(1, 1) + model.M(1, 1) * k(0, 0) + d * d - g(0, 1) * g(1, 0);
  p.a1 = d * (k(0, 0) + k(1, 1)) - (g(0, 1) * n(1, 0) + g(1, 0) * n(0, 1));
  p.a0 = k(0, 0) * k(1, 1) - n(0, 1) * n(1, 0);
  return p;
}

double paper_condition_9_spin(const Body& body) {
  const double k = body.mgR();
  if (k <= 0.0) return 0.0;
  return (std::sqrt(body.A) + std::sqrt(body.B)) * std::sqrt(k) / body.C;
}

std::optional<double> paper_body_fixed_spin(const Body& body) {
  const double k = body.mgR();
  if (!(k > 0.0)) throw std::domain_error("paper_body_fixed_spin: needs m g R > 0");
  const double gyro = (body.C - body.A) * (body.C - body.B);
  if (!(gyro > 0.0)) return std::nullopt;
  return (std::sqrt(body.A) + std::sqrt(body.B)) * std::sqrt(k / gyro);
}

}  // namespace heavytop

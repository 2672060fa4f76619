#pragma once
// Private to the library: the principal-axes body in spin-factored variables (docs/nonlinear.md),
// the state the dopri5 driver integrates for it (nonlinear.cpp): its slots, its equations of
// motion (conservative or damped), its conversions to and from a rigid-body state, the axis's
// angles and tilt read from it, and its first integrals for the monitor.

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <tuple>

#include <Eigen/Geometry>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/nonlinear.hpp"

#include "integrators/integration.hpp"

namespace heavytop::detail::spin_factored {

// ---- State and equations of motion ----------------------------------------------------------
//
// The body's attitude is q = p (x) exp(psi e3 / 2): p a quaternion whose frame N shares the
// body's z axis but does not spin about it, psi the spin angle of the body in N. Choosing
// psi' = w3 leaves p only the transverse angular velocity v = Rz(psi) (w1, w2), so nothing in
// (p, v) turns at the spin rate: a fast top costs steps at its nutation frequency, not at its
// spin (docs/nonlinear.md). This is an exact change of variables, valid for any body.
//
// State: p = (w, x, y, z) [0..3], v = (v1, v2) in N axes [4, 5] (rad/s), w3 [6] (rad/s),
// psi [7] (rad). A damped body (SPEC section 6) adds the integrals of what its torques take
// away: the work [8] (J), the vertical [9] and the axial [10] angular momentum (kg m^2/s), so
// that E + work, L_zeta + loss and C w3 + loss are first integrals the monitor checks.
template <bool Damped>
using StateOf = std::array<double, Damped ? 11 : 8>;
using State = StateOf<false>;
constexpr int kPw = 0, kPx = 1, kPy = 2, kPz = 3, kV1 = 4, kV2 = 5, kW3 = 6, kPsi = 7;
constexpr int kWork = 8, kVerticalLoss = 9, kAxialLoss = 10;

// gamma = R_p^T e_zeta, the vertical in N axes (third row of R_p). Dividing by |p|^2 makes the
// equations depend on the direction of p only, so its norm can drift without effect.
struct Vertical {
  double g1, g2, g3;
};
template <class S>
inline Vertical vertical(const S& x) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz];
  const double inv = 1.0 / (w * w + qx * qx + qy * qy + qz * qz);
  return {2.0 * (qx * qz - w * qy) * inv, 2.0 * (qy * qz + w * qx) * inv,
          (w * w - qx * qx - qy * qy + qz * qz) * inv};
}

// p' = 1/2 p (x) (0, v1, v2, 0).
template <class S>
inline void attitude_rate(const S& x, S& d) {
  const double w = x[kPw], qx = x[kPx], qy = x[kPy], qz = x[kPz], v1 = x[kV1], v2 = x[kV2];
  d[kPw] = -0.5 * (qx * v1 + qy * v2);
  d[kPx] = 0.5 * (w * v1 - qz * v2);
  d[kPy] = 0.5 * (w * v2 + qz * v1);
  d[kPz] = 0.5 * (qx * v2 - qy * v1);
}

// Euler: I w' + w x I w = m g R (gamma x e3) + tau in body axes; v = Rz(psi) (w1, w2) adds
// w3 J v. Symmetric (A == B): the transverse inertia is isotropic, psi drops out, no
// trigonometry. Damped: tau = -d_t w_perp + tau_z k, with tau_z the axial torque of the mode:
// sliding (-d_a w3 - tau0 sign, sign = `mode`), stuck (mode 0: static friction holds w3 = 0),
// or driven (the motor cancels what would change w3).
template <bool Symmetric, bool Damped = false>
struct Equations {
  using State = StateOf<Damped>;
  double c_over_a = 0.0;  // C / A (symmetric case)
  double bc_a = 0.0;      // (B - C) / A
  double ca_b = 0.0;      // (C - A) / B
  double ab_c = 0.0;      // (A - B) / C
  double k_a = 0.0;       // m g R / A, 1/s^2
  double k_b = 0.0;       // m g R / B, 1/s^2
  double drag = 0.0;      // d_t, N m s
  double axial = 0.0;     // d_a, N m s
  double friction = 0.0;  // tau0, N m
  double a = 0.0, b = 0.0, c = 0.0;  // A, B, C
  bool driven = false;
  double mode = 1.0;      // sign of w3 while sliding; 0 while dry friction holds it

  explicit Equations(const Body& b)
      : c_over_a(b.C / b.A),
        bc_a((b.B - b.C) / b.A),
        ca_b((b.C - b.A) / b.B),
        ab_c((b.A - b.B) / b.C),
        k_a(b.mgR() / b.A),
        k_b(b.mgR() / b.B),
        drag(b.damping.transverse),
        axial(b.damping.axial),
        friction(b.damping.friction),
        a(b.A), b(b.B), c(b.C),
        driven(b.damping.driven) {}

  // N m, the axial torque tau_z on the body, given the gyroscopic (A - B) w1 w2.
  double axial_torque(double w3, double gyroscopic) const {
    if (driven || mode == 0.0) return -gyroscopic;  // the motor or static friction holds w3
    return -axial * w3 - friction * mode;
  }

  void operator()(const State& x, State& d, double /*t*/) const {
    attitude_rate(x, d);
    const Vertical g = vertical(x);
    const double v1 = x[kV1], v2 = x[kV2], w3 = x[kW3];
    [[maybe_unused]] double gyroscopic = 0.0;  // (A - B) w1 w2, N m
    if constexpr (Symmetric) {
      const double n = c_over_a * w3;  // nutation frequency C w3 / A
      d[kV1] = -n * v2 + k_a * g.g2;
      d[kV2] = n * v1 - k_a * g.g1;
      d[kW3] = 0.0;
      if constexpr (Damped) {  // -d_t w_perp / A, the same in N axes as in body axes
        d[kV1] -= drag / a * v1;
        d[kV2] -= drag / a * v2;
      }
    } else {
      const double cs = std::cos(x[kPsi]), sn = std::sin(x[kPsi]);
      const double w1 = cs * v1 + sn * v2, w2 = cs * v2 - sn * v1;  // body axes: Rz(-psi)
      const double b1 = cs * g.g1 + sn * g.g2, b2 = cs * g.g2 - sn * g.g1;
      double dw1 = bc_a * w2 * w3 + k_a * b2;
      double dw2 = ca_b * w3 * w1 - k_b * b1;
      if constexpr (Damped) {
        dw1 -= drag / a * w1;
        dw2 -= drag / b * w2;
        gyroscopic = (a - b) * w1 * w2;
      }
      d[kV1] = cs * dw1 - sn * dw2 - w3 * v2;  // back to N: Rz(psi), plus w3 J v
      d[kV2] = sn * dw1 + cs * dw2 + w3 * v1;
      d[kW3] = ab_c * w1 * w2;
    }
    if constexpr (Damped) {
      const double tz = axial_torque(w3, gyroscopic);
      d[kW3] += tz / c;
      // What the torques take away: -tau.w, -tau.zeta (gravity's torque has none) and -tau_z.
      d[kWork] = drag * (v1 * v1 + v2 * v2) - tz * w3;
      d[kVerticalLoss] = drag * (v1 * g.g1 + v2 * g.g2) - tz * g.g3;
      d[kAxialLoss] = -tz;
    }
    d[kPsi] = w3;
  }
};

// ---- Conversions ------------------------------------------------------------------------------

template <class S = State>
S to_state(const RigidBodyState& rb) {
  const Eigen::Quaterniond q = unit_quaternion(rb.attitude);
  S x{};  // the integrals of a damped body start at 0
  const double head[] = {q.w(), q.x(), q.y(), q.z(), rb.omega.x(), rb.omega.y(), rb.omega.z(), 0.0};
  std::copy(std::begin(head), std::end(head), x.begin());
  return x;
}

template <class S>
Eigen::Matrix3d attitude_of_p(const S& x) {
  return Eigen::Quaterniond(x[kPw], x[kPx], x[kPy], x[kPz]).normalized().toRotationMatrix();
}

template <class S>
RigidBodyState to_rigid_body(const S& x) {
  const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
  Eigen::Matrix3d rz;
  rz << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  RigidBodyState rb;
  rb.attitude = attitude_of_p(x) * rz;
  rb.omega = Eigen::Vector3d(c * x[kV1] + s * x[kV2], c * x[kV2] - s * x[kV1], x[kW3]);
  return rb;
}

// The axis k = R_p e3 and k' = R (w x e3) = v2 n1 - v1 n2 (n1, n2 the first columns of R_p):
// the spin never enters, so k' carries no rounding error of size |w3|.
template <class S>
AxisAngles angles_of(const S& x) {
  const Eigen::Matrix3d rp = attitude_of_p(x);
  const Eigen::Vector3d k = rp.col(2);
  const Eigen::Vector3d k_rate = x[kV2] * rp.col(0) - x[kV1] * rp.col(1);
  return axis_angles(k, k_rate);
}

// Tilt acos(k_zeta), by the one tilt formula (frames.hpp): accurate near 0 as well.
template <class S>
double tilt_of(const S& x) {
  const Vertical g = vertical(x);  // (n1.zeta, n2.zeta, k.zeta), normalised
  return tilt_of_axis(g.g1, g.g2, g.g3);
}

// d(k_zeta)/dt = (v2 n1 - v1 n2).zeta.
template <class S>
double tilt_cos_rate(const S& x) {
  const Vertical g = vertical(x);
  return x[kV2] * g.g1 - x[kV1] * g.g2;
}

// ---- First integrals (for the monitor) ----------------------------------------------------------

// E, L_zeta, C w3 straight from the integration state (no matrices; used at every step).
template <class S>
ConservedQuantities conserved_of_state(const Body& body, const S& x, bool symmetric) {
  const Vertical g = vertical(x);
  double w1 = x[kV1], w2 = x[kV2], b1 = g.g1, b2 = g.g2;
  if (!symmetric) {  // to body axes; for A == B the transverse terms are invariant under Rz
    const double c = std::cos(x[kPsi]), s = std::sin(x[kPsi]);
    w1 = c * x[kV1] + s * x[kV2];
    w2 = c * x[kV2] - s * x[kV1];
    b1 = c * g.g1 + s * g.g2;
    b2 = c * g.g2 - s * g.g1;
  }
  ConservedQuantities q = conserved_from(body, w1, w2, x[kW3], b1, b2, g.g3);
  if constexpr (std::tuple_size_v<S> > kWork) {  // damped: plus what the torques took away
    q.energy += x[kWork];
    q.vertical_momentum += x[kVerticalLoss];
    q.axial_momentum += x[kAxialLoss];
  }
  return q;
}

}  // namespace heavytop::detail::spin_factored

#pragma once
// Private to the Taylor integrator (src/integrators/taylor/): its sets of variables, what
// each holds in which slot, its constants from the body, how it reads and writes a rigid-body
// state, and its conserved quantities and drift scales. The recurrence of each set (its
// coefficients, order by order) is in recurrence.hpp.

#include <algorithm>
#include <array>

#include <Eigen/Core>

#include "heavytop/body.hpp"
#include "heavytop/general_body.hpp"
#include "heavytop/rigid_body.hpp"
#include "heavytop/taylor.hpp"

#include "integrators/integration.hpp"
#include "integrators/taylor/series.hpp"

namespace heavytop::detail::taylor {

// ---- The sets of variables --------------------------------------------------------------------
//
// Both keep the attitude quaternion in slots 0..3 (w, x, y, z) and compute the series of the
// upward vertical's first two components gamma_1, gamma_2 along the way: the torque
// m g R (gamma x e3) = m g R (gamma_2, -gamma_1, 0) needs them, and so does the tilt's rate
// d(k_zeta)/dt = gamma_1 u_2 - gamma_2 u_1 (u = w, or v in the non-spinning frame).
// gamma = R(q)^T e_zeta is quadratic in q for |q| = 1, which the exact flow keeps and every
// step restores (normalise()), so the right-hand side is a quadratic polynomial.
//   gamma_1 = 2 (qx qz - qw qy),  gamma_2 = 2 (qy qz + qw qx).
//
// A damped body has its own two sets (DampedPlain, DampedSpinFactored, below), whose torques
// linear in w are linear terms in the w (or v, w3) rows: - d_t/A w1[n] etc.
struct Gamma {
  Coefficients g1{}, g2{};
};

// The conserved quantities and drift scales of a body on principal axes (every set but General).
struct OrdinaryBody {
  static ConservedQuantities conserved(const Body& body, const RigidBodyState& x) {
    return conserved_quantities(body, x);
  }
  static Scales scales(const Body& body, const RigidBodyState& x0) { return scales_of(body, x0); }
};

// The seven variables of the conservative sets: a quaternion in slots 0..3 (q, or SpinFactored's
// p) and an angular velocity in 4..6 (body-axes w, or v1, v2, w3), as to_vector/from_vector
// (rigid_body.hpp) hold them, the quaternion normalised on the way out. For SpinFactored
// psi = 0 at the start (p = q, v = (w1, w2)), and its state read as a body (attitude R_p,
// angular velocity (v1, v2, w3)) has the body's axis, the axis's rate (k' = v2 n1 - v1 n2) and
// E, L_zeta, C w3 (all Rz-invariant for A == B).
struct SevenVariables {
  static constexpr int kSize = 7, kWidth = 8;
  static constexpr bool kDamped = false;
  static constexpr int kU1 = 4, kU2 = 5;  // the velocity components in d(k_zeta)/dt
  static std::array<double, 7> state_of(const RigidBodyState& rb) { return to_vector(rb); }
  static RigidBodyState rigid_body(const std::array<double, 7>& x) { return from_vector(x); }
};

// The plain state of rigid_body.hpp: q (body to fixed), w in body axes. 19 Cauchy products
// per order: q (x) w (all 12 pairs q_i w_m), gamma (4), w x I w (3).
struct Plain : OrdinaryBody, SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::Plain;
  double e1, e2, e3, ka, kb;  // (B - C)/A, (C - A)/B, (A - B)/C (1), m g R / A, m g R / B (1/s^2)

  explicit Plain(const Body& b)
      : e1((b.B - b.C) / b.A), e2((b.C - b.A) / b.B), e3((b.A - b.B) / b.C), ka(b.mgR() / b.A),
        kb(b.mgR() / b.B) {}

  // Coefficients 1..p of every variable from row 0; gamma up to order p - 1.
  void coefficients(Jet& x, Gamma& g, int p) const;  // recurrence.hpp
};

// The general body of general_body.hpp (SPEC section 11) in the plain state: I w' = (I w) x w
// + gamma x (m g c), with the full inertia tensor I and the centre of mass c anywhere in body
// axes. 26 Cauchy products per order: q (x) w (12), gamma (all three components: 8), (I w) x w
// (6, the series of L = I w being linear in w's). w' = I^-1 (...) is linear.
struct General : SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::General;
  Eigen::Matrix3d inertia, inverse;  // kg m^2, I about O, and its inverse (body axes)
  Eigen::Vector3d weight;            // N m, m g c
  mutable double L[kM + 1][3] = {};  // the series of I w (kg m^2/s), filled order by order

  explicit General(const Body& b) {
    const GeneralRigidBodySystem system(b);
    inertia = system.inertia, inverse = system.inverse, weight = system.weight;
  }

  void coefficients(Jet& x, Gamma& g, int p) const;  // recurrence.hpp

  static ConservedQuantities conserved(const Body& body, const RigidBodyState& x) {
    return general_conserved_quantities(body, x);
  }
  static Scales scales(const Body& body, const RigidBodyState& x0) { return general_scales(body, x0); }
};

// The spin-factored state of nonlinear.hpp for A == B: q = p (x) exp(psi e3 / 2) with
// psi' = w3, p's frame N turns with the transverse angular velocity v = Rz(psi)(w1, w2) only.
// For A == B, w3 is constant and psi drops out: v' = (C w3 / A) J v + (m g R / A) J gamma.
// Slot 6 holds w3 (its series is the constant). 12 Cauchy products per order:
// p (x) v (the 8 pairs p_i v_m) and gamma (4).
struct SpinFactored : OrdinaryBody, SevenVariables {
  static constexpr TaylorVariables kVariables = TaylorVariables::SpinFactored;
  double c_over_a, ka;  // C / A (1), m g R / A (1/s^2)

  explicit SpinFactored(const Body& b) : c_over_a(b.C / b.A), ka(b.mgR() / b.A) {}

  void coefficients(Jet& x, Gamma& g, int p) const;  // recurrence.hpp
};

// ---- A damped body (SPEC section 6) ------------------------------------------------------------
//
// The state of the conservative sets, plus the integrals of what the torques take away, as in
// dopri5's damped state: the work [7] (J), the vertical [8] and the axial [9] angular momentum
// (kg m^2/s), so that E + work, L_zeta + loss and C w3 + loss are first integrals. Torques:
// -d_t w_perp, and the axial tau_z of the friction mode (detail::initial_friction_mode):
// sliding -d_a w3 - tau0 mode, held (stuck, or driven) -(A - B) w1 w2 with w3' = 0 exactly.
// Within a mode the right-hand side stays a quadratic polynomial: the linear torques are
// linear terms of the w (v) rows, at no extra product; the integrals' rates add |w_perp|^2
// (2 products), gamma_3 (4), w_perp.gamma (2), tau_z w3 and tau_z gamma_3 (2).
struct DampedTerms : OrdinaryBody {
  static constexpr int kSize = 10, kWidth = 10;
  static constexpr bool kDamped = true;
  static constexpr int kWork = 7, kVerticalLoss = 8, kAxialLoss = 9;
  using State = std::array<double, kSize>;
  double drag, axial, friction, inv_c;  // d_t (N m s), d_a (N m s), tau0 (N m), 1/C
  bool driven;
  double mode = 1.0;        // the friction mode: sign of w3 while sliding, 0 while held
  Coefficients g3{}, tz{};  // gamma_3 and tau_z (N m), order by order

  explicit DampedTerms(const Body& b)
      : drag(b.damping.transverse), axial(b.damping.axial), friction(b.damping.friction), inv_c(1.0 / b.C),
        driven(b.damping.driven) {}

  bool held() const { return driven || mode == 0.0; }

  // The integrals start at 0 (for A == B: psi = 0, p = q, v = (w1, w2)).
  static State state_of(const RigidBodyState& rb) {
    State x{};
    const RigidBodyVector v = to_vector(rb);
    std::copy(v.begin(), v.end(), x.begin());
    return x;
  }
  static RigidBodyState rigid_body(const State& x) {
    RigidBodyVector v;
    std::copy(x.begin(), x.begin() + 7, v.begin());
    return from_vector(v);
  }
  static constexpr int kU1 = 4, kU2 = 5;

  // Order n's tau_z (given (A - B) (w1 w2)[n]), then the rows n + 1 of the three integrals,
  // once gamma's coefficient n is stored and with (w_perp . w_perp)[n] = `perp2`.
  void integrals(JetOf<kWidth>& x, const Gamma& g, int n, double gyroscopic, double perp2);  // recurrence.hpp
};

// A damped body with A != B: Plain's state (q, body-axes w) and the integrals. 29 Cauchy
// products per order.
struct DampedPlain : DampedTerms {
  static constexpr TaylorVariables kVariables = TaylorVariables::Plain;
  double e1, e2, e3, ka, kb;  // as Plain's
  double da, db;              // d_t / A, d_t / B (1/s)
  double a_minus_b;           // A - B (kg m^2)

  explicit DampedPlain(const Body& b)
      : DampedTerms(b), e1((b.B - b.C) / b.A), e2((b.C - b.A) / b.B), e3((b.A - b.B) / b.C), ka(b.mgR() / b.A),
        kb(b.mgR() / b.B), da(b.damping.transverse / b.A), db(b.damping.transverse / b.B), a_minus_b(b.A - b.B) {}

  void coefficients(JetOf<kWidth>& x, Gamma& g, int p);  // recurrence.hpp
};

// A damped body with A == B: SpinFactored's state (p, v in N, w3) and the integrals. The
// transverse inertia and drag are isotropic, so psi still drops out:
// v' = (C w3 / A) J v + (m g R / A) J gamma - (d_t / A) v, C w3' = tau_z (no gyroscopic
// torque: a stopped spin stays stopped). w3 now has a series, so C w3 / A J v is a product
// (2): 24 Cauchy products per order. For A == B the outputs are Rz-invariant (SpinFactored).
struct DampedSpinFactored : DampedTerms {
  static constexpr TaylorVariables kVariables = TaylorVariables::SpinFactored;
  double c_over_a, ka, da;  // C / A (1), m g R / A (1/s^2), d_t / A (1/s)

  explicit DampedSpinFactored(const Body& b)
      : DampedTerms(b), c_over_a(b.C / b.A), ka(b.mgR() / b.A), da(b.damping.transverse / b.A) {}

  void coefficients(JetOf<kWidth>& x, Gamma& g, int p);  // recurrence.hpp
};

}  // namespace heavytop::detail::taylor

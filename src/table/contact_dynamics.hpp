#pragma once
// Private to the library: the equations of the body on a table (SPEC section 16), in body axes,
// templated on the scalar so that the same lines give the integrator's right-hand side (double)
// and the linearisation's exact derivatives (std::complex<double>, the complex step).
//
// Body axes x, y, z through O, principal, z the axis (k = e3); gamma is the upward vertical in
// body axes (gamma_3 = k_zeta = cos tilt); omega the angular velocity and v the velocity of
// the centre of mass G, both in body axes. The body touches the table at P, the lowest point of
// its sphere (radius r about O) or torus (ring of radius rho about the axis, thickened by r):
//   P - O = rho u - r gamma,  u = (c e3 - gamma) / S,  c = gamma_3,  S = sqrt(1 - c^2)
//   s = G - P = l e3 - rho u + r gamma
// and the height of G is the exact function of the attitude z_G = f(c) = r + rho S + l c.
// Derivations: docs/table.md.

#include <cmath>
#include <complex>
#include <type_traits>

#include <Eigen/Core>

#include "heavytop/body.hpp"
#include "heavytop/table.hpp"

namespace heavytop::detail {

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// The constants of the equations, from the body and the table (SI).
struct TableParameters {
  double Ag = 0.0, Bg = 0.0, C = 0.0;  // kg m^2: central moments (about G)
  double mass = 0.0, gravity = 0.0;    // kg, m/s^2
  double length = 0.0;                 // m: l, G = O + l k
  double tip_radius = 0.0;             // m: r
  double rim_radius = 0.0;             // m: rho
  Contact contact = Contact::Frictionless;
  FrictionLaw law = FrictionLaw::Viscous;
  double friction = 0.0;               // mu
  double slip_speed = 1.0;             // m/s

  static TableParameters of(const Body& body, const Table& table) {
    TableParameters p;
    p.Ag = central_moment_A(body);
    p.Bg = central_moment_B(body);
    p.C = body.C;
    p.mass = body.mass;
    p.gravity = body.gravity;
    p.length = body.length;
    p.tip_radius = body.tip_radius;
    p.rim_radius = body.rim_radius;
    p.contact = table.contact;
    p.law = table.friction_law;
    p.friction = table.friction;
    p.slip_speed = table.slip_speed;
    return p;
  }
};

// abs-free sqrt that works for the complex step (the argument's real part is >= 0 here).
inline double sqrt_of(double x) { return std::sqrt(x); }
inline std::complex<double> sqrt_of(const std::complex<double>& x) { return std::sqrt(x); }

// a . b and a x b without the conjugation Eigen applies to complex scalars (its dot conjugates
// `a`, its cross the result): the complex step needs their analytic continuation. Eigen's own
// for double.
template <class T>
T dot(const Vec3<T>& a, const Vec3<T>& b) {
  if constexpr (std::is_same_v<T, double>)
    return a.dot(b);
  else
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class T>
Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  if constexpr (std::is_same_v<T, double>)
    return a.cross(b);
  else
    return Vec3<T>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

template <class T>
Vec3<T> inertia_times(const TableParameters& p, const Vec3<T>& w) {
  return Vec3<T>(p.Ag * w[0], p.Bg * w[1], p.C * w[2]);
}
template <class T>
Vec3<T> inertia_solve(const TableParameters& p, const Vec3<T>& t) {
  return Vec3<T>(t[0] / p.Ag, t[1] / p.Bg, t[2] / p.C);
}

// Where the body touches: s = G - P, the height function's derivatives, ds/dt (body axes).
template <class T>
struct ContactGeometry {
  T c;        // gamma_3 = cos tilt
  T S;        // sin tilt (>= 0)
  Vec3<T> u;  // the unit vector from O towards P's side in the ring's plane (rim only; else 0)
  Vec3<T> s;  // m: G - P
  T f1, f2;   // dz_G/dc (m), d2 z_G/dc^2 (m)

  /// m: O's height above the table, r + rho S.
  T height_of_O(const TableParameters& p) const { return p.tip_radius + p.rim_radius * S; }
  /// m: G's height above the table, f(c) = r + rho S + l c.
  T height_of_G(const TableParameters& p) const { return height_of_O(p) + p.length * c; }
};

template <class T>
ContactGeometry<T> contact_geometry(const TableParameters& p, const Vec3<T>& gamma) {
  ContactGeometry<T> g;
  g.c = gamma[2];
  g.S = sqrt_of(gamma[0] * gamma[0] + gamma[1] * gamma[1]);
  const Vec3<T> e3(T(0.0), T(0.0), T(1.0));
  g.s = p.length * e3 + p.tip_radius * gamma;
  g.f1 = T(p.length);
  g.f2 = T(0.0);
  g.u = Vec3<T>::Zero();
  if (p.rim_radius > 0.0) {
    g.u = (g.c * e3 - gamma) / g.S;
    g.s -= p.rim_radius * g.u;
    g.f1 -= p.rim_radius * g.c / g.S;
    g.f2 = -p.rim_radius / (g.S * g.S * g.S);
  }
  return g;
}

// The accelerations and the contact force of one instant (body axes).
template <class T>
struct ContactMotion {
  Vec3<T> omega_dot;  // rad/s^2
  Vec3<T> accel;      // m/s^2: G's acceleration
  Vec3<T> force;      // N: the table's force on the body at P
  T normal;           // N: force . gamma
  T denominator;      // 1/kg: N's coefficient (> 0 unless Painleve's paradox); 1 / m for rolling
  Vec3<T> slip;       // m/s: the velocity of the body's material point at P
};

// The velocity of the material point at P (body axes), given G's velocity v.
template <class T>
Vec3<T> contact_point_velocity(const ContactGeometry<T>& g, const Vec3<T>& omega, const Vec3<T>& v) {
  return v - cross(omega, g.s);
}

// The friction force per unit normal force (body axes), for the frictionless and viscous laws.
template <class T>
Vec3<T> friction_per_normal(const TableParameters& p, const Vec3<T>& gamma, const Vec3<T>& slip) {
  if (p.contact != Contact::Sliding || p.friction == 0.0) return Vec3<T>::Zero();
  const Vec3<T> tangential = slip - dot(slip, gamma) * gamma;
  if (p.law == FrictionLaw::Coulomb) {  // slipping (the sticking contact's equations are rolling's)
    if constexpr (std::is_same_v<T, double>) {
      const double size = tangential.norm();
      return size > 0.0 ? Vec3<T>((-p.friction / size) * tangential) : Vec3<T>::Zero();
    } else {  // |t| continued analytically (no conjugate), for the complex step
      const T size = sqrt_of(dot(tangential, tangential));
      return std::real(size) > 0.0 ? Vec3<T>((-p.friction / size) * tangential) : Vec3<T>::Zero();
    }
  }
  return (-p.friction / p.slip_speed) * tangential;
}

// Frictionless and sliding (viscous): N from the height constraint z_G'' = f'' c'^2 + f' c''.
// `v` is G's velocity in body axes (its vertical part f' c', as the constraint demands).
template <class T>
ContactMotion<T> sliding_motion(const TableParameters& p, const Vec3<T>& gamma, const Vec3<T>& omega,
                                const Vec3<T>& v) {
  const ContactGeometry<T> g = contact_geometry(p, gamma);
  ContactMotion<T> m;
  m.slip = contact_point_velocity(g, omega, v);
  const Vec3<T> phi = friction_per_normal(p, gamma, m.slip);
  const Vec3<T> arm = -g.s;  // P - G
  const Vec3<T> wdot0 = inertia_solve(p, Vec3<T>(-cross(omega, inertia_times(p, omega))));
  const Vec3<T> wdot1 = inertia_solve(p, cross(arm, Vec3<T>(gamma + phi)));
  const Vec3<T> gamma_dot = cross(gamma, omega);
  const T c_dot = gamma_dot[2];
  // c'' = (gamma' x omega)_3 + (gamma x omega')_3, omega' = wdot0 + N wdot1.
  const T c_ddot0 = cross(gamma_dot, omega)[2] + cross(gamma, wdot0)[2];
  const T c_ddot1 = cross(gamma, wdot1)[2];
  m.denominator = 1.0 / p.mass - g.f1 * c_ddot1;
  m.normal = (p.gravity + g.f2 * c_dot * c_dot + g.f1 * c_ddot0) / m.denominator;
  m.omega_dot = wdot0 + m.normal * wdot1;
  m.force = m.normal * (gamma + phi);
  m.accel = m.force / p.mass - p.gravity * gamma;
  return m;
}

// Rolling: P's material point at rest, v = omega x s; the force from Newton's law.
template <class T>
ContactMotion<T> rolling_motion(const TableParameters& p, const Vec3<T>& gamma, const Vec3<T>& omega) {
  const ContactGeometry<T> g = contact_geometry(p, gamma);
  const Vec3<T> e3(T(0.0), T(0.0), T(1.0));
  const Vec3<T> gamma_dot = cross(gamma, omega);
  // ds/dt in body axes: r gamma' - rho u', u' = (c' e3 - gamma') / S + (c e3 - gamma) c c' / S^3.
  Vec3<T> s_dot = p.tip_radius * gamma_dot;
  if (p.rim_radius > 0.0) {
    const T c_dot = gamma_dot[2];
    const Vec3<T> u_dot = (c_dot * e3 - gamma_dot) / g.S + g.u * (g.c * c_dot / (g.S * g.S));
    s_dot -= p.rim_radius * u_dot;
  }
  const Vec3<T>& s = g.s;
  // (I_G + m (|s|^2 1 - s s^T)) omega' = -omega x I_G omega - m s x (omega x (omega x s) + omega x s' + g gamma)
  const Vec3<T> drift = cross(omega, cross(omega, s)) + cross(omega, s_dot);
  const Vec3<T> rhs = -cross(omega, inertia_times(p, omega)) - p.mass * cross(s, Vec3<T>(drift + p.gravity * gamma));
  Eigen::Matrix<T, 3, 3> K = -p.mass * s * s.transpose();
  const T s2 = dot(s, s);
  K(0, 0) += p.Ag + p.mass * s2;
  K(1, 1) += p.Bg + p.mass * s2;
  K(2, 2) += p.C + p.mass * s2;
  ContactMotion<T> m;
  m.omega_dot = K.inverse() * rhs;  // 3x3: the cofactor formula
  m.accel = cross(m.omega_dot, s) + drift;
  m.force = p.mass * (m.accel + p.gravity * gamma);
  m.normal = dot(m.force, gamma);
  m.denominator = T(1.0 / p.mass);
  m.slip = Vec3<T>::Zero();
  return m;
}

}  // namespace heavytop::detail

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
#include "heavytop/contact_losses.hpp"
#include "heavytop/table.hpp"
#include "table/loss_laws.hpp"

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
  double contact_modulus = 0.0;        // Pa: E* of the tip and the table (Contensou's law)
  bool drilling = true;                // Contensou's law: its drilling torque acts (not in the linearisation)
  double rolling_resistance = 0.0;     // m: the rolling resistance's length
  bool air = false;                    // the air's torque on the spinning parts
  Air air_properties;
  std::vector<AirSurface> air_surfaces;

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
    if (table.friction_law == FrictionLaw::Contensou)
      p.contact_modulus = heavytop::contact_modulus(*table.tip_material, *table.material);
    p.rolling_resistance = table.rolling_resistance;
    p.air = table.air.has_value();
    if (p.air) {
      p.air_properties = *table.air;
      p.air_surfaces = table.air_surfaces.empty() ? equivalent_disc(body) : table.air_surfaces;
    }
    return p;
  }

  /// True if the contact's own losses act (Table::has_losses()).
  bool has_losses() const noexcept { return law == FrictionLaw::Contensou || rolling_resistance > 0.0 || air; }
};

// m/s: Contensou's law is regularised below this speed of the patch (slip and drilling
// together): a spinning or sliding top never comes near it; a top at rest does.
inline constexpr double kContensouRegularisation = 1e-6;
// rad/s: the rolling resistance's torque grows linearly below this rolling rate (it is
// set-valued at rest).
inline constexpr double kRollingRegularisation = 1e-3;

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
  // N m: the pure torques of the patch's drilling friction, of rolling resistance and of the air
  Vec3<T> drilling = Vec3<T>::Zero(), rolling = Vec3<T>::Zero(), air = Vec3<T>::Zero();
};

// The velocity of the material point at P (body axes), given G's velocity v.
template <class T>
Vec3<T> contact_point_velocity(const ContactGeometry<T>& g, const Vec3<T>& omega, const Vec3<T>& v) {
  return v - cross(omega, g.s);
}

// What the contact exerts per unit normal force (body axes): the friction force at P and the pure
// torques of the patch's drilling friction and of rolling resistance.
template <class T>
struct FrictionPerNormal {
  Vec3<T> force = Vec3<T>::Zero();     // dimensionless (N / N)
  Vec3<T> drilling = Vec3<T>::Zero();  // m (N m / N)
  Vec3<T> rolling = Vec3<T>::Zero();   // m (N m / N)
};

// m: Contensou's arm (3 pi / 16) a at normal force N, a Hertz's patch radius.
template <class T>
T drilling_arm(const TableParameters& p, const T& normal) {
  return kHertzDrillingArm * hertz_radius(normal, p.tip_radius, p.contact_modulus);
}

// `normal` (N) matters to Contensou's law only: its patch grows as N^(1/3).
template <class T>
FrictionPerNormal<T> friction_per_normal(const TableParameters& p, const Vec3<T>& gamma, const Vec3<T>& omega,
                                         const Vec3<T>& slip, const T& normal) {
  FrictionPerNormal<T> f;
  if (p.rolling_resistance > 0.0) {  // against the body's rolling: its angular velocity along the table
    const Vec3<T> rolling = omega - dot(omega, gamma) * gamma;
    const T size = sqrt_of(dot(rolling, rolling) + kRollingRegularisation * kRollingRegularisation);
    f.rolling = (-p.rolling_resistance / size) * rolling;
  }
  if (p.contact != Contact::Sliding || p.friction == 0.0) return f;
  const Vec3<T> tangential = slip - dot(slip, gamma) * gamma;
  if (p.law == FrictionLaw::Coulomb) {  // slipping (the sticking contact's equations are rolling's)
    if constexpr (std::is_same_v<T, double>) {
      const double size = tangential.norm();
      if (size > 0.0) f.force = (-p.friction / size) * tangential;
    } else {  // |t| continued analytically (no conjugate), for the complex step
      const T size = sqrt_of(dot(tangential, tangential));
      if (std::real(size) > 0.0) f.force = (-p.friction / size) * tangential;
    }
  } else if (p.law == FrictionLaw::Contensou) {
    // Coulomb's law over the patch, force and drilling torque coupled: (F, M / eps) on the
    // ellipse of radius mu N, against (v, eps w_n) (Leine and Glocker 2003's approximation).
    const T eps = drilling_arm(p, normal);
    const T spin = dot(omega, gamma);
    const T size = sqrt_of(dot(tangential, tangential) + eps * eps * spin * spin +
                           kContensouRegularisation * kContensouRegularisation);
    f.force = (-p.friction / size) * tangential;
    if (p.drilling) f.drilling = (-p.friction * eps * eps * spin / size) * gamma;
  } else {
    f.force = (-p.friction / p.slip_speed) * tangential;
  }
  return f;
}

// N m (body axes): the air's torque against the spin about the body's axis.
template <class T>
Vec3<T> air_torque_on(const TableParameters& p, const Vec3<T>& omega) {
  Vec3<T> torque = Vec3<T>::Zero();
  if (!p.air) return torque;
  for (const auto& surface : p.air_surfaces) torque[2] -= air_torque_of(surface, p.air_properties, omega[2]);
  return torque;
}

// Frictionless and sliding: N from the height constraint z_G'' = f'' c'^2 + f' c''. The
// contact's force and torques are N times what friction_per_normal() gives, so N solves one
// linear equation; under Contensou's law that depends on N through the patch (as N^(1/3), a
// contraction), so the equation is solved again from its own N until N is still.
// `v` is G's velocity in body axes (its vertical part f' c', as the constraint demands).
template <class T>
ContactMotion<T> sliding_motion(const TableParameters& p, const Vec3<T>& gamma, const Vec3<T>& omega,
                                const Vec3<T>& v) {
  const ContactGeometry<T> g = contact_geometry(p, gamma);
  ContactMotion<T> m;
  m.slip = contact_point_velocity(g, omega, v);
  m.air = air_torque_on(p, omega);
  const Vec3<T> arm = -g.s;  // P - G
  const Vec3<T> wdot0 = inertia_solve(p, Vec3<T>(m.air - cross(omega, inertia_times(p, omega))));
  const Vec3<T> gamma_dot = cross(gamma, omega);
  const T c_dot = gamma_dot[2];
  // c'' = (gamma' x omega)_3 + (gamma x omega')_3, omega' = wdot0 + N wdot1.
  const T c_ddot0 = cross(gamma_dot, omega)[2] + cross(gamma, wdot0)[2];
  T normal = T(p.mass * p.gravity);
  FrictionPerNormal<T> f;
  Vec3<T> wdot1;
  // Contensou: passes until N changes by under 1e-14 of itself, then two more, which carry
  // the complex step's derivative to the same accuracy (the contraction acts on it alike).
  int settled = p.law == FrictionLaw::Contensou && p.contact == Contact::Sliding ? 0 : 2;
  for (int pass = 0;; ++pass) {
    f = friction_per_normal(p, gamma, omega, m.slip, normal);
    wdot1 = inertia_solve(p, Vec3<T>(cross(arm, Vec3<T>(gamma + f.force)) + f.drilling + f.rolling));
    const T c_ddot1 = cross(gamma, wdot1)[2];
    m.denominator = 1.0 / p.mass - g.f1 * c_ddot1;
    const T next = (p.gravity + g.f2 * c_dot * c_dot + g.f1 * c_ddot0) / m.denominator;
    if (settled > 0 || std::abs(std::real(next - normal)) <= 1e-14 * std::abs(std::real(next))) ++settled;
    normal = next;
    if (settled > 2 || pass == 60) break;
  }
  m.normal = normal;
  m.omega_dot = wdot0 + m.normal * wdot1;
  m.force = m.normal * (gamma + f.force);
  m.drilling = m.normal * f.drilling;
  m.rolling = m.normal * f.rolling;
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
  ContactMotion<T> m;
  m.air = air_torque_on(p, omega);
  const Vec3<T> rhs =
      m.air - cross(omega, inertia_times(p, omega)) - p.mass * cross(s, Vec3<T>(drift + p.gravity * gamma));
  Eigen::Matrix<T, 3, 3> K = -p.mass * s * s.transpose();
  const T s2 = dot(s, s);
  K(0, 0) += p.Ag + p.mass * s2;
  K(1, 1) += p.Bg + p.mass * s2;
  K(2, 2) += p.C + p.mass * s2;
  m.omega_dot = K.inverse() * rhs;  // 3x3: the cofactor formula
  m.accel = cross(m.omega_dot, s) + drift;
  m.force = p.mass * (m.accel + p.gravity * gamma);
  m.normal = dot(m.force, gamma);
  m.denominator = T(1.0 / p.mass);
  m.slip = Vec3<T>::Zero();
  return m;
}

}  // namespace heavytop::detail

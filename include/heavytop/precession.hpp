#pragma once
/// \file
/// Steady motions at a tilt (derived in docs/steady-precession.md): the symmetric top's steady
/// precessions (the axis on a cone about the vertical at a constant rate, the tilt constant)
/// and the asymmetric body's tilted permanent rotations (the whole body turning uniformly about
/// the vertical), each with an initial state (SPEC section 2) that starts exactly on it.

#include <array>
#include <complex>
#include <optional>
#include <string>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// One steady precession of a symmetric top (A = B).
struct SteadyPrecession {
  double rate = 0.0;     ///< rad/s, Omega: the axis's rate about the upward vertical (> 0 counter-clockwise seen from above)
  double period = 0.0;   ///< s, 2 pi / |Omega|
  /// rad/s, the frequency of small nutation about this motion, sqrt((C w3 / A - 2 Omega cos theta)^2
  /// + Omega^2 sin^2 theta) (> 0: every steady precession of the Lagrange top is stable in theta).
  double nutation_frequency = 0.0;
  InitialState state;    ///< SPEC section 2's state on it: theta0 = tilt, phi0 = 0, phi_rate0 = -Omega sin(tilt)
};

/// The steady precessions of a symmetric top at a tilt and a spin: the roots Omega of
/// A cos(theta) Omega^2 - C w3 Omega + m g R = 0 (w3 = w.k, the spin).
struct PrecessionAnalysis {
  double tilt = 0.0;  ///< rad, theta: the axis's angle from the upward vertical, in (0, pi)
  double spin = 0.0;  ///< rad/s, w3 = w.k
  std::optional<SteadyPrecession> slow;  ///< the root of smaller |Omega| (none below the minimum spin)
  std::optional<SteadyPrecession> fast;  ///< the other (none below the minimum spin, or at theta = pi/2)
  /// rad/s, the least |w3| with steady precession at this tilt, 2 sqrt(A m g R cos(theta)) / C;
  /// nullopt when every spin has it (m g R cos(theta) <= 0).
  std::optional<double> min_spin;
  double slow_limit = 0.0;  ///< rad/s, m g R / (C w3): the slow rate as the spin grows (0 at w3 = 0)
  /// rad/s, C w3 / (A cos theta): the fast rate as the spin grows (nullopt at theta = pi/2)
  std::optional<double> fast_limit;
};

/// Throws InvalidInput unless the body is valid and symmetric ("body.B"), the tilt ("tilt")
/// finite in (0, pi) and the spin ("motion.spin") finite.
PrecessionAnalysis analyse_precession(const Body& body, double tilt, double spin);

/// A tilted permanent rotation of an asymmetric body: the body turns as a whole about the
/// vertical at rate Omega, its axis z at the tilt alpha, the vertical in a principal plane:
/// cos(alpha) = m g R / ((C - B) Omega^2) (the vertical in the y-z plane) or its twin with A
/// (the x-z plane).
struct PermanentRotation {
  char plane = 'x';      ///< 'x': the vertical in the body's x-z plane (A's twin); 'y': in the y-z plane (B's)
  double rate = 0.0;     ///< rad/s, Omega > 0 about the upward vertical
  double period = 0.0;   ///< s, 2 pi / Omega
  InitialState state;    ///< SPEC section 2's state on it (x: theta0 = alpha; y: phi0 = alpha)
  /// 1/s, the eigenvalues of the Euler-Poisson equations linearised about it (body frame, 6 of them).
  std::array<std::complex<double>, 6> eigenvalues{};
  /// Spectrally stable: the four eigenvalues on the symplectic leaf (all but the two smallest,
  /// which the integrals |gamma| = 1 and the vertical momentum pin at 0) on the imaginary axis.
  bool stable = false;
};

/// The tilted permanent rotations at tilt alpha: one per principal plane whose moment K (B for
/// the y-z plane, A for x-z) gives m g R / ((C - K) cos(alpha)) > 0; none for a plane where it
/// is <= 0 or infinite. Throws InvalidInput as analyse_precession() for the body and tilt
/// (any body; A = B gives both planes the same rate, the steady precession with no relative spin).
std::vector<PermanentRotation> permanent_rotations(const Body& body, double tilt);

}  // namespace heavytop

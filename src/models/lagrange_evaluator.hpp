#pragma once
// Private to the library: the precomputed constants of lagrange_exact.cpp's closed form, held
// by a LagrangeTop (its `evaluator`) and read by every evaluation. tests/test_lagrange_exact.cpp
// reads them too (white-box checks of the poles and the Landen route).

#include <stdexcept>

#include "heavytop/lagrange_exact.hpp"

#include "math/elliptic.hpp"

namespace heavytop::detail {

struct LagrangeEvaluator {
  // The tilt: u = u_a + d sn^2(tau, k), tau = lambda t + tau0; 1 -+ u_{a,b} kept without
  // cancellation (they vanish for a vertical passage).
  double u0 = 1.0, u_a = 1.0, d = 0.0, lambda = 0.0, tau0 = 0.0;
  double one_minus_a = 0.0, one_minus_b = 0.0, one_plus_a = 2.0, one_plus_b = 2.0;
  // Jacobi sn, cn, dn of the modulus k (k'^2 kept separately) and the quarter period K in tau;
  // jacobi.periodic: K finite, tau reduced modulo 2K.
  JacobiElliptic jacobi;
  // Elliptic integrals of the third kind for the poles of phi' at u = 1 (index 0) and
  // u = -1 (index 1): J(tau) = int_0^tau dtau / (1 - n sn^2). mode 0: absent (coefficient
  // 0), 1: direct, 2: n < 0 transformed to (k^2, 1). signed_form: the factor sqrt(1 -+ u)
  // vanishes at a root (a vertical passage) and is carried with its sign: 0 no, 1 ~ sn, 2 ~ cn.
  struct Pole {
    int mode = 0;
    int signed_form = 0;
    double coefficient = 0.0;  // rad per unit J: (P or Q) / ((1 -+ u_a) lambda)
    double residue = 0.0;      // rad/s: P = (a - b)/2 or Q = (a + b)/2
    double n = 0.0, one_minus_n = 1.0;
    double N = 0.0, one_minus_N = 1.0, c1 = 0.0, c2 = 0.0, c3 = 0.0, p2 = 0.0;
    double complete2 = 0.0;    // 2 Pi(n, k): increase of J per period 2K
  } pole[2];
  double sqrt_abs_d = 0.0;
  double spin_rate_linear = 0.0;  // rad/s: w3 - b, the part of psi' without poles
  double phi_ref_cos = 1.0, phi_ref_sin = 0.0, psi_ref = 0.0;  // the state's rotation
  double phi_per_period_mod = 0.0, psi_per_period_mod = 0.0;   // the increments mod 2 pi
  // Constant tilt: phi' and psi' (rad/s), sin(tilt) at t = 0.
  double phi_rate = 0.0, psi_rate = 0.0, sin_tilt0 = 0.0;
  // The pole terms of phi and psi as Fourier sine series in pi tau / K (rad), when they
  // converge within kMaxSeries terms and match the elliptic integrals at setup.
  static constexpr int kMaxSeries = 64;
  int series_terms = 0;
  double phi_slope = 0.0, psi_slope = 0.0;  // rad per unit tau, the secular parts
  double phi_series[kMaxSeries] = {}, psi_series[kMaxSeries] = {};
};

/// The constants of a LagrangeTop built by lagrange_top(); std::invalid_argument for one that
/// was not (a default-constructed LagrangeTop has none).
inline const LagrangeEvaluator& evaluator_of(const LagrangeTop& top) {
  if (!top.evaluator) throw std::invalid_argument("LagrangeTop: not built by lagrange_top()");
  return *top.evaluator;
}

}  // namespace heavytop::detail

// The order-4 Birkhoff normal form of the asymmetric heavy top (SPEC section 7, the paper
// notes' E7, docs/lyapunov.md) and the KAM verdicts it gives, each against an independent route:
// the chart's expansion against the exact reduced Hamiltonian, the diagonalisation against the
// linearized model's frequencies, the coefficients against a closed form at A = B, the
// predicted frequency shifts against long nonlinear runs of the full rigid body (odeint on
// RigidBodySystem, not the chart), E7's worked example, D = 0 and the resonances.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <boost/numeric/odeint.hpp>
#include <gtest/gtest.h>

#include "heavytop/linear_models.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/normal_form.hpp"
#include "heavytop/rigid_body.hpp"
#include "heavytop/stability.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;
using V = LyapunovVerdictKind;
using Cert = LyapunovCertificate;

Eigen::Matrix4d canonical_J() {
  Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
  J(0, 2) = J(1, 3) = 1.0;
  J(2, 0) = J(3, 1) = -1.0;
  return J;
}

struct Case {
  double A, B, C, mgR, spin;
};
// Asymmetric, index 2, linearly stable, away from 1:1 and 1:3: E7's example, a prolate body
// above its pivot, and the hanging body of erratum E3 above its unstable window.
const Case kCases[] = {{1.0, 1.5, 0.5, 1.0, 6.0}, {1.0, 1.2, 0.8, 1.0, 4.0}, {1.0, 1.2, 0.7, -1.0, 3.0}};

// ---- The chart: H2 and H4 against the exact reduced Hamiltonian -----------------------------

/// E7's chart and Hamiltonian as written there, in long double (for finite differences).
long double exact_hamiltonian(const Body& b, double L, const Eigen::Matrix<long double, 4, 1>& z) {
  const long double q1 = z[0], q2 = z[1], p1 = z[2], p2 = z[3], g3 = std::sqrt(1.0L - q1 * q1 - q2 * q2);
  const long double P1 = g3 * p2 + L * q1 / (1 + g3), P2 = -g3 * p1 + L * q2 / (1 + g3), P3 = L - (q1 * p2 - q2 * p1);
  return P1 * P1 / (2 * (long double)b.A) + P2 * P2 / (2 * (long double)b.B) + P3 * P3 / (2 * (long double)b.C) +
         (long double)b.mgR() * g3;
}

TEST(NormalForm, QuadraticAndQuarticPartsAreTheExpansionOfTheExactHamiltonian) {
  std::mt19937_64 rng(29);
  std::normal_distribution<double> n(0.0, 1.0);
  for (const Case& c : kCases) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    const double L = c.C * c.spin;
    const Eigen::Matrix4d S = reduced_quadratic_form(b, L);
    const double H0 = reduced_hamiltonian(b, L, Eigen::Vector4d::Zero());
    EXPECT_NEAR(H0, L * L / (2.0 * c.C) + c.mgR, 1e-14 * std::abs(H0));
    const Eigen::Vector4d z0(0.1, -0.2, 0.3, 0.4);
    EXPECT_NEAR(reduced_hamiltonian(b, L, z0), double(exact_hamiltonian(b, L, z0.cast<long double>())), 1e-14 * std::abs(H0));
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector4d z(n(rng), n(rng), L * n(rng), L * n(rng));
      // f(e) = (H(e z) - H0 - e^2 H2(z)) / e^4 = H4(z) + e^2 H6(z) + e^4 H8(z) + ..: two
      // Richardson steps on e, e/2, e/4 leave O(e^6); long double keeps rounding (eps H0 / e^4) small.
      auto f = [&](long double e) {
        const long double h2 = 0.5L * z.cast<long double>().dot(S.cast<long double>() * z.cast<long double>());
        return double((exact_hamiltonian(b, L, e * z.cast<long double>()) - exact_hamiltonian(b, L, {0, 0, 0, 0}) -
                       e * e * h2) / (e * e * e * e));
      };
      auto richardson = [&](double e) { return (4.0 * f(e / 2) - f(e)) / 3.0; };
      const double e = 0.05, extrapolated = (16.0 * richardson(e / 2) - richardson(e)) / 15.0;
      const double h4 = reduced_quartic(b, L, z);
      const double rho = z.head<2>().squaredNorm(), pp = z.tail<2>().squaredNorm();
      const double size = rho * (pp + L * L * rho) * (1.0 / c.A + 1.0 / c.B + 1.0 / c.C) + std::abs(c.mgR) * rho * rho;
      EXPECT_NEAR(extrapolated, h4, 1e-7 * size) << c.A << " " << c.B << " " << c.C << " trial " << trial;
    }
  }
}

// ---- The diagonalisation: symplectic, Krein-signed, the linearized model's frequencies ------

TEST(NormalForm, DiagonalisationIsSymplecticWithTheLinearisedFrequencies) {
  const Eigen::Matrix4d J = canonical_J();
  for (const Case& c : kCases) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    const auto nf = birkhoff_normal_form(b, c.spin);
    ASSERT_TRUE(nf.has_value());
    const Eigen::Matrix4d S = reduced_quadratic_form(b, nf->L);
    EXPECT_LT((nf->T.transpose() * J * nf->T - J).norm(), 1e-12);
    Eigen::Matrix4d H2 = Eigen::Matrix4d::Zero();
    H2.diagonal() << nf->w1, -nf->w2, nf->w1, -nf->w2;
    EXPECT_LT((nf->T.transpose() * S * nf->T - H2).norm(), 1e-12 * (nf->w1 + nf->w2));
    // The chart's H2 is the body-frame linearisation on the leaf: the same two frequencies.
    const StabilityVerdict lin = linear_stability(linear_model(LinearModelKind::Linearized, b), c.spin);
    ASSERT_TRUE(lin.stable);
    ASSERT_EQ(lin.frequencies.size(), 2u);
    const double lo = std::min(nf->w1, nf->w2), hi = std::max(nf->w1, nf->w2);
    EXPECT_NEAR(lin.frequencies[0], lo, 1e-10 * hi);
    EXPECT_NEAR(lin.frequencies[1], hi, 1e-10 * hi);
  }
}

// ---- A = B: the closed form (docs/lyapunov.md, "The symmetric top") --------------------------

struct ClosedForm {
  double w1, w2, c20, c11, c02;
};

/// The symmetric top's normal form: with kappa = L^2/(4A) - m g R, Omega = sqrt(kappa/A),
/// beta = L (1/(2A) - 1/C), the circular modes R+- have H2 = (Omega + beta) R+ + (Omega - beta) R-
/// and <H4> = a++ R+^2 + a+- R+ R- + a-- R-^2.
ClosedForm symmetric_closed_form(double A, double C, double k, double L) {
  const double kappa = L * L / (4.0 * A) - k, Omega = std::sqrt(kappa / A), beta = L * (0.5 / A - 1.0 / C);
  const double u = 1.0 / (A * kappa), lambda2 = std::sqrt(u);
  const double E = u / 16.0 * (L * L / A - 2.0 * k);
  const double app = -0.5 / A - L * lambda2 / (8.0 * A) + E + 0.5 / C;
  const double amm = -0.5 / A + L * lambda2 / (8.0 * A) + E + 0.5 / C;
  const double apm = 4.0 * E - 1.0 / C;
  if (Omega + beta < 0.0) return {Omega - beta, -(Omega + beta), amm, apm, app};  // r1 = R-, r2 = R+
  return {Omega + beta, beta - Omega, app, apm, amm};                              // r1 = R+, r2 = R-
}

TEST(NormalForm, SymmetricTopMatchesTheClosedFormTo1e12) {
  const Case symmetric[] = {{1.0, 1.0, 0.5, 1.0, 6.0},  {1.0, 1.0, 0.5, 1.0, -6.0}, {1.0, 1.0, 0.5, -1.0, 6.0},
                            {2.0, 2.0, 1.2, 3.0, 9.0},  {1.0, 1.0, 0.9, 0.5, 2.3},  {1.0, 1.0, 0.2, -2.0, 40.0}};
  double worst = 0.0;
  for (const Case& c : symmetric) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    const auto nf = birkhoff_normal_form(b, c.spin);
    ASSERT_TRUE(nf.has_value()) << c.C << " " << c.spin;
    const ClosedForm cf = symmetric_closed_form(c.A, c.C, c.mgR, c.C * c.spin);
    const double scale = std::abs(cf.c20) + std::abs(cf.c11) + std::abs(cf.c02);
    EXPECT_NEAR(nf->w1, cf.w1, 1e-12 * cf.w1);
    EXPECT_NEAR(nf->w2, cf.w2, 1e-12 * cf.w1);
    for (auto [got, want] : {std::pair{nf->c20, cf.c20}, {nf->c11, cf.c11}, {nf->c02, cf.c02}}) {
      EXPECT_NEAR(got, want, 1e-12 * scale) << c.A << " " << c.C << " " << c.mgR << " " << c.spin;
      worst = std::max(worst, std::abs(got - want) / scale);
    }
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
  std::printf("A = B: worst |c - closed form| / sum |c| = %.3g\n", worst);
}

// ---- E7's worked example ---------------------------------------------------------------------

TEST(NormalForm, PaperNotesE7Example) {
  const Body b = make_body(1.0, 1.5, 0.5, 1.0);
  const LyapunovVerdict v = lyapunov_stability(b, 6.0);
  EXPECT_EQ(v.energy_index, 2);
  EXPECT_EQ(v.verdict, V::Stable);
  EXPECT_EQ(v.certificate, Cert::Kam);
  ASSERT_TRUE(v.normal_form.has_value());
  const NormalForm& nf = *v.normal_form;
  EXPECT_NEAR(nf.w1, 5.604869, 5e-7);
  EXPECT_NEAR(nf.w2, 3.862483, 5e-7);
  EXPECT_NEAR(nf.c20, 1.213458, 5e-7);
  EXPECT_NEAR(nf.c11, -0.681260, 5e-7);
  EXPECT_NEAR(nf.c02, 0.604105, 5e-7);
  EXPECT_NEAR(nf.D, 22.3326, 5e-5);
  EXPECT_EQ(nf.resonance, 0);
  EXPECT_FALSE(nf.a13.has_value());
}

// ---- The frequency shifts against long nonlinear runs of the full body ----------------------

/// The full rigid body from the chart point z on the leaf L: vertical gamma, momentum Pi in
/// body axes; any attitude with R^T e_zeta = gamma.
RigidBodyVector body_state(const Body& b, double L, const Eigen::Vector4d& z) {
  Eigen::Vector3d Pi, gamma;
  chart_to_euler_poisson(L, z, Pi, gamma);
  RigidBodyState s;
  s.attitude = Eigen::Quaterniond::FromTwoVectors(gamma, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.omega = {Pi[0] / b.A, Pi[1] / b.B, Pi[2] / b.C};
  return to_vector(s);
}

/// The chart point of a rigid-body state (the inverse of chart_to_euler_poisson on the leaf L).
Eigen::Vector4d chart_point(const Body& b, double L, const RigidBodyVector& x) {
  const RigidBodyState s = from_vector(x);
  const Eigen::Vector3d gamma = s.attitude.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d Pi(b.A * s.omega[0], b.B * s.omega[1], b.C * s.omega[2]);
  const double g3 = gamma[2];
  return {gamma[0], gamma[1], -(Pi[1] - L * gamma[1] / (1.0 + g3)) / g3, (Pi[0] - L * gamma[0] / (1.0 + g3)) / g3};
}

/// -d(phase)/dt of each mode (rad/s), fitted over `periods` periods of the slower mode, from the
/// nonlinear motion started on the torus (r1, r2) of the linear normal form: -a_i' = dH/dr_i.
std::array<double, 2> measured_dH_dr(const Body& b, const NormalForm& nf, double r1, double r2, double periods) {
  const Eigen::Vector4d zeta(std::sqrt(2.0 * r1), std::sqrt(2.0 * r2), 0.0, 0.0);
  RigidBodyVector x = body_state(b, nf.L, nf.T * zeta);
  const Eigen::Matrix4d Tinv = nf.T.inverse();
  const double t_end = periods * 2.0 * std::numbers::pi / std::min(nf.w1, nf.w2);
  const double dt = 2.0 * std::numbers::pi / std::max(nf.w1, nf.w2) / 16.0;
  std::vector<double> times;
  for (double t = 0.0; t <= t_end; t += dt) times.push_back(t);
  std::vector<double> phase[2];
  namespace ode = boost::numeric::odeint;
  ode::integrate_times(ode::make_dense_output(1e-14, 1e-13, ode::runge_kutta_dopri5<RigidBodyVector>()),
                       RigidBodySystem{b}, x, times.begin(), times.end(), dt, [&](const RigidBodyVector& s, double) {
                         const Eigen::Vector4d zt = Tinv * chart_point(b, nf.L, s);
                         for (int i = 0; i < 2; ++i) {
                           double a = std::atan2(zt[i + 2], zt[i]);
                           if (!phase[i].empty())  // unwrap
                             a += 2.0 * std::numbers::pi * std::round((phase[i].back() - a) / (2.0 * std::numbers::pi));
                           phase[i].push_back(a);
                         }
                       });
  std::array<double, 2> out{};
  for (int i = 0; i < 2; ++i) {  // least-squares slope of the phase against time
    const std::size_t n = phase[i].size();
    double st = 0, sa = 0, stt = 0, sta = 0;
    for (std::size_t j = 0; j < n; ++j) {
      st += times[j];
      sa += phase[i][j];
      stt += times[j] * times[j];
      sta += times[j] * phase[i][j];
    }
    out[i] = -(n * sta - st * sa) / (n * stt - st * st);
  }
  return out;
}

TEST(NormalForm, FrequencyShiftsMatchLongNonlinearRuns) {
  for (const Case& c : kCases) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    const auto nf = birkhoff_normal_form(b, c.spin);
    ASSERT_TRUE(nf.has_value());
    // Actions giving tilts of a few 1e-3 rad: r = eps * (the action of a unit tilt).
    const double unit = 1.0 / (nf->T.row(0).squaredNorm() + nf->T.row(1).squaredNorm());
    const double eps = 1e-4 * unit;
    // Two tori per amplitude a, (a, a/2) and (a/2, a); the errors of the linear prediction must
    // shrink like a^2 and the Richardson-extrapolated shifts must match it closely.
    double err_small = 0.0, err_large = 0.0, err_extrapolated = 0.0, shift_size = 0.0;
    for (auto [f1, f2] : {std::pair{1.0, 0.5}, {0.5, 1.0}}) {
      std::array<double, 2> shift[2], predicted[2];
      for (int k = 0; k < 2; ++k) {
        const double a = eps * (k + 1), r1 = f1 * a, r2 = f2 * a;
        const auto dH = measured_dH_dr(b, *nf, r1, r2, 300.0);
        shift[k] = {dH[0] - nf->w1, dH[1] + nf->w2};
        predicted[k] = {2.0 * nf->c20 * r1 + nf->c11 * r2, nf->c11 * r1 + 2.0 * nf->c02 * r2};
      }
      for (int i = 0; i < 2; ++i) {
        err_small = std::max(err_small, std::abs(shift[0][i] - predicted[0][i]));
        err_large = std::max(err_large, std::abs(shift[1][i] - predicted[1][i]));
        shift_size = std::max(shift_size, std::abs(predicted[0][i]));
        // s(a) = p a + q a^2: p a = 2 s(a) - s(2a) / 2.
        err_extrapolated = std::max(err_extrapolated, std::abs(2.0 * shift[0][i] - 0.5 * shift[1][i] - predicted[0][i]));
      }
    }
    std::printf("A=%g B=%g C=%g mgR=%g w0=%g: shift %.3g, error at a %.3g, at 2a %.3g (ratio %.2f), "
                "extrapolated %.3g\n",
                c.A, c.B, c.C, c.mgR, c.spin, shift_size, err_small, err_large, err_large / err_small,
                err_extrapolated);
    EXPECT_LT(err_small, 1e-2 * shift_size);             // the prediction is the leading term
    EXPECT_GT(err_large / err_small, 3.0);               // and its error is of order a^2
    EXPECT_LT(err_large / err_small, 5.0);
    EXPECT_LT(err_extrapolated, 2e-5 * shift_size);      // the coefficients themselves
  }
}

// ---- D = 0, resonances, the stable spins -----------------------------------------------------

TEST(NormalForm, DZeroIsUndecidedAndKamOnEitherSide) {
  // An oblate body (found by scanning random bodies with kam_exceptions) whose D changes sign.
  const Body b = make_body(1.52594, 1.894034, 1.59991, 1.0);
  const auto exceptions = kam_exceptions(b);
  const auto e = std::find_if(exceptions.begin(), exceptions.end(), [](const KamException& x) { return x.what == "D = 0"; });
  ASSERT_NE(e, exceptions.end());
  const LyapunovVerdict at = lyapunov_stability(b, e->spin);
  EXPECT_EQ(at.verdict, V::Undecided);
  EXPECT_EQ(at.certificate, Cert::None);
  ASSERT_TRUE(at.normal_form.has_value());
  EXPECT_LE(std::abs(at.normal_form->D), kDegeneracyTolerance * at.normal_form->D_scale);
  const LyapunovVerdict below = lyapunov_stability(b, e->spin * (1.0 - 1e-6));
  const LyapunovVerdict above = lyapunov_stability(b, e->spin * (1.0 + 1e-6));
  EXPECT_EQ(below.certificate, Cert::Kam);
  EXPECT_EQ(above.certificate, Cert::Kam);
  EXPECT_LT(below.normal_form->D * above.normal_form->D, 0.0);
  // The stable spins exclude it and contain its neighbours.
  const auto intervals = lyapunov_stable_spin_intervals(b);
  bool excluded = true, below_in = false;
  for (const auto& i : intervals) {
    if (e->spin > i.lo && (!i.hi || e->spin < *i.hi)) excluded = false;
    if (below.normal_form && e->spin * (1.0 - 1e-6) > i.lo && i.hi && std::abs(*i.hi - e->spin) < 1e-12 * e->spin) below_in = true;
  }
  EXPECT_TRUE(excluded);
  EXPECT_TRUE(below_in);
}

/// rad/s, the spin in (lo, hi) where w1 / w2 = ratio, by bisection (w1 / w2 increasing there).
double spin_at_ratio(const Body& b, double lo, double hi, double ratio) {
  auto f = [&](double w) {
    const auto nf = birkhoff_normal_form(b, w);
    return nf->w1 / nf->w2 - ratio;
  };
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi);
    if (m <= lo || m >= hi) break;
    (f(m) < 0.0 ? lo : hi) = m;
  }
  return 0.5 * (lo + hi);
}

TEST(NormalForm, ResonancesOneToTwoAndOneToThree) {
  const Body b = make_body(1.0, 1.2, 0.8, 1.0);
  const double w12 = spin_at_ratio(b, 2.7, 4.0, 2.0), w13 = spin_at_ratio(b, 4.0, 6.0, 3.0);
  const LyapunovVerdict v12 = lyapunov_stability(b, w12), v13 = lyapunov_stability(b, w13);
  ASSERT_TRUE(v12.normal_form && v13.normal_form);
  EXPECT_EQ(v12.normal_form->resonance, 2);  // harmless: no cubic terms
  EXPECT_EQ(v12.certificate, Cert::Kam);
  EXPECT_FALSE(v12.normal_form->a13.has_value());
  EXPECT_EQ(v13.normal_form->resonance, 3);
  ASSERT_TRUE(v13.normal_form->a13.has_value());
  const NormalForm& nf = *v13.normal_form;
  const double bound = 3.0 * std::sqrt(3.0) * *nf.a13 * nf.w2 * nf.w2;
  EXPECT_GT(*nf.a13, 0.0);
  EXPECT_EQ(v13.certificate, std::abs(nf.D) > bound ? Cert::KamMarkeev : Cert::Resonance);
  EXPECT_EQ(v13.verdict, std::abs(nf.D) > bound ? V::Stable : V::Unstable);
  // Just off the resonance Arnold's theorem applies again.
  EXPECT_EQ(lyapunov_stability(b, w13 * (1.0 + 1e-6)).certificate, Cert::Kam);
}

TEST(NormalForm, StableSpinsAgreeWithTheVerdictAtEverySpin) {
  for (const Case& c : kCases) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    const auto intervals = lyapunov_stable_spin_intervals(b);
    for (int i = 1; i < 400; ++i) {
      const double w = 0.02 * i;
      bool inside = false;
      for (const auto& iv : intervals)
        inside = inside || ((w > iv.lo || (w == iv.lo && iv.lo_included)) &&
                            (!iv.hi || w < *iv.hi || (w == *iv.hi && iv.hi_included)));
      EXPECT_EQ(inside, lyapunov_stability(b, w).verdict == V::Stable) << c.A << " " << c.B << " " << c.C << " w0 " << w;
    }
  }
}

TEST(NormalForm, EndsOfTheLinearlyStableSpinsAreTheOneToOneCaseUndecided) {
  // At a Krein collision the computed frequencies differ by ~sqrt(eps) only: the verdict there
  // must be the 1:1 case (undecided), as the linear model's Jordan block says, not kam.
  const Case bodies[] = {{1.0, 1.2, 1.5, 1.0, 0.0}, {1.0, 1.2, 0.8, 1.0, 0.0}, {1.0, 1.5, 0.5, 1.0, 0.0}};
  for (const Case& c : bodies) {
    const Body b = make_body(c.A, c.B, c.C, c.mgR);
    for (const SpinInterval& i : stable_spin_intervals(linear_model(LinearModelKind::Linearized, b))) {
      const LyapunovVerdict v = lyapunov_stability(b, i.lo);
      if (v.energy_index != 2) continue;
      EXPECT_EQ(v.verdict, V::Undecided) << c.C << " at " << i.lo;
      EXPECT_EQ(v.certificate, Cert::None) << c.C << " at " << i.lo;
      EXPECT_FALSE(v.normal_form.has_value());
      EXPECT_EQ(lyapunov_stability(b, i.lo * (1.0 + 1e-9)).certificate, Cert::Kam) << c.C << " above " << i.lo;
    }
    for (const SpinInterval& i : lyapunov_stable_spin_intervals(b)) {
      if (i.lo_included) { EXPECT_EQ(lyapunov_stability(b, i.lo).verdict, V::Stable); }
      if (i.hi && i.hi_included) { EXPECT_EQ(lyapunov_stability(b, *i.hi).verdict, V::Stable); }
    }
  }
}

// ---- Long runs at the resonances, the slow exchange at 1:3, a falling control ---------------

/// Samples of the chart point of the full body's motion from z0 on the leaf L, every dt (s) up
/// to t_end, until |q| > stop (then the last sample is the first beyond it).
std::vector<Eigen::Vector4d> nonlinear_chart_run(const Body& b, double L, const Eigen::Vector4d& z0, double dt,
                                                 double t_end, double stop = 2.0) {
  RigidBodyVector x = body_state(b, L, z0);
  namespace ode = boost::numeric::odeint;
  auto stepper = ode::make_dense_output(1e-12, 1e-12, ode::runge_kutta_dopri5<RigidBodyVector>());
  stepper.initialize(x, 0.0, dt);
  std::vector<Eigen::Vector4d> out{z0};
  RigidBodySystem sys{b};
  for (std::size_t i = 1; i * dt <= t_end; ++i) {
    const double t = i * dt;
    while (stepper.current_time() < t) stepper.do_step(sys);
    stepper.calc_state(t, x);
    out.push_back(chart_point(b, L, x));
    if (out.back().head<2>().norm() > stop || !std::isfinite(out.back()[0])) break;
  }
  return out;
}

/// The largest |q| = sin(tilt) that the linear normal-form motion from zeta0 can reach.
double linear_bound(const NormalForm& nf, const Eigen::Vector4d& zeta0) {
  double bound = 0.0;
  for (int i = 0; i < 2; ++i) {
    Eigen::Matrix2d block;
    block << nf.T(0, i), nf.T(0, i + 2), nf.T(1, i), nf.T(1, i + 2);
    bound += std::hypot(zeta0[i], zeta0[i + 2]) * Eigen::JacobiSVD<Eigen::Matrix2d>(block).singularValues()[0];
  }
  return bound;
}

TEST(NormalForm, LongRunsAtOneToTwoAndOneToThreeStayOnTheLinearBoundAndAnUnstableControlFalls) {
  const Body b = make_body(1.0, 1.2, 0.8, 1.0);
  for (double ratio : {2.0, 3.0}) {
    const double w0 = spin_at_ratio(b, ratio == 2.0 ? 2.7 : 4.0, ratio == 2.0 ? 4.0 : 6.0, ratio);
    const NormalForm nf = *birkhoff_normal_form(b, w0);
    ASSERT_EQ(nf.resonance, int(ratio));
    const double unit = 1.0 / (nf.T.row(0).squaredNorm() + nf.T.row(1).squaredNorm());
    const double r = 1e-4 * unit;  // tilts of about 1e-2 rad
    const Eigen::Vector4d zeta0(std::sqrt(2.0 * r), std::sqrt(2.0 * r), 0.0, 0.0);
    const double slow = 2.0 * std::numbers::pi / std::min(nf.w1, nf.w2), periods = 1e4;
    const auto run = nonlinear_chart_run(b, nf.L, nf.T * zeta0, slow / 48.0, periods * slow);
    double largest = 0.0;
    for (const auto& z : run) largest = std::max(largest, z.head<2>().norm());
    const double bound = linear_bound(nf, zeta0);
    std::printf("1:%g at w0 = %.12g: %g periods (%.0f s), max |q| %.6g, linear bound %.6g (ratio %.4f)\n", ratio,
                w0, periods, periods * slow, largest, bound, largest / bound);
    EXPECT_EQ(run.size(), std::size_t(periods * 48.0) + 1);
    EXPECT_LT(largest, 1.05 * bound);
  }
  // The control: the same body below its linear-stability threshold (a Krein collision passed)
  // grows exponentially and falls.
  const double w0 = 2.3;
  ASSERT_FALSE(linear_stability(linear_model(LinearModelKind::Linearized, b), w0).stable);
  ASSERT_FALSE(birkhoff_normal_form(b, w0).has_value());
  const auto fall = nonlinear_chart_run(b, b.C * w0, Eigen::Vector4d(1e-3, 0.0, 0.0, 0.0), 0.05, 2000.0, std::sin(1.0));
  EXPECT_GT(fall.back().head<2>().norm(), std::sin(1.0));
  std::printf("control at w0 = 2.3: |q| passes sin(1 rad) at t = %.1f s\n", 0.05 * (fall.size() - 1));
}

struct Exchange {
  double excursion;  ///< J s, the largest |r1 - r1(0)| the resonant normal form predicts
  double deviation;  ///< J s, the largest |measured - predicted| (both averaged per slow period)
  double r;          ///< J s, the starting actions
};

/// The 1:3 exchange of body (1, 1.2, 0.8, 1) at its exact 1:3 spin, from r1 = r2 = action x (the
/// action of a unit tilt), over 0.4 / action slow periods (the actions' slow cycle scales as 1/r).
Exchange one_to_three_exchange(double action) {
  const Body b = make_body(1.0, 1.2, 0.8, 1.0);
  const double w0 = spin_at_ratio(b, 4.0, 6.0, 3.0);
  const NormalForm nf = *birkhoff_normal_form(b, w0);
  EXPECT_EQ(nf.resonance, 3);
  EXPECT_GT(nf.w1, nf.w2);  // w1 = 3 w2: the harmonic a1 + 3 a2
  if (nf.resonance != 3 || !(nf.w1 > nf.w2)) return {0.0, 1.0, 1.0};
  // chi, the phase of the resonant harmonic (a13/2) e^{i chi} on the torus (1, 1).
  std::complex<double> F = 0.0;
  constexpr int N = 8;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const double a1 = 2 * std::numbers::pi * i / N, a2 = 2 * std::numbers::pi * j / N;
      const Eigen::Vector4d z = nf.T * Eigen::Vector4d(std::sqrt(2.0) * std::cos(a1), std::sqrt(2.0) * std::cos(a2),
                                                       std::sqrt(2.0) * std::sin(a1), std::sqrt(2.0) * std::sin(a2));
      F += reduced_quartic(b, nf.L, z) * std::polar(1.0, -(a1 + 3 * a2)) / double(N * N);
    }
  EXPECT_NEAR(2.0 * std::abs(F), *nf.a13, 1e-12 * *nf.a13);
  const double chi = std::arg(F);
  // Start on the torus r1 = r2 = r with psi = a1 + 3 a2 + chi = pi/2 (the fastest exchange).
  const double unit = 1.0 / (nf.T.row(0).squaredNorm() + nf.T.row(1).squaredNorm());
  const double r = action * unit, a2 = (std::numbers::pi / 2 - chi) / 3.0;
  const Eigen::Vector4d zeta0(std::sqrt(2 * r), std::sqrt(2 * r) * std::cos(a2), 0.0, std::sqrt(2 * r) * std::sin(a2));
  // The resonant normal form's own motion: r1' = -a13 sqrt(r1 r2^3) sin psi, r2' = 3 r1',
  // psi' = -dH/dr1 - 3 dH/dr2 (RK4); with a13 = 0 the actions would not move at all.
  auto normal_form_r1 = [&](double T, double h) {
    std::vector<double> r1s;
    std::array<double, 3> y{r, r, std::numbers::pi / 2};
    auto f = [&](const std::array<double, 3>& s) {
      const double r1 = s[0], r2 = s[1], p = s[2], a = *nf.a13;
      const double dr1 = -a * std::sqrt(r1 * r2 * r2 * r2) * std::sin(p);
      const double dH1 = nf.w1 + 2 * nf.c20 * r1 + nf.c11 * r2 + 0.5 * a * std::sqrt(r2 * r2 * r2 / r1) * std::cos(p);
      const double dH2 = -nf.w2 + nf.c11 * r1 + 2 * nf.c02 * r2 + 1.5 * a * std::sqrt(r1 * r2) * std::cos(p);
      return std::array<double, 3>{dr1, 3 * dr1, -dH1 - 3 * dH2};
    };
    for (double t = 0; t <= T; t += h) {
      r1s.push_back(y[0]);
      auto add = [](std::array<double, 3> u, const std::array<double, 3>& v, double c) {
        for (int i = 0; i < 3; ++i) u[i] += c * v[i];
        return u;
      };
      const auto k1 = f(y), k2 = f(add(y, k1, h / 2)), k3 = f(add(y, k2, h / 2)), k4 = f(add(y, k3, h));
      for (int i = 0; i < 3; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    return r1s;
  };
  const double slow = 2.0 * std::numbers::pi / nf.w2, T = 0.4 / action * slow;
  const auto run = nonlinear_chart_run(b, nf.L, nf.T * zeta0, slow / 48.0, T);
  const Eigen::Matrix4d Tinv = nf.T.inverse();
  // r1 averaged over each slow period (at exact 1:3 every fast harmonic has that period).
  std::vector<double> measured;
  for (std::size_t k = 0; (k + 1) * 48 < run.size(); ++k) {
    double sum = 0.0;
    for (std::size_t i = k * 48; i < (k + 1) * 48; ++i) {
      const Eigen::Vector4d zeta = Tinv * run[i];
      sum += 0.5 * (zeta[0] * zeta[0] + zeta[2] * zeta[2]);
    }
    measured.push_back(sum / 48.0);
  }
  const auto predicted_all = normal_form_r1(T, slow / 48.0);
  double max_dev = 0.0, excursion = 0.0;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    double mean = 0.0;  // the prediction averaged over the same slow period
    for (std::size_t i = k * 48; i < (k + 1) * 48; ++i) mean += predicted_all[i] / 48.0;
    max_dev = std::max(max_dev, std::abs(measured[k] - mean));
    excursion = std::max(excursion, std::abs(mean - r));
  }
  const double measured_excursion = std::abs(*std::max_element(measured.begin(), measured.end(), [&](double x, double y) {
    return std::abs(x - r) < std::abs(y - r);
  }) - r);
  std::printf("1:3 exchange from r = %g: a13 = %.6g, r1 moves by %.4g of r (normal form %.4g), largest difference "
              "%.3g of r\n", action, *nf.a13, measured_excursion / r, excursion / r, max_dev / r);
  return {excursion, max_dev, r};
}

TEST(NormalForm, SlowExchangeAtOneToThreeFollowsTheResonantCoefficient) {
  const Exchange large = one_to_three_exchange(3e-4), small = one_to_three_exchange(1e-4);
  EXPECT_GT(small.excursion, 1e-3 * small.r);            // the exchange is there (none with a13 = 0)
  EXPECT_LT(small.deviation, 0.05 * small.excursion);    // the resonant coefficient predicts it,
  const double order = (large.deviation / large.r) / (small.deviation / small.r);
  EXPECT_GT(order, 2.0);                                 // to O(r) (3x the action, 3x the relative error)
  EXPECT_LT(order, 4.5);
}

// ---- Scale-free in mass (issue 46) -----------------------------------------------------------

/// The body (A, B, C, m g R) with A, B, C and the mass all times `mass_scale`: the same motion
/// (time is unchanged), so the same verdict, frequencies and stable spins; the c's, D and a13
/// divided by mass_scale (they are per J s^2), L and the actions times it.
Body mass_scaled(const Case& c, double mass_scale) {
  Body b;
  b.A = c.A * mass_scale;
  b.B = c.B * mass_scale;
  b.C = c.C * mass_scale;
  b.mass = mass_scale;
  b.gravity = 1.0;
  b.length = c.mgR;
  return b;
}

/// Relative difference, 0 for two zeros.
double relative(double x, double y) {
  const double size = std::max(std::abs(x), std::abs(y));
  return size == 0.0 ? 0.0 : std::abs(x - y) / size;
}

bool same_intervals(const std::vector<SpinInterval>& x, const std::vector<SpinInterval>& y, double tolerance,
                    std::string& why) {
  if (x.size() != y.size()) {
    why = "pieces " + std::to_string(x.size()) + " against " + std::to_string(y.size());
    return false;
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool same = relative(x[i].lo, y[i].lo) <= tolerance && x[i].lo_included == y[i].lo_included &&
                      x[i].hi.has_value() == y[i].hi.has_value() &&
                      (!x[i].hi || (relative(*x[i].hi, *y[i].hi) <= tolerance && x[i].hi_included == y[i].hi_included));
    if (!same) {
      why = "piece " + std::to_string(i) + " lo " + std::to_string(x[i].lo) + " against " + std::to_string(y[i].lo);
      return false;
    }
  }
  return true;
}

// Index 2, linearly stable, away from 1:1 and 1:3 (kCases), and the oblate body of the D = 0 test,
// whose stable spins have a D = 0 exception: the bodies and spins scaled below.
const Case kScaledCases[] = {{1.0, 1.5, 0.5, 1.0, 6.0}, {1.0, 1.2, 0.8, 1.0, 4.0}, {1.0, 1.2, 0.7, -1.0, 3.0},
                             {1.52594, 1.894034, 1.59991, 1.0, 3.0}};

class MassScaling : public ::testing::TestWithParam<double> {};

TEST_P(MassScaling, KamVerdictFrequenciesAndStableSpinsAreThoseOfTheUnscaledBody) {
  const double scale = GetParam(), tolerance = 1e-9;
  const Eigen::Matrix4d J = canonical_J();
  for (const Case& c : kScaledCases) {
    SCOPED_TRACE(::testing::Message() << "A " << c.A << " B " << c.B << " C " << c.C << " mgR " << c.mgR
                                      << " spin " << c.spin << " scaled by " << scale);
    const Body one = mass_scaled(c, 1.0), b = mass_scaled(c, scale);
    const LyapunovVerdict want = lyapunov_stability(one, c.spin), got = lyapunov_stability(b, c.spin);
    EXPECT_EQ(got.verdict, want.verdict);
    EXPECT_EQ(got.certificate, want.certificate);
    EXPECT_EQ(got.energy_index, want.energy_index);
    ASSERT_TRUE(want.normal_form && got.normal_form);
    const NormalForm &nf = *got.normal_form, &nf1 = *want.normal_form;
    EXPECT_LE(relative(nf.w1, nf1.w1), tolerance);
    EXPECT_LE(relative(nf.w2, nf1.w2), tolerance);
    EXPECT_EQ(nf.resonance, nf1.resonance);
    const double c_size = std::abs(nf1.c20) + std::abs(nf1.c11) + std::abs(nf1.c02);
    for (auto [x, y] : {std::pair{nf.c20, nf1.c20}, {nf.c11, nf1.c11}, {nf.c02, nf1.c02}})
      EXPECT_LE(std::abs(x * scale - y), tolerance * c_size);
    EXPECT_LE(relative(nf.D * scale, nf1.D), tolerance);
    EXPECT_LE(relative(nf.D_scale * scale, nf1.D_scale), tolerance);
    // The change is still symplectic and diagonalises the chart's H2 in its own units.
    EXPECT_LT((nf.T.transpose() * J * nf.T - J).norm(), 1e-12);
    Eigen::Matrix4d H2 = Eigen::Matrix4d::Zero();
    H2.diagonal() << nf.w1, -nf.w2, nf.w1, -nf.w2;
    EXPECT_LT((nf.T.transpose() * reduced_quadratic_form(b, nf.L) * nf.T - H2).norm(), 1e-12 * (nf.w1 + nf.w2));
    // The frequencies are the scaled body's own linearized model's (the tolerance of
    // DiagonalisationIsSymplecticWithTheLinearisedFrequencies).
    const StabilityVerdict lin = linear_stability(linear_model(LinearModelKind::Linearized, b), c.spin);
    ASSERT_TRUE(lin.stable);
    ASSERT_EQ(lin.frequencies.size(), 2u);
    const double lo = std::min(nf.w1, nf.w2), hi = std::max(nf.w1, nf.w2);
    EXPECT_NEAR(lin.frequencies[0], lo, 1e-10 * hi);
    EXPECT_NEAR(lin.frequencies[1], hi, 1e-10 * hi);

    // The stable spins: the Lyapunov ones (their KAM exceptions found by the same scan) and
    // every linear model's.
    std::string why;
    EXPECT_TRUE(same_intervals(lyapunov_stable_spin_intervals(b), lyapunov_stable_spin_intervals(one), tolerance, why))
        << why;
    const auto exceptions = kam_exceptions(b), exceptions1 = kam_exceptions(one);
    ASSERT_EQ(exceptions.size(), exceptions1.size());
    for (std::size_t i = 0; i < exceptions.size(); ++i) {
      EXPECT_LE(relative(exceptions[i].spin, exceptions1[i].spin), tolerance);
      EXPECT_EQ(exceptions[i].what, exceptions1[i].what);
    }
    for (LinearModelKind kind : kLinearModels)
      EXPECT_TRUE(same_intervals(stable_spin_intervals(linear_model(kind, b)),
                                 stable_spin_intervals(linear_model(kind, one)), tolerance, why))
          << name(kind) << ": " << why;
  }
}

TEST_P(MassScaling, OneToThreeResonanceAndItsCoefficientScale) {
  const double scale = GetParam();
  const Case c{1.0, 1.2, 0.8, 1.0, 0.0};
  const Body one = mass_scaled(c, 1.0), b = mass_scaled(c, scale);
  const double w13 = spin_at_ratio(one, 4.0, 6.0, 3.0);
  const LyapunovVerdict want = lyapunov_stability(one, w13), got = lyapunov_stability(b, w13);
  ASSERT_TRUE(want.normal_form && got.normal_form);
  EXPECT_EQ(got.normal_form->resonance, 3);
  EXPECT_EQ(got.certificate, want.certificate);
  ASSERT_TRUE(got.normal_form->a13 && want.normal_form->a13);
  EXPECT_LE(relative(*got.normal_form->a13 * scale, *want.normal_form->a13), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(NormalForm, MassScaling,
                         ::testing::Values(1e-20, 1e-16, 1e-12, 1e-8, 1e-4, 1.0, 1e4, 1e8, 1e12, 1e16, 1e20),
                         [](const ::testing::TestParamInfo<double>& info) {
                           const int e = static_cast<int>(std::lround(std::log10(info.param)));
                           return e < 0 ? "MassTimes1em" + std::to_string(-e) : "MassTimes1e" + std::to_string(e);
                         });

}  // namespace
}  // namespace heavytop

// Linear stability of the three linear models (SPEC section 3; errata E2, E3).
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "heavytop/stability.hpp"

namespace heavytop {
namespace {

/// A body with m g R = mgR exactly (mass 1, gravity 1, length mgR).
Body body_with(double A, double B, double C, double mgR) {
  return Body{.A = A, .B = B, .C = C, .mass = 1.0, .gravity = 1.0, .length = mgR};
}

std::optional<double> critical(LinearModelKind kind, const Body& b) {
  return critical_spin(stable_spin_intervals(linear_model(kind, b)));
}

bool stable(LinearModelKind kind, const Body& b, double spin) {
  return linear_stability(linear_model(kind, b), spin).stable;
}

constexpr auto kFirst = LinearModelKind::FirstOrder;
constexpr auto kFixed = LinearModelKind::BodyFixed;
constexpr auto kLinear = LinearModelKind::Linearized;

// ---- The classical sleeping top, A = B: C^2 w0^2 > 4 A m g R -------------------------------

class SymmetricTop : public ::testing::TestWithParam<std::tuple<double, double, double>> {};

TEST_P(SymmetricTop, AllRoutesButBodyFixedGiveTheClassicalCriterion) {
  const auto [A, C, mgR] = GetParam();
  const Body b = body_with(A, A, C, mgR);
  const double classical = 2.0 * std::sqrt(A * mgR) / C;  // C^2 w0^2 = 4 A m g R
  ASSERT_TRUE(critical(kFirst, b));
  ASSERT_TRUE(critical(kLinear, b));
  EXPECT_NEAR(*critical(kFirst, b), classical, 1e-12 * classical);
  EXPECT_NEAR(*critical(kLinear, b), classical, 1e-9 * classical);
  // Just either side of it.
  for (auto kind : {kFirst, kLinear}) {
    EXPECT_FALSE(stable(kind, b, classical * (1.0 - 1e-6)));
    EXPECT_TRUE(stable(kind, b, classical * (1.0 + 1e-6)));
  }
  // The body-fixed model (5) puts it at 2 sqrt(A m g R) / |C - A|: wrong unless A << C.
  const auto fixed = critical(kFixed, b);
  if (C == A) {
    EXPECT_FALSE(fixed);
  } else {
    ASSERT_TRUE(fixed);
    EXPECT_NEAR(*fixed, 2.0 * std::sqrt(A * mgR) / std::abs(C - A), 1e-9 * *fixed);
    if (A != 2.0 * C) { EXPECT_GT(std::abs(*fixed - classical), 0.01 * classical); }
  }
}

INSTANTIATE_TEST_SUITE_P(Bodies, SymmetricTop,
                         ::testing::Values(std::make_tuple(1.0, 2.0, 1.0),   // flat disc, C = 2A
                                           std::make_tuple(1.0, 1.5, 1.0),
                                           std::make_tuple(1.0, 0.5, 1.0),   // prolate
                                           std::make_tuple(4.35e-5, 1.2e-5, 0.0147),  // toy top
                                           std::make_tuple(2.0, 3.9, 0.3)));

TEST(Stability, HookCaseCriticalSpinIsOne) {
  // A = B = 1, C = 2, m g R = 1: C^2 w0^2 = 4 gives w0 = 1 for (4) and the linearisation.
  EXPECT_NEAR(*critical(kFirst, body_with(1, 1, 2, 1)), 1.0, 1e-15);
  EXPECT_NEAR(*critical(kLinear, body_with(1, 1, 2, 1)), 1.0, 1e-12);
}

TEST(Stability, SphericalBodyFixedModelIsNeverStable) {
  // A = B = C: model (5) has no gyroscopic term at all; (9) gives w0^2 > 4 m g R / A.
  const Body b = body_with(2.0, 2.0, 2.0, 0.5);
  EXPECT_TRUE(stable_spin_intervals(linear_model(kFixed, b)).empty());
  EXPECT_FALSE(critical(kFixed, b));
  EXPECT_FALSE(paper_body_fixed_spin(b));
  EXPECT_FALSE(stable(kFixed, b, 1e6));
  EXPECT_NEAR(*critical(kFirst, b), std::sqrt(4.0 * 0.5 / 2.0), 1e-15);
  EXPECT_NEAR(paper_condition_9_spin(b), std::sqrt(4.0 * 0.5 / 2.0), 1e-15);
}

// ---- Erratum E2: the boundary of (9) is not stable -----------------------------------------

TEST(Stability, SpinExactlyAtConditionNineIsUnstable) {
  for (const Body& b : {body_with(1.0, 1.3, 2.0, 1.0), body_with(1.0, 1.0, 2.0, 1.0),
                        body_with(4.35e-5, 4.35e-5, 1.2e-5, 0.0147)}) {
    const double boundary = paper_condition_9_spin(b);
    const StabilityVerdict v = linear_stability(linear_model(kFirst, b), boundary);
    EXPECT_FALSE(v.stable) << v.reason;
    EXPECT_NE(v.reason.find("Jordan"), std::string::npos) << v.reason;
    // The double frequency is (m g R)^2 / (A B) to the quarter (the paper's alpha at (15)).
    EXPECT_NEAR(std::abs(v.eigenvalues[0].imag()), std::pow(b.mgR() * b.mgR() / (b.A * b.B), 0.25),
                1e-6);
    EXPECT_TRUE(linear_stability(linear_model(kFirst, b), boundary * (1 + 1e-7)).stable);
  }
}

TEST(Stability, SemisimpleDoubleEigenvaluesAreStable) {
  // In the body frame a symmetric body with C = 2A has double eigenvalues at every spin, and
  // they are semisimple: no Jordan block, so stable above the classical threshold.
  const Body disc = body_with(1.0, 1.0, 2.0, 1.0);
  for (double spin : {1.5, 3.0, 10.0}) {
    const StabilityVerdict v = linear_stability(linear_model(kLinear, disc), spin);
    EXPECT_TRUE(v.stable) << spin << ": " << v.reason;
    ASSERT_EQ(v.frequencies.size(), 1u);
    EXPECT_NEAR(v.frequencies[0], std::sqrt(spin * spin - 1.0), 1e-9);  // sqrt(A w0^2 - mgR)/A... for A=1
  }
  // C > A: at w0^2 = m g R / (C - A) the stiffness vanishes (a double zero eigenvalue), and
  // it is semisimple, so the stable set has no hole there.
  const Body b = body_with(1.0, 1.0, 1.5, 1.0);
  const double hole = std::sqrt(1.0 / 0.5);
  const StabilityVerdict v = linear_stability(linear_model(kLinear, b), hole);
  EXPECT_TRUE(v.stable) << v.reason;
  const auto intervals = stable_spin_intervals(linear_model(kLinear, b));
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_NEAR(intervals[0].lo, 2.0 * std::sqrt(1.0) / 1.5, 1e-12);
  EXPECT_FALSE(intervals[0].hi);
}

// ---- Erratum E3: (4) is the linearisation only for A = B -----------------------------------

TEST(Stability, ErratumE3AsymmetricTopNeedsMoreSpinThanConditionNine) {
  const Body b = body_with(1.0, 1.5, 2.0, 1.0);
  EXPECT_NEAR(paper_condition_9_spin(b), 1.112372, 1e-6);
  EXPECT_NEAR(*critical(kFirst, b), paper_condition_9_spin(b), 1e-12);
  EXPECT_NEAR(*critical(kLinear, b), std::sqrt(2.0), 1e-12);
  for (double spin : {1.2, 1.3}) {
    EXPECT_TRUE(stable(kFirst, b, spin));
    EXPECT_FALSE(stable(kLinear, b, spin));
  }
  EXPECT_TRUE(stable(kLinear, b, 1.45));
}

TEST(Stability, ErratumE3ElongatedBodyConditionNineTooStrict) {
  const Body b = body_with(2.0, 1.2, 0.9, 1.0);
  EXPECT_NEAR(paper_condition_9_spin(b), 2.789, 5e-4);
  // Exact: the larger root of the discriminant 4.2849 s^2 - 30.912 s + 0.64 in s = w0^2.
  const double s = (30.912 + std::sqrt(30.912 * 30.912 - 4 * 4.2849 * 0.64)) / (2 * 4.2849);
  EXPECT_NEAR(*critical(kLinear, b), std::sqrt(s), 1e-9 * std::sqrt(s));
  EXPECT_NEAR(*critical(kLinear, b), 2.682, 5e-4);
}

TEST(Stability, SymmetricHangingBodyIsStableAtEverySpin) {
  for (double C : {0.5, 1.2, 2.0}) {
    const Body b = body_with(1.0, 1.0, C, -1.0);
    for (auto kind : {kFirst, kLinear}) {
      const auto intervals = stable_spin_intervals(linear_model(kind, b));
      ASSERT_EQ(intervals.size(), 1u) << name(kind) << " C=" << C;
      EXPECT_EQ(intervals[0].lo, 0.0);
      EXPECT_FALSE(intervals[0].hi);
      EXPECT_EQ(*critical(kind, b), 0.0);
    }
  }
}

TEST(Stability, AsymmetricHangingBodyHasAnUnstableSpinBand) {
  const Body b = body_with(1.0, 1.2, 0.7, -1.0);
  // (4) calls it stable at every spin.
  const auto paper = stable_spin_intervals(linear_model(kFirst, b));
  ASSERT_EQ(paper.size(), 1u);
  EXPECT_EQ(paper[0].lo, 0.0);
  EXPECT_FALSE(paper[0].hi);
  // The linearisation: unstable for sqrt(2) < w0 < sqrt(10/3) (stiffness (C-B)w0^2 - mgR and
  // (C-A)w0^2 - mgR of opposite signs).
  const auto truth = stable_spin_intervals(linear_model(kLinear, b));
  ASSERT_EQ(truth.size(), 2u);
  EXPECT_EQ(truth[0].lo, 0.0);
  EXPECT_NEAR(*truth[0].hi, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(truth[1].lo, std::sqrt(10.0 / 3.0), 1e-12);
  EXPECT_NEAR(truth[1].lo, 1.826, 1e-3);
  EXPECT_FALSE(truth[1].hi);
  EXPECT_FALSE(stable(kLinear, b, 1.6));
  EXPECT_TRUE(stable(kLinear, b, 1.2));
  EXPECT_TRUE(stable(kLinear, b, 2.0));
}

/// The largest |condition| / size among the linearisation's conditions at s = w0^2, written out
/// as in docs/linearization.md: an interval end must make one of them vanish.
double nearest_condition(double A, double B, double C, double k, double w0) {
  const double s = w0 * w0;
  const double k11 = (C - B) * s - k, k22 = (C - A) * s - k;
  const double a2 = ((C - A) * (C - B) + A * B) * s - (A + B) * k;
  const double disc = a2 * a2 - 4.0 * A * B * k11 * k22;
  const double size = std::abs(k) + (A + B + C) * s;
  return std::min({std::abs(k11), std::abs(k22), std::abs(a2), std::abs(disc) / size}) / size;
}

TEST(Stability, IntervalShapesTwoWindowsBoundedAndNone) {
  // Two windows, C > B > A: the lower one closes where the discriminant vanishes.
  auto two = stable_spin_intervals(linear_model(kLinear, body_with(1.0, 1.26, 1.54, 1.0)));
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[0].lo, 1.3402, 1e-4);
  EXPECT_NEAR(*two[0].hi, 1.3608, 1e-4);
  EXPECT_NEAR(two[1].lo, 1.8898, 1e-4);
  EXPECT_FALSE(two[1].hi);
  for (double end : {two[0].lo, *two[0].hi, two[1].lo})
    EXPECT_LT(nearest_condition(1.0, 1.26, 1.54, 1.0, end), 1e-12);
  // A bounded window only, A < C < B: it closes at (C - A) w0^2 = m g R, w0 = sqrt(5), and
  // opens at the larger root of the discriminant 2.4336 s^2 - 7.8 s + 0.25.
  auto bounded = stable_spin_intervals(linear_model(kLinear, body_with(1.0, 1.5, 1.2, 1.0)));
  ASSERT_EQ(bounded.size(), 1u);
  ASSERT_TRUE(bounded[0].hi);
  const double s_lo = (7.8 + std::sqrt(7.8 * 7.8 - 4 * 2.4336 * 0.25)) / (2 * 2.4336);
  EXPECT_NEAR(bounded[0].lo, std::sqrt(s_lo), 1e-9 * std::sqrt(s_lo));
  EXPECT_NEAR(*bounded[0].hi, std::sqrt(5.0), 1e-12);
  EXPECT_FALSE(critical_spin(bounded));
  // Hanging and bounded: stable from rest up to a spin, never above.
  auto hanging = stable_spin_intervals(linear_model(kLinear, body_with(1.0, 2.14, 1.36, -1.0)));
  ASSERT_EQ(hanging.size(), 1u);
  EXPECT_EQ(hanging[0].lo, 0.0);
  ASSERT_TRUE(hanging[0].hi);
  EXPECT_LT(nearest_condition(1.0, 2.14, 1.36, -1.0, *hanging[0].hi), 1e-12);
  // No stable spin at all.
  EXPECT_TRUE(stable_spin_intervals(linear_model(kLinear, body_with(1.0, 0.36, 0.74, 1.0))).empty());
  EXPECT_FALSE(critical(kLinear, body_with(1.0, 0.36, 0.74, 1.0)));
}

// ---- Cross-checks against independent routes -----------------------------------------------

TEST(Stability, PaperClosedFormsEqualTheGeneralAnalysis) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  int checked = 0;
  while (checked < 200) {
    const Body b = body_with(u(rng), u(rng), u(rng), u(rng));
    if (b.A + b.B < b.C || b.B + b.C < b.A || b.C + b.A < b.B) continue;
    ++checked;
    EXPECT_NEAR(*critical(kFirst, b), paper_condition_9_spin(b), 1e-12 * paper_condition_9_spin(b));
    const auto paper_fixed = paper_body_fixed_spin(b);
    const auto fixed = critical(kFixed, b);
    ASSERT_EQ(paper_fixed.has_value(), fixed.has_value());
    if (fixed) { EXPECT_NEAR(*fixed, *paper_fixed, 1e-12 * *paper_fixed); }
  }
}

/// Stable by Eigen's general eigensolver: every real part negligible (no Jordan test; used
/// away from double roots only).
bool eigen_says_stable(const LinearModel& m, double spin) {
  const Eigen::Matrix4d j = state_matrix(m, spin);
  Eigen::EigenSolver<Eigen::Matrix4d> es(j);
  const double scale = es.eigenvalues().cwiseAbs().maxCoeff();
  return es.eigenvalues().real().cwiseAbs().maxCoeff() <= 1e-7 * scale;
}

TEST(Stability, IntervalsAgreeWithAnEigensolverScanOverRandomBodies) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  int bodies = 0, disagreements = 0, samples = 0;
  while (bodies < 60) {
    const Body b = body_with(1.0, u(rng), u(rng), bodies % 2 ? 1.0 : -1.0);
    if (b.A + b.B < b.C || b.B + b.C < b.A || b.C + b.A < b.B) continue;
    ++bodies;
    for (auto kind : kLinearModels) {
      const LinearModel m = linear_model(kind, b);
      const auto intervals = stable_spin_intervals(m);
      for (int i = 1; i <= 400; ++i) {
        const double spin = 0.0125 * i;
        bool inside = false, near_end = false;
        for (const auto& iv : intervals) {
          inside = inside || (spin >= iv.lo && (!iv.hi || spin <= *iv.hi));
          near_end = near_end || std::abs(spin - iv.lo) < 1e-3 || (iv.hi && std::abs(spin - *iv.hi) < 1e-3);
        }
        if (near_end) continue;
        ++samples;
        if (inside != eigen_says_stable(m, spin)) ++disagreements;
        EXPECT_EQ(inside, linear_stability(m, spin).stable) << name(kind) << " spin " << spin;
      }
    }
  }
  EXPECT_GT(samples, 50000);
  // The eigensolver's real parts near a double root can exceed its tolerance; allow a handful.
  EXPECT_LE(disagreements, samples / 2000) << disagreements << " of " << samples;
}

TEST(Stability, EigenvaluesAreRootsOfTheCharacteristicPolynomialAndOfTheSystemMatrix) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  for (int n = 0; n < 300; ++n) {
    const Body b = body_with(u(rng), u(rng), u(rng), u(rng) - 1.5);
    if (b.A + b.B < b.C || b.B + b.C < b.A || b.C + b.A < b.B) continue;
    const double spin = 3.0 * u(rng);
    for (auto kind : kLinearModels) {
      const LinearModel m = linear_model(kind, b);
      const StabilityVerdict v = linear_stability(m, spin);
      ASSERT_EQ(v.eigenvalues.size(), 4u);
      for (const auto& l : v.eigenvalues) {
        // det(M l^2 + G l + K) = 0, relative to the size of its terms.
        const Eigen::Matrix2cd d = m.M.cast<std::complex<double>>() * l * l +
                                   m.G(spin).cast<std::complex<double>>() * l +
                                   m.K(spin).cast<std::complex<double>>();
        const double size = (m.M.norm() * std::norm(l) + m.G(spin).norm() * std::abs(l) + m.K(spin).norm());
        EXPECT_LT(std::abs(d.determinant()), 1e-9 * size * size);
      }
      // And the product of the eigenvalues is det J = a0 / a4.
      std::complex<double> product = 1.0;
      for (const auto& l : v.eigenvalues) product *= l;
      const CharacteristicPolynomial p = characteristic_polynomial(m, spin);
      EXPECT_NEAR(product.real(), state_matrix(m, spin).determinant(), 1e-8 * (1 + std::abs(p.a0 / p.a4)));
      EXPECT_NEAR(p.a0 / p.a4, state_matrix(m, spin).determinant(), 1e-10 * (1 + std::abs(p.a0 / p.a4)));
    }
  }
}

TEST(Stability, FrequenciesOfTheFirstOrderModelMatchTheCharacteristicEquation) {
  // (8): lambda^4 + 2p lambda^2 + q = 0; alpha1^2 alpha2^2 = q, alpha1^2 + alpha2^2 = 2p.
  const Body b = body_with(1.0, 1.3, 2.0, 1.0);
  const double w0 = 1.6;
  const StabilityVerdict v = linear_stability(linear_model(kFirst, b), w0);
  ASSERT_TRUE(v.stable);
  ASSERT_EQ(v.frequencies.size(), 2u);
  const double two_p = (4.0 * w0 * w0 - 2.3) / 1.3, q = 1.0 / 1.3;
  const double a = v.frequencies[0], c = v.frequencies[1];
  EXPECT_NEAR(a * a + c * c, two_p, 1e-13);
  EXPECT_NEAR(a * a * c * c, q, 1e-13);
}

TEST(Stability, FreeBodyWithoutGravityIsStableAtAnyNonzeroSpin) {
  // m g R = 0: a neutral (semisimple) zero eigenvalue pair; at zero spin the axis drifts.
  const Body b = Body{.A = 1.0, .B = 1.0, .C = 1.5, .mass = 1.0, .gravity = 0.0, .length = 1.0};
  EXPECT_TRUE(stable(kFirst, b, 2.0));
  EXPECT_FALSE(stable(kFirst, b, 0.0));
  const auto intervals = stable_spin_intervals(linear_model(kFirst, b));
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_EQ(intervals[0].lo, 0.0);
  EXPECT_EQ(*critical_spin(intervals), 0.0);
}

}  // namespace
}  // namespace heavytop

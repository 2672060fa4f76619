// The symbolic derivations reproduce the paper's results (and its errata), and agree with the
// numeric core's linear models.
#include <chrono>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "heavytop/linear_models.hpp"
#include "heavytop/symbolic/derive.hpp"
#include "heavytop/symbolic/print.hpp"
#include "heavytop/symbolic/symbols.hpp"

namespace hs = heavytop::symbolic;
using GiNaC::ex;
using GiNaC::matrix;

namespace {

const hs::Symbols& S = hs::symbols();

// a == b as expressions: their difference normalises to zero.
::testing::AssertionResult Same(const ex& a, const ex& b) {
  const ex diff = GiNaC::normal((a - b).expand());
  if (diff.is_zero()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << "  !=  " << b << "  (difference " << diff << ")";
}

::testing::AssertionResult SameMatrix(const matrix& a, const matrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << "shapes differ";
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j)
      if (auto r = Same(a(i, j), b(i, j)); !r) return r << " at (" << i << ", " << j << ")";
  return ::testing::AssertionSuccess();
}

matrix vec(const ex& x, const ex& y, const ex& z) { return {{x}, {y}, {z}}; }

matrix without_psi(const matrix& a) {
  return GiNaC::ex_to<matrix>(a.subs(GiNaC::exmap{{S.psi, 0}, {S.psi_t, 0}}));
}

const ex kmgR = S.m * S.g * S.R;

}  // namespace

// ---- Section 1: small rotations -----------------------------------------------------------

TEST(Rotations, FirstOrderRotationsCommuteAndGiveThePapersTable) {
  const hs::Rotations r = hs::rotations(1);
  EXPECT_TRUE(SameMatrix(r.A1, {{1, 0, 0}, {0, 1, S.phi}, {0, -S.phi, 1}}));
  EXPECT_TRUE(SameMatrix(r.A2, {{1, 0, -S.theta}, {0, 1, 0}, {S.theta, 0, 1}}));
  EXPECT_TRUE(SameMatrix(r.A3, {{1, S.psi, 0}, {-S.psi, 1, 0}, {0, 0, 1}}));
  const matrix product = {{1, 0, -S.theta}, {0, 1, S.phi}, {S.theta, -S.phi, 1}};
  EXPECT_TRUE(SameMatrix(r.A1A2, product));
  EXPECT_TRUE(SameMatrix(r.A2A1, product));
  EXPECT_TRUE(SameMatrix(r.commutator, matrix(3, 3)));
  // The transition table A = A3 A2 A1 (psi theta = 0 at first order).
  const matrix table = hs::truncate(r.A3.mul(r.A2A1), 1);
  EXPECT_TRUE(SameMatrix(table, {{1, S.psi, -S.theta}, {-S.psi, 1, S.phi}, {S.theta, -S.phi, 1}}));
}

TEST(Rotations, SecondOrderRotationsDoNotCommuteByMatrix1sPhiThetaTerms) {
  const hs::Rotations r = hs::rotations(2);
  const ex cp = 1 - pow(S.phi, 2) / 2, ct = 1 - pow(S.theta, 2) / 2;
  EXPECT_TRUE(SameMatrix(r.A1, {{1, 0, 0}, {0, cp, S.phi}, {0, -S.phi, cp}}));
  // The paper's (1), with cos a = 1 - a^2/2 and cos(phi) cos(theta) to second order.
  const ex cc = 1 - pow(S.phi, 2) / 2 - pow(S.theta, 2) / 2;
  EXPECT_TRUE(SameMatrix(r.A2A1, {{ct, S.phi * S.theta, -S.theta}, {0, cp, S.phi},
                                  {S.theta, -S.phi, cc}}));
  EXPECT_TRUE(SameMatrix(r.A1A2, {{ct, 0, -S.theta}, {S.phi * S.theta, cp, S.phi},
                                  {S.theta, -S.phi, cc}}));
  EXPECT_TRUE(SameMatrix(r.commutator, {{0, -S.phi * S.theta, 0},
                                        {S.phi * S.theta, 0, 0},
                                        {0, 0, 0}}));
}

TEST(Rotations, TruncationIsASeriesInTheOrderOfSmallness) {
  EXPECT_TRUE(Same(hs::truncate(sin(S.phi) * cos(S.theta), 2), S.phi));
  EXPECT_TRUE(Same(hs::truncate(cos(S.phi) * cos(S.theta), 2),
                   1 - pow(S.phi, 2) / 2 - pow(S.theta, 2) / 2));
  // omega0 is not small: it survives at every order.
  EXPECT_TRUE(Same(hs::truncate(S.omega0 * cos(S.phi) + S.omega0 * S.phi_t * S.theta, 1), S.omega0));
  EXPECT_THROW(hs::rotations(3), std::invalid_argument);
}

// ---- Sections 2 and 4: angular velocities -------------------------------------------------

TEST(AngularVelocity, FirstOrderIsThePapers2And3ForBothSequences) {
  for (hs::Sequence seq : hs::kSequences) {
    SCOPED_TRACE(std::string(hs::name(seq)));
    const hs::AngularVelocities w = hs::angular_velocities(seq, 1);
    EXPECT_TRUE(SameMatrix(w.frame_axes, vec(S.phi_t, S.theta_t, S.psi_t)));
    EXPECT_TRUE(SameMatrix(w.frame_fixed, vec(S.phi_t, S.theta_t, S.psi_t)));
    EXPECT_TRUE(SameMatrix(w.body_axes, vec(S.phi_t, S.theta_t, S.psi_t + S.omega0)));  // (2)
    EXPECT_TRUE(SameMatrix(w.body_fixed, vec(S.phi_t + S.omega0 * S.theta,               // (3)
                                             S.theta_t - S.omega0 * S.phi, S.psi_t + S.omega0)));
  }
}

TEST(AngularVelocity, SecondOrderDependsOnTheSequenceAsInSection4) {
  // phi then theta: w = phi' i + theta' j + (omega0 + phi' theta) k; theta then phi:
  // (omega0 - theta' phi) k (psi = 0 as in the paper).
  const hs::AngularVelocities w1 = hs::angular_velocities(hs::Sequence::PhiTheta, 2);
  const hs::AngularVelocities w2 = hs::angular_velocities(hs::Sequence::ThetaPhi, 2);
  EXPECT_TRUE(SameMatrix(without_psi(w1.body_axes),
                         vec(S.phi_t, S.theta_t, S.omega0 + S.phi_t * S.theta)));
  EXPECT_TRUE(SameMatrix(without_psi(w2.body_axes),
                         vec(S.phi_t, S.theta_t, S.omega0 - S.theta_t * S.phi)));
}

TEST(AngularVelocity, TruncatingTheRotationFirstLosesNothing) {
  // The library truncates R before forming R^T R'; the exact product truncated afterwards
  // (a genuine series in eps) must agree.
  const auto coords = hs::coordinates();
  for (hs::Sequence seq : hs::kSequences)
    for (int order : {1, 2}) {
      const matrix R = hs::frame_rotation(seq);
      const matrix exact = hs::vee(R.transpose().mul(hs::time_derivative(R, coords)));
      EXPECT_TRUE(SameMatrix(hs::truncate(exact, order),
                             hs::angular_velocities(seq, order).frame_axes));
    }
}

// ---- Sections 3, 5, 6: the routes ---------------------------------------------------------

TEST(Routes, EveryRouteButEulerBodyGivesModel4ForBothSequences) {
  const hs::PaperMatrices four = hs::paper_model(hs::PaperModel::Four);
  for (hs::Method method : {hs::Method::EulerMoving, hs::Method::EulerFixed, hs::Method::Lagrange})
    for (hs::Sequence seq : hs::kSequences)
      for (int order : {1, 2}) {
        if (method == hs::Method::Lagrange && order == 1) continue;  // see the next test
        SCOPED_TRACE(std::string(hs::name(method)) + " " + std::string(hs::name(seq)) + " " +
                     std::to_string(order));
        const hs::Derivation d = hs::derive(method, seq, order);
        EXPECT_TRUE(SameMatrix(d.M, {{S.A, 0}, {0, S.B}}));
        EXPECT_TRUE(SameMatrix(d.G, {{0, S.C * S.omega0}, {-S.C * S.omega0, 0}}));
        EXPECT_TRUE(SameMatrix(d.K, {{-kmgR, 0}, {0, -kmgR}}));
        EXPECT_TRUE(SameMatrix(d.G, four.G));
        EXPECT_EQ(hs::identify(d), hs::PaperModel::Four);
        // Its third equation is C psi'' = 0, which lets the paper set psi = 0.
        EXPECT_TRUE(Same(d.psi_equation, S.C * S.psi_tt));
      }
}

TEST(Routes, EulerBodyGivesModel5) {
  for (hs::Sequence seq : hs::kSequences)
    for (int order : {1, 2}) {
      const hs::Derivation d = hs::derive(hs::Method::EulerBody, seq, order);
      EXPECT_TRUE(SameMatrix(d.M, {{S.A, 0}, {0, S.B}}));
      EXPECT_TRUE(SameMatrix(d.G, {{0, (S.C - S.B) * S.omega0}, {-(S.C - S.A) * S.omega0, 0}}));
      EXPECT_TRUE(SameMatrix(d.K, {{-kmgR, 0}, {0, -kmgR}}));
      EXPECT_EQ(hs::identify(d), hs::PaperModel::Five);
      // The frame is the body: w1 = w = (phi', theta', omega0) to first order.
      if (order == 1) {
        EXPECT_TRUE(SameMatrix(d.omega, vec(S.phi_t, S.theta_t, S.omega0)));
      }
      EXPECT_TRUE(Same(d.psi_equation, 0));  // C d(omega0)/dt = 0
    }
}

TEST(Routes, LagrangeNeedsSecondOrderKinematics) {
  // Section 6: with first-order angular velocity T lacks the doubled product C omega0 phi' theta
  // and V = m g R is constant, so the gyroscopic and gravity terms are lost.
  for (hs::Sequence seq : hs::kSequences) {
    const hs::Derivation d = hs::derive(hs::Method::Lagrange, seq, 1);
    EXPECT_TRUE(SameMatrix(d.M, {{S.A, 0}, {0, S.B}}));
    EXPECT_TRUE(SameMatrix(d.G, matrix(2, 2)));
    EXPECT_TRUE(SameMatrix(d.K, matrix(2, 2)));
    EXPECT_TRUE(Same(d.V, kmgR));
    EXPECT_FALSE(hs::identify(d).has_value());
    EXPECT_TRUE(d.stability.never);  // q = q0 + q0' t: a Jordan block at lambda = 0
  }
}

TEST(Routes, LagrangeEnergiesAreThePapersToSecondOrder) {
  const ex T0 = (S.A * pow(S.phi_t, 2) + S.B * pow(S.theta_t, 2) + S.C * pow(S.omega0, 2)) / 2;
  const ex V = kmgR * (1 - pow(S.phi, 2) / 2 - pow(S.theta, 2) / 2);  // m g R cos(theta) cos(phi)
  const GiNaC::exmap no_psi = {{S.psi, 0}, {S.psi_t, 0}};
  const hs::Derivation d1 = hs::derive(hs::Method::Lagrange, hs::Sequence::PhiTheta, 2);
  const hs::Derivation d2 = hs::derive(hs::Method::Lagrange, hs::Sequence::ThetaPhi, 2);
  EXPECT_TRUE(Same(d1.T.subs(no_psi), T0 + S.C * S.omega0 * S.phi_t * S.theta));
  EXPECT_TRUE(Same(d2.T.subs(no_psi), T0 - S.C * S.omega0 * S.phi * S.theta_t));
  EXPECT_TRUE(Same(d1.V, V));
  EXPECT_TRUE(Same(d2.V, V));
}

TEST(Routes, MethodAndSequenceNamesRoundTrip) {
  for (hs::Method m : hs::kMethods) EXPECT_EQ(hs::method_from_name(hs::name(m)), m);
  for (hs::Sequence s : hs::kSequences) EXPECT_EQ(hs::sequence_from_name(hs::name(s)), s);
  EXPECT_FALSE(hs::method_from_name("euler").has_value());
  EXPECT_THROW(hs::derive(hs::Method::EulerMoving, hs::Sequence::PhiTheta, 0),
               std::invalid_argument);
}

TEST(Routes, CheckAgreesWithThePaperEverywhere) {
  const auto rows = hs::check();
  ASSERT_EQ(rows.size(), 16u);
  for (const auto& row : rows) {
    SCOPED_TRACE(std::string(hs::name(row.derivation.method)) + " order " +
                 std::to_string(row.derivation.order));
    EXPECT_TRUE(row.as_expected());
  }
}

// ---- Section 7: polynomial (8) and condition (9) ------------------------------------------

TEST(Stability, CharacteristicPolynomialIsAbTimesThePapers8) {
  const hs::Derivation d = hs::derive(hs::Method::EulerMoving, hs::Sequence::PhiTheta, 1);
  EXPECT_TRUE(Same(d.characteristic_polynomial, S.A * S.B * hs::paper_polynomial_8()));
  const hs::Derivation d5 = hs::derive(hs::Method::EulerBody, hs::Sequence::PhiTheta, 1);
  EXPECT_TRUE(Same(d5.characteristic_polynomial,
                   S.A * S.B * pow(S.lambda, 4) +
                       ((S.C - S.A) * (S.C - S.B) * pow(S.omega0, 2) - (S.A + S.B) * kmgR) *
                           pow(S.lambda, 2) +
                       pow(kmgR, 2)));
}

TEST(Stability, ConditionIsThePapers9Strictly) {
  for (hs::Method method : {hs::Method::EulerMoving, hs::Method::EulerFixed, hs::Method::Lagrange}) {
    const hs::Derivation d = hs::derive(method, hs::Sequence::ThetaPhi, 2);
    ASSERT_FALSE(d.stability.never);
    ASSERT_EQ(d.stability.all_of.size(), 1u);
    const hs::Inequality& in = d.stability.all_of[0];
    EXPECT_TRUE(Same(in.lhs, pow(S.omega0, 2)));
    EXPECT_TRUE(Same(in.rhs, hs::paper_bound_9()));
    EXPECT_TRUE(in.strict) << "erratum E2: the boundary of (9) is a Jordan block";
    // A = B: the classical sleeping-top criterion 4 A m g R / C^2.
    EXPECT_TRUE(Same(in.rhs.subs(S.B == S.A), 4 * S.A * kmgR / pow(S.C, 2)));
  }
}

TEST(Stability, Model5NeedsCAboveOrBelowBothAndItsOwnBound) {
  const hs::Derivation d = hs::derive(hs::Method::EulerBody, hs::Sequence::PhiTheta, 1);
  ASSERT_EQ(d.stability.all_of.size(), 2u);
  EXPECT_TRUE(Same(d.stability.all_of[0].lhs, (S.C - S.A) * (S.C - S.B)));
  EXPECT_TRUE(Same(d.stability.all_of[0].rhs, 0));
  const ex bound = d.stability.all_of[1].rhs;
  EXPECT_TRUE(Same(bound, pow(sqrt(S.A) + sqrt(S.B), 2) * kmgR / ((S.C - S.A) * (S.C - S.B))));
  // The paper's A = B form: 4 A m g R / (C - A)^2.
  EXPECT_TRUE(Same(bound.subs(S.B == S.A), 4 * S.A * kmgR / pow(S.C - S.A, 2)));
}

TEST(Stability, ConditionHandlesOtherBiquadraticSystems) {
  const GiNaC::possymbol k("k");
  const matrix I2 = {{1, 0}, {0, 1}};
  // A spring (K > 0, no gyroscope): stable always. An inverted one: never.
  const auto spring = hs::stability_condition(I2, matrix(2, 2), {{k, 0}, {0, k}});
  EXPECT_FALSE(spring.never);
  EXPECT_TRUE(spring.all_of.empty());
  const auto inverted = hs::stability_condition(I2, matrix(2, 2), {{-k, 0}, {0, -k}});
  EXPECT_TRUE(inverted.never);
  // A free gyroscope (K = 0): the zero roots are semisimple, the nutation pair needs a spin.
  const auto free = hs::stability_condition(I2, {{0, S.C * S.omega0}, {-S.C * S.omega0, 0}},
                                            matrix(2, 2));
  EXPECT_FALSE(free.never);
  ASSERT_EQ(free.all_of.size(), 1u);
  EXPECT_TRUE(Same(free.all_of[0].lhs, pow(S.omega0, 2)));
  EXPECT_TRUE(Same(free.all_of[0].rhs, 0));
  // Unequal springs, no gyroscope: stable; equal inverted springs under a gyroscope: the
  // paper's (9) with A = B = 1, C = 1, m g R = k.
  const auto unequal = hs::stability_condition(I2, matrix(2, 2), {{k, 0}, {0, 2 * k}});
  EXPECT_FALSE(unequal.never);
  EXPECT_TRUE(unequal.all_of.empty());
  // Odd powers of lambda (damping) are refused rather than misread.
  EXPECT_THROW(hs::stability_condition(I2, I2, I2), std::domain_error);
}

TEST(Stability, FactorRadicalsFindsTheSquare) {
  const ex e = S.A + S.B + 2 * sqrt(S.A) * sqrt(S.B);
  EXPECT_TRUE(Same(hs::factor_radicals(e), pow(sqrt(S.A) + sqrt(S.B), 2)));
  EXPECT_EQ(hs::to_string(hs::factor_radicals(e), hs::Style::Cas), "(sqrt(A)+sqrt(B))^2");
}

// ---- Against the numeric core -------------------------------------------------------------

namespace {

double value(const ex& e, const GiNaC::exmap& at) {
  const ex v = GiNaC::evalf(e.subs(at));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::runtime_error("not numeric");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

void expect_close(const matrix& symbolic, const Eigen::Matrix2d& numeric, const GiNaC::exmap& at,
                  const char* what) {
  const double scale = numeric.cwiseAbs().maxCoeff();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      EXPECT_LE(std::abs(value(symbolic(i, j), at) - numeric(i, j)), 1e-14 * scale)
          << what << "(" << i << ", " << j << ")";
}

}  // namespace

TEST(Numeric, SymbolicModelsEqualTheCoreLinearModels) {
  std::mt19937 rng(20070401);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const hs::Derivation four = hs::derive(hs::Method::Lagrange, hs::Sequence::PhiTheta, 2);
  const hs::Derivation five = hs::derive(hs::Method::EulerBody, hs::Sequence::ThetaPhi, 2);
  for (int trial = 0; trial < 20; ++trial) {
    heavytop::Body body;
    body.A = 0.5 + 1.5 * u(rng);
    body.B = 0.5 + 1.5 * u(rng);
    const double lo = std::abs(body.A - body.B), hi = body.A + body.B;  // triangle inequalities
    body.C = lo + (hi - lo) * (0.05 + 0.9 * u(rng));
    body.mass = 0.1 + 2.0 * u(rng);
    body.gravity = 9.81 * (0.5 + u(rng));
    body.length = 0.01 + 0.5 * u(rng);
    const double w0 = 0.1 + 50.0 * u(rng);
    const GiNaC::exmap at = {{S.A, body.A},         {S.B, body.B},
                             {S.C, body.C},         {S.m, body.mass},
                             {S.g, body.gravity},   {S.R, body.length},
                             {S.omega0, w0}};
    for (const auto& [kind, d] : {std::pair{heavytop::LinearModelKind::FirstOrder, &four},
                                  std::pair{heavytop::LinearModelKind::BodyFixed, &five}}) {
      SCOPED_TRACE(std::string(heavytop::name(kind)) + " trial " + std::to_string(trial));
      const heavytop::LinearModel model = heavytop::linear_model(kind, body);
      expect_close(d->M, model.M, at, "M");
      expect_close(d->G, model.G(w0), at, "G");
      expect_close(d->K, model.K(w0), at, "K");
      const auto p = heavytop::characteristic_polynomial(model, w0);
      const ex poly = d->characteristic_polynomial;
      EXPECT_NEAR(value(poly.coeff(S.lambda, 4), at), p.a4, 1e-14 * std::abs(p.a4));
      EXPECT_NEAR(value(poly.coeff(S.lambda, 2), at), p.a2,
                  1e-13 * (std::abs(p.a2) + std::abs(p.a4 * w0 * w0)));
      EXPECT_NEAR(value(poly.coeff(S.lambda, 0), at), p.a0, 1e-14 * std::abs(p.a0));
    }
    // The derived thresholds equal the core's closed forms of (9) and its analogue for (5).
    const double spin9 = std::sqrt(value(four.stability.all_of.at(0).rhs, at));
    EXPECT_NEAR(spin9, heavytop::paper_condition_9_spin(body), 1e-14 * spin9);
    const auto spin5 = heavytop::paper_body_fixed_spin(body);
    const bool gyro5 = value(five.stability.all_of.at(0).lhs, at) > 0.0;
    EXPECT_EQ(gyro5, spin5.has_value());
    if (spin5) {
      const double derived = std::sqrt(value(five.stability.all_of.at(1).rhs, at));
      EXPECT_NEAR(derived, *spin5, 1e-13 * derived);
    }
  }
}

// ---- Printing -----------------------------------------------------------------------------

TEST(Printing, CasStringsParseBackToTheSameExpression) {
  GiNaC::symtab table;
  for (const ex& x : GiNaC::lst{S.A, S.B, S.C, S.m, S.g, S.R, S.omega0, S.lambda, S.phi, S.theta,
                                S.psi})
    table[GiNaC::ex_to<GiNaC::symbol>(x).get_name()] = x;
  GiNaC::parser read(table, true);  // strict: every name must be one of ours
  for (hs::Method method : hs::kMethods) {
    const hs::Derivation d = hs::derive(method, hs::Sequence::PhiTheta, 2);
    for (const matrix* a : {&d.M, &d.G, &d.K})
      for (unsigned i = 0; i < 2; ++i)
        for (unsigned j = 0; j < 2; ++j) {
          const std::string s = hs::to_string(hs::tidy((*a)(i, j)), hs::Style::Cas);
          EXPECT_TRUE(Same(read(s), (*a)(i, j))) << s;
        }
    const std::string p = hs::to_string(hs::tidy(d.characteristic_polynomial), hs::Style::Cas);
    EXPECT_TRUE(Same(read(p), d.characteristic_polynomial)) << p;
    for (const auto& in : d.stability.all_of) {
      const std::string s = hs::to_string(in.rhs, hs::Style::Cas);
      EXPECT_TRUE(Same(read(s), in.rhs)) << s;
    }
  }
  const hs::Rotations r = hs::rotations(2);
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j) {
      const std::string s = hs::to_string(r.A1A2(i, j), hs::Style::Cas);
      EXPECT_TRUE(Same(read(s), r.A1A2(i, j))) << s;
    }
}

TEST(Printing, ReadsLikeThePaper) {
  const hs::Derivation d = hs::derive(hs::Method::EulerBody, hs::Sequence::PhiTheta, 1);
  EXPECT_EQ(hs::to_string(hs::tidy(d.G(0, 1)), hs::Style::Text), "(C - B) omega0");
  EXPECT_EQ(hs::to_string(hs::tidy(d.G(1, 0)), hs::Style::Text), "-(C - A) omega0");
  EXPECT_EQ(hs::to_string(hs::tidy(d.K(0, 0)), hs::Style::Cas), "-m*g*R");
  EXPECT_EQ(hs::to_string(hs::paper_bound_9(), hs::Style::Cas), "(sqrt(A)+sqrt(B))^2*m*g*R/C^2");
  EXPECT_EQ(hs::to_string(hs::paper_bound_9(), hs::Style::Latex),
            "\\frac{{\\left(\\sqrt{A} + \\sqrt{B}\\right)}^{2} m g R}{{C}^{2}}");
  const hs::Derivation d4 = hs::derive(hs::Method::EulerMoving, hs::Sequence::PhiTheta, 1);
  EXPECT_EQ(hs::to_string(hs::tidy(d4.characteristic_polynomial), hs::Style::Text),
            "A B lambda^4 + (C^2 omega0^2 - (A + B) m g R) lambda^2 + m^2 g^2 R^2");
}

// ---- Cost ---------------------------------------------------------------------------------

TEST(Cost, EveryRouteAndSequenceAtOrderTwoTakesUnderASecond) {
  const auto start = std::chrono::steady_clock::now();
  const auto rows = hs::check({2});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(rows.size(), 8u);
  EXPECT_LT(seconds, 1.0);
}

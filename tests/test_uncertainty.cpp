// Uncertain inputs (SPEC section 17): the law of propagation against the symmetric top's closed
// form 2 sqrt(A m g R) / C, the exact derivatives against Richardson-extrapolated differences,
// the linear result against the Monte Carlo where the model is nearly linear and their
// disagreement where it is not, p_stays_up against the normal law of the spin, reproducibility.
#include <cmath>
#include <string>

#include <boost/math/distributions/normal.hpp>
#include <gtest/gtest.h>

#include "heavytop/uncertainty.hpp"

namespace heavytop {
namespace {

Body toy() { return example_toy_top(); }
InitialState toy_motion() { return example_motion(); }

double closed_form(const Body& b) { return 2.0 * std::sqrt(b.A * b.mass * b.gravity * b.length) / b.C; }

double sensitivity(const UncertaintyAnalysis& u, const std::string& key) {
  for (const auto& [k, v] : u.sensitivity)
    if (k == key) return v;
  ADD_FAILURE() << "no sensitivity for " << key;
  return 0.0;
}

// The linearized model's critical spin of a symmetric body is the classical 2 sqrt(A m g R) / C.
TEST(Uncertainty, CriticalSpinIsTheClosedForm) {
  const Body b = toy();
  ASSERT_TRUE(linearized_critical_spin(b));
  EXPECT_NEAR(*linearized_critical_spin(b), closed_form(b), 1e-12 * closed_form(b));
}

// d w_c / d p of 2 sqrt(A m g R) / C: w_c / (2 A) (A and B together), w_c / (2 m), w_c / (2 g),
// w_c / (2 R), -w_c / C; 0 for the motion's keys. Exact, so to 1e-12.
TEST(Uncertainty, SymmetricSensitivitiesAreExact) {
  const Body b = toy();
  const double wc = closed_form(b);
  auto d = [&](const std::string& key, bool with_b = false) { return *critical_spin_derivative(b, key, with_b); };
  EXPECT_NEAR(d("A", true), wc / (2.0 * b.A), 1e-12 * wc / b.A);
  EXPECT_NEAR(d("mass"), wc / (2.0 * b.mass), 1e-12 * wc / b.mass);
  EXPECT_NEAR(d("gravity"), wc / (2.0 * b.gravity), 1e-12 * wc / b.gravity);
  EXPECT_NEAR(d("length"), wc / (2.0 * b.length), 1e-12 * wc / b.length);
  EXPECT_NEAR(d("C"), -wc / b.C, 1e-12 * wc / b.C);
  EXPECT_EQ(d("spin"), 0.0);
  EXPECT_EQ(d("theta0"), 0.0);
}

// An asymmetric body's critical spin has no simple closed form: its derivatives against central
// differences of the library's own critical spin, Richardson-extrapolated (error O(h^4)).
TEST(Uncertainty, AsymmetricDerivativesAgreeWithExtrapolatedDifferences) {
  Body b = toy();
  b.B = 1.3 * b.A;  // oblate enough to have a critical spin (C < A < B: a tall asymmetric top)
  ASSERT_TRUE(linearized_critical_spin(b));
  for (const std::string key : {"A", "B", "C", "mass", "length"}) {
    auto at = [&](double factor) {
      Body p = b;
      double* x = key == "A" ? &p.A : key == "B" ? &p.B : key == "C" ? &p.C : key == "mass" ? &p.mass : &p.length;
      const double x0 = *x;
      *x = x0 * factor;
      return *linearized_critical_spin(p);
    };
    double x0 = key == "A" ? b.A : key == "B" ? b.B : key == "C" ? b.C : key == "mass" ? b.mass : b.length;
    const double h = 1e-3;
    const double d1 = (at(1 + h) - at(1 - h)) / (2 * h * x0);
    const double d2 = (at(1 + 2 * h) - at(1 - 2 * h)) / (4 * h * x0);
    const double richardson = (4 * d1 - d2) / 3;
    const double exact = *critical_spin_derivative(b, key);
    EXPECT_NEAR(exact, richardson, 1e-6 * std::abs(exact)) << key;
  }
}

// JCGM 100 on the closed form: u(w_c) / w_c = sqrt((u_A / 2A)^2 + (u_m / 2m)^2 + (u_R / 2R)^2 +
// (u_C / C)^2), computed here by hand from the relative inputs.
TEST(Uncertainty, LinearLawMatchesTheClosedFormsRelativeUncertainty) {
  const Body b = toy();
  UncertaintyOptions o;
  o.inputs["A"] = {0.01, true};
  o.inputs["mass"] = {0.004, true};
  o.inputs["length"] = {0.5e-3, false};  // 0.5 mm absolute: 2 % of 25 mm
  o.inputs["C"] = {0.006, true};
  o.draws = 2000;
  const UncertaintyAnalysis u = analyse_uncertainty(b, toy_motion(), o);
  const double rel = std::sqrt(std::pow(0.01 / 2, 2) + std::pow(0.004 / 2, 2) +
                               std::pow(0.5e-3 / b.length / 2, 2) + std::pow(0.006, 2));
  ASSERT_TRUE(u.critical_linear);
  EXPECT_NEAR(u.critical_linear->standard_uncertainty, rel * closed_form(b), 1e-12 * closed_form(b));
  EXPECT_NEAR(u.critical_linear->hi - u.critical_linear->value, 1.96 * rel * closed_form(b), 1e-9 * closed_form(b));
  const double wc = closed_form(b);
  EXPECT_NEAR(sensitivity(u, "A"), wc / (2 * b.A), 1e-12 * wc / b.A);
  EXPECT_NEAR(sensitivity(u, "C"), -wc / b.C, 1e-12 * wc / b.C);
  // Small relative uncertainties: the model is linear over them, so JCGM 101 section 8 passes.
  EXPECT_EQ(u.method, UncertaintyMethod::Linear);
  ASSERT_TRUE(u.critical_monte_carlo);
  EXPECT_LE(u.d_low, u.tolerance);
  EXPECT_LE(u.d_high, u.tolerance);
  // Two significant digits of u: the Monte Carlo's agrees with the law's.
  EXPECT_NEAR(u.critical_monte_carlo->standard_uncertainty, u.critical_linear->standard_uncertainty,
              2 * u.tolerance);
  ASSERT_TRUE(u.critical_spin);
  EXPECT_NEAR(u.critical_spin->value, wc, 1e-12 * wc);  // linear reports the nominal value
}

// Large uncertainties: w_c ~ 1 / C is skewed (its mean above the nominal, its interval
// asymmetric), the linear interval fails the comparison and the Monte Carlo is reported.
TEST(Uncertainty, LargeUncertaintiesAreReportedByMonteCarlo) {
  const Body b = toy();
  UncertaintyOptions o;
  o.inputs["C"] = {0.2, true};
  o.draws = 200;
  // The skewed output's interval ends converge slowly (7.9 wants ~4 10^5 draws for two digits);
  // 4 10^4 decide the method already (d_high ~ 0.25 w_c is ~70 delta), and keep the test short.
  o.max_draws = 40000;
  const UncertaintyAnalysis u = analyse_uncertainty(b, toy_motion(), o);
  EXPECT_EQ(u.method, UncertaintyMethod::MonteCarlo);
  ASSERT_TRUE(u.critical_spin && u.critical_monte_carlo && u.critical_linear);
  EXPECT_GT(std::max(u.d_low, u.d_high), u.tolerance);
  // 1 / C for C ~ N(C0, (0.2 C0)^2) (draws with C <= 0 redrawn): its mean exceeds 1 / C0 (Jensen),
  // and the interval reaches further above than below.
  EXPECT_GT(u.critical_spin->value, closed_form(b) * 1.03);
  EXPECT_GT(u.critical_spin->hi - closed_form(b), closed_form(b) - u.critical_spin->lo);
  // The quantiles of 1 / C are 1 / the quantiles of C (a monotone map): w_c at C0 (1 -+ 1.96 0.2).
  EXPECT_NEAR(u.critical_spin->hi, closed_form(b) / (1 - 1.96 * 0.2), 0.02 * closed_form(b));
  EXPECT_NEAR(u.critical_spin->lo, closed_form(b) / (1 + 1.96 * 0.2), 0.02 * closed_form(b));
}

// A symmetric top stays up (proven, Lyapunov) exactly when |w| > w_c; with w ~ N(w0, u^2)
// and the body exact, P = Phi((w0 - w_c) / u) + Phi((-w_c - w0) / u).
TEST(Uncertainty, StaysUpProbabilityFollowsTheNormalLawOfTheSpin) {
  const Body b = toy();
  InitialState s = toy_motion();
  const double wc = closed_form(b);
  s.spin = wc + 4.0;
  UncertaintyOptions o;
  o.inputs["spin"] = {5.0, false};
  o.draws = 3000;
  AnswerOptions answer;
  answer.horizon = 5.0;  // the unproven draws fall within a second or two
  const UncertaintyAnalysis u = analyse_uncertainty(b, s, o, answer);
  const boost::math::normal n;
  const double p = boost::math::cdf(n, (s.spin - wc) / 5.0) + boost::math::cdf(n, (-wc - s.spin) / 5.0);
  EXPECT_GE(p, u.p_stays_up_lo);
  EXPECT_LE(p, u.p_stays_up_hi);
  EXPECT_LT(u.p_stays_up_hi - u.p_stays_up_lo, 0.05);  // the interval is informative
  EXPECT_EQ(u.draws, 3000);
  // Only the spin is uncertain: the critical spin is exact and the linear result holds.
  ASSERT_TRUE(u.critical_spin);
  EXPECT_EQ(u.method, UncertaintyMethod::Linear);
  EXPECT_EQ(u.critical_spin->standard_uncertainty, 0.0);
}

// Below the critical spin every draw falls: p_stays_up is 0 with Clopper-Pearson's closed form at
// k = 0, [0, 1 - (0.025)^(1/n)]; the fall times are those of the nonlinear runs, the nominal
// body's own fall (analyse_top, the answer of SPEC 14) inside their interval.
TEST(Uncertainty, BelowTheCriticalSpinEveryDrawFalls) {
  const Body b = toy();
  InitialState s = toy_motion();
  s.spin = 100.0;
  UncertaintyOptions o;
  o.inputs["spin"] = {0.02, true};
  o.draws = 200;
  AnswerOptions answer;
  answer.horizon = 20.0;
  const UncertaintyAnalysis u = analyse_uncertainty(b, s, o, answer);
  EXPECT_EQ(u.p_stays_up, 0.0);
  EXPECT_EQ(u.p_stays_up_lo, 0.0);
  EXPECT_NEAR(u.p_stays_up_hi, 1.0 - std::pow(0.025, 1.0 / 200.0), 1e-12);
  ASSERT_TRUE(u.falls_at);
  EXPECT_EQ(u.falls_at->fraction, 1.0);
  const TopAnalysis nominal = analyse_top(b, s, answer);
  ASSERT_TRUE(nominal.answer.falls_at);
  EXPECT_LT(u.falls_at->lo, *nominal.answer.falls_at);
  EXPECT_GT(u.falls_at->hi, *nominal.answer.falls_at);
  ASSERT_TRUE(u.max_tilt);
  EXPECT_NEAR(u.max_tilt->value, answer.max_tilt, 1e-9);  // every run stops at the fall's tilt
}

// A uniform input of half-width a has the standard uncertainty a / sqrt(3) (JCGM 100 4.3.7).
TEST(Uncertainty, UniformInputsEnterWithTheirStandardUncertainty) {
  const Body b = toy();
  UncertaintyOptions o;
  o.distribution = UncertaintyDistribution::Uniform;
  o.inputs["mass"] = {0.003, false};  // 3 g of 60 g
  o.draws = 100;
  const UncertaintyAnalysis u = analyse_uncertainty(b, toy_motion(), o);
  const double wc = closed_form(b);
  ASSERT_TRUE(u.critical_linear);
  EXPECT_NEAR(u.critical_linear->standard_uncertainty, wc / (2 * b.mass) * 0.003 / std::sqrt(3.0), 1e-12 * wc);
}

// The draws are a function of (seed, index): the same seed gives the same result on one thread
// or two; another seed other draws.
TEST(Uncertainty, ReproducibleAndIndependentOfThreads) {
  const Body b = toy();
  UncertaintyOptions o;
  o.inputs["A"] = {0.02, true};
  o.inputs["spin"] = {0.03, true};
  o.draws = 500;
  o.seed = 7;
  o.threads = 1;
  const UncertaintyAnalysis one = analyse_uncertainty(b, toy_motion(), o);
  o.threads = 2;
  const UncertaintyAnalysis two = analyse_uncertainty(b, toy_motion(), o);
  EXPECT_EQ(one.p_stays_up, two.p_stays_up);
  ASSERT_TRUE(one.max_tilt && two.max_tilt);
  EXPECT_EQ(one.max_tilt->value, two.max_tilt->value);
  EXPECT_EQ(one.max_tilt->hi, two.max_tilt->hi);
  EXPECT_EQ(one.critical_monte_carlo->value, two.critical_monte_carlo->value);
  EXPECT_EQ(one.critical_draws, two.critical_draws);
  o.seed = 8;
  const UncertaintyAnalysis other = analyse_uncertainty(b, toy_motion(), o);
  EXPECT_NE(one.max_tilt->value, other.max_tilt->value);
}

// SPEC 17's symmetric body: A's uncertainty moves B with it, unless B has its own; draws stay in
// the physical region (a 60 % uncertainty on C would give C <= 0 or C > A + B often).
TEST(Uncertainty, DrawsKeepSymmetryAndThePhysicalRegion) {
  const Body b = toy();
  UncertaintyOptions o;
  o.inputs["A"] = {0.05, true};
  o.inputs["C"] = {0.6, true};
  for (std::uint64_t i = 0; i < 200; ++i) {
    const auto [d, s] = uncertain_draw(b, toy_motion(), o, i);
    EXPECT_EQ(d.A, d.B);
    EXPECT_GT(d.C, 0.0);
    EXPECT_LE(d.C, d.A + d.B);
  }
  o.inputs["B"] = {0.05, true};
  const auto [d, s] = uncertain_draw(b, toy_motion(), o, 3);
  EXPECT_NE(d.A, d.B);
  // Uniform: within the half-width.
  UncertaintyOptions uni;
  uni.distribution = UncertaintyDistribution::Uniform;
  uni.inputs["mass"] = {0.001, false};
  for (std::uint64_t i = 0; i < 200; ++i) EXPECT_LE(std::abs(uncertain_draw(b, toy_motion(), uni, i).first.mass - b.mass), 0.001);
}

TEST(Uncertainty, BadOptionsAreRefusedByKey) {
  const Body b = toy();
  auto key_of = [&](const UncertaintyOptions& o) {
    try {
      validate(o, b, toy_motion());
    } catch (const InvalidInput& e) {
      return e.key();
    }
    return std::string("none");
  };
  UncertaintyOptions o;
  o.inputs["A"] = {-1.0, false};
  EXPECT_EQ(key_of(o), "uncertainty.A");
  o.inputs.clear();
  o.inputs["D"] = {1.0, false};
  EXPECT_EQ(key_of(o), "uncertainty.D");
  o.inputs.clear();
  o.draws = -1;
  EXPECT_EQ(key_of(o), "uncertainty.draws");
  o.draws = 0;
  o.inputs["phi0"] = {0.01, true};  // nominal 0: a percentage of nothing
  EXPECT_EQ(key_of(o), "uncertainty.phi0");
  o.inputs["phi0"] = {0.01, false};
  EXPECT_EQ(key_of(o), "none");
}

}  // namespace
}  // namespace heavytop

// The answer first (SPEC section 14) and the people's angles tilt and azimuth (SPEC section 2):
// the columns against k, the answer's branches against independent routes (the closed-form
// threshold, a separate nonlinear run by another integrator, lifetime()).
#include <cmath>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "heavytop/answer.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/simulate.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::axis_of;
using test_support::column;
using test_support::make_body;
using test_support::make_state;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Every model's trajectory carries tilt and azimuth right after SPEC's five columns, equal to
// acos(k_zeta) and atan2(k_eta, k_xi) (mod 2 pi) of its own axis, the azimuth continuous.
TEST(AxisDirection, EveryModelHasTiltAndAzimuthOfItsAxis) {
  const Body symmetric = example_toy_top();
  const Body asymmetric = make_body(1.0, 1.5, 2.0, 1.0);
  struct Case {
    Model model;
    const Body& body;
    InitialState state;
  };
  const Case cases[] = {
      {Model::FirstOrder, asymmetric, make_state(10.0, 0.02, 0.01)},
      {Model::BodyFixed, asymmetric, make_state(10.0, 0.02, 0.01)},
      {Model::Linearized, asymmetric, make_state(10.0, 0.02, 0.01)},
      {Model::Nonlinear, asymmetric, make_state(10.0, 0.3, 0.1, 0.5)},  // large tilt: acos is well-conditioned
      {Model::LagrangeExact, symmetric, make_state(200.0, 0.05)},
      {Model::Nonlinear, symmetric, make_state(200.0, 0.05)},
  };
  for (const Case& c : cases) {
    const Simulation sim = simulate(c.model, c.body, c.state, sample_times(20.0, 4001));
    ASSERT_TRUE(sim.summary.ok()) << sim.summary.message;
    const auto names = sim.trajectory.column_names();
    ASSERT_GE(names.size(), 7u);
    EXPECT_EQ(names[5], "tilt");
    EXPECT_EQ(names[6], "azimuth");
    const auto& tilt = column(sim.trajectory, "tilt");
    const auto& azimuth = column(sim.trajectory, "azimuth");
    double turned = 0.0;
    for (std::size_t i = 0; i < sim.trajectory.size(); ++i) {
      const Eigen::Vector3d k = axis_of(sim.trajectory.theta[i], sim.trajectory.phi[i]);
      EXPECT_NEAR(tilt[i], std::acos(k.z()), 1e-12) << name(c.model) << " at sample " << i;
      const double turns = (azimuth[i] - std::atan2(k.y(), k.x())) / kTwoPi;
      EXPECT_NEAR(turns, std::round(turns), 1e-9) << name(c.model) << " at sample " << i;
      if (i == 0) {
        EXPECT_NEAR(azimuth[0], std::atan2(k.y(), k.x()), 1e-15);
      } else {
        EXPECT_LT(std::abs(azimuth[i] - azimuth[i - 1]), std::numbers::pi) << name(c.model);
        turned = std::max(turned, std::abs(azimuth[i] - azimuth[0]));
      }
    }
    if (c.model == Model::LagrangeExact) {
      EXPECT_GT(turned, 2.0 * kTwoPi);  // it went round: unwrapped
    }
  }
}

// The continuous azimuth of a fast top grows at the gyroscopic precession rate m g R / (C w0)
// (the leading term of the slow precession; the next is O(A m g R / (C w0)^2) relative).
TEST(AxisDirection, AzimuthAdvancesAtThePrecessionRate) {
  const Body top = example_toy_top();
  const double spin = 400.0;
  const double precession = top.mgR() / (top.C * spin);
  const double horizon = 6.0 * kTwoPi / precession;  // six turns round the vertical
  const Simulation sim = simulate(Model::LagrangeExact, top, make_state(spin, 0.05), sample_times(horizon, 20001));
  ASSERT_TRUE(sim.summary.ok());
  const auto& azimuth = column(sim.trajectory, "azimuth");
  const double measured = (azimuth.back() - azimuth.front()) / horizon;
  const double next_order = top.A * top.mgR() / std::pow(top.C * spin, 2);
  RecordProperty("precession_relative_error", test_support::sci(measured / precession - 1.0));
  EXPECT_NEAR(measured / precession, 1.0, 4.0 * next_order);
}

// The azimuth keeps its value while the axis is exactly vertical, and starts at 0 there.
TEST(AxisDirection, VerticalAxisKeepsThePreviousAzimuth) {
  ContinuousAzimuth azimuth;
  EXPECT_EQ(azimuth(0.0, 0.0), 0.0);
  EXPECT_NEAR(azimuth(0.0, -0.1), std::numbers::pi / 2, 1e-15);  // k_eta = sin 0.1 > 0, k_xi = 0
  EXPECT_NEAR(azimuth(0.0, 0.0), std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(azimuth(-0.1, 0.0), std::numbers::pi, 1e-15);
  EXPECT_NEAR(azimuth(-0.1, 0.1), std::numbers::pi + std::atan2(std::sin(0.1), std::sin(0.1) * std::cos(0.1)),
              1e-12);  // past pi: continued, not wrapped to -pi
}

// Proven stable: the toy top above the sleeping-top threshold 2 sqrt(A m g R) / C.
TEST(Answer, ProvenStableWithTheClosedFormThreshold) {
  const Body top = example_toy_top();
  const TopAnalysis a = analyse_top(top, example_motion());
  EXPECT_EQ(a.answer.verdict, AnswerVerdict::StaysUp);
  EXPECT_TRUE(a.answer.proven);
  ASSERT_TRUE(a.answer.max_tilt && a.wander.max_tilt);
  EXPECT_EQ(*a.answer.max_tilt, *a.wander.max_tilt);
  EXPECT_GT(*a.answer.max_tilt, 0.05);  // it nutates out from its start
  ASSERT_TRUE(a.answer.min_spin);
  EXPECT_NEAR(*a.answer.min_spin, 2.0 * std::sqrt(top.A * top.mgR()) / top.C, 1e-12 * *a.answer.min_spin);
  EXPECT_TRUE(a.answer.falls_below_min_spin);  // below it the linearisation grows
  EXPECT_FALSE(a.answer.falls_at);
  EXPECT_FALSE(a.answer.lifetime);
}

// Falls: below the threshold; the fall time agrees with a separate run by dopri5 sampled finely.
TEST(Answer, FallsAtTheTimeAnotherIntegratorFinds) {
  const Body top = example_toy_top();
  const InitialState start = make_state(100.0, 0.05);
  const TopAnalysis a = analyse_top(top, start);
  ASSERT_EQ(a.answer.verdict, AnswerVerdict::Falls);
  EXPECT_TRUE(a.answer.proven);
  ASSERT_TRUE(a.answer.falls_at);
  SimulateOptions dopri5;
  dopri5.integrator = Integrator::Adaptive;
  dopri5.adaptive.rtol = dopri5.adaptive.atol = 1e-11;
  const double dt = 1e-5;
  const double end = 1.5 * *a.answer.falls_at;
  const Simulation sim = simulate(Model::Nonlinear, top, start, sample_times(end, std::size_t(end / dt) + 1), dopri5);
  ASSERT_TRUE(sim.summary.ok());
  const auto& tilt = column(sim.trajectory, "tilt");
  std::size_t first = 0;
  while (first < tilt.size() && tilt[first] <= 1.0) ++first;
  ASSERT_LT(first, tilt.size());
  EXPECT_LE(sim.trajectory.t[first - 1], *a.answer.falls_at + 1e-7);
  EXPECT_GE(sim.trajectory.t[first], *a.answer.falls_at - 1e-7);
  ASSERT_TRUE(a.answer.fall_spin);
  EXPECT_NEAR(*a.answer.fall_spin, 100.0, 1e-9);  // A = B: w3 is conserved
}

// Damped: lifetime() decides, falls_at = lifetime = its fall time.
TEST(Answer, DampedBodyFallsAtItsLifetime) {
  Body top = example_toy_top();
  top.damping.axial = 2e-6;
  const InitialState start = example_motion();
  const TopAnalysis a = analyse_top(top, start);
  const Lifetime life = lifetime(top, start);
  ASSERT_TRUE(life.fall_time);
  EXPECT_EQ(a.answer.verdict, AnswerVerdict::Falls);
  EXPECT_TRUE(a.answer.proven);
  ASSERT_TRUE(a.answer.falls_at && a.answer.lifetime);
  EXPECT_EQ(*a.answer.falls_at, *life.fall_time);
  EXPECT_EQ(*a.answer.lifetime, *life.fall_time);
  EXPECT_EQ(a.answer.horizon, life.horizon);
  // The spin law's closed form: the fall comes after the spin passes the critical spin.
  ASSERT_TRUE(life.time_to_critical);
  EXPECT_GT(*a.answer.falls_at, *life.time_to_critical);
}

// A damped top started exactly upright never tilts in the computation, but once its spin has
// decayed below the critical spin it is an unstable equilibrium (issue 45): the answer says when,
// at the closed form of the spin law C w' = -d_a w - tau0: t = (C / d_a) ln((w0 + tau0/d_a) /
// (wc + tau0/d_a)).
TEST(Answer, ADampedTopExactlyUprightIsBalancedOnlyUntilItsCriticalSpin) {
  Body top = example_toy_top();
  top.damping.axial = 2e-7;
  top.damping.friction = 1e-5;
  const double w0 = 1500.0 * 3.141592653589793 / 30.0;
  const Answer a = analyse_top(top, make_state(w0, 0.0)).answer;
  EXPECT_EQ(a.why, AnswerCase::BalancedDamped);
  EXPECT_EQ(a.verdict, AnswerVerdict::StaysUpForHorizon);
  EXPECT_FALSE(a.proven);
  const double wc = 2.0 * std::sqrt(top.A * top.mass * top.gravity * top.length) / top.C;
  const double k = top.damping.friction / top.damping.axial;
  ASSERT_TRUE(a.time_to_critical);
  EXPECT_NEAR(*a.time_to_critical, top.C / top.damping.axial * std::log((w0 + k) / (wc + k)), 1e-9);
  // A start off the vertical is the ordinary damped answer: it falls.
  EXPECT_EQ(analyse_top(top, make_state(w0, 1e-3)).answer.why, AnswerCase::FallsDamped);
}

// The analysis keeps the damped body's lifetime() run (issue 41: the report reuses it): the run
// a direct call with the same options makes, to the step; none for a conservative body.
TEST(Answer, DampedAnalysisCarriesTheLifetimeItRan) {
  Body top = example_toy_top();
  top.damping.axial = 2e-6;
  const InitialState start = example_motion();
  AnswerOptions tilted;
  tilted.max_tilt = 0.7;
  tilted.damped_horizon = 40.0;
  LifetimeOptions same;
  same.max_tilt = 0.7;
  same.horizon = 40.0;
  for (const auto& [answer_options, life_options] : {std::pair{AnswerOptions{}, LifetimeOptions{}}, std::pair{tilted, same}}) {
    const TopAnalysis a = analyse_top(top, start, answer_options);
    const Lifetime direct = lifetime(top, start, life_options);
    ASSERT_TRUE(a.lifetime && direct.fall_time && a.lifetime->fall_time);
    EXPECT_EQ(*a.lifetime->fall_time, *direct.fall_time);
    EXPECT_EQ(*a.lifetime->fall_spin, *direct.fall_spin);
    EXPECT_EQ(a.lifetime->largest_tilt, direct.largest_tilt);
    EXPECT_EQ(a.lifetime->horizon, direct.horizon);
    EXPECT_EQ(a.lifetime->summary.steps, direct.summary.steps);
    EXPECT_EQ(a.lifetime->summary.rhs_evaluations, direct.summary.rhs_evaluations);
    EXPECT_EQ(a.lifetime->time_to_critical, direct.time_to_critical);
    EXPECT_EQ(*a.answer.lifetime, *direct.fall_time);
  }
  EXPECT_EQ(analyse_top(top, start, tilted).lifetime->horizon, 40.0);
  EXPECT_FALSE(analyse_top(example_toy_top(), start).lifetime);
  AnswerOptions few_steps;  // a stopped run: no lifetime kept
  few_steps.integrator.max_steps = 200;
  EXPECT_FALSE(analyse_top(top, make_state(100.0, 0.05), few_steps).lifetime);
}

// A hanging body is stable at every spin: min_spin 0.
TEST(Answer, HangingBodyIsProvenStableAtEverySpin) {
  const Body hanging = make_body(1.0, 1.0, 0.5, -1.0);
  const TopAnalysis a = analyse_top(hanging, make_state(0.0, 0.2));
  EXPECT_EQ(a.answer.verdict, AnswerVerdict::StaysUp);
  EXPECT_TRUE(a.answer.hanging);
  ASSERT_TRUE(a.answer.min_spin);
  EXPECT_EQ(*a.answer.min_spin, 0.0);
  ASSERT_TRUE(a.answer.max_tilt);
  EXPECT_NEAR(*a.answer.max_tilt, 0.2, 1e-12);  // a pendulum released at rest swings back to its start
}

// An index-2 body held up by its gyroscopic forces alone (undecided without a KAM proof) never
// "falls" from a small tilt; the answer is proven only if the Lyapunov verdict proves it.
TEST(Answer, GyroscopicallyStableBodyDoesNotFall) {
  const Body asym = make_body(1.0, 1.2, 0.7, -1.0);
  const TopAnalysis a = analyse_top(asym, make_state(2.0, 1e-3));
  EXPECT_EQ(a.lyapunov.verdict.energy_index, 2);
  EXPECT_NE(a.answer.verdict, AnswerVerdict::Falls);
  EXPECT_EQ(a.answer.proven, a.lyapunov.verdict.verdict == LyapunovVerdictKind::Stable);
  ASSERT_TRUE(a.answer.max_tilt);
  EXPECT_LT(*a.answer.max_tilt, 0.05);
}

// Exactly upright at an unstable spin: the computation stays balanced, the answer is not proven.
TEST(Answer, BalancedOnAnUnstableUprightIsNotProven) {
  const TopAnalysis a = analyse_top(example_toy_top(), make_state(100.0, 0.0));
  EXPECT_EQ(a.answer.verdict, AnswerVerdict::StaysUpForHorizon);
  EXPECT_EQ(a.answer.why, AnswerCase::BalancedUnstable);
  EXPECT_FALSE(a.answer.proven);
  EXPECT_EQ(a.answer.max_tilt.value_or(-1.0), 0.0);
}

TEST(Answer, OptionsAreChecked) {
  AnswerOptions bad;
  bad.max_tilt = 4.0;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_EQ(why.substr(0, 8), "max_tilt");
  EXPECT_THROW(analyse_top(example_toy_top(), example_motion(), bad), InvalidInput);
}

InvalidInput refusal(const Body& body, const InitialState& start, const AnswerOptions& options) {
  try {
    analyse_top(body, start, options);
  } catch (const InvalidInput& e) {
    return e;
  }
  ADD_FAILURE() << "not refused";
  return InvalidInput("", "");
}

// Each horizon is refused under its own key (issue 46: the damped run's was named "horizon",
// the conservative run's), and one a double cannot resolve before anything runs.
TEST(Answer, EachHorizonIsRefusedUnderItsOwnKey) {
  Body damped = example_toy_top();
  damped.damping.axial = 2e-7;
  AnswerOptions options;
  options.damped_horizon = -1.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_EQ(why.substr(0, 17), "lifetime_horizon:");
  EXPECT_EQ(refusal(damped, example_motion(), options).key(), "lifetime_horizon");
  options.damped_horizon = 1e300;  // valid as a number, beyond what a double resolves at this spin
  EXPECT_EQ(refusal(damped, example_motion(), options).key(), "lifetime_horizon");
  AnswerOptions conservative;
  conservative.horizon = 1e300;
  EXPECT_EQ(refusal(example_toy_top(), make_state(100.0, 0.05), conservative).key(), "horizon");
}

// A run that cannot go on states how far it got: the answer's horizon is that time, not the one
// asked (issue 46: "stays up for the horizon" with horizon 1e300 after following 3e4 s).
TEST(Answer, StoppedRunStatesTheHorizonItCovered) {
  AnswerOptions few_steps;
  few_steps.integrator.max_steps = 200;
  Body damped = example_toy_top();
  damped.damping.axial = 2e-7;
  for (const Body& body : {example_toy_top(), damped}) {
    const TopAnalysis a = analyse_top(body, make_state(100.0, 0.05), few_steps);
    EXPECT_EQ(a.answer.why, AnswerCase::RunStopped);
    EXPECT_EQ(a.answer.verdict, AnswerVerdict::StaysUpForHorizon);
    EXPECT_FALSE(a.answer.proven);
    EXPECT_FALSE(a.answer.max_tilt);
    // 200 steps of a spin of 100 rad/s at rtol 1e-10 cover a fraction of a second, all of it.
    EXPECT_GT(a.answer.horizon, 0.0);
    EXPECT_LT(a.answer.horizon, 1.0);
    EXPECT_NE(a.answer.stopped.find("max_steps = 200"), std::string::npos) << a.answer.stopped;
    // The time stated is the run's own: the same run to just before it covers it without failing.
    AnswerOptions up_to = few_steps;
    up_to.horizon = 0.9 * a.answer.horizon;
    up_to.damped_horizon = up_to.horizon;
    EXPECT_NE(analyse_top(body, make_state(100.0, 0.05), up_to).answer.why, AnswerCase::RunStopped);
  }
}

// A start at or beyond the limit given: a fall is a tilt past halfway from the start to upside
// down (fall_tilt), in the answer and lifetime() alike, never "falls at t = 0".
TEST(Answer, StartBeyondTheLimitFallsOnlyPastHalfwayToUpsideDown) {
  EXPECT_EQ(fall_tilt(0.5, 1.0), 1.0);
  EXPECT_EQ(fall_tilt(1.0, 1.0), 0.5 * (1.0 + std::numbers::pi));
  AnswerOptions tight;
  tight.max_tilt = 0.1;
  const TopAnalysis proven = analyse_top(example_toy_top(), make_state(200.0, 0.5), tight);
  EXPECT_EQ(proven.answer.fall_threshold, 0.5 * (0.5 + std::numbers::pi));
  EXPECT_EQ(proven.answer.limit_given, 0.1);
  EXPECT_EQ(proven.answer.verdict, AnswerVerdict::StaysUp);  // its closed-form wander stays below 1.82 rad
  // Woodhouse's top set off at 60 degrees precessing below its critical spin (202 rad/s): it does
  // not fall, and its tilt stays about its start (the review's run said "falls at t = 0").
  Body woodhouse = make_body(1e-4, 1e-4, 1.2e-5, 0.06 * 9.81 * 0.025);
  InitialState start = make_state(175.089, 1.0472);
  start.phi_rate0 = -12.1305;
  const TopAnalysis w = analyse_top(woodhouse, start);
  EXPECT_EQ(w.lyapunov.verdict.verdict, LyapunovVerdictKind::Unstable);
  EXPECT_EQ(w.answer.verdict, AnswerVerdict::StaysUpForHorizon);
  ASSERT_TRUE(w.answer.max_tilt);
  EXPECT_LT(*w.answer.max_tilt, w.answer.fall_threshold);
  // Upside down: the proof's bound (the wander reaches pi) proves nothing; not "stays up", proven.
  const TopAnalysis down = analyse_top(example_toy_top(), make_state(200.0, std::numbers::pi));
  EXPECT_FALSE(down.answer.proven);
  EXPECT_EQ(down.answer.fall_threshold, std::numbers::pi);
  // lifetime(): a damped top started at 1.2 rad with the default 1 rad does not fall at t = 0; it
  // falls where a separate run's tilt passes (1.2 + pi) / 2.
  Body damped = example_toy_top();
  damped.damping.axial = 2e-6;
  const InitialState tilted = make_state(200.0, 1.2);
  const Lifetime life = lifetime(damped, tilted);
  EXPECT_EQ(life.max_tilt, 0.5 * (1.2 + std::numbers::pi));
  EXPECT_EQ(life.limit_given, 1.0);
  ASSERT_TRUE(life.fall_time);
  const TiltExtremes separate = tilt_extremes(Integrator::Taylor, damped, tilted, 100.0, life.max_tilt, Tolerances{});
  EXPECT_GT(*life.fall_time, 0.5);
  ASSERT_TRUE(separate.exceeded);
  EXPECT_NEAR(*life.fall_time, separate.t_end, 1e-6 * separate.t_end);
}

// Without gravity every spin > 0 is stable but rest is not (issue 46: "stable at every spin"
// while the verdict at spin 0 was unstable): the answer keeps the open end.
TEST(Answer, WithoutGravityRestIsNotStable) {
  Body free = example_toy_top();
  free.gravity = 0.0;
  const TopAnalysis a = analyse_top(free, make_state(0.0, 0.05));
  EXPECT_EQ(a.lyapunov.verdict.verdict, LyapunovVerdictKind::Unstable);
  ASSERT_TRUE(a.answer.min_spin);
  EXPECT_EQ(*a.answer.min_spin, 0.0);
  EXPECT_FALSE(a.answer.min_spin_included);
  EXPECT_TRUE(analyse_top(make_body(1.0, 1.0, 0.5, -1.0), make_state(0.0, 0.2)).answer.min_spin_included);
}

// A key or rule holding a newline or an escape sequence still makes a one-line message.
TEST(Answer, RefusalsAreOneLine) {
  const InvalidInput e("body.part[0].na\nme\x1b[31m", "unknown key 'a\nb'");
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  EXPECT_EQ(std::string(e.what()).find('\x1b'), std::string::npos);
  EXPECT_EQ(e.key(), "body.part[0].na\\nme\\x1b[31m");
}

}  // namespace
}  // namespace heavytop

// The answer's words (io/src/answer_words.cpp) say what the computation found and nothing more:
// a damped run that stopped decides nothing, and "slows its spin" only where the spin slowed.
#include <string>

#include <gtest/gtest.h>

#include "heavytop/answer.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lifetime.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

bool says(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Transverse damping alone (Kelvin-Tait-Chetaev) makes the fast toy top fall while w.k keeps its
// value, within the lifetime run's tolerance; axial damping slows the spin before the fall.
TEST(AnswerWords, SlowsTheSpinOnlyWhereTheSpinSlowed) {
  Body top = example_toy_top();
  InitialState start = example_motion();
  start.spin = 300.0;
  top.damping.transverse = 1e-2;
  const TopAnalysis transverse = analyse_top(top, start);
  ASSERT_EQ(transverse.answer.verdict, AnswerVerdict::Falls);
  ASSERT_TRUE(transverse.answer.fall_spin);
  EXPECT_NEAR(*transverse.answer.fall_spin, 300.0, 1e-6 * 300.0);
  EXPECT_FALSE(says(io::answer_text(transverse.answer), "slows"));

  top.damping.transverse = 0.0;
  top.damping.axial = 2e-6;
  const TopAnalysis axial = analyse_top(top, start);
  ASSERT_EQ(axial.answer.verdict, AnswerVerdict::Falls);
  ASSERT_TRUE(axial.answer.fall_spin);
  EXPECT_LT(*axial.answer.fall_spin, 0.9 * 300.0);
  EXPECT_TRUE(says(io::answer_text(axial.answer), "slows its spin"));
}

// A damped run that stops (here: the integrator's step limit) decides nothing: the words say so,
// give the run's reason and the conservative body's critical spin, and claim no horizon.
TEST(AnswerWords, AStoppedDampedRunDecidesNothing) {
  Answer a;
  a.verdict = AnswerVerdict::StaysUpForHorizon;
  a.why = AnswerCase::RunStopped;
  a.damped = true;
  a.spin = 300.0;
  a.min_spin = 133.344;
  a.falls_below_min_spin = true;
  a.stopped = "nonlinear: more than max_steps = 100 integration steps before t = 0.5 s";
  const std::string text = io::answer_text(a);
  EXPECT_EQ(io::answer_headline(a), "Not decided.");
  EXPECT_TRUE(says(text, a.stopped));
  EXPECT_TRUE(says(text, "Without damping it needs at least 133.3 rad/s"));
  EXPECT_FALSE(says(text, "Stays up"));
  EXPECT_FALSE(says(text, "within the"));  // no "did not tilt past ... within the 0 s computed"
  EXPECT_FALSE(says(text, "No spin holds it up"));
}

}  // namespace
}  // namespace heavytop

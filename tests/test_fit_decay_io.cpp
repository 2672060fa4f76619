// The io side of fit-decay: the decay CSV (every rule, with its line number) and the [damping]
// section the text prints, which pasted into a configuration is read back by the io layer
// with the fitted values exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "heavytop/body.hpp"
#include "heavytop/damping.hpp"
#include "heavytop/fit_decay.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/decay_data.hpp"
#include "heavytop/io/formats.hpp"

namespace heavytop {
namespace {

std::string refusal(const std::string& text, std::size_t min_points = 3) {
  try {
    io::parse_decay_csv(text, min_points);
  } catch (const InvalidInput& e) {
    return e.key() + ": " + e.rule();
  }
  return "accepted";
}

TEST(DecayCsv, ReadsCommentsBlankLinesCrlfAndEitherUnit) {
  const DecayData d = io::parse_decay_csv("\xEF\xBB\xBF# a stopwatch\r\nt, spin\r\n\r\n0,200\r\n# halfway\n2.5,+190.5\n5,181\n", 3);
  ASSERT_EQ(d.t.size(), 3u);
  EXPECT_EQ(d.t[1], 2.5);
  EXPECT_EQ(d.spin[1], 190.5);
  // rpm, columns swapped: 60 rpm is 2 pi rad/s.
  const DecayData r = io::parse_decay_csv("spin_rpm,t\n60,0\n30,1\n0,2\n", 3);
  EXPECT_DOUBLE_EQ(r.spin[0], 2.0 * std::numbers::pi);
  EXPECT_DOUBLE_EQ(r.spin[1], std::numbers::pi);
  EXPECT_EQ(r.t[2], 2.0);
}

TEST(DecayCsv, RefusesEveryBadLineNamingIt) {
  const std::string head = "# generated\nt,spin\n0,200\n1,190\n";
  EXPECT_EQ(refusal(head + "2,180\n"), "accepted");
  EXPECT_EQ(refusal(head + "2,abc\n"), "data: line 5: spin 'abc' is not a number");
  EXPECT_EQ(refusal(head + "2,180x\n"), "data: line 5: spin '180x' is not a number");
  EXPECT_EQ(refusal(head + "2,nan\n"), "data: line 5: spin must be a finite number");
  EXPECT_EQ(refusal(head + "inf,1\n"), "data: line 5: t must be a finite number");
  EXPECT_EQ(refusal(head + "0.5,180\n"), "data: line 5: t = 0.5 is before the previous line's 1 (t must not decrease)");
  EXPECT_EQ(refusal(head + "2,-1\n"), "data: line 5: the spin must be >= 0 (its magnitude)");
  EXPECT_EQ(refusal(head + "2\n"), "data: line 5: 1 fields, the header has 2");
  EXPECT_EQ(refusal(head + "2,180,3\n"), "data: line 5: 3 fields, the header has 2");
  EXPECT_EQ(refusal(head + "2,\n"), "data: line 5: spin '' is not a number");
  EXPECT_EQ(refusal("t,spin\n-1,200\n0,1\n1,0\n"), "data: line 2: t must be >= 0 (s from the start)");
  EXPECT_EQ(refusal("\n#\nt,omega\n"), "data: line 3: unknown column 'omega' (the header names t and spin (rad/s) or "
                                       "spin_rpm (rpm))");
  EXPECT_EQ(refusal("t,spin,spin_rpm\n"), "data: line 1: give one of spin and spin_rpm, once");
  EXPECT_EQ(refusal("t\n0\n"), "data: line 1: the header must name the columns t and spin (rad/s) or spin_rpm "
                               "(rpm), e.g. 't,spin'");
  EXPECT_EQ(refusal("0,200\n1,190\n"), "data: line 1: unknown column '0' (the header names t and spin (rad/s) or "
                                       "spin_rpm (rpm))");
  EXPECT_EQ(refusal("# nothing\n"), "data: no header line (t,spin or t,spin_rpm) and no data");
  EXPECT_EQ(refusal(head, 4), "data: 2 points; at least 4 are needed");
  EXPECT_EQ(refusal("t,spin\n0,1\x01\n"), "data: line 2: spin '1\\x01' is not a number");
}

TEST(DecayCsv, TheFilesSizeIsCapped) {
  try {
    io::read_decay_csv("/dev/zero", "--data", 4);
    FAIL() << "read /dev/zero";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "--data");
    EXPECT_NE(e.rule().find("is larger than"), std::string::npos) << e.rule();
  }
}

// The [damping] section of the text, pasted under a [body], is read back by the io layer with
// the fitted values to the last bit, and the configured transverse damping kept.
TEST(FitDecayText, TheDampingSectionPastesBackExactly) {
  const Body top = example_toy_top();
  const SpinDecayLaw law{top.C, 2e-7, 1e-5};
  DecayData d;
  for (int i = 0; i < 50; ++i) {
    d.t.push_back(2.0 * i);
    d.spin.push_back(law.spin(200.0, d.t.back()) * (1.0 + 1e-3 * std::sin(7.0 * i)));  // not exactly the law
  }
  const DecayFit fit = fit_spin_decay(top, d);
  ASSERT_TRUE(fit.summary.converged);
  Damping configured;
  configured.transverse = 3.25e-6;
  const std::string text = io::fit_decay_text(fit, configured);
  const auto at = text.find("[damping]\n");
  ASSERT_NE(at, std::string::npos) << text;
  const std::string config = "[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n" +
                             text.substr(at);
  const io::Configuration parsed = io::parse_configuration(config, "pasted.toml", "--config");
  EXPECT_EQ(parsed.body.damping.axial, fit.axial.value);
  EXPECT_EQ(parsed.body.damping.friction, fit.friction.value);
  EXPECT_EQ(parsed.body.damping.transverse, 3.25e-6);
  EXPECT_TRUE(parsed.given.count("damping.axial"));
  validate(parsed.body);  // the pasted body is a valid one
  EXPECT_NE(text.find("Assumed: the law C w' = -d_a w - tau0 sign(w) of a free spin"), std::string::npos);

  const std::string json = io::fit_decay_json(fit);
  for (const char* key : {"\"axial\"", "\"friction\"", "\"spin0\"", "\"uncertainty\"", "\"rms_residual\"",
                          "\"points\": 50", "\"converged\": true"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace heavytop

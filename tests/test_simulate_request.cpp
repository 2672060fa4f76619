// resolve() (simulate.hpp): each rule of what applies to which model, a request that breaks it
// refused naming the core's key, in the documented order; what a valid request resolves to;
// and spelled(), the adapters' one step (the command line's flags, Python's keywords).

#include "heavytop/simulate.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "heavytop/body.hpp"

namespace heavytop {
namespace {

// The refusal of `request` (for `body`) as "key: rule", or "" if it resolves.
std::string refusal(const SimulateRequest& request, const Body& body = example_toy_top()) {
  try {
    resolve(request, body);
  } catch (const InvalidInput& e) {
    return e.key() + ": " + e.rule();
  }
  return "";
}

SimulateRequest asking(std::string model) {
  SimulateRequest r;
  r.model = Requested<std::string>::of(model);
  return r;
}

TEST(SimulateRequest, EachRuleRefusesNamingItsKey) {
  SimulateRequest r = asking("spinning");
  EXPECT_EQ(refusal(r), "model: must be one of " + model_names(", "));

  Body asymmetric = example_toy_top();
  asymmetric.B = 1.5 * asymmetric.A;
  EXPECT_EQ(refusal(asking("lagrange-exact"), asymmetric).substr(0, 8), "body.B: ");

  r = asking("linearized");
  r.method = Requested<std::string>::of("guess");
  EXPECT_EQ(refusal(r), "method: must be analytic or numeric");

  r = asking("nonlinear");
  r.t_end = 0.0;
  EXPECT_EQ(refusal(r), "t_end: must be finite and > 0");
  r.t_end = std::numeric_limits<double>::infinity();
  EXPECT_EQ(refusal(r), "t_end: must be finite and > 0");

  r = asking("nonlinear");
  r.samples = 1;
  EXPECT_EQ(refusal(r), "samples: must be an integer in [2, 100000000]");
  r.samples = 100'000'001;
  EXPECT_EQ(refusal(r), "samples: must be an integer in [2, 100000000]");

  r = asking("nonlinear");
  r.method = Requested<std::string>::of("numeric");
  EXPECT_EQ(refusal(r), "method: applies to the linear models only");

  r = asking("nonlinear");
  r.integrator = Requested<std::string>::of("leapfrog");
  EXPECT_EQ(refusal(r), "integrator: must be {integrators}");

  r = asking("first-order");
  r.integrator = Requested<std::string>::of("taylor");
  EXPECT_EQ(refusal(r), "integrator: applies to {model=nonlinear} only");
  r = asking("body-fixed");
  r.step = Requested<double>::of(1e-3);
  EXPECT_EQ(refusal(r), "step: applies to {model=nonlinear} only");
  r = asking("linearized");
  r.order = Requested<int>::of(4);
  EXPECT_EQ(refusal(r), "order: applies to {model=nonlinear} only");
  r = asking("lagrange-exact");
  r.max_steps = Requested<long long>::of(10);
  EXPECT_EQ(refusal(r), "max_steps: applies to {model=nonlinear} only");
  r = asking("lagrange-exact");
  r.rtol = Requested<double>::of(1e-9);
  EXPECT_EQ(refusal(r), "rtol: applies to {model=nonlinear} only (the other models are closed forms or a matrix "
                        "exponential, exact to rounding)");
  r = asking("first-order");
  r.atol = Requested<double>::of(1e-9);
  EXPECT_EQ(refusal(r), "atol: applies to {model=nonlinear} only (the other models are closed forms or a matrix "
                        "exponential, exact to rounding)");

  r = asking("nonlinear");
  r.step = Requested<double>::of(1e-3);
  EXPECT_EQ(refusal(r), "step: applies to {integrator=splitting} only");
  r.step = {};
  r.integrator = Requested<std::string>::of("dopri5");
  r.order = Requested<int>::of(4);
  EXPECT_EQ(refusal(r), "order: applies to {integrator=splitting} only");
}

TEST(SimulateRequest, TheFirstBrokenRuleIsTheOneNamed) {
  // A bad t_end and an option the model does not use: the t_end, checked first.
  SimulateRequest r = asking("linearized");
  r.t_end = -1.0;
  r.integrator = Requested<std::string>::of("taylor");
  EXPECT_EQ(refusal(r), "t_end: must be finite and > 0");
  // The body's check comes right after the model's name.
  r = asking("first-order");
  r.t_end = -1.0;
  bool checked = false;
  try {
    resolve(r, example_toy_top(), [&](Model m) {
      checked = true;
      EXPECT_EQ(m, Model::FirstOrder);
      throw InvalidInput("body.offset_x", "is nonzero");
    });
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.offset_x");
  }
  EXPECT_TRUE(checked);
}

TEST(SimulateRequest, ValuesNotAskedForAreDefaultsNotRefused) {
  // A configuration file's integrator with a linear model: a value, not asked for.
  SimulateRequest r = asking("linearized");
  r.integrator = {"taylor", false};
  r.step = {1e-3, false};
  EXPECT_EQ(refusal(r), "");
  // ... but a name that is no integrator is refused all the same.
  r.integrator = {"leapfrog", false};
  EXPECT_EQ(refusal(r), "integrator: must be {integrators}");
}

TEST(SimulateRequest, ResolvesToTheOptions) {
  SimulateRequest r = asking("nonlinear");
  r.integrator = Requested<std::string>::of("splitting");
  r.step = Requested<double>::of(2e-4);
  r.order = Requested<int>::of(4);
  r.max_steps = Requested<long long>::of(1234);
  r.rtol = Requested<double>::of(1e-9);
  r.t_end = 2.5;
  r.samples = 11;
  const ResolvedSimulate s = resolve(r, example_toy_top());
  EXPECT_EQ(s.model, Model::Nonlinear);
  EXPECT_EQ(s.t_end, 2.5);
  EXPECT_EQ(s.samples, 11u);
  EXPECT_EQ(s.options.integrator, Integrator::Splitting);
  EXPECT_EQ(s.options.splitting.step, 2e-4);
  EXPECT_EQ(s.options.splitting.order, 4);
  EXPECT_EQ(s.options.splitting.max_steps, 1234u);
  EXPECT_EQ(s.options.adaptive.max_steps, 1234u);
  EXPECT_EQ(s.options.adaptive.rtol, 1e-9);
  EXPECT_EQ(s.options.adaptive.atol, Tolerances{}.atol);
  // "adaptive" is dopri5's old name; unset, the integrator is auto and the model nonlinear.
  r = SimulateRequest{};
  EXPECT_EQ(resolve(r, example_toy_top()).model, Model::Nonlinear);
  EXPECT_EQ(resolve(r, example_toy_top()).options.integrator, Integrator::Auto);
  r.integrator = Requested<std::string>::of("adaptive");
  EXPECT_EQ(resolve(r, example_toy_top()).options.integrator, Integrator::Dopri5);
  // max_steps below 1 is left to simulate()'s check ("max_steps: must be > 0").
  r.max_steps = Requested<long long>::of(-5);
  const ResolvedSimulate low = resolve(r, example_toy_top());
  std::string why;
  EXPECT_FALSE(low.options.IsValid(&why));
  EXPECT_EQ(why, "max_steps: must be > 0");
}

TEST(SimulateRequest, ADampedLinearModelTakesTheNumericRouteUnasked) {
  Body damped = example_toy_top();
  damped.damping.transverse = 1e-6;
  EXPECT_EQ(resolve(asking("linearized"), damped).options.method, LinearMethod::Numeric);
  EXPECT_EQ(resolve(asking("linearized"), example_toy_top()).options.method, LinearMethod::Analytic);
  SimulateRequest r = asking("linearized");
  r.method = Requested<std::string>::of("analytic");
  EXPECT_EQ(resolve(r, damped).options.method, LinearMethod::Analytic);
}

TEST(SimulateRequest, SpelledWritesTheAdaptersKeys) {
  const Spelling flags{[](std::string_view k) {
                         std::string f = "--" + std::string(k);
                         for (char& c : f)
                           if (c == '_') c = '-';
                         return f;
                       },
                       [](std::string_view k, std::string_view v) { return "--" + std::string(k) + " " + std::string(v); },
                       "auto, taylor, dop853, dopri5 or splitting"};
  const Spelling keywords{[](std::string_view k) { return std::string(k); },
                          [](std::string_view k, std::string_view v) {
                            return std::string(k) + "=\"" + std::string(v) + "\"";
                          },
                          "auto, taylor, dop853, dopri5 (adaptive) or splitting"};
  auto text = [](const InvalidInput& e) { return e.key() + ": " + e.rule(); };
  const InvalidInput step("step", "applies to {integrator=splitting} only");
  EXPECT_EQ(text(spelled(step, flags)), "--step: applies to --integrator splitting only");
  EXPECT_EQ(text(spelled(step, keywords)), "step: applies to integrator=\"splitting\" only");
  const InvalidInput steps("max_steps", "applies to {model=nonlinear} only");
  EXPECT_EQ(text(spelled(steps, flags)), "--max-steps: applies to --model nonlinear only");
  EXPECT_EQ(text(spelled(steps, keywords)), "max_steps: applies to model=\"nonlinear\" only");
  const InvalidInput name("integrator", "must be {integrators}");
  EXPECT_EQ(text(spelled(name, flags)), "--integrator: must be auto, taylor, dop853, dopri5 or splitting");
  EXPECT_EQ(text(spelled(name, keywords)), "integrator: must be auto, taylor, dop853, dopri5 (adaptive) or splitting");
  // Keys that are not a request's (the body's) stay as they are.
  const InvalidInput body("body.B", "lagrange-exact needs a symmetric body");
  EXPECT_EQ(text(spelled(body, flags)), "body.B: lagrange-exact needs a symmetric body");
  EXPECT_EQ(text(spelled(InvalidInput("t_end", "must be finite and > 0"), flags)), "--t-end: must be finite and > 0");
}

}  // namespace
}  // namespace heavytop

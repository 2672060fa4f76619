// resolve(): a simulate() request's options, by the core's rules of what applies to which
// model (the command line and Python only spell the keys their way: spelled()).
#include <cmath>
#include <string>
#include <string_view>

#include "heavytop/lagrange_exact.hpp"
#include "heavytop/simulate.hpp"

namespace heavytop {

namespace {

// A rule's placeholder for another option with its value, written by spelled().
std::string option(std::string_view key, std::string_view value) {
  return "{" + std::string(key) + "=" + std::string(value) + "}";
}

constexpr std::string_view kKeys[] = {"model", "method", "integrator", "t_end", "samples",
                                      "rtol",  "atol",   "step",       "order", "max_steps"};

}  // namespace

ResolvedSimulate resolve(const SimulateRequest& r, const Body& body, const std::function<void(Model)>& check_body) {
  const std::string model_name = r.model.value.value_or("nonlinear");
  const auto model = model_from_name(model_name);
  if (!model) throw InvalidInput("model", "must be one of " + model_names(", "));
  const bool nonlinear = *model == Model::Nonlinear, linear = linear_kind(*model).has_value();
  if (check_body) check_body(*model);
  if (*model == Model::LagrangeExact) validate_symmetric(body);
  // Unasked, a damped linear model takes the route that covers it (the closed form does not).
  const std::string method = r.method.value.value_or(body.damping.transverse > 0.0 ? "numeric" : "analytic");
  if (method != "analytic" && method != "numeric") throw InvalidInput("method", "must be analytic or numeric");
  if (!(std::isfinite(r.t_end) && r.t_end > 0.0)) throw InvalidInput("t_end", "must be finite and > 0");
  if (r.samples < 2 || r.samples > 100'000'000) throw InvalidInput("samples", "must be an integer in [2, 100000000]");
  if (r.method.asked && !linear) throw InvalidInput("method", "applies to the linear models only");
  const auto integrator = integrator_from_name(r.integrator.value.value_or("auto"));
  if (!integrator) throw InvalidInput("integrator", "must be {integrators}");
  const std::pair<const char*, bool> nonlinear_only[] = {{"integrator", r.integrator.asked},
                                                          {"step", r.step.asked},
                                                          {"order", r.order.asked},
                                                          {"max_steps", r.max_steps.asked}};
  for (const auto& [key, asked] : nonlinear_only)
    if (asked && !nonlinear) throw InvalidInput(key, "applies to " + option("model", "nonlinear") + " only");
  // The tolerances: the nonlinear integrators' (the other models are exact to rounding).
  for (const auto& [key, asked] : {std::pair{"rtol", r.rtol.asked}, std::pair{"atol", r.atol.asked}})
    if (asked && !nonlinear)
      throw InvalidInput(key, "applies to " + option("model", "nonlinear") +
                                  " only (the other models are closed forms or a matrix exponential, exact to "
                                  "rounding)");
  if (*integrator != Integrator::Splitting && (r.step.asked || r.order.asked))
    throw InvalidInput(r.step.asked ? "step" : "order", "applies to " + option("integrator", "splitting") + " only");

  ResolvedSimulate out;
  out.model = *model;
  out.t_end = r.t_end;
  out.samples = static_cast<std::size_t>(r.samples);
  SimulateOptions& o = out.options;
  o.method = method == "numeric" ? LinearMethod::Numeric : LinearMethod::Analytic;
  o.integrator = *integrator;
  if (r.rtol.value) o.adaptive.rtol = *r.rtol.value;
  if (r.atol.value) o.adaptive.atol = *r.atol.value;
  if (r.step.value) o.splitting.step = *r.step.value;
  if (r.order.value) o.splitting.order = *r.order.value;
  if (r.max_steps.value) {  // < 1: simulate()'s "max_steps: must be > 0"
    const auto steps = static_cast<std::size_t>(std::max(0LL, *r.max_steps.value));
    o.adaptive.max_steps = o.splitting.max_steps = steps;
  }
  return out;
}

InvalidInput spelled(const InvalidInput& refusal, const Spelling& spelling) {
  std::string key = refusal.key();
  for (std::string_view k : kKeys)
    if (key == k) key = spelling.key(k);
  std::string rule = refusal.rule();
  for (std::size_t open = rule.find('{'); open != std::string::npos; open = rule.find('{', open)) {
    const std::size_t close = rule.find('}', open);
    if (close == std::string::npos) break;
    const std::string inside = rule.substr(open + 1, close - open - 1);
    const std::size_t equals = inside.find('=');
    const std::string text = inside == "integrators"      ? spelling.integrators
                             : equals != std::string::npos ? spelling.option(std::string_view(inside).substr(0, equals),
                                                                             std::string_view(inside).substr(equals + 1))
                                                           : "{" + inside + "}";
    rule.replace(open, close - open + 1, text);
    open += text.size();
  }
  return InvalidInput(key, rule);
}

}  // namespace heavytop

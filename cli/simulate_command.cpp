// heavytop simulate: one model's motion, theta(t), phi(t) and their rates, as CSV or JSON.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "formats.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/linear_motion.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/splitting.hpp"

namespace heavytop::cli {
namespace {

struct SimulateOptions {
  std::string model = "nonlinear";
  double t_end = 10.0;
  long long samples = 1001;
  std::string method = "analytic";
  double rtol = NonlinearOptions{}.rtol;
  double atol = NonlinearOptions{}.atol;
  CLI::Option* model_option = nullptr;
  CLI::Option* t_end_option = nullptr;
  CLI::Option* samples_option = nullptr;
  CLI::Option* method_option = nullptr;
  CLI::Option* rtol_option = nullptr;
  CLI::Option* atol_option = nullptr;
  std::string integrator = "adaptive";
  SplittingOptions splitting;
  CLI::Option* integrator_option = nullptr;
  CLI::Option* step_option = nullptr;
  CLI::Option* order_option = nullptr;
};

std::string to_json(const std::string& model, const Inputs& in, const Trajectory& tr,
                    const NonlinearSummary* summary) {
  nlohmann::ordered_json out;
  out["model"] = model;
  const Body& b = in.body();
  out["body"] = {{"A", b.A}, {"B", b.B}, {"C", b.C}, {"mass", b.mass}, {"gravity", b.gravity}, {"length", b.length}};
  const InitialState& s = in.state();
  out["motion"] = {{"spin", s.spin}, {"theta0", s.theta0}, {"phi0", s.phi0},
                   {"theta_rate0", s.theta_rate0}, {"phi_rate0", s.phi_rate0}};
  const auto names = trajectory_columns(tr);
  out["columns"] = names;
  for (std::size_t c = 0; c < names.size(); ++c) out[names[c]] = trajectory_column(tr, c);
  if (summary) {
    out["summary"] = {{"steps", summary->steps},
                      {"rejected_steps", summary->rejected_steps},
                      {"rhs_evaluations", summary->rhs_evaluations},
                      {"max_relative_energy_drift", summary->max_relative_energy_drift},
                      {"max_relative_vertical_momentum_drift", summary->max_relative_vertical_momentum_drift}};
  }
  return out.dump() + "\n";
}

/// The linear models sample by sample, in chunks so a long run shows its progress (each
/// sample is computed on its own, so chunking changes nothing).
Trajectory simulate_linear_in_chunks(LinearModelKind kind, const Inputs& in, const std::vector<double>& times,
                                     const std::string& method, ProgressBar& progress) {
  const LinearModel model = linear_model(kind, in.body());
  const LinearMethod how = method == "numeric" ? LinearMethod::Numeric : LinearMethod::Analytic;
  constexpr std::size_t kChunk = 1 << 16;
  if (times.size() <= kChunk) return simulate_linear(model, in.state(), times, how);
  Trajectory out;
  out.reserve(times.size());
  for (std::size_t begin = 0; begin < times.size(); begin += kChunk) {
    const std::vector<double> part(times.begin() + static_cast<std::ptrdiff_t>(begin),
                                   times.begin() + static_cast<std::ptrdiff_t>(std::min(times.size(), begin + kChunk)));
    const Trajectory piece = simulate_linear(model, in.state(), part, how);
    for (auto [to, from] : {std::pair{&out.t, &piece.t}, {&out.theta, &piece.theta}, {&out.phi, &piece.phi},
                            {&out.theta_rate, &piece.theta_rate}, {&out.phi_rate, &piece.phi_rate}})
      to->insert(to->end(), from->begin(), from->end());
    progress.update(part.back());
  }
  return out;
}

}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate", "The motion of one model: CSV columns t,theta,phi,theta_rate,phi_rate (SI units)");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"csv", "json"});
  auto o = std::make_shared<SimulateOptions>();
  o->model_option = cmd->add_option("--model", o->model, "first-order | body-fixed | linearized | nonlinear | lagrange-exact (A = B)")
                        ->check(CLI::IsMember({"first-order", "body-fixed", "linearized", "nonlinear", "lagrange-exact"}))
                        ->default_str(o->model);
  o->t_end_option = cmd->add_option("--t-end", o->t_end, "s, end of the simulated interval (> 0)")
                        ->default_str("10");
  o->samples_option = cmd->add_option("--samples", o->samples, "rows, at t_i = i T / (N - 1) (>= 2)")
                          ->default_str("1001");
  o->method_option = cmd->add_option("--method", o->method,
                                     "linear models: analytic (closed form) | numeric (matrix exponential)")
                         ->check(CLI::IsMember({"analytic", "numeric"}))
                         ->default_str("analytic");
  o->rtol_option = cmd->add_option("--rtol", o->rtol, "nonlinear: relative tolerance per step")
                       ->default_str(fmt::format("{}", o->rtol));
  o->atol_option = cmd->add_option("--atol", o->atol, "nonlinear: absolute tolerance per step")
                       ->default_str(fmt::format("{}", o->atol));
  o->integrator_option =
      cmd->add_option("--integrator", o->integrator,
                      "nonlinear: adaptive (Dormand-Prince, error control) | splitting (fixed step, "
                      "structure-preserving: bounded energy error over long runs)")
          ->check(CLI::IsMember({"adaptive", "splitting"}))
          ->default_str("adaptive");
  o->step_option = cmd->add_option("--step", o->splitting.step, "s, splitting: the fixed step")
                       ->default_str(fmt::format("{}", o->splitting.step));
  o->order_option = cmd->add_option("--order", o->splitting.order, "splitting: order 2 (Strang) or 4 (Suzuki)")
                        ->default_str("2");
  inputs->allow_section("simulate", {"model", "t_end", "samples", "method", "rtol", "atol", "integrator", "step", "order"});

  return [inputs, o] {
    inputs->resolve();
    // The [simulate] section of the configuration, where the command line says nothing.
    if (!o->model_option->count()) o->model = inputs->section_string("simulate", "model").value_or(o->model);
    if (!o->method_option->count()) o->method = inputs->section_string("simulate", "method").value_or(o->method);
    if (!o->t_end_option->count()) o->t_end = inputs->section_number("simulate", "t_end").value_or(o->t_end);
    if (!o->samples_option->count())
      o->samples = static_cast<long long>(inputs->section_number("simulate", "samples").value_or(static_cast<double>(o->samples)));
    if (!o->rtol_option->count()) o->rtol = inputs->section_number("simulate", "rtol").value_or(o->rtol);
    if (!o->atol_option->count()) o->atol = inputs->section_number("simulate", "atol").value_or(o->atol);
    if (!o->integrator_option->count())
      o->integrator = inputs->section_string("simulate", "integrator").value_or(o->integrator);
    if (!o->step_option->count()) o->splitting.step = inputs->section_number("simulate", "step").value_or(o->splitting.step);
    if (!o->order_option->count())
      o->splitting.order = static_cast<int>(inputs->section_number("simulate", "order").value_or(o->splitting.order));

    const bool nonlinear = o->model == "nonlinear", exact = o->model == "lagrange-exact";
    const auto kind = linear_model_from_name(o->model);
    if (!nonlinear && !exact && !kind)
      throw InvalidInput("--model", "must be one of first-order, body-fixed, linearized, nonlinear, lagrange-exact");
    if (exact) validate_symmetric(inputs->body());
    if (o->method != "analytic" && o->method != "numeric")
      throw InvalidInput("--method", "must be analytic or numeric");
    if (!(std::isfinite(o->t_end) && o->t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    if (o->samples < 2 || o->samples > 100'000'000) throw InvalidInput("--samples", "must be an integer in [2, 100000000]");
    if (!kind && o->method_option->count())
      throw InvalidInput("--method", "applies to the linear models only");
    if (o->integrator != "adaptive" && o->integrator != "splitting")
      throw InvalidInput("--integrator", "must be adaptive or splitting");
    const bool splitting = o->integrator == "splitting";
    for (CLI::Option* given : {o->integrator_option, o->step_option, o->order_option})
      if (given->count() && !nonlinear)
        throw InvalidInput(given->get_name(), "applies to --model nonlinear only");
    if (!splitting && (o->step_option->count() || o->order_option->count()))
      throw InvalidInput(o->step_option->count() ? "--step" : "--order", "applies to --integrator splitting only");
    if (splitting) validate(o->splitting);
    NonlinearOptions options;
    options.rtol = o->rtol;
    options.atol = o->atol;
    validate(options);

    const auto times = sample_times(o->t_end, static_cast<std::size_t>(o->samples));
    NonlinearSummary summary;
    ProgressBar progress("simulate", o->t_end);
    options.progress = [&](double t) { progress.update(t); };
    const Trajectory tr = nonlinear && splitting ? simulate_splitting(inputs->body(), inputs->state(), times, o->splitting)
                          : nonlinear ? simulate_nonlinear(inputs->body(), inputs->state(), times, options, &summary)
                          : exact   ? simulate_lagrange_exact(inputs->body(), inputs->state(), times)
                                    : simulate_linear_in_chunks(*kind, *inputs, times, o->method, progress);
    write_output(inputs->output(), inputs->format() == "json"
                                       ? to_json(o->model, *inputs, tr, nonlinear && !splitting ? &summary : nullptr)
                                       : trajectory_csv(tr));
  };
}

}  // namespace heavytop::cli

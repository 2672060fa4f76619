// heavytop simulate: one model's motion, theta(t), phi(t) and their rates, as CSV or JSON.
#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/simulate.hpp"

namespace heavytop::cli {
namespace {

struct SimulateFlags {
  std::string model = "nonlinear";
  double t_end = 10.0;
  long long samples = 1001;
  std::string method = "analytic";
  std::string integrator = "auto";
  SimulateOptions options;
  CLI::Option* model_option = nullptr;
  CLI::Option* t_end_option = nullptr;
  CLI::Option* samples_option = nullptr;
  CLI::Option* method_option = nullptr;
  CLI::Option* rtol_option = nullptr;
  CLI::Option* atol_option = nullptr;
  CLI::Option* integrator_option = nullptr;
  CLI::Option* step_option = nullptr;
  CLI::Option* order_option = nullptr;
  long long max_steps = 0;
  CLI::Option* max_steps_option = nullptr;
};

// --format json holds the whole trajectory (11 columns of doubles, then the text) in memory.
constexpr long long kMaxJsonSamples = 2'000'000;

}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate", "The motion of one model: CSV columns t,theta,phi,theta_rate,phi_rate (SI units)");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"csv", "json"});
  auto o = std::make_shared<SimulateFlags>();
  std::vector<std::string> models;
  for (Model m : kModels) models.emplace_back(name(m));
  o->model_option = cmd->add_option("--model", o->model, "first-order | body-fixed | linearized | nonlinear | lagrange-exact (A = B)")
                        ->check(CLI::IsMember(models))
                        ->default_str(o->model);
  o->t_end_option = cmd->add_option("--t-end", o->t_end, "s, end of the simulated interval (> 0)")
                        ->default_str("10");
  o->samples_option = cmd->add_option("--samples", o->samples, "rows, at t_i = i T / (N - 1) (>= 2)")
                          ->default_str("1001");
  o->method_option = cmd->add_option("--method", o->method,
                                     "linear models: analytic (closed form) | numeric (matrix exponential)")
                         ->check(CLI::IsMember({"analytic", "numeric"}))
                         ->default_str("analytic");
  Tolerances& adaptive = o->options.adaptive;
  o->rtol_option = cmd->add_option("--rtol", adaptive.rtol, "nonlinear: relative tolerance per step")
                       ->default_str(fmt::format("{}", adaptive.rtol));
  o->atol_option = cmd->add_option("--atol", adaptive.atol, "nonlinear: absolute tolerance per step")
                       ->default_str(fmt::format("{}", adaptive.atol));
  o->integrator_option =
      cmd->add_option("--integrator", o->integrator,
                      "nonlinear: auto (the fastest for the body and tolerance) | taylor (Taylor series) | dop853 "
                      "(Dormand-Prince 8) | dopri5 (Dormand-Prince 5) | splitting (fixed step, "
                      "structure-preserving: bounded energy error over long runs)")
          ->type_name("NAME")  // checked below: dopri5's old name "adaptive" is accepted, not listed
          ->default_str("auto");
  SplittingOptions& splitting = o->options.splitting;
  o->step_option = cmd->add_option("--step", splitting.step, "s, splitting: the fixed step")
                       ->default_str(fmt::format("{}", splitting.step));
  o->order_option = cmd->add_option("--order", splitting.order, "splitting: order 2 (Strang) or 4 (Suzuki)")
                        ->default_str("2");
  o->max_steps_option =
      cmd->add_option("--max-steps", o->max_steps,
                      "nonlinear: the most integration steps a run may take before it gives up")
          ->default_str(fmt::format("{} (auto, taylor, dopri5, dop853), {} (splitting)", Tolerances{}.max_steps,
                                    SplittingOptions{}.max_steps));

  return [inputs, o] {
    inputs->resolve(/*allow_general=*/true);  // nonlinear integrates it; every other model refuses it below
    // The [simulate] section of the configuration, where the command line says nothing.
    const io::Configuration& config = inputs->configuration();
    apply_setting(config, "simulate.model", o->model_option, o->model);
    apply_setting(config, "simulate.method", o->method_option, o->method);
    apply_setting(config, "simulate.t_end", o->t_end_option, o->t_end);
    apply_setting(config, "simulate.samples", o->samples_option, o->samples);
    apply_setting(config, "simulate.rtol", o->rtol_option, o->options.adaptive.rtol);
    apply_setting(config, "simulate.atol", o->atol_option, o->options.adaptive.atol);
    apply_setting(config, "simulate.integrator", o->integrator_option, o->integrator);
    apply_setting(config, "simulate.step", o->step_option, o->options.splitting.step);
    apply_setting(config, "simulate.order", o->order_option, o->options.splitting.order);

    const auto model = model_from_name(o->model);
    if (!model) throw InvalidInput("--model", "must be one of " + model_names(", "));
    const bool nonlinear = *model == Model::Nonlinear, linear = linear_kind(*model).has_value();
    if (!nonlinear) inputs->refuse_general("simulate --model " + o->model);
    if (*model == Model::LagrangeExact) validate_symmetric(inputs->body());
    if (o->method != "analytic" && o->method != "numeric")
      throw InvalidInput("--method", "must be analytic or numeric");
    if (!(std::isfinite(o->t_end) && o->t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    if (o->samples < 2 || o->samples > 100'000'000) throw InvalidInput("--samples", "must be an integer in [2, 100000000]");
    if (!linear && o->method_option->count())
      throw InvalidInput("--method", "applies to the linear models only");
    const auto integrator = integrator_from_name(o->integrator);
    if (!integrator) throw InvalidInput("--integrator", "must be " + integrator_names(", ", " or "));
    for (CLI::Option* given : {o->integrator_option, o->step_option, o->order_option, o->max_steps_option})
      if (given->count() && !nonlinear)
        throw InvalidInput(given->get_name(), "applies to --model nonlinear only");
    // The tolerances: the nonlinear integrators', and the linear models' numeric route (the
    // matrix exponential takes none; the closed forms and lagrange-exact are exact).
    for (CLI::Option* given : {o->rtol_option, o->atol_option})
      if (given->count() && !nonlinear)
        throw InvalidInput(given->get_name(), "applies to --model nonlinear only (the other models are closed "
                                              "forms or a matrix exponential, exact to rounding)");
    if (*integrator != Integrator::Splitting && (o->step_option->count() || o->order_option->count()))
      throw InvalidInput(o->step_option->count() ? "--step" : "--order", "applies to --integrator splitting only");
    o->options.method = o->method == "numeric" ? LinearMethod::Numeric : LinearMethod::Analytic;
    // Unasked, a damped linear model takes the route that covers it (the closed form does not).
    if (!o->method_option->count() && !config.settings.count("simulate.method") &&
        inputs->body().damping.transverse > 0.0)
      o->options.method = LinearMethod::Numeric;
    o->options.integrator = *integrator;

    const bool json = inputs->format() == "json";
    if (json && o->samples > kMaxJsonSamples)
      throw InvalidInput("--samples", fmt::format("must be at most {} with --format json, which holds the whole "
                                                  "trajectory in memory (--format csv streams any number)",
                                                  kMaxJsonSamples));
    if (o->max_steps_option->count()) {
      if (o->max_steps < 1) throw InvalidInput("--max-steps", "must be an integer >= 1");
      o->options.adaptive.max_steps = o->options.splitting.max_steps = static_cast<std::size_t>(o->max_steps);
    }

    ProgressBar progress("simulate", o->t_end);
    o->options.progress = [&](double t) { progress.update(t); };
    const SampleGrid grid{o->t_end, static_cast<std::size_t>(o->samples)};
    // Open the output first: a path that cannot be written is bad input, found before any work.
    io::OutputStream out(inputs->output(), "--output");
    SimulationSummary summary;
    if (json) {  // the whole trajectory in memory (at most kMaxJsonSamples)
      const Simulation run = simulate(*model, inputs->body(), inputs->state(), sample_times(grid.t_end, grid.count),
                                      o->options);
      summary = run.summary;
      if (!summary.ok()) throw Failure(summary.message);
      out.write(io::trajectory_json(*model, inputs->body(), inputs->state(), run.trajectory,
                                    run.adaptive ? &*run.adaptive : nullptr));
    } else {
      // CSV rows as they are computed: memory stays flat in the number of samples. 64 samples a
      // piece (at most 22 KB of text): a short run touches few fresh pages, each a page fault
      // (a 1000-sample run: 266 faults with the library's 4096, 111 with 256, 89 with 64, the
      // last step 0.07 ms; issue 17), and 10 million samples take no longer (2.6 s either way).
      bool header = false;
      const auto sink = [&](const Trajectory& part) {
        if (!header) out.write(io::trajectory_csv_header(part));
        header = true;
        out.write(io::trajectory_csv_rows(part, 0, part.size()));
      };
      summary = simulate_streaming(*model, inputs->body(), inputs->state(), grid, o->options, sink, 64);
      if (!summary.ok()) throw Failure(summary.message);
    }
    for (const std::string& warning : summary.warnings) std::cerr << "heavytop: warning: " << warning << "\n";
    out.commit();
  };
}

}  // namespace heavytop::cli

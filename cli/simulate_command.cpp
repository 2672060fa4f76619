// heavytop simulate: one model's motion, theta(t), phi(t) and their rates, as CSV or JSON.
#include <algorithm>
#include <cmath>
#include <optional>
#include <iostream>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/table.hpp"

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

// A core key as its flag: "t_end" -> "--t-end".
std::string flag_spelling(std::string_view key) {
  std::string flag = "--" + std::string(key);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

// --format json holds the whole trajectory (11 columns of doubles, then the text) in memory.
constexpr long long kMaxJsonSamples = 2'000'000;

// The body on a table (SPEC section 16): the nonlinear model only, by DOP853; the run ends
// early, with one line on stderr, when the body leaves the table.
void run_on_table(const Inputs& inputs, const SimulateFlags& o, Model model) {
  const Table& table = inputs.table();
  if (model != Model::Nonlinear)
    throw InvalidInput("table.contact", fmt::format("--model {} is the pivot's (SPEC section 16): on a table (contact = "
                                                    "\"{}\") use --model nonlinear",
                                                    name(model), name(table.contact)));
  if (auto why = integrator_refusal(o.options.integrator, inputs.body(), true, false))
    throw InvalidInput("--integrator", *why);
  ProgressBar bar("simulate", o.t_end);
  const Progress progress = [&bar](double t) { bar.update(t); };
  const SampleGrid grid{o.t_end, static_cast<std::size_t>(o.samples)};
  io::OutputStream out(inputs.output(), "--output");
  const TableRun run =
      simulate_on_table(inputs.body(), table, inputs.state(), grid, o.options.adaptive, progress, o.options.integrator);
  out.write(inputs.format() == "json" ? io::table_trajectory_json(inputs.body(), table, inputs.state(), run)
                                      : io::trajectory_csv(run.trajectory));
  if (run.summary.end == TableSummary::End::LeftTable)
    std::cerr << fmt::format("heavytop: the body leaves the table at t = {:.9g} s\n", run.summary.end_time);
  out.commit();
}

}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate", "The motion of one model: CSV columns t,theta,phi,theta_rate,phi_rate (SI units)");
  InputUses uses;
  uses.table = true;
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"csv", "json"}, uses);
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
                      "structure-preserving: bounded energy error over long runs) | rosenbrock4 (implicit: a body "
                      "sliding on a table, stiff at a small slip speed)")
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

    // The core's rules (resolve()); here only its keys spelled as flags and the general body's
    // refusal in the command line's words. Flags are asked for; the configuration's values are not.
    SimulateRequest request;
    request.model = {o->model, o->model_option->count() > 0};
    if (o->method_option->count() || config.settings.count("simulate.method"))
      request.method = {o->method, o->method_option->count() > 0};
    request.integrator = {o->integrator, o->integrator_option->count() > 0};
    request.t_end = o->t_end;
    request.samples = o->samples;
    request.rtol = {o->options.adaptive.rtol, o->rtol_option->count() > 0};
    request.atol = {o->options.adaptive.atol, o->atol_option->count() > 0};
    request.step = {o->options.splitting.step, o->step_option->count() > 0};
    request.order = {o->options.splitting.order, o->order_option->count() > 0};
    if (o->max_steps_option->count()) request.max_steps = Requested<long long>::of(o->max_steps);
    ResolvedSimulate resolved;
    try {
      resolved = resolve(request, inputs->body(), [&](Model m) {
        if (m != Model::Nonlinear) inputs->refuse_general("simulate --model " + o->model);
      });
    } catch (const InvalidInput& e) {
      throw spelled(e, Spelling{[](std::string_view key) { return flag_spelling(key); },
                                [](std::string_view key, std::string_view value) {
                                  return fmt::format("{} {}", flag_spelling(key), value);
                                },
                                integrator_names(", ", " or ")});
    }
    o->options.method = resolved.options.method;
    o->options.integrator = resolved.options.integrator;
    const std::optional<Model> model = resolved.model;

    const bool json = inputs->format() == "json";
    if (json && o->samples > kMaxJsonSamples)
      throw InvalidInput("--samples", fmt::format("must be at most {} with --format json, which holds the whole "
                                                  "trajectory in memory (--format csv streams any number)",
                                                  kMaxJsonSamples));
    if (o->max_steps_option->count()) {
      if (o->max_steps < 1) throw InvalidInput("--max-steps", "must be an integer >= 1");
      o->options.adaptive.max_steps = o->options.splitting.max_steps = static_cast<std::size_t>(o->max_steps);
    }

    if (inputs->table().on_table()) {
      run_on_table(*inputs, *o, *model);
      return;
    }
    ProgressBar bar("simulate", o->t_end);
    const Progress progress = [&bar](double t) { bar.update(t); };
    const SampleGrid grid{o->t_end, static_cast<std::size_t>(o->samples)};
    // Open the output first: a path that cannot be written is bad input, found before any work.
    io::OutputStream out(inputs->output(), "--output");
    SimulationSummary summary;
    if (json) {  // the whole trajectory in memory (at most kMaxJsonSamples)
      const Simulation run = simulate(*model, inputs->body(), inputs->state(), sample_times(grid.t_end, grid.count),
                                      o->options, progress);
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
      summary = simulate_streaming(*model, inputs->body(), inputs->state(), grid, o->options, sink, 64, nullptr, progress);
      if (!summary.ok()) throw Failure(summary.message);
    }
    for (const std::string& warning : summary.warnings) std::cerr << "heavytop: warning: " << warning << "\n";
    out.commit();
  };
}

}  // namespace heavytop::cli

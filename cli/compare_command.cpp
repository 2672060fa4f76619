// heavytop compare: every approximate model against the nonlinear body, one state, one horizon.
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/simulate.hpp"

namespace heavytop::cli {
Action add_compare_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "Every approximate model against the nonlinear body: angle errors, frequencies");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json", "csv"});
  auto t_end = std::make_shared<double>(10.0);
  auto samples = std::make_shared<long long>(10001);
  auto tol = std::make_shared<Tolerances>();
  cmd->add_option("--t-end", *t_end, "s, horizon (> 0)")->default_str("10");
  cmd->add_option("--samples", *samples, "samples over the horizon (>= 3)")->default_str("10001");
  cmd->add_option("--rtol", tol->rtol, "nonlinear: relative tolerance per step")->default_str(fmt::format("{}", tol->rtol));
  cmd->add_option("--atol", tol->atol, "nonlinear: absolute tolerance per step")->default_str(fmt::format("{}", tol->atol));
  auto max_steps = std::make_shared<long long>(0);
  auto* max_steps_option = cmd->add_option("--max-steps", *max_steps, "nonlinear: the most integration steps before it gives up")
                               ->default_str(fmt::format("{}", tol->max_steps));
  return [inputs, t_end, samples, tol, max_steps, max_steps_option] {
    inputs->resolve();
    if (!(std::isfinite(*t_end) && *t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    if (*samples < 3 || *samples > static_cast<long long>(kMaxComparisonSamples))
      throw InvalidInput("--samples", fmt::format("must be an integer in [3, {}]", kMaxComparisonSamples));
    validate_horizon(inputs->body(), inputs->state(), *t_end, "--t-end");
    if (max_steps_option->count()) {
      if (*max_steps < 1) throw InvalidInput("--max-steps", "must be an integer >= 1");
      tol->max_steps = static_cast<std::size_t>(*max_steps);
    }
    validate(*tol);
    const Comparison c = compare_models(inputs->body(), inputs->state(),
                                        sample_times(*t_end, static_cast<std::size_t>(*samples)), *tol);
    const std::string& f = inputs->format();
    write_output(inputs->output(), f == "json" ? io::comparison_json(c) : f == "csv" ? io::comparison_csv(c) : io::comparison_text(c, *t_end));
  };
}

}  // namespace heavytop::cli

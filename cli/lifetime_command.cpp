// heavytop lifetime: how long a top stays up (SPEC section 8): when its spin reaches the
// critical spin (closed form) and when, spinning how fast, it falls (nonlinear, damped).
#include <cmath>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/table.hpp"

namespace heavytop::cli {

Action add_lifetime_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "lifetime", "How long the top stays up: its spin's decay to the critical spin and the fall of the "
                  "damped nonlinear body");
  InputUses uses;
  uses.table = true;  // on a table: the spin-down by the body's own losses, then the motion
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"}, uses);
  auto options = std::make_shared<LifetimeOptions>();
  auto horizon = std::make_shared<double>(0.0);
  auto* horizon_option = cmd->add_option("--horizon", *horizon,
                                         "s, the longest nonlinear run (default: 10 times the time to the "
                                         "critical spin, or 1000)");
  auto* max_tilt =
      cmd->add_option("--max-tilt", options->max_tilt, "rad, the tilt past which the top has fallen")->default_str("1");
  auto max_tilt_deg = std::make_shared<DegreesOption>(*cmd, max_tilt, "max_tilt", "--max-tilt-deg",
                                                      "degrees, the same (instead of --max-tilt)");
  cmd->add_option("--rtol", options->integrator.rtol, "nonlinear: relative tolerance per step")
      ->default_str(fmt::format("{}", options->integrator.rtol));
  cmd->add_option("--atol", options->integrator.atol, "nonlinear: absolute tolerance per step")
      ->default_str(fmt::format("{}", options->integrator.atol));
  cmd->add_option("--max-steps", options->integrator.max_steps,
                  "nonlinear: the most integration steps before it gives up")
      ->check(positive_count());
  return [inputs, options, horizon, horizon_option, max_tilt_deg] {
    inputs->resolve();
    LifetimeOptions o = *options;
    max_tilt_deg->apply(o.max_tilt);
    if (horizon_option->count()) o.horizon = *horizon;
    validate(o);
    if (const Table& table = inputs->table(); table.on_table()) {
      AnswerOptions a;
      a.max_tilt = o.max_tilt;
      a.integrator = o.integrator;
      const TableLifetime life = table_lifetime(inputs->body(), table, inputs->state(), o.horizon, a);
      write_output(inputs->output(), inputs->format() == "json" ? io::table_lifetime_json(life)
                                                                : io::table_lifetime_text(life, table));
      return;
    }
    const Lifetime life = [&] {
      ProgressBar bar("lifetime", spin_decay(inputs->body(), inputs->state(), o).horizon);
      return lifetime(inputs->body(), inputs->state(), o, [&bar](double t) { bar.update(t); });
    }();
    write_output(inputs->output(), inputs->format() == "json"
                                       ? io::lifetime_json(life)
                                       : io::lifetime_text(inputs->body(), inputs->state(), life));
  };
}

}  // namespace heavytop::cli

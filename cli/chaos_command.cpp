// heavytop chaos: how long the motion can be predicted (SPEC section 17, "Chaos"): the largest
// Lyapunov exponent and its history, the spectrum, MEGNO and the prediction horizon; with
// --section the Poincare section psi = 0 instead.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/chaos.hpp"
#include "heavytop/uncertainty.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/chaos_formats.hpp"

namespace heavytop::cli {
namespace {

// The library's option names this command line spells its own way ("precision" ->
// "--precision"); flag_of() knows the shared ones.
std::string chaos_flag(const std::string& key) {
  if (key == "precision") return "--precision";
  if (key == "renormalisation_interval") return "--renormalisation-interval";
  return flag_of(key);
}

}  // namespace

Action add_chaos_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "chaos", "How long the motion can be predicted: the Lyapunov exponents of the nonlinear body on its pivot, "
               "MEGNO and the prediction horizon (or, with --section, the Poincare section psi = 0)");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json", "csv"});
  auto options = std::make_shared<ChaosOptions>();
  auto precision = std::make_shared<double>(kDefaultChaosPrecision);
  auto section = std::make_shared<bool>(false);
  cmd->add_option("--horizon", options->horizon, "s, the run's length T")->default_str("1000");
  auto* precision_option = cmd->add_option(
      "--precision", *precision, "the relative precision delta, in (0, 1), to which the start is known (default: the largest relative "
      "standard uncertainty of the file's [uncertainty], else 1e-15)");
  cmd->add_option("--renormalisation-interval", options->renormalisation_interval,
                  "s, how often the tangent vectors are re-orthonormalised")
      ->default_str("1");
  cmd->add_flag("--section", *section,
                "the Poincare section instead: t, tilt, tilt_rate at each crossing of psi = 0 with psi' > 0");
  cmd->add_option("--rtol", options->tolerances.rtol, "relative tolerance per step")
      ->default_str(fmt::format("{}", options->tolerances.rtol));
  cmd->add_option("--atol", options->tolerances.atol, "absolute tolerance per step")
      ->default_str(fmt::format("{}", options->tolerances.atol));
  cmd->add_option("--max-steps", options->tolerances.max_steps, "the most integration steps before it gives up")
      ->check(positive_count());
  return [inputs, options, precision, precision_option, section] {
    inputs->resolve(/*allow_general=*/true);
    ChaosOptions o = *options;
    if (precision_option->count()) {
      o.precision = *precision;
    } else if (const UncertaintyOptions u = io::uncertainty_of(inputs->configuration()); u.any()) {
      // SPEC 17: the inputs' largest relative standard uncertainty (a start known to 1 or worse
      // is not predicted at all: its horizon is 0 from 1e-2 on).
      if (const auto d = largest_relative_uncertainty(u, inputs->body(), inputs->state())) o.precision = std::min(*d, 0.5);
    }
    o.section = false;
    try {
      validate(o);
      if (inputs->format() == "csv" && !*section)
        throw InvalidInput("--format", "csv is the Poincare section's (add --section); the exponents are text or json");
      if (*section) {
        const PoincareSection s = [&] {
          ProgressBar bar("chaos --section", o.horizon);
          return poincare_section(inputs->body(), inputs->state(), o, [&bar](double t) { bar.update(t); });
        }();
        const std::string& f = inputs->format();
        write_output(inputs->output(), f == "csv"    ? io::section_csv(s)
                                       : f == "json" ? io::section_json(s)
                                                     : io::section_text(s, o.horizon));
        return;
      }
      const ChaosResult r = [&] {
        ProgressBar bar("chaos", o.horizon);
        return analyse_chaos(inputs->body(), inputs->state(), o, [&bar](double t) { bar.update(t); });
      }();
      write_output(inputs->output(), inputs->format() == "json" ? io::chaos_json(r) : io::chaos_text(r));
    } catch (const InvalidInput& e) {
      throw InvalidInput(chaos_flag(e.key()), e.rule());
    }
  };
}

}  // namespace heavytop::cli

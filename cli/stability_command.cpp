// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues;
// then the real body's Lyapunov verdict (SPEC section 7) and how far its axis wanders.
#include <cmath>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"

namespace heavytop::cli {

Action add_stability_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "stability", "Linear stability of the first-order, body-fixed and linearized models at a spin, "
                   "and the real body's Lyapunov verdict");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"});
  auto horizon = std::make_shared<double>(100.0);
  cmd->add_option("--horizon", *horizon,
                  "s, for A != B: the wander (largest tilt) is that of a nonlinear run this long")
      ->default_str("100");
  return [inputs, horizon] {
    inputs->resolve();
    if (!(std::isfinite(*horizon) && *horizon > 0.0)) throw InvalidInput("--horizon", "must be a finite number > 0");
    const Body& body = inputs->body();
    const double spin = inputs->state().spin;
    const auto models = analyse_stability(body, spin);
    const auto lyapunov = analyse_lyapunov(body, spin);
    const auto wander = axis_wander(body, inputs->state(), *horizon);
    write_output(inputs->output(), inputs->format() == "json"
                                       ? io::stability_json(body, spin, models, lyapunov, wander)
                                       : io::stability_text(body, spin, models, lyapunov, wander));
  };
}

}  // namespace heavytop::cli

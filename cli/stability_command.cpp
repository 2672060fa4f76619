// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues.
#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/stability.hpp"

namespace heavytop::cli {

Action add_stability_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "stability", "Linear stability of the first-order, body-fixed and linearized models at a spin");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"});
  return [inputs] {
    inputs->resolve();
    const auto models = analyse_stability(inputs->body(), inputs->state().spin);
    write_output(inputs->output(), inputs->format() == "json"
                                       ? io::stability_json(inputs->body(), inputs->state().spin, models)
                                       : io::stability_text(inputs->body(), inputs->state().spin, models));
  };
}

}  // namespace heavytop::cli

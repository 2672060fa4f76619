// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues.
#include "commands.hpp"
#include "common.hpp"
#include "formats.hpp"

namespace heavytop::cli {

Action add_stability_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "stability", "Linear stability of the first-order, body-fixed and linearized models at a spin");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"});
  return [inputs] {
    inputs->resolve();
    const auto reports = analyse(inputs->body(), inputs->state().spin);
    write_output(inputs->output(), inputs->format() == "json"
                                       ? stability_json(inputs->body(), inputs->state().spin, reports)
                                       : stability_text(inputs->body(), inputs->state().spin, reports));
  };
}

}  // namespace heavytop::cli

// heavytop body: the body a configuration's parts (or moments) make (SPEC section 10).
#include <memory>
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/body_formats.hpp"
#include "heavytop/lifetime.hpp"

namespace heavytop::cli {

Action add_body_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("body", "The body its [[body.part]] list (or its moments) makes: A, B, C, mass, "
                                         "length, products of inertia and offset about O");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"},
                                         InputUses{.motion = false, .damping = false});
  return [inputs] {
    inputs->resolve(/*allow_general=*/true);
    const double g = inputs->body().gravity;
    std::optional<io::UprightSpin> upright;  // the general body has none: the models refuse it
    if (!is_general(inputs->body())) upright = io::UprightSpin{spin_decay(inputs->body(), InitialState{}).critical_spin};
    write_output(inputs->output(), inputs->format() == "json" ? io::body_json(inputs->assembly(), g)
                                                              : io::body_text(inputs->assembly(), g, upright));
  };
}

}  // namespace heavytop::cli

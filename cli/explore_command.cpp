// heavytop explore: the explorer page (SPEC section 15), one self-contained HTML file with the
// core compiled to WebAssembly inside it, its inputs starting at the body and motion given here
// (--config and the body options; the built-in toy top without them). The page is built by
// Emscripten (web/, the CMake target heavytop_web); this command copies it with that start
// (report::explorer_page(), which every report's explore.html comes from too).
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/report/report.hpp"

namespace heavytop::cli {

Action add_explore_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "explore", "Write the explorer page: one self-contained HTML file (the core in WebAssembly) that answers any "
                 "body and spin live in a browser, from file:// with no network");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"html"});
  return [inputs] {
    inputs->resolve();
    if (inputs->output().empty() || inputs->output() == "-")
      throw InvalidInput("--output", "give the page's file, e.g. --output explore.html");
    const auto page = report::explorer_page(inputs->body(), inputs->state());
    if (!page) throw InvalidInput("explore", io::kExplorerPageMissing);
    write_output(inputs->output(), *page);
  };
}

}  // namespace heavytop::cli

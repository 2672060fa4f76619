// heavytop explore: the explorer page (SPEC section 15), one self-contained HTML file with the
// core compiled to WebAssembly inside it, its inputs starting at the body and motion given here
// (--config and the body options; the built-in toy top without them). The page is built by
// Emscripten (web/, the CMake target heavytop_web); this command copies it with that start.
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"

namespace heavytop::cli {
namespace {
namespace fs = std::filesystem;

// The page beside this program (the build tree: build/web/) or where it is installed.
std::optional<fs::path> find_page() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return std::nullopt;
  for (const fs::path& candidate : {self.parent_path() / "web" / "heavytop-explore.html",
                                    self.parent_path().parent_path() / "share" / "heavytop" / "heavytop-explore.html"})
    if (fs::is_regular_file(candidate, ec)) return candidate;
  return std::nullopt;
}

}  // namespace

Action add_explore_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "explore", "Write the explorer page: one self-contained HTML file (the core in WebAssembly) that answers any "
                 "body and spin live in a browser, from file:// with no network");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"html"});
  return [inputs] {
    inputs->resolve();
    if (inputs->output().empty() || inputs->output() == "-")
      throw InvalidInput("--output", "give the page's file, e.g. --output explore.html");
    const auto page = find_page();
    if (!page) throw InvalidInput("explore", io::kExplorerPageMissing);
    std::ifstream in(*page, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const auto html = io::explorer_page(text.str(), inputs->body(), inputs->state());
    if (!in || !html) throw Failure(fmt::format("explore: '{}' is not the explorer page", page->string()));
    write_output(inputs->output(), *html);
  };
}

}  // namespace heavytop::cli

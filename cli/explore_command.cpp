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

constexpr const char* kHowToBuild =
    "this heavytop was built without the explorer page, which needs Emscripten: run ./scripts/build.sh --web "
    "(or configure with -DHEAVYTOP_BUILD_WEB=ON and build the target heavytop_web), then run this again";

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

// The page's starting inputs, as its window.HEAVYTOP_INITIAL (explore.js): the configuration's
// sections as a JavaScript object.
std::string initial_json(const Body& b, const InitialState& s) {
  using io::number;
  return fmt::format(
      "{{\"body\": {{\"A\": {}, \"B\": {}, \"C\": {}, \"mass\": {}, \"gravity\": {}, \"length\": {}}}, "
      "\"motion\": {{\"spin\": {}, \"theta0\": {}, \"phi0\": {}, \"theta_rate0\": {}, \"phi_rate0\": {}}}, "
      "\"damping\": {{\"transverse\": {}, \"axial\": {}, \"friction\": {}}}}}",
      number(b.A), number(b.B), number(b.C), number(b.mass), number(b.gravity), number(b.length), number(s.spin),
      number(s.theta0), number(s.phi0), number(s.theta_rate0), number(s.phi_rate0), number(b.damping.transverse),
      number(b.damping.axial), number(b.damping.friction));
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
    if (!page) throw InvalidInput("explore", kHowToBuild);
    std::ifstream in(*page, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    std::string html = text.str();
    const std::string mark = "/*HEAVYTOP_INITIAL*/null";
    const auto at = html.find(mark);
    if (!in || at == std::string::npos) throw Failure(fmt::format("explore: '{}' is not the explorer page", page->string()));
    html.replace(at, mark.size(), initial_json(inputs->body(), inputs->state()));
    write_output(inputs->output(), html);
  };
}

}  // namespace heavytop::cli

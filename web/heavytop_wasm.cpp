// The core in WebAssembly (SPEC section 15): what the page's window.heavytop calls.
//
// No second front end: each call runs the command line's own command (cli/stability_command.cpp,
// simulate_command.cpp, lifetime_command.cpp, with cli/common.cpp's Inputs and error handling)
// on a configuration file that the page writes into Emscripten's in-memory file system, and
// returns what the command wrote to --output. So the page's JSON is io/'s serialiser's, its
// validation and its one-line messages are the command line's, byte for byte.
//
// Built by web/build.sh (Emscripten, embind) from the same sources as the native library.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cstdio>
#include <functional>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/version.hpp"

namespace {

using namespace heavytop;
using Make = std::function<cli::Action(CLI::App&)>;

// The configuration's name in the in-memory file system (the current folder, "/"), as a
// message that names the file shows it: the browser test runs the command line on a file of
// this name in its current folder, so that the two messages are the same.
constexpr const char* kConfig = "config.toml";
// --output: a file under /dev/, which io::OutputStream writes directly (as it does a device or
// a pipe) rather than through a temporary, a lock and a rename beside it.
constexpr const char* kOutput = "/dev/heavytop-output";

struct Result {
  int status = 0;       // the command line's exit status
  std::string output;   // what it wrote to --output (status 0)
  std::string message;  // what it wrote on stderr: the one-line error, or warnings
};

std::string slurp(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `heavytop COMMAND --config config.toml ARGS... --output heavytop-output`, as cli/app.cpp runs it.
Result run(const char* command, Make make, const std::string& config, std::vector<std::string> args) {
  {
    std::ofstream out(kConfig, std::ios::binary | std::ios::trunc);
    out << config;
  }
  std::ofstream(kOutput, std::ios::binary | std::ios::trunc).close();
  std::vector<std::string> words = {"heavytop", command, "--config", kConfig};
  words.insert(words.end(), args.begin(), args.end());
  words.insert(words.end(), {"--output", kOutput});
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());

  CLI::App app{"heavytop"};
  app.require_subcommand(0, 1);
  cli::Action action = make(app);
  std::ostringstream err;
  std::streambuf* old = std::cerr.rdbuf(err.rdbuf());
  Result r;
  r.status = cli::run_reporting_errors(app, [&] {
    app.parse(static_cast<int>(argv.size()), argv.data());
    action();
    return 0;
  });
  std::cerr.rdbuf(old);
  r.message = err.str();
  while (!r.message.empty() && r.message.back() == '\n') r.message.pop_back();
  if (r.status == 0) r.output = slurp(kOutput);
  return r;
}

emscripten::val to_js(const Result& r) {
  emscripten::val o = emscripten::val::object();
  o.set("status", r.status);
  o.set("output", r.output);
  o.set("message", r.message);
  return o;
}

emscripten::val stability(const std::string& config) {
  return to_js(run("stability", cli::add_stability_command, config, {"--format", "json"}));
}

emscripten::val lifetime(const std::string& config) {
  return to_js(run("lifetime", cli::add_lifetime_command, config, {"--format", "json"}));
}

// args: the simulate flags the page passes (--model, --t-end, --samples), as text.
emscripten::val js_simulate(const std::string& config, const std::vector<std::string>& args) {
  std::vector<std::string> all = args;
  all.insert(all.end(), {"--format", "csv"});
  return to_js(run("simulate", cli::add_simulate_command, config, all));
}

// The page's stability map: `heavytop sweep`'s verdicts (the library's sweep_verdicts, one
// thread) over two axes, one byte per grid point (the first axis slowest): bits 0-2 the linear
// models (first-order, body-fixed, linearized), bit 3 proven Lyapunov stable. The base body
// and state are resolved by the command line's Inputs (the same checks and messages) and the
// grid checked by validate_sweep, as `heavytop sweep` does.
emscripten::val js_stability_map(const std::string& config, const std::string& key_x, double x0, double x1,
                              int nx, const std::string& key_y, double y0, double y1, int ny) {
  static std::vector<unsigned char> bytes;  // alive until the next call: the page copies the view
  bytes.clear();
  const auto make = [&](CLI::App& app) -> cli::Action {
    auto* cmd = app.add_subcommand("sweep", "");
    auto inputs = std::make_shared<cli::Inputs>(*cmd, std::vector<std::string>{"csv"});
    return [&, inputs] {
      inputs->resolve();
      if (nx < 1 || ny < 1) throw InvalidInput("vary", "COUNT must be >= 1");
      const std::vector<SweepAxis> axes = {{key_x, x0, x1, static_cast<std::size_t>(nx)},
                                           {key_y, y0, y1, static_cast<std::size_t>(ny)}};
      SweepOptions options;
      options.threads = 1;
      validate_sweep(inputs->body(), inputs->state(), axes, options);
      const auto verdicts = sweep_verdicts(inputs->body(), inputs->state(), axes, options, 0, grid_size(axes));
      bytes.resize(verdicts.size());
      for (std::size_t i = 0; i < verdicts.size(); ++i)
        bytes[i] = static_cast<unsigned char>(verdicts[i].linear[0] | verdicts[i].linear[1] << 1 |
                                              verdicts[i].linear[2] << 2 | verdicts[i].lyapunov << 3);
      cli::write_output(inputs->output(), "");
    };
  };
  emscripten::val o = to_js(run("sweep", make, config, {}));
  o.set("verdicts", emscripten::val(emscripten::typed_memory_view(bytes.size(), bytes.data())));
  return o;
}

std::string version() { return std::string("heavytop ") + std::string(kVersion); }

}  // namespace

EMSCRIPTEN_BINDINGS(heavytop) {
  emscripten::register_vector<std::string>("StringList");
  emscripten::function("stability", &stability);
  emscripten::function("lifetime", &lifetime);
  emscripten::function("simulate", &js_simulate);
  emscripten::function("stabilityMap", &js_stability_map);
  emscripten::function("version", &version);
}

// The core in WebAssembly (SPEC section 15): what the page's window.heavytop calls.
//
// No second front end: each call runs the command line's own command (cli/stability_command.cpp,
// simulate_command.cpp, lifetime_command.cpp, with cli/common.cpp's Inputs and error handling)
// on a configuration file that the page writes into Emscripten's in-memory file system, and
// returns what the command wrote to --output. So the page's JSON is io/'s serialiser's, its
// validation and its one-line messages are the command line's, byte for byte.
//
// Built by web/Makefile (Emscripten, embind) from the same sources as the native library.
// Compiled natively (the CMake target heavytop_web_bench) it is instead a benchmark of the
// same calls in one process, the native side of the page's figures (web/README.md).
#if defined(__EMSCRIPTEN__)
#include <emscripten/bind.h>
#include <emscripten/val.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>
#include <functional>
#include <optional>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include <nlohmann/json.hpp>

#include "heavytop/frames.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/report/report.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/table.hpp"
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
#if defined(__EMSCRIPTEN__)
constexpr const char* kOutput = "/dev/heavytop-output";
#else
constexpr const char* kOutput = "/dev/shm/heavytop-web-bench-output";
#endif

struct Result {
  int status = 0;       // the command line's exit status
  std::string output;   // what it wrote to --output (status 0)
  std::string message;  // what it wrote on stderr: the one-line error, or warnings
};

// The whole file in one read (a stream's rdbuf() copies it a character at a time).
std::string slurp(const char* path) {
  std::string text;
  if (std::FILE* f = std::fopen(path, "rb")) {
    std::fseek(f, 0, SEEK_END);
    text.resize(static_cast<std::size_t>(std::max(0L, std::ftell(f))));
    std::fseek(f, 0, SEEK_SET);
    text.resize(std::fread(text.data(), 1, text.size(), f));
    std::fclose(f);
  }
  return text;
}

// The most samples the page's simulate() returns: the command line's limit where it holds the
// whole run in memory (`simulate --format json`, cli/simulate_command.cpp), as the page does
// (the CSV's text, then its rows in JavaScript); the command line's CSV streams any number.
constexpr long long kMaxPageSamples = 2'000'000;

// The most integration steps of a page's run (--max-steps, given to the commands that take it; the
// command line's 10^8 are minutes here, the page frozen): about 3 s of the run's slowest step, in
// Node on the built module (web/step_rate.cjs, web/README.md): a damped body's Taylor step 2.85 us,
// DOP853 on a table 2.42 us; DOPRI5, the answer's and lifetime's run on a pivot, 0.23 us.
constexpr long long kPageMaxSteps = 1'000'000;         // simulate, the 3D view, an answer on a table
constexpr long long kPageMaxDopri5Steps = 5'000'000;  // stability and lifetime on a pivot

// The flags the page sets itself (ARGS may not): the configuration's file, the output and its format;
// --help would print the help and succeed with no output.
bool reserved_flag(const std::string& word) {
  for (const char* flag : {"--config", "--output", "--format", "--help", "-h", "--help-all", "--version"})
    if (word == flag || word.starts_with(std::string(flag) + "=")) return true;
  return false;
}

// A refusal as the command line words one (exit status 2, one line naming the key and the rule).
Result refused(const std::string& key, const std::string& rule) {
  Result r;
  r.status = 2;
  r.message = fmt::format("heavytop: error: {}: {}", key, rule);
  return r;
}

// True if `text` is a number above `limit` (anything else is the command's to refuse).
bool above(const std::string& text, double limit) {
  char* end = nullptr;
  const double n = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && n > limit;
}

// The page's options (ARGS: "--flag", "value" pairs) checked before the command runs: no flag the
// page sets itself, --samples within kMaxPageSamples, --max-steps within MAX_STEPS (the command's
// limit; 0: none). Unknown flags are CLI11's to refuse.
std::optional<Result> refuse_page_args(const char* command, const std::vector<std::string>& args, long long max_steps) {
  for (std::size_t i = 0; i < args.size(); i += 2) {
    const std::string& flag = args[i];
    if (reserved_flag(flag))
      return refused(flag, fmt::format("not an option of the page's {}() (the page gives the configuration, the "
                                       "output and its format itself)",
                                       command));
    if (flag == "--samples" && i + 1 < args.size() && above(args[i + 1], kMaxPageSamples))
      return refused("--samples", fmt::format("must be at most {} in the page, which holds the whole run in memory "
                                              "(the command line's --format csv streams any number)",
                                              kMaxPageSamples));
    if (flag == "--max-steps" && max_steps > 0 && i + 1 < args.size() && above(args[i + 1], max_steps))
      return refused("--max-steps", fmt::format("must be at most {} in the page, which a longer run would hold still "
                                                "(the command line's default is 10^8 steps, with a progress bar)",
                                                max_steps));
  }
  return std::nullopt;
}

bool has_flag(const std::vector<std::string>& args, const char* flag) {
  for (std::size_t i = 0; i < args.size(); i += 2)
    if (args[i] == flag) return true;
  return false;
}

// `heavytop COMMAND --config config.toml ARGS... --output heavytop-output`, as cli/app.cpp runs it;
// with `--max-steps MAX_STEPS` when it is > 0, the command takes it and ARGS do not give it.
Result run(const char* command, Make make, const std::string& config, std::vector<std::string> args, long long max_steps = 0) {
  {
    std::ofstream out(kConfig, std::ios::binary | std::ios::trunc);
    out << config;
  }
  std::ofstream(kOutput, std::ios::binary | std::ios::trunc).close();
  CLI::App app{"heavytop"};
  app.require_subcommand(0, 1);
  cli::Action action = make(app);

  std::vector<std::string> words = {"heavytop", command, "--config", kConfig};
  words.insert(words.end(), args.begin(), args.end());
  if (max_steps > 0 && app.get_subcommand(command)->get_option_no_throw("--max-steps") && !has_flag(args, "--max-steps"))
    words.insert(words.end(), {"--max-steps", std::to_string(max_steps)});
  words.insert(words.end(), {"--output", kOutput});
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
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

Result map_verdicts(std::vector<unsigned char>& bytes, const std::string& config, const std::string& key_x, double x0, double x1,
                              int nx, const std::string& key_y, double y0, double y1, int ny) {
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
  return run("sweep", make, config, {});
}

// What the 3D view draws on a table (report/web/src/main.js buildView() with D.table): the view's
// data for the run's attitude (psi from the axial momentum C w3, w3 the run's `spin`), and O's
// position at the samples drawn, P's track at every sample, the tip's and rim's radii. The same
// as the table report's report-data.js (report/src/report.cpp table_view_json(), which the report
// library does not export: were it, this would be one call).
std::string table_view(const Body& body, const Table& table, const Trajectory& run, const std::vector<report::DrawnPart>& parts) {
  const auto column = [&](std::string_view name) -> const std::vector<double>& {
    for (const auto& [key, values] : run.extra)
      if (key == name && values.size() == run.size()) return values;
    throw cli::Failure(fmt::format("a table run needs its '{}' column", name));
  };
  Trajectory attitude = run;
  std::vector<double> axial = column("spin");
  for (double& w : axial) w *= body.C;
  attitude.extra.emplace_back("axial_momentum", std::move(axial));
  nlohmann::json data = nlohmann::json::parse(report::view_data(body, attitude, parts));
  const std::vector<double>&x = column("x"), &y = column("y"), &height = column("height");
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json ox = nlohmann::json::array(), oy = nlohmann::json::array(), oz = nlohmann::json::array();
  for (std::size_t i : report::display_samples(run.size())) {  // O = P + r e_zeta - rho u, as the report
    const Eigen::Vector3d k = axis_frame(run.phi[i], run.theta[i]).col(2);
    const double s = std::hypot(k.x(), k.y());
    const double across = s > 1e-12 ? body.rim_radius * k.z() / s : 0.0;
    ox.push_back(value(x[i] - across * k.x()));
    oy.push_back(value(y[i] - across * k.y()));
    oz.push_back(value(height[i]));
  }
  nlohmann::json tt = nlohmann::json::array(), tx = nlohmann::json::array(), ty = nlohmann::json::array();
  for (std::size_t i = 0; i < run.size(); ++i) {
    tt.push_back(value(run.t[i]));
    tx.push_back(value(x[i]));
    ty.push_back(value(y[i]));
  }
  data["table"] = {{"contact", name(table.contact)},
                   {"tip_radius", body.tip_radius},
                   {"rim_radius", body.rim_radius},
                   {"origin", {{"x", ox}, {"y", oy}, {"z", oz}}},
                   {"track", {{"t", tt}, {"x", tx}, {"y", ty}}}};
  return data.dump();
}

// What the 3D view draws (the report's own view data, report::view_data()): the nonlinear run of
// the configuration's body over t_end (s) at `samples` times, by the integrator `simulate`
// chooses unasked, and the body's parts as the report draws them (a mesh from its file); on a
// table (SPEC section 16) the run on the table, with the table and P's track (table_view()).
Result view_of(const std::string& config, double t_end, int samples) {
  const auto make = [&](CLI::App& app) -> cli::Action {
    auto* cmd = app.add_subcommand("view", "");
    cli::InputUses uses;
    uses.table = true;
    auto inputs = std::make_shared<cli::Inputs>(*cmd, std::vector<std::string>{"json"}, uses);
    return [&, inputs] {
      inputs->resolve();
      if (!(std::isfinite(t_end) && t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
      if (samples < 2) throw InvalidInput("--samples", "must be an integer >= 2");
      if (samples > kMaxPageSamples) throw InvalidInput("--samples", fmt::format("must be at most {} in the page", kMaxPageSamples));
      std::vector<report::DrawnPart> parts;  // as `heavytop report` hands them on (cli/report_command.cpp)
      for (const io::PartSpec& p : inputs->configuration().parts)
        parts.push_back(p.mesh ? report::DrawnPart{.label = p.label, .solid = std::nullopt, .mesh_file = p.file, .scale = p.scale}
                               : report::DrawnPart{.label = p.label, .solid = p.solid, .mesh_file = {}, .scale = 1.0});
      if (const Table& table = inputs->table(); table.on_table()) {
        Tolerances tolerances;
        tolerances.max_steps = kPageMaxSteps;
        const TableRun run = simulate_on_table(inputs->body(), table, inputs->state(),
                                               SampleGrid{t_end, static_cast<std::size_t>(samples)}, tolerances);
        cli::write_output(inputs->output(), table_view(inputs->body(), table, run.trajectory, parts));
        return;
      }
      SimulateOptions options;
      options.integrator = Integrator::Auto;
      options.adaptive.max_steps = options.splitting.max_steps = kPageMaxSteps;
      const Simulation run = simulate(Model::Nonlinear, inputs->body(), inputs->state(),
                                      sample_times(t_end, static_cast<std::size_t>(samples)), options);
      if (!run.summary.ok()) throw cli::Failure(run.summary.message);
      cli::write_output(inputs->output(), report::view_data(inputs->body(), run.trajectory, parts));
    };
  };
  return run("view", make, config, {});
}

#if defined(__EMSCRIPTEN__)
// A setting as the command reads it: ARGS' last FLAG, else the configuration's KEY (nullopt also
// for a configuration that does not parse: the command refuses it before any run).
std::optional<std::string> setting(const std::string& config, const std::vector<std::string>& args, const char* flag,
                                   const char* key) {
  std::optional<std::string> value;
  for (std::size_t i = 0; i + 1 < args.size(); i += 2)
    if (args[i] == flag) value = args[i + 1];
  if (!value) try {
      value = io::parse_configuration(config, kConfig, "--config").string(key);
    } catch (const std::exception&) {
    }
  return value;
}

// COMMAND's step limit in the page, by the integrator of its run: simulate's nonlinear model and a
// table's answer kPageMaxSteps, the DOPRI5 runs of stability and lifetime on a pivot
// kPageMaxDopri5Steps; 0 for simulate's other models, which refuse --max-steps.
long long page_max_steps(const std::string& command, const std::string& config, const std::vector<std::string>& args) {
  if (command == "simulate")
    return setting(config, args, "--model", "simulate.model").value_or("nonlinear") == "nonlinear" ? kPageMaxSteps : 0;
  if (command == "stability" && setting(config, args, "--contact", "table.contact").value_or("pivot") != "pivot")
    return kPageMaxSteps;
  return kPageMaxDopri5Steps;
}

std::string version() { return std::string("heavytop ") + std::string(kVersion); }

// The output as a view of its bytes (UTF-8), alive until the next call: the page decodes it
// with TextDecoder, far faster than embind's conversion of a long std::string.
emscripten::val to_js(const Result& r) {
  static std::string output;
  output = r.output;
  emscripten::val o = emscripten::val::object();
  o.set("status", r.status);
  o.set("output", emscripten::val(emscripten::typed_memory_view(output.size(), output.data())));
  o.set("message", r.message);
  return o;
}

// args: the answer's options the page passes (--horizon, --max-tilt, --lifetime-horizon), as text;
// format: "json" (the object) or "text" (the words, for people).
emscripten::val stability(const std::string& config, const std::vector<std::string>& args, const std::string& format) {
  const long long max_steps = page_max_steps("stability", config, args);
  if (auto no = refuse_page_args("stability", args, max_steps)) return to_js(*no);
  std::vector<std::string> all = args;
  all.insert(all.end(), {"--format", format});
  return to_js(run("stability", cli::add_stability_command, config, all, max_steps));
}

emscripten::val js_lifetime(const std::string& config) {
  return to_js(run("lifetime", cli::add_lifetime_command, config, {"--format", "json"}, page_max_steps("lifetime", config, {})));
}

// `heavytop body --format json`: the body's mass properties (of its parts, meshes read from the
// in-memory file system, where the page puts a dropped file).
emscripten::val body(const std::string& config) {
  return to_js(run("body", cli::add_body_command, config, {"--format", "json"}));
}

emscripten::val js_view(const std::string& config, double t_end, int samples) { return to_js(view_of(config, t_end, samples)); }

// args: the simulate flags the page passes (--model, --t-end, --samples), as text.
emscripten::val js_simulate(const std::string& config, const std::vector<std::string>& args) {
  const long long max_steps = page_max_steps("simulate", config, args);
  if (auto no = refuse_page_args("simulate", args, max_steps)) return to_js(*no);
  std::vector<std::string> all = args;
  all.insert(all.end(), {"--format", "csv"});
  return to_js(run("simulate", cli::add_simulate_command, config, all, max_steps));
}

emscripten::val js_stability_map(const std::string& config, const std::string& key_x, double x0, double x1,
                                 int nx, const std::string& key_y, double y0, double y1, int ny) {
  static std::vector<unsigned char> bytes;  // alive until the next call: the page copies the view
  emscripten::val o = to_js(map_verdicts(bytes, config, key_x, x0, x1, nx, key_y, y0, y1, ny));
  o.set("verdicts", emscripten::val(emscripten::typed_memory_view(bytes.size(), bytes.data())));
  return o;
}

}  // namespace

EMSCRIPTEN_BINDINGS(heavytop) {
  // stderr is not a terminal here: the commands' progress bars (cli/common.hpp) stay off and do
  // not read the clock at every step. Their messages reach std::cerr, which run() captures.
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) ::dup2(null, STDERR_FILENO);
  emscripten::register_vector<std::string>("StringList");
  emscripten::function("stability", &stability);
  emscripten::function("lifetime", &js_lifetime);
  emscripten::function("body", &body);
  emscripten::function("view", &js_view);
  emscripten::function("simulate", &js_simulate);
  emscripten::function("stabilityMap", &js_stability_map);
  emscripten::function("version", &version);
}

#else  // native: the benchmark of the same calls (heavytop_web_bench)

double median_ms(int n, const std::function<void(int)>& f) {
  std::vector<double> t;
  for (int i = 0; i < n; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f(i);
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
std::string toy(double spin) {
  return fmt::format("[body]\nA = 4.35e-05\nB = 4.35e-05\nC = 1.2e-05\nmass = 0.06\nlength = 0.025\ngravity = 9.81\n"
                     "[motion]\nspin = {}\ntheta0 = 0.05\nphi0 = 0.0\n", spin);
}

}  // namespace

// The page's benchmark (web/explore.js benchmark()) natively: the same calls, medians in ms.
int main() {
  char folder[] = "/dev/shm/heavytop-web-bench-XXXXXX";  // memory, as the page's file system
  if (!::mkdtemp(folder) || ::chdir(folder) != 0) return 1;
  std::vector<unsigned char> bytes;
  const auto ok = [](const Result& r) { if (r.status != 0) throw std::runtime_error(r.message); };
  const double verdict = median_ms(51, [&](int i) { ok(run("stability", cli::add_stability_command, toy(100.0 + i), {"--format", "json"})); });
  if (std::getenv("HEAVYTOP_BENCH_VERDICT_ONLY")) return std::printf("{\"verdict_ms\": %.3f}\n", verdict) < 0;
  const double simulate = median_ms(11, [&](int) {
    ok(run("simulate", cli::add_simulate_command, toy(200.0), {"--model", "nonlinear", "--t-end", "10", "--samples", "1001", "--format", "csv"}));
  });
  const double map = median_ms(5, [&](int) { ok(map_verdicts(bytes, toy(200.0), "spin", 0, 400, 200, "B/A", 0.75, 1.25, 200)); });
  std::printf("{\"verdict_ms\": %.3f, \"toy_top_10s_1001_ms\": %.3f, \"map_200x200_ms\": %.3f}\n", verdict, simulate, map);
  std::remove("config.toml");
  std::remove(kOutput);
  ::rmdir(folder);
  return 0;
}
#endif

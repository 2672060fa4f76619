// heavytop sweep: a stability map over one or two parameters, resumable when written to a file.
//
// With --output FILE the rows go to FILE.partial as they are computed (in grid order, whole
// lines), beside FILE.partial.args, which records the arguments. Run again with the same
// arguments after an interruption and it goes on from the last complete row; at the end
// FILE.partial is renamed to FILE. Nothing is lost or written twice.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <functional>
#include <sstream>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::cli {
namespace {

struct SweepSettings {
  std::vector<std::string> vary;
  std::string model;
  std::string integrator = "auto";
  SweepOptions options;
};

/// Everything the rows depend on, in one line: a resumed sweep must have the same.
std::string fingerprint(const Inputs& in, const std::vector<SweepAxis>& axes, const SweepOptions& o) {
  const Body& b = in.body();
  const InitialState& s = in.state();
  std::string f = fmt::format("heavytop-sweep-v3 body {} {} {} {} {} {} state {} {} {} {} {}", b.A, b.B, b.C, b.mass,
                              b.gravity, b.length, s.spin, s.theta0, s.phi0, s.theta_rate0, s.phi_rate0);
  for (const auto& a : axes) f += fmt::format(" vary {}={}:{}:{}", a.key, a.start, a.stop, a.count);
  if (o.nonlinear)
    f += fmt::format(" nonlinear {} {} {} {} {}", o.horizon, o.max_tilt, o.integrator.rtol, o.integrator.atol,
                     name(o.nonlinear_integrator));
  return f + "\n";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "A stability map: each model's verdict over a grid of one or two parameters");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"csv"});
  auto s = std::make_shared<SweepSettings>();
  cmd->add_option("--vary", s->vary, "KEY=START:STOP:COUNT, KEY a body key, spin, spin_rpm (rpm; the CSV keeps spin in rad/s), B/A or C/A (once or twice)")
      ->required()
      ->expected(1, 2)
      ->take_all();
  cmd->add_option("--model", s->model, "nonlinear: add the column `nonlinear`, the verdict of a simulation")
      ->check(CLI::IsMember({"nonlinear"}));
  cmd->add_option("--horizon", s->options.horizon, "s, simulated time of each nonlinear run")->default_str("100");
  cmd->add_option("--max-tilt", s->options.max_tilt, "rad, a nonlinear run is stable if its tilt stays below")->default_str("0.5");
  cmd->add_option("--integrator", s->integrator,
                  "nonlinear: auto (batched Taylor series, the default), taylor (the same), dopri5 or dop853 (one point at a time)")
      ->check(CLI::IsMember({"auto", "taylor", "dopri5", "dop853"}))
      ->default_str("auto");
  cmd->add_option("--rtol", s->options.integrator.rtol, "nonlinear: relative tolerance per step");
  cmd->add_option("--atol", s->options.integrator.atol, "nonlinear: absolute tolerance per step");
  cmd->add_option("--max-steps", s->options.integrator.max_steps,
                  "nonlinear: the most integration steps one point's run may take")
      ->default_str(fmt::format("{}", s->options.integrator.max_steps));
  return [inputs, s] {
    inputs->resolve();
    if (s->vary.size() > 2) throw InvalidInput("--vary", "give one or two parameters");
    std::vector<SweepAxis> axes;
    for (const auto& v : s->vary) axes.push_back(parse_sweep_axis(v));
    s->options.nonlinear = s->model == "nonlinear";
    s->options.nonlinear_integrator = *integrator_from_name(s->integrator);
    validate_sweep(inputs->body(), inputs->state(), axes, s->options);

    const std::size_t total = grid_size(axes);
    const std::string path = io::resolved(inputs->output());
    const std::string partial = path + ".partial", args_file = path + ".partial.args";
    const std::string args = fingerprint(*inputs, axes, s->options);
    const std::string head = io::sweep_csv_header(axes, s->options.nonlinear);

    // Rows in chunks of grid order: each computed in parallel, then appended whole.
    const std::size_t chunk = std::clamp<std::size_t>(total / 200, s->options.nonlinear ? 8 : 256, 20000);
    ProgressBar progress("sweep", static_cast<double>(total));
    auto compute = [&](std::size_t done, const std::function<void(const std::string&)>& write) {
      for (; done < total; progress.update(static_cast<double>(done))) {
        const std::size_t end = std::min(total, done + chunk);
        write(io::sweep_csv_rows(axes, done, sweep_verdicts(inputs->body(), inputs->state(), axes, s->options, done, end)));
        done = end;
      }
    };
    if (!io::is_regular_target(path)) {  // stdout, a device or a pipe: written directly
      io::OutputStream out(path, "--output");
      out.write(head);
      compute(0, [&](const std::string& rows) { out.write(rows); });
      out.commit();
      return;
    }

    const io::OutputLock lock(path, "--output");  // one sweep per output at a time: a second is refused
    namespace fs = std::filesystem;
    std::size_t done = 0;
    if (fs::exists(partial) && fs::exists(args_file) && read_file(args_file) == args) {
      std::string content = read_file(partial);
      content.erase(content.rfind('\n') == std::string::npos ? 0 : content.rfind('\n') + 1);  // drop a torn line
      if (content.starts_with(head)) {
        done = static_cast<std::size_t>(std::count(content.begin(), content.end(), '\n')) - 1;
        fs::resize_file(partial, content.size());
      }
    }
    if (done == 0) {
      write_output(args_file, args);
      write_output(partial, head);
    } else {
      std::cerr << fmt::format("heavytop: resuming the sweep at row {} of {} ({})\n", done + 1, total, partial);
    }
    std::FILE* out = std::fopen(partial.c_str(), "ab");
    if (!out) throw Failure(fmt::format("--output: cannot write '{}'", partial));
    compute(done, [&](const std::string& rows) {
      // Whole chunks, flushed: an interrupted sweep leaves complete rows (at most one torn line).
      if (std::fwrite(rows.data(), 1, rows.size(), out) != rows.size() || std::fflush(out) != 0)
        throw Failure(fmt::format("--output: cannot write '{}'", partial));
    });
    if (std::fclose(out) != 0) throw Failure(fmt::format("--output: cannot write '{}'", partial));
    io::copy_mode(path, partial);
    if (std::rename(partial.c_str(), path.c_str()) != 0)
      throw Failure(fmt::format("--output: cannot replace '{}'", path));
    std::error_code ignored;
    fs::remove(args_file, ignored);
  };
}

}  // namespace heavytop::cli

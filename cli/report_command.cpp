// heavytop report: the report folder (heavytop_report) for the body and motion given.
#include <cmath>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/report/report.hpp"

namespace heavytop::cli {

Action add_report_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("report", "Write DIR/report.html with figures (PNG, SVG) and data (CSV, JSON)");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"html"});
  auto t_end = std::make_shared<double>(0.0);
  auto* t_end_option = cmd->add_option("--t-end", *t_end, "s, horizon of the motion (default: a few precession periods)");
  return [inputs, t_end, t_end_option] {
    inputs->resolve();
    if (inputs->output().empty() || inputs->output() == "-") throw InvalidInput("--output", "give the report's folder, e.g. --output report");
    if (t_end_option->count() && !(std::isfinite(*t_end) && *t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    report::write_report(inputs->output(), inputs->body(), inputs->state(),
                 t_end_option->count() ? std::optional<double>(*t_end) : std::nullopt);
    std::cout << "heavytop: wrote " << (std::filesystem::path(inputs->output()) / "report.html").string() << "\n";
  };
}

}  // namespace heavytop::cli

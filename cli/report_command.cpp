// heavytop report: the report folder (heavytop_report) for the body and motion given.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/report/report.hpp"
#include "heavytop/table.hpp"

#include <fmt/format.h>

namespace heavytop::cli {

Action add_report_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("report", "Write DIR/report.html with figures (PNG, SVG) and data (CSV, JSON)");
  InputUses uses;
  uses.table = true;  // SPEC section 16: a body on a table has its own report (write_table_report)
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"html"}, uses);
  auto t_end = std::make_shared<double>(0.0);
  auto* t_end_option = cmd->add_option("--t-end", *t_end, "s, horizon of the motion (default: a few precession periods; on a table twice the "
                                                              "answer's event, else its horizon up to 10 s)");
  auto map_file = std::make_shared<std::string>();
  auto slices = std::make_shared<std::string>();
  cmd->add_option("--map", *map_file, "a sweep's output (CSV or HDF5) to draw: two keys whole, three as slices");
  cmd->add_option("--slice", *slices,
                  "KEY=V1[,V2...]: the key a three-key map's heat maps hold, at its grid values nearest these "
                  "(default: the last key at its first, middle and last values)");
  return [inputs, t_end, t_end_option, map_file, slices] {
    inputs->resolve();
    if (inputs->output().empty() || inputs->output() == "-") throw InvalidInput("--output", "give the report's folder, e.g. --output report");
    if (t_end_option->count() && !(std::isfinite(*t_end) && *t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    std::optional<report::ReportMap> map;
    if (inputs->table().on_table() && !map_file->empty())
      throw InvalidInput("--map", fmt::format("a stability map is drawn for a pivot; on a table (contact = \"{}\") the "
                                              "report has no map",
                                              name(inputs->table().contact)));
    if (!map_file->empty()) {
      map = report::ReportMap{.file = *map_file, .map = io::read_map(*map_file, "--map"), .held = {}, .values = {}};
      if (!slices->empty()) {
        const auto eq = slices->find('=');
        if (eq == std::string::npos || eq == 0) throw InvalidInput("--slice", "must be KEY=V1[,V2...]");
        map->held = slices->substr(0, eq);
        std::string_view list = std::string_view(*slices).substr(eq + 1);
        for (;;) {
          const auto comma = std::min(list.find(','), list.size());
          double v = 0.0;
          const std::string_view cell = list.substr(0, comma);
          const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
          if (error != std::errc() || end != cell.data() + cell.size() || !std::isfinite(v))
            throw InvalidInput("--slice", fmt::format("'{}' is not a finite number (KEY=V1[,V2...])", io::printable(cell)));
          map->values.push_back(v);
          if (comma == list.size()) break;
          list.remove_prefix(comma + 1);
        }
      }
    } else if (!slices->empty()) {
      throw InvalidInput("--slice", "needs --map FILE");
    }
    // A body of parts is drawn as those parts (a mesh from its own file).
    std::vector<report::DrawnPart> parts;
    for (const io::PartSpec& p : inputs->configuration().parts)
      parts.push_back(p.mesh ? report::DrawnPart{.label = p.label, .solid = std::nullopt, .mesh_file = p.file, .scale = p.scale}
                             : report::DrawnPart{.label = p.label, .solid = p.solid, .mesh_file = {}, .scale = 1.0});
    const std::string source = inputs->builtin_example()     ? std::string()
                               : inputs->config_path().empty() ? std::string("A body given on the command line")
                                                               : inputs->config_path();
    const std::optional<double> horizon = t_end_option->count() ? std::optional<double>(*t_end) : std::nullopt;
    if (inputs->table().on_table())  // SPEC section 16
      report::write_table_report(inputs->output(), inputs->body(), inputs->table(), inputs->state(), horizon, source, parts);
    else
      report::write_report(inputs->output(), inputs->body(), inputs->state(), horizon, map, source, parts);
    std::cout << "heavytop: wrote " << (std::filesystem::path(inputs->output()) / "report.html").string() << "\n";
  };
}

}  // namespace heavytop::cli

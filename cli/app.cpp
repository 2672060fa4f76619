// heavytop: the command-line tool. Thin: parses, calls the library, formats. main.cpp calls
// run(); so does the fuzz target fuzz/fuzz_cli.cpp.
#include "app.hpp"

#include <filesystem>
#include <string_view>
#include <iostream>
#include <new>
#include <map>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/report.hpp"

namespace heavytop::cli {

int run(int argc, char** argv) {
  CLI::App app{"heavytop: the heavy top (a rigid body about a fixed point in gravity), its "
               "approximate models, their stability and motion.\nUnits SI; conventions in SPEC.md. With no command, "
               "writes the built-in example's report to ./heavytop-report."};
  app.require_subcommand(0, 1);
  std::map<CLI::App*, cli::Action> actions;
  auto add = [&](cli::Action (*make)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    cli::Action action = make(app);
    actions[app.get_subcommands({}).at(before)] = std::move(action);
  };
  add(cli::add_stability_command);
  add(cli::add_lifetime_command);
  add(cli::add_simulate_command);
  // derive lives in its own program, heavytop-derive, so that no other command pays for
  // loading the computer algebra (GiNaC, CLN, GMP) at start-up; listed here for --help.
  app.add_subcommand("derive", "Derive the paper's models symbolically: M q'' + G q' + K q = 0, its characteristic "
                               "polynomial and stability condition (`heavytop derive --help`)")
      ->allow_extras();
  if (argc > 1 && std::string_view(argv[1]) == "derive") return run_derive(argc, argv, false);
  add(cli::add_compare_command);
  add(cli::add_sweep_command);
  add(cli::add_report_command);
  add(cli::add_body_command);
  add(cli::add_precession_command);
  add(cli::add_fit_decay_command);

  io::remove_temporaries_on_signals();
  return run_reporting_errors(app, [&] {
    app.parse(argc, argv);
    for (auto& [command, action] : actions)
      if (command->parsed()) {
        action();
        return 0;
      }
    // No command: the report for the built-in example, a toy top.
    const std::string dir = "heavytop-report";
    std::cout << "heavytop: the built-in example, a wooden toy top (60 g, 40 mm disc, centre of mass 25 mm "
                 "above the tip) spun at 200 rad/s, started 0.05 rad off vertical.\n";
    report::write_report(dir, example_toy_top(), example_motion(), std::nullopt);
    std::cout << "heavytop: wrote " << dir << "/report.html (open it in a browser); "
              << "`heavytop --help` lists the commands.\n";
    return 0;
  });
}


}  // namespace heavytop::cli

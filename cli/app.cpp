// heavytop: the command-line tool. Thin: parses, calls the library, formats. main.cpp calls
// run(); so does the fuzz target fuzz/fuzz_cli.cpp.
#include "app.hpp"

#include <algorithm>
#include <filesystem>
#include <string_view>
#include <iostream>
#include <new>
#include <map>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/body.hpp"
#include "heavytop/version.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/report.hpp"

namespace heavytop::cli {

int run(int argc, char** argv) {
  const std::string_view first = argc > 1 ? argv[1] : "";
  // derive lives in its own program, heavytop-derive, so that no other command pays for
  // loading the computer algebra (GiNaC, CLN, GMP) at start-up; listed below for --help.
  if (first == "derive") return run_derive(argc, argv, false);
  CLI::App app{"heavytop: does a spinning top stay up, and for how long? The heavy top (a rigid body about a "
               "fixed point in gravity), its approximate models, their stability and motion.\nUnits SI (rad/s, "
               "or rpm with --spin-rpm); the contract is docs/contract.md. With no command, writes the built-in "
               "example's report to ./heavytop-report and says where."};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", fmt::format("heavytop {}", kVersion), "print `heavytop VERSION` and exit");
  // When argv[1] names a command, only that command's options are built: building all five
  // commands' (CLI11 checks each new option's names against the command's others) was 60% of
  // the instructions of `heavytop stability` (callgrind). Anything else (no command, --help, a
  // misspelt command) builds all of them, for the full help and errors.
  using Make = cli::Action (*)(CLI::App&);
  static constexpr std::pair<std::string_view, Make> kCommands[] = {
      {"stability", cli::add_stability_command},   {"lifetime", cli::add_lifetime_command},
      {"simulate", cli::add_simulate_command},     {"compare", cli::add_compare_command},
      {"sweep", cli::add_sweep_command},           {"report", cli::add_report_command},
      {"body", cli::add_body_command},             {"precession", cli::add_precession_command},
      {"fit-decay", cli::add_fit_decay_command},
      {"explore", cli::add_explore_command},
      {"chaos", cli::add_chaos_command},
  };
  const bool one = std::any_of(std::begin(kCommands), std::end(kCommands),
                               [&](const auto& c) { return c.first == first; });
  std::map<CLI::App*, cli::Action> actions;
  auto add = [&](std::string_view command, cli::Action (*make)(CLI::App&)) {
    if (one && command != first) return;
    const std::size_t before = app.get_subcommands({}).size();
    cli::Action action = make(app);
    actions[app.get_subcommands({}).at(before)] = std::move(action);
  };
  for (const auto& [command, make] : kCommands) {
    add(command, make);
    if (command == "simulate" && !one)  // derive after simulate in the help, as before
      app.add_subcommand("derive", "Derive the paper's models symbolically: M q'' + G q' + K q = 0, its characteristic "
                                   "polynomial and stability condition (`heavytop derive --help`)")
          ->allow_extras();
  }

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
    // The answer first, then what it is about and where the report went.
    std::cout << io::answer_text(analyse_top(example_toy_top(), example_motion()).answer) << "\n";
    std::cout << "heavytop: that is the built-in example, a wooden toy top (60 g, 40 mm disc, centre of mass "
                 "25 mm above the tip) spun at 200 rad/s, started 0.05 rad off vertical.\n";
    report::write_report(dir, example_toy_top(), example_motion(), std::nullopt);
    std::cout << "heavytop: wrote " << dir << "/report.html (open it in a browser); "
              << "`heavytop --help` lists the commands.\n";
    return 0;
  });
}


}  // namespace heavytop::cli

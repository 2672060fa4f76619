// heavytop: the command-line tool. Thin: parses, calls the library, formats.
#include <filesystem>
#include <iostream>
#include <new>
#include <map>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/report.hpp"

int main(int argc, char** argv) {
  using namespace heavytop;
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
  add(cli::add_simulate_command);
  add(cli::add_derive_command);
  add(cli::add_compare_command);
  add(cli::add_sweep_command);
  add(cli::add_report_command);

  io::remove_temporaries_on_signals();
  try {
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
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << fmt::format("heavytop: error: {}\n", e.what());
    return 2;
  } catch (const InvalidInput& e) {
    std::cerr << fmt::format("heavytop: error: {}: {}\n", cli::flag_of(e.key()), e.rule());
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "heavytop: error: out of memory (fewer --samples, or --format csv, which streams)\n";
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {  // its what() is the library's wording
    std::cerr << fmt::format("heavytop: error: cannot use '{}': {}\n", e.path1().string(), e.code().message());
    return 1;
  } catch (const std::exception& e) {
    std::cerr << fmt::format("heavytop: error: {}\n", e.what());
    return 1;
  }
}

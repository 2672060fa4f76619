#pragma once
// Each heavytop command registers itself on the application and returns the action to run
// once the command line has been parsed. Actions throw InvalidInput (exit 2) or Failure (1).

#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::cli {

using Action = std::function<void()>;

Action add_stability_command(CLI::App& app);
Action add_simulate_command(CLI::App& app);
Action add_derive_command(CLI::App& app);  ///< in heavytop-derive only (derive_main.cpp)
Action add_compare_command(CLI::App& app);
Action add_sweep_command(CLI::App& app);
Action add_report_command(CLI::App& app);
Action add_lifetime_command(CLI::App& app);
Action add_body_command(CLI::App& app);
Action add_precession_command(CLI::App& app);
Action add_fit_decay_command(CLI::App& app);
Action add_explore_command(CLI::App& app);
Action add_chaos_command(CLI::App& app);

}  // namespace heavytop::cli

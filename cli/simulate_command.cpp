// placeholder
#include "commands.hpp"
namespace heavytop::cli { Action add_simulate_command(CLI::App& app) { app.add_subcommand("simulate", "(being written)"); return []{}; } }

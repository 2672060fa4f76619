// placeholder
#include "commands.hpp"
namespace heavytop::cli { Action add_derive_command(CLI::App& app) { app.add_subcommand("derive", "(being written)"); return []{}; } }

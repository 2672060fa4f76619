// heavytop: the command-line tool (cli/app.cpp).
#include <string_view>

#include "app.hpp"
#include "common.hpp"

int main(int argc, char** argv) {
  // derive: straight into heavytop-derive, this process replaced (no second start-up).
  if (argc > 1 && std::string_view(argv[1]) == "derive") return heavytop::cli::run_derive(argc, argv, true);
  return heavytop::cli::run(argc, argv);
}

// heavytop-derive: `heavytop derive`, in a program of its own so that only it loads the
// computer algebra (GiNaC, CLN, GMP); heavytop runs it with the same arguments.
#include "commands.hpp"
#include "common.hpp"

int main(int argc, char** argv) {
  using namespace heavytop::cli;
  CLI::App app{"heavytop derive: the paper's models derived symbolically (GiNaC)"};
  app.name("heavytop");
  app.require_subcommand(1, 1);
  const Action derive = add_derive_command(app);
  return run_reporting_errors(app, [&] {
    app.parse(argc, argv);
    derive();
    return 0;
  });
}

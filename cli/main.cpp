// heavytop: the command-line tool (cli/app.cpp).
#include <string_view>

#include "app.hpp"
#include "common.hpp"

int main(int argc, char** argv) {
  // derive: straight into heavytop-derive, this process replaced (no second start-up).
  if (argc > 1 && std::string_view(argv[1]) == "derive") return heavytop::cli::run_derive(argc, argv, true);
  // sweep started by mpirun or srun: into heavytop-mpi, which shares the grid among the ranks.
  if (argc > 1 && std::string_view(argv[1]) == "sweep" && heavytop::cli::mpi_launch_size() > 0)
    if (const int status = heavytop::cli::run_sweep_under_mpi(argc, argv, true); status >= 0) return status;
  return heavytop::cli::run(argc, argv);
}

// heavytop-mpi: `heavytop sweep` across the ranks of an MPI job. `mpirun -n N heavytop sweep
// ...` starts N copies of heavytop, and each replaces itself with this program (cli/main.cpp)
// keeping its arguments and environment, so the MPI library (linked only here, not into
// heavytop's start-up) finds its job. The sweep command is heavytop's own; only where its
// blocks are computed differs (mpi_distribution.hpp).
#include <mpi.h>

#include <cstdio>
#include <string_view>

#include "app.hpp"
#include "mpi_distribution.hpp"

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  heavytop::mpi::MpiDistribution distribution;
  int status = 0;
  if (argc < 2 || std::string_view(argv[1]) != "sweep") {
    if (distribution.rank() == 0)
      std::fputs("heavytop: error: heavytop-mpi runs `heavytop sweep` only (mpirun -n N heavytop sweep ...)\n", stderr);
    status = 2;
  } else {
    distribution.capture_stderr();
    heavytop::cli::set_sweep_distribution(&distribution);
    status = heavytop::cli::run(argc, argv);
    heavytop::cli::set_sweep_distribution(nullptr);
  }
  status = distribution.finish(status);
  MPI_Finalize();
  return status;
}

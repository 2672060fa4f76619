#pragma once
// A sweep shared among the ranks of an MPI job. Rank 0 hands out blocks of grid points on
// request (dynamic distribution: nonlinear points differ a hundredfold in cost), computes
// blocks itself in a second thread, and writes the verdicts in grid order as they become
// contiguous; the other ranks compute the blocks they are given and send back the packed
// verdicts (io::pack_verdicts). Only rank 0 touches files, so the output, the resume and the
// exit status are the serial sweep's. Only the main thread of each rank calls MPI
// (MPI_THREAD_FUNNELED).

#include <cstdio>
#include <vector>

#include "sweep_distribution.hpp"

namespace heavytop::mpi {

class MpiDistribution final : public cli::SweepDistribution {
 public:
  /// After MPI_Init: this rank, the job's size, and the threads each rank should use.
  MpiDistribution();

  bool writes() const override { return rank_ == 0; }
  unsigned threads() const override { return threads_; }
  void run(std::size_t begin, std::size_t total, std::size_t block, const cli::ComputeBlock& compute,
           const cli::WriteBlock& write) const override;

  /// At the end of this rank's command, `status` its exit status: on rank 0, releases every
  /// rank still waiting for work and collects each rank's first word (a failure there makes
  /// the job fail with that rank's message and status); on the others, reports a failure
  /// before or during the work to rank 0. Returns the status this process should exit with.
  int finish(int status);

  int rank() const { return rank_; }
  /// Where this rank's messages go: stderr on rank 0; on the others, a buffer sent to rank 0
  /// on failure (so that an input error shows once, not once per rank).
  void capture_stderr();

 private:
  int rank_ = 0;
  int size_ = 1;
  unsigned threads_ = 1;
  mutable bool served_ = false;    // a worker: it entered run(); rank 0: the work is complete
  mutable bool failed_ = false;    // rank 0: run() began and did not complete
  mutable std::vector<char> heard_;    // rank 0: each rank's first word has arrived
  mutable std::vector<char> stopped_;  // rank 0: each rank has been told to stop
  std::FILE* captured_ = nullptr;  // a worker's stderr
};

}  // namespace heavytop::mpi

#pragma once
// Where a sweep's grid points are computed: in this process (threads on every core), or
// shared among the ranks of an MPI job (heavytop-mpi, mpi/). The sweep command is the same
// either way: it asks its distribution for the verdicts in grid order and writes them, so the
// output, the resume from FILE.partial and the exit status do not depend on which it is.

#include <cstddef>
#include <functional>
#include <vector>

#include "heavytop/sweep.hpp"

namespace heavytop::cli {

/// The verdicts of grid points [begin, end), in grid order.
using ComputeBlock = std::function<std::vector<SweepVerdict>(std::size_t begin, std::size_t end)>;
/// Takes the verdicts of the block that starts at grid point `begin`: called with the blocks
/// in grid order, each once, on the writing process only.
using WriteBlock = std::function<void(std::size_t begin, std::vector<SweepVerdict> verdicts)>;

/// Runs a sweep's blocks. This one, the default, computes them here, one after another (each
/// block in parallel on every core, sweep_verdicts).
class SweepDistribution {
 public:
  virtual ~SweepDistribution() = default;
  /// True on the one process that reads and writes files (every process of a serial run).
  virtual bool writes() const { return true; }
  /// Threads for each block's points in this process (SweepOptions::threads; 0: one per core).
  virtual unsigned threads() const { return 0; }
  /// Computes grid points [begin, total) in blocks of at most `block` points and hands each
  /// block's verdicts to `write` in grid order (on the writing process). A process that does
  /// not write computes what it is given and ignores begin and total.
  virtual void run(std::size_t begin, std::size_t total, std::size_t block, const ComputeBlock& compute,
                   const WriteBlock& write) const;
};

/// The distribution the sweep command uses: the serial one unless another was installed.
const SweepDistribution& sweep_distribution();
/// Installs `distribution` (not owned; must outlive the sweep; nullptr restores the serial one).
void set_sweep_distribution(const SweepDistribution* distribution);

}  // namespace heavytop::cli

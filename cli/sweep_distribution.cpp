#include "sweep_distribution.hpp"

#include <algorithm>

namespace heavytop::cli {
namespace {
const SweepDistribution kSerial;
const SweepDistribution* installed = &kSerial;
}  // namespace

void SweepDistribution::run(std::size_t begin, std::size_t total, std::size_t block, const ComputeBlock& compute,
                            const WriteBlock& write) const {
  for (std::size_t end; begin < total; begin = end) {
    end = std::min(total, begin + block);
    write(begin, compute(begin, end));
  }
}

const SweepDistribution& sweep_distribution() { return *installed; }

void set_sweep_distribution(const SweepDistribution* distribution) {
  installed = distribution ? distribution : &kSerial;
}

}  // namespace heavytop::cli

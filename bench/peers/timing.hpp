#pragma once
// The peers' benchmarks' timing (peers.cpp, paired.cpp, maps.cpp): CPU time, medians, and the
// warm-up before a timed run.

#include <algorithm>
#include <ctime>
#include <vector>

namespace peers {

// s, CPU time of this thread: on a machine shared with other jobs wall time measures the
// others as much as the method.
inline double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Untimed runs of a method before its timed one, until 1 ms of CPU time has gone into them (at
// least one run): each method then starts warm, with its code and data in the caches, not those
// of the method before it, and with the processor's vector units in the state its own code
// leaves them. The last matters for code with 256-bit instructions (heavytop's AVX2
// recurrence, and GSL's through glibc's memcpy): on this VM a run after more than ~1 ms without
// any took 2-3x its warm time (docs/performance.md, "The wide units' warm-up"); heavytop with
// its SSE2 recurrence, 1.1x. One warm-up run was not enough for a 44 us run.
template <class Run>
void warm_up(const Run& run) {
  const double start = cpu_seconds();
  do run();
  while (cpu_seconds() - start < 1e-3);
}

}  // namespace peers

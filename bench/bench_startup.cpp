// The cost of one call of the built command, start-up included, as scripts pay it (they call
// heavytop once per body). Each iteration spawns the binary once, its output to /dev/null, and
// waits for it. Reported per call:
//   real time   wall time, spawn to exit (Google Benchmark's manual time: the mean)
//   cpu_ms      CPU time of the child, user + system, from wait4()'s rusage: the median of the
//               run's calls (ms), robust to the odd call slowed by a busy machine
//   wall_ms     the median of the calls' wall times (ms)
// (rusage's split into user and system time is by clock ticks, meaningless for a 1 ms process:
// only their sum is reported.) Call/floor runs bench/startup_floor, a static program that
// returns at once: what any process costs on this machine at this moment, for reference.
// Run: build/bench/bench_startup --heavytop=build/heavytop --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (medians over repetitions of 100 calls)

#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "spawn.hpp"

namespace {

using heavytop::bench::Cost;
using heavytop::bench::median_ms;
using heavytop::bench::run_once;

std::string g_heavytop = "heavytop";
std::string g_floor = "startup_floor";

void Call(benchmark::State& state, const std::string* program, std::vector<std::string> args) {
  std::vector<double> cpu, wall;
  for (auto _ : state) {
    Cost c;
    if (!run_once(*program, args, c)) {
      state.SkipWithError("the command failed (is --heavytop=PATH right?)");
      return;
    }
    cpu.push_back(c.cpu);
    wall.push_back(c.wall);
    state.SetIterationTime(c.wall);
  }
  state.counters["cpu_ms"] = median_ms(cpu);
  state.counters["wall_ms"] = median_ms(wall);
}

}  // namespace

BENCHMARK_CAPTURE(Call, stability_json, &g_heavytop, {"stability", "--format", "json"})->UseManualTime()->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Call, simulate_first_order_101, &g_heavytop, {"simulate", "--model", "first-order", "--samples", "101"})
    ->UseManualTime()->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Call, simulate_nonlinear_1ms, &g_heavytop, {"simulate", "--model", "nonlinear", "--t-end", "1e-3"})
    ->UseManualTime()->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Call, derive, &g_heavytop, {"derive"})->UseManualTime()->Iterations(20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Call, floor, &g_floor, {})->UseManualTime()->Iterations(100)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  // --heavytop=PATH: the binary to time (default: heavytop beside this benchmark's build tree).
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--heavytop=", 11) == 0) g_heavytop = argv[i] + 11;
    else rest.push_back(argv[i]);
  }
  const auto here = std::filesystem::canonical("/proc/self/exe").parent_path();
  if (g_heavytop == "heavytop") g_heavytop = (here.parent_path() / "heavytop").string();
  g_floor = (here / "startup_floor").string();
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

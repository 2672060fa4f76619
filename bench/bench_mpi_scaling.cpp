// Strong scaling of `heavytop sweep` under MPI: the same map with 1 and 2 ranks, one core each
// (mpirun --bind-to core: heavytop-mpi then uses one thread per rank), whole commands as a
// user runs them (mpirun's start-up included). Reported per map:
//   real time        wall time of the command (Google Benchmark's manual time)
//   points_per_s     grid points per second of wall time
//   per_core_point_ms ms of one core per grid point: wall time x ranks / points (what a
//                    cluster's throughput is estimated from, README "Sweeps on a cluster")
// Run: build/bench/bench_mpi_scaling --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (needs mpirun on PATH and build/heavytop-mpi; as root it passes --allow-run-as-root).

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "spawn.hpp"

namespace {

std::string g_heavytop;  // --heavytop=PATH

void Sweep(benchmark::State& state, std::vector<std::string> map, double points) {
  const int ranks = static_cast<int>(state.range(0));
  const std::string output = std::filesystem::temp_directory_path() / ("heavytop-bench-mpi-" + std::to_string(getpid()) + ".csv");
  std::vector<std::string> args;
  if (geteuid() == 0) args.push_back("--allow-run-as-root");
  for (const char* a : {"--bind-to", "core", "-n"}) args.push_back(a);
  args.push_back(std::to_string(ranks));
  args.push_back(g_heavytop);
  args.push_back("sweep");
  args.insert(args.end(), map.begin(), map.end());
  args.push_back("--output");
  args.push_back(output);
  double wall = 0.0;  // s, over the iterations
  for (auto _ : state) {
    heavytop::bench::Cost cost;
    if (!heavytop::bench::run_once("mpirun", args, cost)) {
      state.SkipWithError("mpirun heavytop sweep failed (mpirun on PATH? heavytop-mpi built?)");
      return;
    }
    state.SetIterationTime(cost.wall);
    wall += cost.wall;
    std::filesystem::remove(output);
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["points_per_s"] = points * runs / wall;
  state.counters["per_core_point_ms"] = 1e3 * wall * ranks / (points * runs);
}

}  // namespace

// Nonlinear verdicts: the toy top (the built-in example) at spins above its critical 133 rad/s,
// 1600 simulations of 100 s that all stay up (the batched Taylor integrator, `auto`); and the
// asymmetric plate's linear verdicts at 160 000 points.
BENCHMARK_CAPTURE(Sweep, nonlinear_toy_top_40x40,
                  {"--vary", "spin=150:400:40", "--vary", "C/A=0.25:0.4:40", "--model", "nonlinear", "--theta0", "0.05",
                   "--horizon", "100"},
                  1600.0)
    ->Arg(1)->Arg(2)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep, linear_plate_400x400,
                  {"--config", HEAVYTOP_EXAMPLES "/asymmetric-plate.toml", "--vary", "B/A=1:3:400", "--vary", "spin=0:3:400"},
                  160000.0)
    ->Arg(1)->Arg(2)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) { return heavytop::bench::run_benchmarks(argc, argv, g_heavytop); }

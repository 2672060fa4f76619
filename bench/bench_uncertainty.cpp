// SPEC 17's Monte Carlo (issue 44's target: 10^4 draws of the toy top's answer in under 1 s on
// 2 cores): analyse_uncertainty() on examples/toy-top.toml with 2 % on A and 1e-7 kg m^2 on C,
// draws = 10^4, on 1 and 2 threads. Each call also makes the critical spin's adaptive comparison
// run (JCGM 101 7.9: at least 2 batches of 10^4 critical spins, the first reused from the
// answer's draws), so this is the whole of what `stability --uncertain ... draws=10000` adds.
#include <benchmark/benchmark.h>

#include "heavytop/uncertainty.hpp"

namespace {

using namespace heavytop;

void ToyTopAnswerDraws(benchmark::State& state) {
  UncertaintyOptions options;
  options.inputs["A"] = {0.02, true};
  options.inputs["C"] = {1e-7, false};
  options.draws = 10000;
  options.threads = static_cast<unsigned>(state.range(0));
  double p = 0.0;
  for (auto _ : state) {
    const UncertaintyAnalysis u = analyse_uncertainty(example_toy_top(), example_motion(), options);
    p = u.p_stays_up;  // the call starts threads: it cannot be optimised away
    // (benchmark 1.7's DoNotOptimize(double&) lets GCC read p back from a wrong register.)
  }
  if (p != 1.0) state.SkipWithError("the toy top at 200 rad/s should stay up in every draw");
  state.counters["draws_per_s"] = benchmark::Counter(10000.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(ToyTopAnswerDraws)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

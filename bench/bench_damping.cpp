// The cost of the torques of SPEC section 6 in the nonlinear model: the toy top (and its
// asymmetric copy, B = 1.01 A) over 10 s at rtol = atol = 1e-10, conservative beside damped
// (d_t = 1e-7, d_a = 2e-7 N m s, and with dry friction tau0 = 1e-7 N m), in one run.
// Counters: sim_s_per_wall_s (simulated seconds per wall second), rhs, steps.
// Target (issue 18): a damped run costs less than 1.3 times the conservative one.

#include <benchmark/benchmark.h>

#include "heavytop/nonlinear.hpp"

namespace {

constexpr double kHorizon = 10.0;  // s

// Arguments: torques (0 none, 1 drag, 2 drag and dry friction), asymmetric (0/1).
void BM_DampedToyTop(benchmark::State& state) {
  heavytop::Body body = heavytop::example_toy_top();
  if (state.range(1)) body.B = 1.01 * body.A;
  if (state.range(0) >= 1) body.damping = {.transverse = 1e-7, .axial = 2e-7};
  if (state.range(0) >= 2) body.damping.friction = 1e-7;
  heavytop::InitialState s = heavytop::example_motion();
  heavytop::Tolerances options;
  options.rtol = options.atol = 1e-10;
  const std::vector<double> times = {0.0, kHorizon};
  heavytop::NonlinearSummary summary;
  for (auto _ : state) {
    auto tr = heavytop::simulate_nonlinear(body, s, times, options, &summary);
    benchmark::DoNotOptimize(tr.theta.data());
  }
  state.counters["sim_s_per_wall_s"] =
      benchmark::Counter(kHorizon * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rhs"] = static_cast<double>(summary.rhs_evaluations);
  state.counters["steps"] = static_cast<double>(summary.steps);
}
BENCHMARK(BM_DampedToyTop)
    ->ArgNames({"torques", "asym"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

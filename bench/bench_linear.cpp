// Speed of the linear models: closed-form samples per second, stability analyses per second.
#include <benchmark/benchmark.h>

#include "heavytop/linear_motion.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"

namespace {

using namespace heavytop;

const InitialState kState = example_motion();

// One sample of the closed form (the built-in toy top, first-order model), as a user's
// time loop calls it: items_per_second is samples per second on one core.
void BM_ClosedFormSample(benchmark::State& state) {
  const LinearModel model = linear_model(LinearModelKind::FirstOrder, example_toy_top());
  const LinearSolution solution = closed_form_solution(model, kState.spin, initial_linear_state(model, kState));
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluate(solution, t));
    t += 1e-4;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosedFormSample);

// A whole trajectory in SPEC's angles, per model: samples per second including the output.
void BM_SimulateLinear(benchmark::State& state) {
  const auto kind = kLinearModels[static_cast<std::size_t>(state.range(0))];
  const LinearModel model = linear_model(kind, example_toy_top());
  const auto times = sample_times(10.0, 100000);
  for (auto _ : state) benchmark::DoNotOptimize(simulate_linear(model, kState, times, LinearMethod::Analytic));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(times.size()));
  state.SetLabel(std::string(name(kind)));
}
BENCHMARK(BM_SimulateLinear)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The matrix exponential route, for comparison.
void BM_MatrixExponentialSample(benchmark::State& state) {
  const LinearModel model = linear_model(LinearModelKind::FirstOrder, example_toy_top());
  const LinearState x0 = initial_linear_state(model, kState);
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(matrix_exponential_solution(model, kState.spin, x0, t));
    t += 1e-4;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MatrixExponentialSample);

// A full stability analysis (verdict at the spin + exact stable intervals) of the linearisation.
void BM_StabilityAnalysis(benchmark::State& state) {
  const LinearModel model = linear_model(LinearModelKind::Linearized, Body{.A = 1, .B = 1.26, .C = 1.54, .mass = 1, .gravity = 1, .length = 1});
  for (auto _ : state) {
    benchmark::DoNotOptimize(linear_stability(model, 1.5));
    benchmark::DoNotOptimize(stable_spin_intervals(model));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_StabilityAnalysis);

}  // namespace

// A 400 x 400 stability map (B/A against spin) of the linear models, on every core, as
// `heavytop sweep --vary B/A=0.5:2:400 --vary spin=0:5:400` computes it (without printing).
void BM_Sweep400x400(benchmark::State& state) {
  const Body base{.A = 1.0, .B = 1.0, .C = 1.5, .mass = 1.0, .gravity = 1.0, .length = 1.0};
  const std::vector<SweepAxis> axes{parse_sweep_axis("B/A=0.5:2:400"), parse_sweep_axis("spin=0:5:400")};
  for (auto _ : state) benchmark::DoNotOptimize(sweep_verdicts(base, InitialState{}, axes, SweepOptions{}, 0, grid_size(axes)));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(grid_size(axes)));
}
BENCHMARK(BM_Sweep400x400)->Unit(benchmark::kMillisecond)->UseRealTime();

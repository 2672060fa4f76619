// Speed of the nonlinear model on the built-in example (a toy top spun at 200 rad/s, started
// 0.05 rad off vertical). Counters:
//   sim_s_per_wall_s  simulated seconds per wall-clock second (real time, not CPU time)
//   time_per_rhs      wall time per right-hand-side evaluation, stepper overhead included (s)
//   rhs, steps        work per run
//   end_error         rad, largest |theta|, |phi| error at the end against a 1e-14 run
//   theta_end, phi_end  rad, the end state (bench/scipy_dop853.py reads them from the JSON)
// bench/scipy_dop853.py runs the same equations in SciPy's DOP853 for the side-by-side ratio.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "heavytop/general_body.hpp"
#include "heavytop/nonlinear.hpp"

namespace {

using heavytop::InitialState;
using heavytop::Tolerances;
using heavytop::NonlinearSummary;

constexpr double kHorizon = 10.0;  // s

InitialState toy_state() {
  InitialState s;
  s.spin = 200.0;
  s.theta0 = 0.05;
  return s;
}

// A slightly asymmetric copy of the toy top (B = 1.01 A): the general right-hand side.
heavytop::Body asymmetric_toy_top() {
  heavytop::Body b = heavytop::example_toy_top();
  b.B = 1.01 * b.A;
  return b;
}

// The same run at rtol = atol = 1e-14, computed once per (body, samples).
const heavytop::Trajectory& reference(bool asymmetric, std::size_t samples) {
  static std::map<std::pair<bool, std::size_t>, heavytop::Trajectory> cache;
  auto [it, added] = cache.try_emplace({asymmetric, samples});
  if (added) {
    Tolerances tight;
    tight.rtol = tight.atol = 1e-14;
    it->second = heavytop::simulate_nonlinear(
        asymmetric ? asymmetric_toy_top() : heavytop::example_toy_top(), toy_state(),
        heavytop::sample_times(kHorizon, samples), tight);
  }
  return it->second;
}

// Arguments: samples, -log10(tolerance), asymmetric (0/1).
void BM_NonlinearToyTop(benchmark::State& state) {
  const std::size_t samples = static_cast<std::size_t>(state.range(0));
  const double tol = std::pow(10.0, -static_cast<double>(state.range(1)));
  const heavytop::Body body =
      state.range(2) ? asymmetric_toy_top() : heavytop::example_toy_top();
  Tolerances options;
  options.rtol = options.atol = tol;
  const std::vector<double> times = heavytop::sample_times(kHorizon, samples);
  NonlinearSummary summary;
  heavytop::Trajectory tr;
  std::size_t rhs = 0;
  for (auto _ : state) {
    tr = heavytop::simulate_nonlinear(body, toy_state(), times, options, &summary);
    benchmark::DoNotOptimize(tr.theta.data());
    rhs += summary.rhs_evaluations;
  }
  const heavytop::Trajectory& ref = reference(state.range(2) != 0, samples);
  double error = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i)
    error = std::max({error, std::abs(tr.theta[i] - ref.theta[i]), std::abs(tr.phi[i] - ref.phi[i])});
  const double runs = static_cast<double>(state.iterations());
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(kHorizon * runs, benchmark::Counter::kIsRate);
  state.counters["time_per_rhs"] = benchmark::Counter(
      static_cast<double>(rhs), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["rhs"] = static_cast<double>(summary.rhs_evaluations);
  state.counters["steps"] = static_cast<double>(summary.steps);
  state.counters["end_error"] = error;
  state.counters["theta_end"] = tr.theta.back();
  state.counters["phi_end"] = tr.phi.back();
}
BENCHMARK(BM_NonlinearToyTop)
    ->ArgNames({"samples", "tol_exp", "asym"})
    ->Args({2, 10, 0})      // the headline: end state only, rtol = atol = 1e-10
    ->Args({1001, 10, 0})   // plus 1000 dense-output samples
    ->Args({2, 12, 0})      // the default tolerance
    ->Args({2, 10, 1})      // the general (asymmetric) right-hand side
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The stability-sweep primitive: largest tilt over the horizon, refined on the dense output.
void BM_MaxTiltToyTop(benchmark::State& state) {
  const heavytop::Body body = heavytop::example_toy_top();
  Tolerances options;
  options.rtol = options.atol = 1e-10;
  for (auto _ : state)
    benchmark::DoNotOptimize(heavytop::max_tilt(body, toy_state(), kHorizon, 2.0, options));
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(
      kHorizon * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MaxTiltToyTop)->UseRealTime()->Unit(benchmark::kMillisecond);

// The general body's path (SPEC section 11, general_body.hpp: plain quaternion state, full
// tensor, odeint's dopri5) on the toy top over the same 10 s at rtol = atol = 1e-10, end state
// only: offset 0 (the ordinary body, to set beside BM_NonlinearToyTop/2/10/0, the spin-factored
// path simulate() keeps for it) and offset_x = 0.1 mm (the unbalanced gyroscope).
void BM_GeneralBodyToyTop(benchmark::State& state) {
  heavytop::Body body = heavytop::example_toy_top();
  body.general.offset_x = state.range(0) ? 1e-4 : 0.0;
  Tolerances options;
  options.rtol = options.atol = 1e-10;
  const std::vector<double> times = heavytop::sample_times(kHorizon, 2);
  NonlinearSummary summary;
  for (auto _ : state) {
    const heavytop::Trajectory tr = heavytop::simulate_general_body(body, toy_state(), times, options, &summary);
    benchmark::DoNotOptimize(tr.theta.data());
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(
      kHorizon * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rhs"] = static_cast<double>(summary.rhs_evaluations);
  state.counters["steps"] = static_cast<double>(summary.steps);
}
BENCHMARK(BM_GeneralBodyToyTop)->ArgName("offset")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

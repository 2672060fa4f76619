// The body on a table (table.hpp): Friedl's tippe top turning over (examples/tippe-top.toml, the
// first 5 s: it passes a quarter turn at 5.146 s), at tolerances 1e-6 to 1e-13 (1e-8 and tighter
// keep Jellett's integral to 1e-9); and the rising toy top (examples/rising-top.toml). Each run's
// counters: the steps, Jellett's and the energy's largest relative drift, and the end's tilt,
// spin and P (x, y) for the end error. bench/scipy_table.py integrates the same equations with
// SciPy's DOP853 and compares them at equal end error (docs/table.md, docs/table-performance.md);
// and the stiff tippe top at a small slip_speed by DOP853 and by Rosenbrock 4 side by side.
#include <cmath>

#include <benchmark/benchmark.h>

#include "heavytop/table.hpp"

namespace {

using namespace heavytop;

Body tippe_top() {
  Body b;
  b.mass = 0.006;
  b.length = -0.003;
  b.C = 7e-7;
  b.A = b.B = 8e-7 + b.mass * b.length * b.length;
  b.tip_radius = 0.015;
  return b;
}

Body rising_top() {
  Body b;
  b.mass = 0.060;
  b.length = 0.025;
  b.C = 1.2e-5;
  b.A = b.B = 4.35e-5;
  b.tip_radius = 0.002;
  return b;
}

void run(benchmark::State& state, const Body& body, double spin, double horizon, double slip_speed = 1.0,
         Integrator integrator = Integrator::Auto) {
  Table table;
  table.contact = Contact::Sliding;
  table.friction = 0.3;
  table.slip_speed = slip_speed;
  InitialState start;
  start.spin = spin;
  start.theta0 = 0.1;
  Tolerances tolerances;
  tolerances.rtol = tolerances.atol = std::pow(10.0, -static_cast<double>(state.range(0)));
  TableRun last;
  for (auto _ : state) {
    last = simulate_on_table(body, table, start, {horizon, 2}, tolerances, {}, integrator);
    benchmark::DoNotOptimize(last.trajectory.t.data());
  }
  state.counters["steps"] = static_cast<double>(last.summary.steps);
  state.counters["jellett_drift"] = last.summary.max_relative_jellett_drift;
  state.counters["energy_drift"] = last.summary.max_relative_energy_drift;
  // The last sample's columns, for the error against a tight reference (bench/scipy_table.py).
  for (const auto& [name, column] : last.trajectory.extra)
    if (name == "tilt" || name == "spin" || name == "x" || name == "y") state.counters["end_" + name] = column.back();
}

void BM_TippeTopTurningOver(benchmark::State& state) { run(state, tippe_top(), 180.0, 5.0); }
void BM_RisingTop(benchmark::State& state) { run(state, rising_top(), 400.0, 10.0); }

// Stiff viscous sliding (slip_speed 1e-6 m/s, 1 s of the tippe top): the explicit DOP853, its step
// held by its stability, beside the implicit Rosenbrock 4, at tolerances 1e-6 ... 1e-10 (docs/table.md).
void BM_StiffTippeTopDop853(benchmark::State& state) { run(state, tippe_top(), 180.0, 1.0, 1e-6, Integrator::Dop853); }
void BM_StiffTippeTopRosenbrock4(benchmark::State& state) {
  run(state, tippe_top(), 180.0, 1.0, 1e-6, Integrator::Rosenbrock4);
}

BENCHMARK(BM_TippeTopTurningOver)->DenseRange(6, 13, 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StiffTippeTopDop853)->DenseRange(6, 10, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StiffTippeTopRosenbrock4)->DenseRange(6, 10, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RisingTop)->DenseRange(8, 12, 2)->Unit(benchmark::kMillisecond);

}  // namespace

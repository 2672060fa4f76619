// The nonlinear column of a 400 x 400 stability map (horizon 50 s, max tilt 0.5 rad, the
// sweep's default tolerance rtol = atol = 1e-12), three ways side by side in one run:
//   dopri5    max_tilt() point by point (way 0; `heavytop sweep --integrator dopri5`, the old path)
//   taylor1   taylor_tilt_extremes() point by point (way 1; the Taylor method unbatched)
//   batched   batch_tilt_extremes() on every point at once, with the widest instruction set
//             here (way 2), and with 2 (SSE2, way 3) and 4 (AVX2, way 4) lanes
//   verdicts  batch_tilt_verdicts() (way 5): the same without the tilt's extrema, the call of
//             `heavytop sweep --integrator auto` before issue 31
//   decided   decided_tilt_verdicts() (way 6): each verdict at the tolerance that decides it
//             (verdicts.hpp), the call of `heavytop sweep --integrator auto` now
// on two maps:
//   plate     examples/asymmetric-plate.toml, B/A = 1.05:2.95:400 x spin = 0.5:4:400 rad/s
//             (every point asymmetric: the plain variables)
//   toy       examples/toy-top.toml, C/A = 0.15:0.6:400 x spin = 50:400:400 rad/s
//             (symmetric: the spin-factored variables)
// A representative subset is timed: every 397th grid point (397 is prime, so the subset runs
// across both axes; 404 points, each stable and falling region in proportion). Counter
// items_per_second = grid points per second on one core; `stable` the fraction of the subset
// that stays up (the same for all three, checked). BM_SweepRow: sweep_verdicts() itself (the
// linear models and Lyapunov too) on one contiguous row of 400 points, one thread, dopri5 vs
// auto. Run with --benchmark_enable_random_interleaving=true --benchmark_repetitions=5 and read
// the medians.

#include <benchmark/benchmark.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "heavytop/heavytop.hpp"

namespace {

using namespace heavytop;

constexpr double kHorizon = 50.0, kMaxTilt = 0.5;
constexpr std::size_t kStride = 397;

struct Map {
  Body base;
  InitialState start;
  std::vector<SweepAxis> axes;
};

Map map(int which) {
  Map m;
  if (which == 0) {
    m.base.A = 0.010, m.base.B = 0.015, m.base.C = 0.020, m.base.mass = 1.0, m.base.length = 1.0193679918450561e-3;
    m.start.spin = 1.3, m.start.theta0 = 1e-4;
    m.axes = {parse_sweep_axis("B/A=1.05:2.95:400"), parse_sweep_axis("spin=0.5:4:400")};
  } else {
    m.base = example_toy_top();
    m.start.spin = 200.0, m.start.theta0 = 0.05;
    m.axes = {parse_sweep_axis("C/A=0.15:0.6:400"), parse_sweep_axis("spin=50:400:400")};
  }
  return m;
}

struct Subset {
  std::vector<Body> bodies;
  std::vector<InitialState> starts;
};

Subset subset(const Map& m) {
  Subset s;
  for (std::size_t i = 0; i < grid_size(m.axes); i += kStride) {
    Body b = m.base;
    InitialState st = m.start;
    apply_grid_point(m.axes, i, b, st);
    s.bodies.push_back(b), s.starts.push_back(st);
  }
  return s;
}

enum Way { Dopri5, Taylor1, Batched, BatchedSse2, BatchedAvx2, Verdicts, Decided };

void BM_NonlinearMap(benchmark::State& state) {
  const Map m = map(static_cast<int>(state.range(0)));
  const Way way = static_cast<Way>(state.range(1));
  const Subset s = subset(m);
  const Tolerances tol;  // the sweep's default, 1e-12
  const BatchIsa isa = way == BatchedSse2 ? BatchIsa::Sse2 : way == BatchedAvx2 ? BatchIsa::Avx2 : best_batch_isa();
  if (!batch_isa_supported(isa)) {
    state.SkipWithError("instruction set not supported here");
    return;
  }
  std::vector<TiltExtremes> out(s.bodies.size());
  std::vector<TiltVerdict> verdicts(s.bodies.size());
  std::vector<DecidedVerdict> decided(s.bodies.size());
  std::size_t stable = 0;
  for (auto _ : state) {
    stable = 0;
    if (way == Dopri5) {
      for (std::size_t i = 0; i < s.bodies.size(); ++i)
        stable += max_tilt(s.bodies[i], s.starts[i], kHorizon, kMaxTilt, tol) <= kMaxTilt;
    } else if (way == Taylor1) {
      for (std::size_t i = 0; i < s.bodies.size(); ++i)
        stable += !taylor_tilt_extremes(s.bodies[i], s.starts[i], kHorizon, kMaxTilt, tol).exceeded;
    } else if (way == Verdicts) {
      batch_tilt_verdicts(s.bodies, s.starts, kHorizon, kMaxTilt, tol, verdicts, isa);
      for (const auto& v : verdicts) stable += !v.exceeded;
    } else if (way == Decided) {
      decided_tilt_verdicts(s.bodies, s.starts, kHorizon, kMaxTilt, tol, decided);
      for (const auto& v : decided) stable += !v.exceeded;
    } else {
      batch_tilt_extremes(s.bodies, s.starts, kHorizon, kMaxTilt, tol, out, isa);
      for (const auto& e : out) stable += !e.exceeded;
    }
    benchmark::DoNotOptimize(stable);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.bodies.size()));
  state.counters["points"] = static_cast<double>(s.bodies.size());
  state.counters["stable"] = static_cast<double>(stable) / static_cast<double>(s.bodies.size());
  state.SetLabel(way >= Batched ? std::string(name(isa)) + " " + std::to_string(batch_lanes(isa)) + " lanes" : "");
}

void Args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"map", "way"})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
  for (int map : {0, 1})
    for (int way : {Dopri5, Taylor1, Batched, BatchedSse2, BatchedAvx2, Verdicts, Decided}) b->Args({map, way});
}
BENCHMARK(BM_NonlinearMap)->Apply(Args);

// sweep_verdicts() on row 200 of the map (400 contiguous points, spin varying), one thread.
void BM_SweepRow(benchmark::State& state) {
  const Map m = map(static_cast<int>(state.range(0)));
  SweepOptions o;
  o.nonlinear = true;
  o.horizon = kHorizon;
  o.max_tilt = kMaxTilt;
  o.threads = 1;
  o.nonlinear_integrator = state.range(1) == 0 ? Integrator::Adaptive : Integrator::Auto;
  const std::size_t begin = 200 * 400, end = begin + 400;
  for (auto _ : state) benchmark::DoNotOptimize(sweep_verdicts(m.base, m.start, m.axes, o, begin, end));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (end - begin)));
  state.SetLabel(state.range(1) == 0 ? "dopri5" : "auto");
}
BENCHMARK(BM_SweepRow)
    ->ArgNames({"map", "auto"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

}  // namespace

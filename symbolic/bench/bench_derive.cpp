// How long the symbolic derivations take. The target: every route and sequence at order 2
// in under a second (heavytop derive --check runs them all).
#include <benchmark/benchmark.h>

#include "heavytop/symbolic/derive.hpp"

namespace hs = heavytop::symbolic;

// Every method and sequence at order 2: the 8 derivations behind the invariance results.
static void BM_DeriveEveryRouteOrder2(benchmark::State& state) {
  for (auto _ : state) {
    auto rows = hs::check({2});
    benchmark::DoNotOptimize(rows);
  }
}
BENCHMARK(BM_DeriveEveryRouteOrder2)->Unit(benchmark::kMillisecond);

// One route, to see which costs most.
static void BM_DeriveOneRoute(benchmark::State& state) {
  const auto method = hs::kMethods[state.range(0)];
  for (auto _ : state) {
    auto d = hs::derive(method, hs::Sequence::PhiTheta, 2);
    benchmark::DoNotOptimize(d);
  }
  state.SetLabel(std::string(hs::name(method)));
}
BENCHMARK(BM_DeriveOneRoute)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

// The small-rotation matrices and their products (section 1).
static void BM_Rotations(benchmark::State& state) {
  for (auto _ : state) {
    auto r = hs::rotations(static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_Rotations)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

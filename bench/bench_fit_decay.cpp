// fit_spin_decay's cost: one fit (four Levenberg-Marquardt runs, one per active set of the
// bounds, and the covariance) of the toy top's decay with noise 1 rad/s, for 56 points (the
// example file's size) up to 100 000 points (a logging tachometer).
#include <benchmark/benchmark.h>

#include <random>

#include "heavytop/body.hpp"
#include "heavytop/damping.hpp"
#include "heavytop/fit_decay.hpp"

namespace {

void BM_FitDecay(benchmark::State& state) {
  const heavytop::Body top = heavytop::example_toy_top();
  const heavytop::SpinDecayLaw law{top.C, 2e-7, 1e-5};
  const auto n = static_cast<int>(state.range(0));
  std::mt19937_64 rng(18);
  std::normal_distribution<double> noise(0.0, 1.0);
  heavytop::DecayData data;
  for (int i = 0; i < n; ++i) {
    const double t = 110.0 * i / (n - 1), w = law.spin(200.0, t);
    data.t.push_back(t);
    data.spin.push_back(w > 0.0 ? std::max(0.0, w + noise(rng)) : 0.0);
  }
  for (auto _ : state) {
    const heavytop::DecayFit fit = heavytop::fit_spin_decay(top, data);
    if (!fit.summary.converged) state.SkipWithError("not converged");
    benchmark::DoNotOptimize(fit.axial.value);
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_FitDecay)->Arg(56)->Arg(1000)->Arg(100000)->Unit(benchmark::kMicrosecond);

}  // namespace

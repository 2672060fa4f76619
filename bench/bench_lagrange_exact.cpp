// Speed of lagrange-exact and of the splitting integrator, and the work-precision data of
// docs/integrators.md.
//
//   bench_lagrange_exact                          Google Benchmark (all flags as usual)
//   bench_lagrange_exact --work-precision=FILE    writes the work-precision CSV and exits
//
// Counters:
//   samples_per_s   lagrange-exact samples per second on one core (target >= 2e6)
//   s_per_step      splitting: wall time per grid step (s); `kicks`: kicks per step
//
// The test problem everywhere: the symmetric unit top of tests/test_splitting.cpp, A = B = 1,
// C = 0.5 kg m^2, m g R = 1 N m, spin 5 rad/s, tilt 0.3 rad, tilt rate 0.1 rad/s (nutation
// period 3.85 s).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/splitting.hpp"

namespace {

using namespace heavytop;

Body unit_top() { return Body{.A = 1.0, .B = 1.0, .C = 0.5, .mass = 1.0, .gravity = 1.0, .length = 1.0}; }

InitialState start() { return InitialState{.spin = 5.0, .theta0 = 0.3, .theta_rate0 = 0.1}; }

// A motion whose azimuth series does not converge within 64 terms (the axis passes 0.08 rad
// from the vertical): the elliptic integrals are evaluated at every sample.
InitialState near_vertical_start() {
  return InitialState{.spin = 4.0, .theta0 = 0.3, .phi0 = 0.1, .theta_rate0 = 0.2, .phi_rate0 = -0.3};
}

// ---- lagrange-exact ---------------------------------------------------------------------------

// One sample (theta, phi and rates) as a caller's time loop asks for it, from t0 on in steps
// of 1 ms. Arguments: t0 exponent (t0 = 10^arg), Fourier series (1) or elliptic integrals (0),
// motion (0: the unit top, 1: near the vertical).
void BM_LagrangeExactSample(benchmark::State& state) {
  LagrangeExactOptions options;
  options.fourier_series = state.range(1) != 0;
  const LagrangeTop top =
      lagrange_top(unit_top(), state.range(2) ? near_vertical_start() : start(), options);
  const double t0 = std::pow(10.0, static_cast<double>(state.range(0)));
  double t = t0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lagrange_axis_angles(top, t));
    t += 1e-3;
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["series"] = top.fourier_series ? 1.0 : 0.0;
  state.counters["series_terms"] = top.series_terms;
}
BENCHMARK(BM_LagrangeExactSample)
    ->ArgNames({"t0_exp", "series", "near_vertical"})
    ->Args({0, 1, 0})  // the headline: t = 1 s
    ->Args({6, 1, 0})  // t = 1e6 s: the same cost
    ->Args({0, 0, 0})  // elliptic integrals at every sample
    ->Args({6, 0, 0})
    ->Args({0, 1, 1}); // series not converged: elliptic integrals

// The full rigid-body state (attitude and angular velocity), which adds the spin angle.
void BM_LagrangeExactRigidBody(benchmark::State& state) {
  const LagrangeTop top = lagrange_top(unit_top(), start());
  double t = 1.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lagrange_rigid_body_state(top, t));
    t += 1e-3;
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LagrangeExactRigidBody);

// Setting up the solution: roots, elliptic constants, the Fourier series and its check.
void BM_LagrangeExactSetup(benchmark::State& state) {
  const Body body = unit_top();
  const InitialState s = state.range(0) ? near_vertical_start() : start();
  for (auto _ : state) benchmark::DoNotOptimize(lagrange_top(body, s));
}
BENCHMARK(BM_LagrangeExactSetup)->ArgName("near_vertical")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// simulate_lagrange_exact as the CLI calls it: 10001 samples over 1000 s, setup included.
void BM_SimulateLagrangeExact(benchmark::State& state) {
  const std::vector<double> times = sample_times(1000.0, 10001);
  for (auto _ : state) benchmark::DoNotOptimize(simulate_lagrange_exact(unit_top(), start(), times));
  state.counters["samples_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * times.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateLagrangeExact)->Unit(benchmark::kMillisecond);

// ---- Splitting ------------------------------------------------------------------------------

// 100 s on the grid, end state only. Arguments: order, asymmetric (B = 1.3) or not.
void BM_Splitting(benchmark::State& state) {
  Body body = unit_top();
  if (state.range(1)) body.B = 1.3;
  SplittingOptions options;
  options.order = static_cast<int>(state.range(0));
  options.step = 0.01;
  SplittingSummary summary;
  std::size_t steps = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(simulate_splitting(body, start(), {100.0}, options, &summary));
    steps += summary.steps;
  }
  state.counters["s_per_step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["kicks"] = static_cast<double>(summary.kicks) / static_cast<double>(summary.steps);
}
BENCHMARK(BM_Splitting)
    ->ArgNames({"order", "asym"})
    ->Args({2, 0})
    ->Args({4, 0})
    ->Args({2, 1})
    ->Args({4, 1})
    ->Unit(benchmark::kMillisecond);

// ---- Work-precision -------------------------------------------------------------------------
//
// docs/work-precision.csv: for horizons of 100 and 10^4 nutation periods (1001 samples), each
// integrator setting's wall time (median of 3), work (right-hand-side evaluations or kicks),
// largest angle between its axis and lagrange-exact's (rad) and largest relative energy drift
// over every step (the summaries' max_relative_energy_drift). docs/work-precision.gp plots it.

double axis_error(const Trajectory& a, const Trajectory& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto k = [](double th, double ph) {
      return Eigen::Vector3d(std::sin(th) * std::cos(ph), -std::sin(ph), std::cos(th) * std::cos(ph));
    };
    const Eigen::Vector3d ka = k(a.theta[i], a.phi[i]), kb = k(b.theta[i], b.phi[i]);
    e = std::max(e, std::atan2(ka.cross(kb).norm(), ka.dot(kb)));
  }
  return e;
}

// s, the median of three runs (one run when it takes longer than a second).
double wall_time(const std::function<void()>& run) {
  std::vector<double> t;
  for (int i = 0; i < 3; ++i) {
    const auto a = std::chrono::steady_clock::now();
    run();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
    if (t.back() > 1.0) return t.back();
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

int write_work_precision(const std::string& path) {
  const Body body = unit_top();
  const InitialState s = start();
  const double period = nutation_period(lagrange_top(body, s));
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "work-precision: cannot write %s\n", tmp.c_str());
    return 1;
  }
  std::fprintf(f, "horizon_periods,method,parameter,wall_s,evaluations,max_angle_error_rad,"
                  "max_relative_energy_drift\n");
  for (double periods : {100.0, 10000.0}) {
    const std::vector<double> times = sample_times(periods * period, 1001);
    Trajectory exact;
    const double exact_s = wall_time([&] { exact = simulate_lagrange_exact(body, s, times); });
    std::fprintf(f, "%g,lagrange-exact,0,%.6g,0,0,0\n", periods, exact_s);
    for (int e = 4; e <= 13; ++e) {
      Tolerances o;
      o.rtol = o.atol = std::pow(10.0, -e);
      NonlinearSummary summary;
      Trajectory tr;
      const double w = wall_time([&] { tr = simulate_nonlinear(body, s, times, o, &summary); });
      std::fprintf(f, "%g,adaptive,%g,%.6g,%zu,%.6g,%.6g\n", periods, o.rtol, w,
                   summary.rhs_evaluations, axis_error(tr, exact), summary.max_relative_energy_drift);
      std::fflush(f);
    }
    for (int order : {2, 4}) {
      for (int i = 0; i < 7; ++i) {
        SplittingOptions o;
        o.order = order;
        o.step = (order == 2 ? 0.2 : 0.8) / (1 << i);
        SplittingSummary summary;
        Trajectory tr;
        const double w = wall_time([&] { tr = simulate_splitting(body, s, times, o, &summary); });
        std::fprintf(f, "%g,splitting-%d,%g,%.6g,%zu,%.6g,%.6g\n", periods, order, o.step, w,
                     summary.kicks, axis_error(tr, exact), summary.max_relative_energy_drift);
        std::fflush(f);
      }
    }
  }
  if (std::fclose(f) != 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::fprintf(stderr, "work-precision: cannot write %s\n", path.c_str());
    return 1;
  }
  std::fprintf(stderr, "work-precision: wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* flag = "--work-precision=";
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0)
      return write_work_precision(argv[i] + std::strlen(flag));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// heavytop's error-controlled integrators of the nonlinear body at equal error, on the two
// problems of issue 14 (bench/peers/ runs the same problems in other libraries):
//   toy:  example_toy_top() spun at 200 rad/s, theta0 = 0.05 rad, over 10 s;
//   asym: A = 1, B = 1.5, C = 2 kg m^2, m = 1 kg, g = 9.81 m/s^2, R = 0.1 m, spin 10 rad/s,
//         theta0 = 0.2 rad, over 20 s.
// and two damped ones (SPEC section 6; Taylor and dopri5 only, DOP853 holds no torques):
//   toy-damped:  the toy top with d_t = 1e-7, d_a = 2e-7 N m s (bench_damping's drag);
//   asym-stop:   asym with d_t = 0.01, d_a = 0.05 N m s and dry friction tau0 = 1.5 N m,
//                which stops the spin at 11.5 s (a change of friction mode inside the run).
// Error: the largest angle between the spin axis and the reference's over 101 samples (rad);
// reference lagrange-exact (toy) and DOP853 at rtol = atol = 1e-15 (asym; it agrees with the
// Taylor integrator at 1e-15 to 6e-15 rad and with a long-double Bulirsch-Stoer run to 5e-16,
// bench/peers/); for the damped ones the Taylor integrator at 1e-15 (it agrees with dopri5 at
// 1e-14 to 1.2e-12 and 1.8e-12 rad). For each integrator and error level (1e-6, 1e-9, 1e-12) the tolerance is the
// loosest of 10^(-k/4) whose error, and that of the next 8 tighter ones, are at most the
// level (calibrated once, outside the timing). Timed: simulate(Nonlinear) with 101 samples.
// Counters:
//   tol, error     the tolerance used and the error it gives (rad)
//   steps, evals   steps, and evaluations (Taylor: steps x order, one pass of the recurrence
//                  per order)
//   time_per_eval  wall time / evals (s)
// BM_RightHandSide: one evaluation of RigidBodySystem (the plain equations): with the Taylor
// run's steps x order it gives the "Taylor limit" of docs/integrators.md.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "heavytop/heavytop.hpp"

namespace {

using heavytop::Integrator;

struct Problem {
  heavytop::Body body;
  heavytop::InitialState start;
  double horizon;
};

// 0 toy, 1 asym, 2 toy-damped, 3 asym-stop.
Problem problem(int which) {
  heavytop::InitialState s;
  if (which == 0 || which == 2) {
    s.spin = 200.0, s.theta0 = 0.05;
    heavytop::Body b = heavytop::example_toy_top();
    if (which == 2) b.damping = {.transverse = 1e-7, .axial = 2e-7};
    return {b, s, 10.0};
  }
  heavytop::Body b;
  b.A = 1.0, b.B = 1.5, b.C = 2.0, b.mass = 1.0, b.gravity = 9.81, b.length = 0.1;
  if (which == 3) b.damping = {.transverse = 0.01, .axial = 0.05, .friction = 1.5};
  s.spin = 10.0, s.theta0 = 0.2;
  return {b, s, 20.0};
}

const char* label(int which) {
  const char* names[] = {" toy", " asym", " toy-damped", " asym-stop"};
  return names[which];
}

using Axes = std::vector<Eigen::Vector3d>;

Axes axes_of(const heavytop::Trajectory& tr) {
  Axes a;
  for (std::size_t i = 0; i < tr.size(); ++i)
    a.emplace_back(std::cos(tr.phi[i]) * std::sin(tr.theta[i]), -std::sin(tr.phi[i]),
                   std::cos(tr.phi[i]) * std::cos(tr.theta[i]));
  return a;
}

double max_angle(const Axes& a, const Axes& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::atan2(a[i].cross(b[i]).norm(), a[i].dot(b[i])));
  return e;
}

heavytop::SimulateOptions options(Integrator integrator, double tol) {
  heavytop::SimulateOptions o;
  o.integrator = integrator;
  o.adaptive.rtol = o.adaptive.atol = tol;
  return o;
}

heavytop::Simulation run(const Problem& p, Integrator integrator, double tol) {
  return heavytop::simulate(heavytop::Model::Nonlinear, p.body, p.start, heavytop::sample_times(p.horizon, 101),
                            options(integrator, tol));
}

const Axes& reference(int which) {
  static std::map<int, Axes> cache;
  auto [it, added] = cache.try_emplace(which);
  if (added) {
    const Problem p = problem(which);
    it->second = which == 0   ? axes_of(heavytop::simulate_lagrange_exact(p.body, p.start,
                                                                           heavytop::sample_times(p.horizon, 101)))
                  : which == 1 ? axes_of(run(p, Integrator::Dop853, 1e-15).trajectory)
                               : axes_of(run(p, Integrator::Taylor, 1e-15).trajectory);
  }
  return it->second;
}

// (tolerance, error) reaching `level` for the integrator on the problem (see the header).
std::pair<double, double> calibrate(int which, Integrator integrator, double level) {
  static std::map<std::tuple<int, Integrator, double>, std::pair<double, double>> cache;
  auto [it, added] = cache.try_emplace({which, integrator, level});
  if (!added) return it->second;
  const Problem p = problem(which);
  std::vector<double> errors;
  for (int k = 8; k <= 60; ++k) {
    const heavytop::Simulation s = run(p, integrator, std::pow(10.0, -k / 4.0));
    errors.push_back(s.summary.ok() ? max_angle(axes_of(s.trajectory), reference(which)) : 1e300);
  }
  it->second = {0.0, 0.0};
  for (std::size_t i = 0; i < errors.size(); ++i) {
    bool stays = true;
    for (std::size_t j = i; j < std::min(errors.size(), i + 9); ++j) stays = stays && errors[j] <= level;
    if (stays) {
      it->second = {std::pow(10.0, -static_cast<double>(i + 8) / 4.0), errors[i]};
      break;
    }
  }
  return it->second;
}

// Arguments: problem (0 toy, 1 asym, 2 toy-damped, 3 asym-stop), integrator (Integrator's value), -log10(error level).
void BM_EqualError(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const auto integrator = static_cast<Integrator>(state.range(1));
  const double level = std::pow(10.0, -static_cast<double>(state.range(2)));
  const auto [tol, error] = calibrate(which, integrator, level);
  if (tol == 0.0) {
    state.SkipWithError("level not reached at any tolerance");
    return;
  }
  const Problem p = problem(which);
  heavytop::Simulation s;
  for (auto _ : state) {
    s = run(p, integrator, tol);
    benchmark::DoNotOptimize(s.trajectory.theta.data());
  }
  state.SetLabel(std::string(heavytop::name(integrator)) + label(which));
  state.counters["tol"] = tol;
  state.counters["error"] = error;
  state.counters["steps"] = static_cast<double>(s.summary.steps);
  state.counters["evals"] = static_cast<double>(s.summary.rhs_evaluations);
  state.counters["time_per_eval"] = benchmark::Counter(
      static_cast<double>(s.summary.rhs_evaluations),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void equal_error_cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"problem", "integrator", "level"});
  for (int which : {0, 1})
    for (Integrator i : {Integrator::Taylor, Integrator::Dop853, Integrator::Adaptive})
      for (int level : {6, 9, 12}) b->Args({which, static_cast<int>(i), level});
  for (int which : {2, 3})
    for (Integrator i : {Integrator::Taylor, Integrator::Adaptive})
      for (int level : {4, 6, 9, 12}) b->Args({which, static_cast<int>(i), level});
}
BENCHMARK(BM_EqualError)->Apply(equal_error_cases)->UseRealTime()->Unit(benchmark::kMicrosecond);

// One evaluation of the plain equations of motion (the unit of the Taylor limit).
void BM_RightHandSide(benchmark::State& state) {
  const Problem p = problem(static_cast<int>(state.range(0)));
  const heavytop::RigidBodySystem system{p.body};
  heavytop::RigidBodyVector x = heavytop::to_vector(heavytop::initial_rigid_body_state(p.start)), d{};
  for (auto _ : state) {
    system(x, d, 0.0);
    benchmark::DoNotOptimize(d);
    x[4] += 1e-300;  // a new input each time
  }
}
BENCHMARK(BM_RightHandSide)->Arg(0)->Arg(1);

}  // namespace

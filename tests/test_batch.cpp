// The batched Taylor tilt scan (batch.hpp) and the sweep's nonlinear verdicts built on it:
// a point's result is the same bits whatever shares its batch and on every instruction set,
// equal to the unbatched Taylor integrator's, close to dopri5's and DOP853's, and equal to the
// closed form's largest tilt for symmetric tops; the sweep gives the same verdicts with
// auto and dopri5 away from the threshold, and the same whatever the threads and blocks.
// Every bound says what it was measured at (Release, GCC 12, x86-64, Xeon with AVX-512).

#include "heavytop/batch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "heavytop/dop853.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/taylor.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_state;
using test_support::sci;

struct Problem {
  Body body;
  InitialState start;
};

// Random real bodies around the toy top's and the asymmetric plate's sizes: half of them
// symmetric (A == B exactly, the spin-factored variables), half not (the plain ones); spins
// from well below to well above the critical spin, so some stay up and some fall within the
// horizon, tilts from 0.01 to 0.3 rad and small initial rates.
std::vector<Problem> random_problems(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Problem> out;
  for (std::size_t i = 0; i < count; ++i) {
    Body b;
    b.A = 1e-3 * (0.5 + u(rng));
    b.B = (i % 2 == 0) ? b.A : b.A * (0.7 + 0.6 * u(rng));
    // C in the triangle inequalities (|A - B| <= C <= A + B), R within A + B - C >= 2 m R^2.
    b.C = std::abs(b.A - b.B) + (0.2 + 1.0 * u(rng)) * std::min(b.A, b.B);
    b.mass = 0.2 + u(rng);
    b.gravity = 9.81;
    b.length = std::sqrt((b.A + b.B - b.C) / (2.0 * b.mass)) * (0.1 + 0.5 * u(rng)) * (u(rng) < 0.15 ? -1.0 : 1.0);
    const double critical = 2.0 * std::sqrt(std::max(b.A, b.B) * std::abs(b.mgR())) / b.C;  // the sleeping top's
    InitialState s = make_state(critical * (0.3 + 1.7 * u(rng)), 0.01 + 0.29 * u(rng), 0.05 * (u(rng) - 0.5),
                                0.5 * (u(rng) - 0.5), 0.5 * (u(rng) - 0.5));
    out.push_back({b, s});
  }
  return out;
}

Tolerances tolerance(double tol) {
  Tolerances o;
  o.rtol = o.atol = tol;
  return o;
}

std::vector<TiltExtremes> run(const std::vector<Problem>& problems, const std::vector<std::size_t>& which,
                              double horizon, double stop, const Tolerances& o, BatchIsa isa) {
  std::vector<Body> bodies;
  std::vector<InitialState> starts;
  for (std::size_t i : which) bodies.push_back(problems[i].body), starts.push_back(problems[i].start);
  std::vector<TiltExtremes> out(which.size());
  batch_tilt_extremes(bodies, starts, horizon, stop, o, out, isa);
  return out;
}

std::vector<TiltVerdict> run_verdicts(const std::vector<Problem>& problems, const std::vector<std::size_t>& which,
                                      double horizon, double stop, const Tolerances& o, BatchIsa isa) {
  std::vector<Body> bodies;
  std::vector<InitialState> starts;
  for (std::size_t i : which) bodies.push_back(problems[i].body), starts.push_back(problems[i].start);
  std::vector<TiltVerdict> out(which.size());
  batch_tilt_verdicts(bodies, starts, horizon, stop, o, out, isa);
  return out;
}

std::vector<BatchIsa> supported_isas() {
  std::vector<BatchIsa> isas;
  for (BatchIsa isa : {BatchIsa::Sse2, BatchIsa::Avx2, BatchIsa::Avx512})
    if (batch_isa_supported(isa)) isas.push_back(isa);
  return isas;
}

// Every field the scan reports, as bits.
void expect_same_bits(const TiltExtremes& a, const TiltExtremes& b, const std::string& where) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.max_tilt), std::bit_cast<std::uint64_t>(b.max_tilt)) << where;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.min_tilt), std::bit_cast<std::uint64_t>(b.min_tilt)) << where;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.t_max), std::bit_cast<std::uint64_t>(b.t_max)) << where;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.t_min), std::bit_cast<std::uint64_t>(b.t_min)) << where;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.t_end), std::bit_cast<std::uint64_t>(b.t_end)) << where;
  EXPECT_EQ(a.exceeded, b.exceeded) << where;
}

// A point alone, in batches of every size from 2 to 13 (partly filled lanes, lanes refilled
// after early stops), in reversed and shuffled order, and on every instruction set this
// processor has (2, 4, 8 lanes): the same bits each time, and batch_tilt_verdicts() (the
// sweep's call) the same crossing.
TEST(Batch, APointsResultDoesNotDependOnItsBatch) {
  const std::vector<Problem> problems = random_problems(40, 1);
  const Tolerances o = tolerance(1e-10);
  const double horizon = 5.0, stop = 0.6;
  std::vector<TiltExtremes> alone(problems.size());
  for (std::size_t i = 0; i < problems.size(); ++i) alone[i] = run(problems, {i}, horizon, stop, o, BatchIsa::Sse2)[0];
  std::size_t falls = 0;
  for (const auto& e : alone) falls += e.exceeded;
  RecordProperty("falls", static_cast<int>(falls));
  EXPECT_GT(falls, 5u);  // both outcomes in the mix
  EXPECT_LT(falls, problems.size() - 5);

  std::vector<std::size_t> all(problems.size());
  std::iota(all.begin(), all.end(), 0);
  std::vector<std::vector<std::size_t>> batches;
  for (std::size_t size = 2; size <= 13; ++size)
    for (std::size_t first = 0; first + size <= all.size(); first += size)
      batches.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(first),
                           all.begin() + static_cast<std::ptrdiff_t>(first + size));
  batches.push_back(all);
  batches.emplace_back(all.rbegin(), all.rend());
  std::vector<std::size_t> shuffled = all;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
  batches.push_back(shuffled);
  for (BatchIsa isa : supported_isas())
    for (const auto& which : batches) {
      const std::vector<TiltExtremes> got = run(problems, which, horizon, stop, o, isa);
      const std::vector<TiltVerdict> verdicts = run_verdicts(problems, which, horizon, stop, o, isa);
      for (std::size_t k = 0; k < which.size(); ++k) {
        const std::string where = std::string(name(isa)) + " batch of " + std::to_string(which.size()) +
                                  ", point " + std::to_string(which[k]);
        expect_same_bits(got[k], alone[which[k]], where);
        // The verdict alone (the sweep's call): the same crossing, bit for bit.
        EXPECT_EQ(verdicts[k].exceeded, alone[which[k]].exceeded) << where;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(verdicts[k].t_end), std::bit_cast<std::uint64_t>(alone[which[k]].t_end))
            << where;
      }
    }
}

// The batch is the unbatched Taylor integrator, lane by lane (no contraction into fused
// multiply-adds in either): taylor_tilt_extremes() gives the same bits, over 50 s, at the
// sweep's default tolerance 1e-12 and at 1e-8 (another order and step).
TEST(Batch, EqualsTheUnbatchedTaylorIntegratorBitForBit) {
  const std::vector<Problem> problems = random_problems(24, 2);
  std::vector<std::size_t> all(problems.size());
  std::iota(all.begin(), all.end(), 0);
  for (double tol : {1e-12, 1e-8}) {
    const std::vector<TiltExtremes> got = run(problems, all, 50.0, 0.8, tolerance(tol), best_batch_isa());
    for (std::size_t i = 0; i < problems.size(); ++i)
      expect_same_bits(got[i],
                       taylor_tilt_extremes(problems[i].body, problems[i].start, 50.0, 0.8, tolerance(tol)),
                       "tol " + sci(tol) + ", point " + std::to_string(i));
  }
}

// Against the two other integrators (dopri5 on the spin-factored state, DOP853 on the plain
// one), 60 random bodies over 20 s at tolerance 1e-12, stop at 0.8 rad (37 stay below, 23
// pass it): the same verdict; for those that stay below, the same largest tilt to 2e-9 rad;
// for those that pass it, the same crossing time to 1e-9 relative. (Measured: largest tilt
// within 9.0e-12 of dopri5's and 2.5e-10 of DOP853's; crossing times within 2.9e-11 and
// 1.3e-11 relative. The margin is for the growth of the step errors in a fall and over a run
// of thousands of steps, each held to 1e-12.)
TEST(Batch, AgreesWithDopri5AndDop853OnRandomBodies) {
  const std::vector<Problem> problems = random_problems(60, 3);
  std::vector<std::size_t> all(problems.size());
  std::iota(all.begin(), all.end(), 0);
  const Tolerances o = tolerance(1e-12);
  const double horizon = 20.0, stop = 0.8;
  const std::vector<TiltExtremes> got = run(problems, all, horizon, stop, o, best_batch_isa());
  double worst_tilt[2] = {}, worst_time[2] = {};
  std::size_t stable = 0, fell = 0;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const Problem& p = problems[i];
    const TiltExtremes refs[2] = {tilt_extremes(p.body, p.start, horizon, stop, o),
                                  dop853_tilt_extremes(p.body, p.start, horizon, stop, o)};
    for (int r = 0; r < 2; ++r) {
      const TiltExtremes& ref = refs[r];
      ASSERT_EQ(got[i].exceeded, ref.exceeded) << "point " << i << (r ? " dop853" : " dopri5");
      if (got[i].exceeded) {
        worst_time[r] = std::max(worst_time[r], std::abs(got[i].t_end - ref.t_end) / ref.t_end);
        EXPECT_NEAR(got[i].t_end, ref.t_end, 1e-9 * ref.t_end) << "point " << i << (r ? " dop853" : " dopri5");
      } else {
        worst_tilt[r] = std::max(worst_tilt[r], std::abs(got[i].max_tilt - ref.max_tilt));
        EXPECT_NEAR(got[i].max_tilt, ref.max_tilt, 2e-9) << "point " << i << (r ? " dop853" : " dopri5");
      }
    }
    (got[i].exceeded ? fell : stable) += 1;
  }
  EXPECT_GT(stable, 10u);
  EXPECT_GT(fell, 10u);
  RecordProperty("stable_fell", std::to_string(stable) + "/" + std::to_string(fell));
  RecordProperty("worst_tilt_difference_dopri5_dop853", sci(worst_tilt[0]) + "/" + sci(worst_tilt[1]));
  RecordProperty("worst_crossing_time_difference_dopri5_dop853", sci(worst_time[0]) + "/" + sci(worst_time[1]));
}

// Symmetric tops against the closed form (lagrange-exact): the largest tilt of the motion is
// the lower root of the cubic, nutation_bounds().max_tilt; over 30 nutation periods the scan
// reaches it, to 1e-11 rad at tolerance 1e-12 (40 tops; measured: 7.2e-12 at most, at order 24;
// 2.6e-13 at order 15, the order before taylor_order() took the measured rule).
TEST(Batch, LargestTiltOfSymmetricTopsIsTheClosedForms) {
  std::vector<Problem> problems;
  for (const Problem& p : random_problems(80, 4))
    if (p.body.A == p.body.B) problems.push_back(p);
  std::vector<Body> bodies;
  std::vector<InitialState> starts;
  std::vector<double> exact, horizons;
  double horizon = 0.0;
  for (const Problem& p : problems) {
    const LagrangeTop top = lagrange_top(p.body, p.start);
    const double period = nutation_period(top);
    if (!std::isfinite(period)) continue;
    bodies.push_back(p.body), starts.push_back(p.start);
    exact.push_back(nutation_bounds(top).max_tilt);
    horizons.push_back(30.0 * period);
    horizon = std::max(horizon, 30.0 * period);
  }
  ASSERT_GT(bodies.size(), 30u);
  std::vector<TiltExtremes> got(bodies.size());
  batch_tilt_extremes(bodies, starts, horizon, M_PI, tolerance(1e-12), got);
  double worst = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_FALSE(got[i].exceeded);
    EXPECT_NEAR(got[i].max_tilt, exact[i], 1e-11) << "top " << i;
    worst = std::max(worst, std::abs(got[i].max_tilt - exact[i]));
  }
  RecordProperty("worst_against_closed_form", sci(worst));
  RecordProperty("tops", static_cast<int>(bodies.size()));
}

// Damped bodies are not batched (their torques are in dopri5's equations only).
TEST(Batch, RefusesDampedBodiesNamingTheIntegrator) {
  Body b = example_toy_top();
  b.damping.transverse = 1e-6;
  EXPECT_FALSE(batchable(b));
  std::vector<Body> bodies{b};
  std::vector<InitialState> starts{make_state(200.0, 0.05)};
  std::vector<TiltExtremes> out(1);
  try {
    batch_tilt_extremes(bodies, starts, 1.0, 0.5, {}, out);
    FAIL() << "a damped body was batched";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "integrator");
  }
}

// ---- The sweep ---------------------------------------------------------------------------------

// The asymmetric plate of examples/asymmetric-plate.toml, B/A and spin varied (the map of the
// benchmark), over 20 s: auto (batched Taylor) and dopri5 (one point at a time) give the same
// nonlinear verdict at every point whose largest tilt (dopri5's) is not within 1e-6 rad of
// max_tilt, and the differing points, if any, are all within it.
TEST(BatchSweep, AutoAndDopri5GiveTheSameVerdictsAwayFromTheThreshold) {
  Body base;
  base.A = 0.010, base.B = 0.015, base.C = 0.020, base.mass = 1.0, base.length = 1.0193679918450561e-3;
  const InitialState state = make_state(1.3, 1e-4);
  const std::vector<SweepAxis> axes{parse_sweep_axis("B/A=1.05:1.95:10"), parse_sweep_axis("spin=0.5:3:12")};
  SweepOptions fast, slow;
  fast.nonlinear = slow.nonlinear = true;
  fast.horizon = slow.horizon = 20.0;
  fast.max_tilt = slow.max_tilt = 0.5;
  slow.nonlinear_integrator = Integrator::Adaptive;
  const auto a = sweep_verdicts(base, state, axes, fast, 0, grid_size(axes));
  const auto b = sweep_verdicts(base, state, axes, slow, 0, grid_size(axes));
  std::size_t stable = 0, near = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    Body body = base;
    InitialState s = state;
    apply_grid_point(axes, i, body, s);
    const double tilt = max_tilt(body, s, slow.horizon, slow.max_tilt, slow.integrator);
    const bool close = std::abs(tilt - slow.max_tilt) < 1e-6;
    near += close;
    if (!close) {
      EXPECT_EQ(*a[i].nonlinear, *b[i].nonlinear) << "point " << i << ", max tilt " << tilt;
    }
    EXPECT_EQ(*b[i].nonlinear, tilt <= slow.max_tilt) << "point " << i;
    stable += *a[i].nonlinear;
  }
  EXPECT_GT(stable, 10u);  // both verdicts on the map
  EXPECT_LT(stable, a.size() - 10);
  RecordProperty("points_near_threshold", static_cast<int>(near));
  RecordProperty("stable_points", static_cast<int>(stable));
}

// The nonlinear column does not depend on the threads nor on how the grid is cut into calls
// (the command line's chunks, MPI's blocks): one call, two threads, and calls of 1, 7 and 33
// points give the same verdicts; and taylor is auto.
TEST(BatchSweep, VerdictsDoNotDependOnThreadsOrBlocks) {
  const Body base = example_toy_top();
  const InitialState state = make_state(200.0, 0.05);
  const std::vector<SweepAxis> axes{parse_sweep_axis("C/A=0.2:1.2:9"), parse_sweep_axis("spin=20:200:11")};
  SweepOptions o;
  o.nonlinear = true;
  o.horizon = 5.0;
  o.max_tilt = 0.5;
  o.threads = 1;
  const std::size_t n = grid_size(axes);
  const auto one = sweep_verdicts(base, state, axes, o, 0, n);
  std::size_t stable = 0;
  for (const auto& v : one) stable += *v.nonlinear;
  RecordProperty("stable_points", static_cast<int>(stable));
  EXPECT_GT(stable, 5u);
  EXPECT_LT(stable, n - 5);
  SweepOptions two = o;
  two.threads = 2;
  SweepOptions taylor = o;
  taylor.nonlinear_integrator = Integrator::Taylor;
  const auto b = sweep_verdicts(base, state, axes, two, 0, n), c = sweep_verdicts(base, state, axes, taylor, 0, n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(*one[i].nonlinear, *b[i].nonlinear) << i;
    EXPECT_EQ(*one[i].nonlinear, *c[i].nonlinear) << i;
  }
  for (std::size_t block : {1u, 7u, 33u})
    for (std::size_t first = 0; first < n; first += block) {
      const auto part = sweep_verdicts(base, state, axes, o, first, std::min(n, first + block));
      for (std::size_t k = 0; k < part.size(); ++k) EXPECT_EQ(*part[k].nonlinear, *one[first + k].nonlinear) << first + k;
    }
}

// The splitting has no error control: a sweep refuses it (key "integrator").
TEST(BatchSweep, RefusesTheSplitting) {
  SweepOptions o;
  o.nonlinear_integrator = Integrator::Splitting;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why.substr(0, why.find(':')), "integrator");
}

}  // namespace
}  // namespace heavytop

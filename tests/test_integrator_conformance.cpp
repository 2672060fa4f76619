// One conformance suite over every integrator of the nonlinear model (the pattern of Drake's
// generic_integrator_test.h and MuJoCo's engine_forward_test.cc): dopri5, DOP853, the Taylor
// integrator, the general body's dopri5 and Taylor, the damped dopri5 and Taylor, and the
// splitting, each driven through simulate() and simulate_streaming() as the command line
// drives them. Each property is one a broken sample loop, writer or stepper would violate.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "heavytop/simulate.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::make_body;
using test_support::make_state;

struct Case {
  const char* name;
  Integrator integrator;
  Body body;
  InitialState start;
};

Body damped(Body b) {
  b.damping.transverse = 2e-3;
  b.damping.axial = 1e-3;
  b.damping.friction = 1e-4;
  return b;
}

Body general(Body b) {
  b.general.Ixy = 0.01;
  b.general.Ixz = 0.002;
  b.general.offset_x = 0.01;
  return b;
}

// An asymmetric body (A != B != C) and a symmetric one, spun fast enough to stay up over the
// short runs below, tilted so that every angle and rate moves.
const Body kAsymmetric = make_body(1.0, 1.3, 1.6, 0.5);
const Body kSymmetric = make_body(1.0, 1.0, 0.4, 0.5);
const InitialState kStart = make_state(8.0, 0.2, -0.1, 0.3, 0.2);

std::vector<Case> cases() {
  return {
      {"dopri5", Integrator::Dopri5, kAsymmetric, kStart},
      {"dopri5_symmetric", Integrator::Dopri5, kSymmetric, kStart},
      {"dopri5_damped", Integrator::Dopri5, damped(kAsymmetric), kStart},
      {"dopri5_general", Integrator::Dopri5, general(kAsymmetric), kStart},
      {"dop853", Integrator::Dop853, kAsymmetric, kStart},
      {"taylor", Integrator::Taylor, kAsymmetric, kStart},
      {"taylor_symmetric", Integrator::Taylor, kSymmetric, kStart},
      {"taylor_damped", Integrator::Taylor, damped(kSymmetric), kStart},
      {"taylor_general", Integrator::Taylor, general(kAsymmetric), kStart},
      {"splitting", Integrator::Splitting, kAsymmetric, kStart},
      {"splitting_order4", Integrator::Splitting, kSymmetric, kStart},
  };
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class Conformance : public ::testing::TestWithParam<Case> {
 protected:
  SimulateOptions options() const {
    SimulateOptions o;
    o.integrator = GetParam().integrator;
    o.adaptive.rtol = o.adaptive.atol = 1e-10;
    o.splitting.step = 1e-3;
    o.splitting.order = std::string(GetParam().name) == "splitting_order4" ? 4 : 2;
    return o;
  }
  bool splitting() const { return GetParam().integrator == Integrator::Splitting; }
  Simulation run(const std::vector<double>& times, const SimulateOptions& o, const Progress& progress = {}) const {
    return simulate(Model::Nonlinear, GetParam().body, GetParam().start, times, o, progress);
  }
  Simulation run(const std::vector<double>& times) const { return run(times, options()); }
  // The integrator's tilt scan over [0, kScanHorizon], or nothing where it has none for this
  // body (the splitting; dopri5's general body: InvalidInput).
  static constexpr double kScanHorizon = 1.0;
  std::optional<TiltExtremes> scan(double stop_above, const Progress& progress = {}) const {
    if (splitting()) return std::nullopt;
    try {
      return tilt_extremes(GetParam().integrator, GetParam().body, GetParam().start, kScanHorizon, stop_above,
                           options().adaptive, nullptr, progress);
    } catch (const InvalidInput&) {
      return std::nullopt;
    }
  }
};

const std::vector<double>& named(const Trajectory& t, const std::string& name) {
  const auto names = t.column_names();
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return t.column(c);
  throw std::runtime_error("no column " + name);
}

// The sample at t = 0 is the input state (SPEC section 2), not its round trip through the
// integrator's variables, and every drift and loss is exactly zero there.
TEST_P(Conformance, FirstSampleIsTheInputState) {
  const Simulation s = run(sample_times(0.5, 11));
  ASSERT_TRUE(s.summary.ok()) << s.summary.message;
  const Trajectory& t = s.trajectory;
  const InitialState& x0 = GetParam().start;
  EXPECT_NEAR(t.theta[0], x0.theta0, 1e-15);
  EXPECT_NEAR(t.phi[0], x0.phi0, 1e-15);
  EXPECT_NEAR(t.theta_rate[0], x0.theta_rate0, 1e-14);
  EXPECT_NEAR(t.phi_rate[0], x0.phi_rate0, 1e-14);
  for (const char* column : {"energy_drift", "vertical_momentum_drift", "axial_momentum_drift"})
    EXPECT_EQ(named(t, column)[0], 0.0) << column;
  if (!GetParam().body.damping.conservative()) {
    for (const char* column : {"dissipated_work", "vertical_momentum_loss", "axial_momentum_loss"})
      EXPECT_EQ(named(t, column)[0], 0.0) << column;
  }
}

// Streamed in chunks of 1, 7 and 64 samples, the trajectory is the gathered one, bit for bit,
// and the summaries agree.
TEST_P(Conformance, ChunkedStreamingEqualsGathering) {
  const SampleGrid grid{0.8, 101};
  std::vector<double> times(grid.count);
  for (std::size_t i = 0; i < grid.count; ++i) times[i] = grid.time(i);
  const Simulation gathered = run(times);
  ASSERT_TRUE(gathered.summary.ok()) << gathered.summary.message;
  for (std::size_t chunk : {1u, 7u, 64u}) {
    Trajectory streamed;
    std::size_t pieces = 0;
    const SimulationSummary s = simulate_streaming(Model::Nonlinear, GetParam().body, GetParam().start, grid,
                                                   options(), [&](const Trajectory& part) {
                                                     EXPECT_LE(part.size(), chunk);
                                                     ++pieces;
                                                     if (streamed.size() == 0) streamed = part;
                                                     else streamed.append(part);
                                                   }, chunk);
    ASSERT_TRUE(s.ok()) << s.message;
    EXPECT_EQ(pieces, (grid.count + chunk - 1) / chunk);
    ASSERT_EQ(streamed.column_names(), gathered.trajectory.column_names());
    for (std::size_t c = 0; c < streamed.column_names().size(); ++c)
      EXPECT_EQ(streamed.column(c), gathered.trajectory.column(c)) << streamed.column_names()[c] << ", chunk " << chunk;
    EXPECT_EQ(s.steps, gathered.summary.steps);
    EXPECT_EQ(s.rhs_evaluations, gathered.summary.rhs_evaluations);
  }
}

// Sampling reads the integrator's dense output and never changes its steps: the state at the
// end is the same bits with 2 samples as with 401, and so are the accepted and rejected steps
// (the splitting's shorter steps between grid points are on a copy).
TEST_P(Conformance, SamplingDoesNotChangeTheSteps) {
  const double t_end = 1.0;  // a multiple of the splitting's step: the end is on its grid
  const Simulation few = run({0.0, t_end});
  const Simulation many = run(sample_times(t_end, 401));
  ASSERT_TRUE(few.summary.ok() && many.summary.ok()) << few.summary.message << many.summary.message;
  const auto names = few.trajectory.column_names();
  for (std::size_t c = 0; c < names.size(); ++c)
    EXPECT_EQ(few.trajectory.column(c).back(), many.trajectory.column(c).back()) << names[c];
  if (!splitting()) {
    EXPECT_EQ(few.summary.steps, many.summary.steps);
    EXPECT_EQ(few.summary.rejected_steps, many.summary.rejected_steps);
  }
}

// Too few steps: a failure in one line naming max_steps, with the samples before it kept
// (the splitting refuses the step up front, as bad input).
TEST_P(Conformance, MaxStepsFailsInOneLine) {
  SimulateOptions o = options();
  o.adaptive.max_steps = 3;  // the Taylor integrator's steps are long: 10 s take more than 3
  o.splitting.max_steps = 3;
  if (splitting()) {
    try {
      run(sample_times(10.0, 11), o);
      FAIL() << "no error";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.key(), "step");
    }
    return;
  }
  const Simulation s = run(sample_times(10.0, 11), o);
  ASSERT_FALSE(s.summary.ok());
  EXPECT_EQ(s.summary.message.find('\n'), std::string::npos) << s.summary.message;
  EXPECT_NE(s.summary.message.find("max_steps = 3"), std::string::npos) << s.summary.message;
  EXPECT_LT(s.trajectory.size(), 11u);
  EXPECT_EQ(s.trajectory.size(), s.summary.samples);
}

// A state beyond a double (rates of 1e155 rad/s: w x I w and the energy overflow at once,
// over a run short enough to be meaningful): a failure in one line saying when, never a value
// that is not finite handed on.
TEST_P(Conformance, NonFiniteStateFailsInOneLine) {
  const InitialState x0 = make_state(0.0, 1.0, 0.5, 1e155, 1e155);
  const Simulation s = simulate(Model::Nonlinear, GetParam().body, x0, sample_times(1e-150, 5), options());
  ASSERT_FALSE(s.summary.ok());
  EXPECT_EQ(s.summary.message.find('\n'), std::string::npos) << s.summary.message;
  EXPECT_NE(s.summary.message.find("t = "), std::string::npos) << s.summary.message;
  for (std::size_t c = 0; c < s.trajectory.column_names().size(); ++c)
    for (double v : s.trajectory.column(c)) EXPECT_TRUE(std::isfinite(v));
}

// A progress callback that throws stops the run there: its message is the failure's, the
// samples before it are kept, no later one is computed.
TEST_P(Conformance, ThrowingProgressStopsTheRun) {
  int calls = 0;
  const Simulation s = run(sample_times(1.0, 101), options(), [&calls](double t) {
    if (++calls == 3) throw std::runtime_error("stopped at " + std::to_string(t));
  });
  ASSERT_FALSE(s.summary.ok());
  EXPECT_EQ(s.summary.message.rfind("stopped at ", 0), 0u) << s.summary.message;
  EXPECT_EQ(calls, 3);
  EXPECT_LE(s.trajectory.size(), 3u);
  EXPECT_EQ(s.trajectory.size(), s.summary.samples);
}

// Every tilt scan (the sweep's, lifetime's, the answer's) reports its progress the same way:
// times in [0, horizon], non-decreasing, the last the scan's end; a throw stops the scan (the
// exception goes through).
TEST_P(Conformance, TiltScanReportsProgressAndStopsOnAThrow) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> seen;
  if (!scan(inf, [&seen](double t) { seen.push_back(t); })) GTEST_SKIP() << "no tilt scan for this body";
  ASSERT_FALSE(seen.empty());
  EXPECT_GE(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), kScanHorizon);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  int calls = 0;
  EXPECT_THROW(scan(inf,
                    [&calls](double) {
                      ++calls;
                      throw std::runtime_error("stopped");
                    }),
               std::runtime_error);
  EXPECT_EQ(calls, 1);
}

// One stop contract for every tilt scan: at the first crossing of stop_above, t_end = t_max is
// the crossing (inside the full scan's first rise past it), max_tilt the tilt there (stop_above
// to 1e-9 rad) and spin_at_end w.k there (an independent route: simulate()'s C w3 / C at t_end).
TEST_P(Conformance, TiltScanStopsAtTheCrossing) {
  const std::optional<TiltExtremes> whole = scan(std::numeric_limits<double>::infinity());
  if (!whole) GTEST_SKIP() << "no tilt scan for this body";
  const TiltExtremes& full = *whole;
  const Simulation first = run({0.0, 1e-3});
  ASSERT_TRUE(first.summary.ok()) << first.summary.message;
  const double tilt0 = named(first.trajectory, "tilt").front();
  ASSERT_GT(full.max_tilt, tilt0 + 1e-3) << "the tilt must rise for the test to mean something";
  const double stop = 0.5 * (tilt0 + full.max_tilt);
  const TiltExtremes e = *scan(stop);
  ASSERT_TRUE(e.exceeded);
  EXPECT_GT(e.t_end, 0.0);
  EXPECT_LE(e.t_end, full.t_max);
  EXPECT_EQ(e.t_max, e.t_end);
  EXPECT_NEAR(e.max_tilt, stop, 1e-9);
  EXPECT_LE(e.min_tilt, tilt0);
  const Body& body = GetParam().body;
  if (is_general(body)) return;  // its axial_momentum is (I w).e3, not C w3
  const Simulation s = run({0.0, e.t_end});
  ASSERT_TRUE(s.summary.ok()) << s.summary.message;
  EXPECT_NEAR(e.spin_at_end, named(s.trajectory, "axial_momentum").back() / body.C, 1e-6 * std::abs(GetParam().start.spin));
}

// The summary's counts add up, by each integrator's own rule.
TEST_P(Conformance, SummaryCountsAddUp) {
  const Simulation s = run(sample_times(1.0, 51));
  ASSERT_TRUE(s.summary.ok()) << s.summary.message;
  const SimulationSummary& m = s.summary;
  EXPECT_EQ(m.samples, 51u);
  EXPECT_GT(m.steps, 0u);
  ASSERT_TRUE(m.drifts.has_value());
  const bool friction = GetParam().body.damping.friction > 0.0;
  switch (GetParam().integrator) {
    case Integrator::Dopri5:  // one evaluation at the start, six new stages an attempt (FSAL), one a friction event
      if (friction) EXPECT_GE(m.rhs_evaluations, 1 + 6 * (m.steps + m.rejected_steps));
      else EXPECT_EQ(m.rhs_evaluations, 1 + 6 * (m.steps + m.rejected_steps));
      break;
    case Integrator::Dop853: {  // two to start, twelve an attempt, three a sampled step's dense output
      const std::size_t rest = m.rhs_evaluations - 2 - 12 * (m.steps + m.rejected_steps);
      EXPECT_EQ(rest % 3, 0u);
      EXPECT_LE(rest / 3, m.steps);
      EXPECT_GE(rest / 3, 1u);
      break;
    }
    case Integrator::Taylor: {  // `order` evaluations a step, none rejected
      int order = 0;
      ASSERT_EQ(std::sscanf(m.solver.c_str(), "Taylor, order %d", &order), 1) << m.solver;
      EXPECT_EQ(m.rhs_evaluations, static_cast<std::size_t>(order) * m.steps);
      EXPECT_EQ(m.rejected_steps, 0u);
      break;
    }
    case Integrator::Splitting: {  // two kicks a Strang step, five Strang steps an order-4 step
      const std::size_t strangs = options().splitting.order == 4 ? 5 : 1;
      EXPECT_EQ(m.rhs_evaluations, 2 * strangs * m.steps);
      EXPECT_GE(m.steps, 1000u);  // 1 s of 1 ms steps, plus the shorter ones to samples off the grid
      break;
    }
    default: FAIL();
  }
  if (s.adaptive) {
    EXPECT_EQ(s.adaptive->steps, m.steps);
    EXPECT_EQ(s.adaptive->rhs_evaluations, m.rhs_evaluations);
    EXPECT_GE(s.adaptive->final_time, 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, Conformance, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace heavytop

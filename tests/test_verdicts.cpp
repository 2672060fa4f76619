// decided_tilt_verdicts() (verdicts.hpp): each verdict at the tolerance that decides it gives
// the verdicts of the sweep's default pass (batch_tilt_verdicts at 1e-12) point for point, on
// every example's map and on maps built so that many points lie near the threshold, where the
// loose pass and the closed form must hand their points on; and the tolerance recorded is the
// one that decided each point.

#include "heavytop/verdicts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "heavytop/batch.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/lyapunov.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

struct Grid {
  std::vector<Body> bodies;
  std::vector<InitialState> states;
};

Grid grid(const Body& base, const InitialState& start, const std::vector<SweepAxis>& axes) {
  Grid g;
  for (std::size_t i = 0; i < grid_size(axes); ++i) {
    Body b = base;
    InitialState s = start;
    apply_grid_point(axes, i, b, s);
    g.bodies.push_back(b), g.states.push_back(s);
  }
  return g;
}

struct Outcome {
  // closed: decided by a symmetric top's closed form; barrier: by the conserved quantities
  std::size_t differ = 0, closed = 0, barrier = 0, loose = 0, tight = 0, stable = 0;
};

// The decided verdicts against the default pass's, and who decided them.
Outcome compare(const Grid& g, double horizon, double max_tilt, const Tolerances& o = Tolerances{}) {
  // o: the sweep's tolerance (its default 1e-12 unless given)
  std::vector<TiltVerdict> reference(g.bodies.size());
  batch_tilt_verdicts(g.bodies, g.states, horizon, max_tilt, o, reference);
  std::vector<DecidedVerdict> got(g.bodies.size());
  decided_tilt_verdicts(g.bodies, g.states, horizon, max_tilt, o, got);
  Outcome out;
  for (std::size_t i = 0; i < got.size(); ++i) {
    out.differ += got[i].exceeded != reference[i].exceeded;
    out.stable += !reference[i].exceeded;
    if (got[i].tolerance == 0.0) {
      ++(g.bodies[i].A == g.bodies[i].B ? out.closed : out.barrier);
      EXPECT_FALSE(got[i].exceeded) << "without integration only bodies that stay up are decided, point " << i;
    } else if (got[i].tolerance == kLooseTolerance) {
      ++out.loose;
    } else {
      EXPECT_EQ(got[i].tolerance, o.rtol) << "point " << i;
      ++out.tight;
    }
  }
  return out;
}

// Every example configuration with a [body] (mesh-top's parts are integrated as a general
// body, which the batch does not take): its map over spin and C/A around its own values (the
// plate's over B/A x spin, docs/commands.md's map), 12 x 12 points, horizon 50 s, max tilt
// 0.5 rad (the horizontal gyroscope starts at pi/2: its own tilt + 0.5); at the sweep's
// default tolerance and at 1e-9.
TEST(DecidedVerdicts, EqualTheDefaultPassOnEveryExampleMap) {
  std::size_t maps = 0, points = 0, by_default = 0;
  for (const auto& entry : std::filesystem::directory_iterator(HEAVYTOP_EXAMPLES)) {
    if (entry.path().extension() != ".toml") continue;
    const io::Configuration c = io::read_configuration(entry.path().string(), "--config");
    if (!c.has_body || !c.parts.empty() || !batchable(c.body)) continue;
    SCOPED_TRACE(entry.path().filename().string());
    const Body& b = c.body;
    const InitialState& s = c.motion;
    std::vector<SweepAxis> axes;
    if (b.A != b.B) {
      axes = {parse_sweep_axis("B/A=1.05:2.95:12"), parse_sweep_axis("spin=0.5:4:12")};
    } else {
      const double r = b.C / b.A, top = std::min(1.4 * r, 1.0 + b.B / b.A - 1e-3);
      axes = {parse_sweep_axis("C/A=" + std::to_string(0.6 * r) + ":" + std::to_string(top) + ":12"),
              parse_sweep_axis("spin=" + std::to_string(0.3 * s.spin) + ":" + std::to_string(2.0 * s.spin) + ":12")};
    }
    const double max_tilt = std::max(0.5, tilt(s.theta0, s.phi0) + 0.5);
    const Grid g = grid(b, s, axes);
    const Outcome o = compare(g, 50.0, max_tilt);
    EXPECT_EQ(o.differ, 0u) << entry.path().filename();
    ++maps, points += 144, by_default += o.tight;
    // A looser sweep tolerance (--rtol 1e-9): the same verdicts as the default pass at it.
    Tolerances looser;
    looser.rtol = looser.atol = 1e-9;
    EXPECT_EQ(compare(g, 50.0, max_tilt, looser).differ, 0u) << entry.path().filename() << " at 1e-9";
  }
  EXPECT_GE(maps, 6u);  // plate, equal moments, three gyroscopes, toy top
  // Most points are decided without the default pass (the point of it).
  EXPECT_LT(by_default, points / 2);
  RecordProperty("maps", static_cast<int>(maps));
  RecordProperty("points_by_default_pass", static_cast<int>(by_default));
}

// Symmetric tops whose largest tilt (closed form) lies within 1e-4 rad of the threshold, on
// both sides: the toy top at theta0 = 0.05 over a narrow range of spins around the one whose
// largest tilt is 0.5 rad exactly (found by bisection on the closed form).
TEST(DecidedVerdicts, EqualTheDefaultPassForSymmetricTopsWithin1e4RadOfTheThreshold) {
  Body b = example_toy_top();
  InitialState s;
  s.theta0 = 0.05;
  auto largest = [&](double spin) {
    s.spin = spin;
    return nutation_bounds(lagrange_top(b, s)).max_tilt;
  };
  double lo = 100.0, hi = 400.0;  // the largest tilt falls as the spin grows
  ASSERT_GT(largest(lo), 0.5);
  ASSERT_LT(largest(hi), 0.5);
  for (int k = 0; k < 60; ++k) (largest(0.5 * (lo + hi)) > 0.5 ? lo : hi) = 0.5 * (lo + hi);
  // d(tilt)/d(spin) here, to place the grid at +-1e-4 rad of tilt.
  const double slope = (largest(lo * 1.001) - largest(lo * 0.999)) / (0.002 * lo);
  const double half_width = std::abs(1e-4 / slope);
  const std::vector<SweepAxis> axes = {parse_sweep_axis("spin=" + std::to_string(lo - half_width) + ":" +
                                                        std::to_string(lo + half_width) + ":201")};
  const Grid g = grid(b, s, axes);
  std::size_t near = 0;
  for (std::size_t i = 0; i < g.bodies.size(); ++i)
    near += std::abs(nutation_bounds(lagrange_top(g.bodies[i], g.states[i])).max_tilt - 0.5) < 1.01e-4;
  EXPECT_GE(near, 190u);
  const Outcome o = compare(g, 50.0, 0.5);
  EXPECT_EQ(o.differ, 0u);
  EXPECT_GT(o.closed, 50u);  // those more than 1e-6 rad below decided in closed form
  EXPECT_GT(o.stable, 50u);
  EXPECT_LT(o.stable, 150u);
  RecordProperty("closed_form", static_cast<int>(o.closed));
}

// Nearly symmetric bodies (B/A = 1.002 .. 1.03: the plain variables, the loose pass), the toy
// top's size at theta0 = 0.1, over spins where the largest tilt of their nutation goes from
// about 0.3 to 0.7 rad: many points in the band max_tilt -+ 0.05 and on its edges, where the
// loose pass must decide only what the default pass decides alike.
TEST(DecidedVerdicts, EqualTheDefaultPassForAsymmetricBodiesNearTheThreshold) {
  Body b = example_toy_top();
  InitialState s;
  s.theta0 = 0.1;
  // The symmetric top's spins with largest tilt 0.7 and 0.3 rad bound the range.
  auto spin_at = [&](double target) {
    double lo = 60.0, hi = 600.0;
    for (int k = 0; k < 60; ++k) {
      s.spin = 0.5 * (lo + hi);
      (nutation_bounds(lagrange_top(b, s)).max_tilt > target ? lo : hi) = s.spin;
    }
    return lo;
  };
  const double slow = spin_at(0.7), fast = spin_at(0.3);
  const std::vector<SweepAxis> axes = {parse_sweep_axis("B/A=1.002:1.03:5"),
                                       parse_sweep_axis("spin=" + std::to_string(slow) + ":" + std::to_string(fast) + ":40")};
  const Grid g = grid(b, s, axes);
  const double horizon = 20.0, max_tilt = 0.5;
  std::vector<TiltExtremes> e(g.bodies.size());
  batch_tilt_extremes(g.bodies, g.states, horizon, M_PI, Tolerances{}, e);
  std::size_t in_band = 0, near_edges = 0;
  for (const TiltExtremes& x : e) {
    const double d = std::abs(x.max_tilt - max_tilt);
    in_band += d < 0.05;
    near_edges += d >= 0.05 && d < 0.1;
  }
  EXPECT_GE(in_band, 25u);
  EXPECT_GE(near_edges, 25u);
  const Outcome o = compare(g, horizon, max_tilt);
  EXPECT_EQ(o.differ, 0u);
  EXPECT_EQ(o.closed, 0u);
  EXPECT_GT(o.loose, 40u);  // the loose pass decided some, the rest went on
  EXPECT_GE(o.tight, in_band);
  RecordProperty("in_band", static_cast<int>(in_band));
  RecordProperty("loose", static_cast<int>(o.loose));
}

// The plate's map (B/A x spin, docs/commands.md), 20 x 20: the unstable upright rotations fall
// fast and are decided by the loose pass's growth rule, the superfast ones (stable by the
// energy-Casimir argument) by the conserved quantities' barrier, without integration.
TEST(DecidedVerdicts, DecideMostOfThePlatesMapWithoutTheDefaultPass) {
  Body b;
  b.A = 0.010, b.B = 0.015, b.C = 0.020, b.mass = 1.0, b.length = 1.0193679918450561e-3;
  InitialState s;
  s.spin = 1.3, s.theta0 = 1e-4;
  const Grid g = grid(b, s, {parse_sweep_axis("B/A=1.05:2.95:20"), parse_sweep_axis("spin=0.5:4:20")});
  const Outcome o = compare(g, 50.0, 0.5);
  EXPECT_EQ(o.differ, 0u);
  EXPECT_GT(o.loose + o.barrier, 300u);
  EXPECT_GT(o.barrier, 100u);
  EXPECT_GT(o.stable, 50u);
  RecordProperty("loose", static_cast<int>(o.loose));
  RecordProperty("barrier", static_cast<int>(o.barrier));
}

// The conserved quantities' barrier (tilt_forbidden_by_conserved_quantities) is a proof for the
// exact motion: it never forbids a tilt the motion reaches. Plates at theta0 = 0.1 rad over
// B/A = 1.05 .. 1.9 and spins from below to above the superfast spin sqrt(m g R / (C - B))
// (1.0 .. 3.1 rad/s at these B/A), 20 x 20: each one's largest tilt over 50 s (the batch at
// 1e-12) is not forbidden (at 1 - 1e-9 of it, with no margin); twice it is forbidden for most
// superfast ones (the bound is 1.08 to 5.6 times the largest tilt here, 1.73 at the median);
// and the map with max tilt 0.2 rad, where most stable points' largest tilts lie within 0.1 rad
// below the threshold, gives the default pass's verdicts.
TEST(DecidedVerdicts, TheConservedQuantitiesNeverForbidATiltTheMotionReaches) {
  Body b;
  b.A = 0.010, b.B = 0.015, b.C = 0.020, b.mass = 1.0, b.length = 1.0193679918450561e-3;
  InitialState s;
  s.theta0 = 0.1;
  const Grid g = grid(b, s, {parse_sweep_axis("B/A=1.05:1.9:20"), parse_sweep_axis("spin=0.8:4:20")});
  std::vector<TiltExtremes> e(g.bodies.size());
  batch_tilt_extremes(g.bodies, g.states, 50.0, M_PI, Tolerances{}, e);
  constexpr double kMaxTilt = 0.2;
  std::size_t superfast = 0, forbidden_twice = 0, near = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const Body& x = g.bodies[i];
    const double reached = e[i].max_tilt;
    EXPECT_FALSE(tilt_forbidden_by_conserved_quantities(x, g.states[i], reached * (1.0 - 1e-9), 0.0)) << "point " << i;
    const double spin = g.states[i].spin;
    if ((x.C - std::max(x.A, x.B)) * spin * spin > x.mgR()) {
      ++superfast;
      forbidden_twice += tilt_forbidden_by_conserved_quantities(x, g.states[i], 2.0 * reached, 1e-6);
    }
    near += reached > kMaxTilt - 0.1 && reached < kMaxTilt;
  }
  EXPECT_GT(superfast, 100u);
  EXPECT_GT(forbidden_twice, superfast / 2);
  EXPECT_GT(near, 100u);
  const Outcome o = compare(g, 50.0, kMaxTilt);
  EXPECT_EQ(o.differ, 0u);
  EXPECT_GT(o.barrier, 50u);
  RecordProperty("superfast", static_cast<int>(superfast));
  RecordProperty("forbidden_twice", static_cast<int>(forbidden_twice));
  RecordProperty("near", static_cast<int>(near));
  RecordProperty("barrier", static_cast<int>(o.barrier));
}

// The plate's unstable rotations crossing the threshold near the horizon: seven horizons from
// 3 s to 47.8 s, among them the median and the 90th percentile of their crossing times at
// 1e-12 (10.5 s and 16.3 s on the 40 x 40 map) and the last one, where the loose pass's rule
// for a fall (the crossing's shift) must hand the late ones on. 40 x 40 points.
TEST(DecidedVerdicts, EqualTheDefaultPassWhereThePlateFallsNearTheHorizon) {
  Body b;
  b.A = 0.010, b.B = 0.015, b.C = 0.020, b.mass = 1.0, b.length = 1.0193679918450561e-3;
  InitialState s;
  s.spin = 1.3, s.theta0 = 1e-4;
  const Grid g = grid(b, s, {parse_sweep_axis("B/A=1.05:2.95:40"), parse_sweep_axis("spin=0.5:4:40")});
  std::size_t late_total = 0;
  for (double horizon : {3.0, 6.0, 10.5, 16.3, 25.0, 40.0, 47.8}) {
    std::vector<TiltVerdict> v(g.bodies.size());
    batch_tilt_verdicts(g.bodies, g.states, horizon, 0.5, Tolerances{}, v);
    std::size_t late = 0;  // crossings in the last 20% of the horizon
    for (const TiltVerdict& x : v) late += x.exceeded && x.t_end > 0.8 * horizon;
    if (horizon == 10.5 || horizon == 16.3) {
      EXPECT_GT(late, 50u) << horizon;
    }
    const Outcome o = compare(g, horizon, 0.5);
    EXPECT_EQ(o.differ, 0u) << horizon;
    EXPECT_GT(o.loose + o.barrier, 800u) << horizon;  // the stable ones by the barrier
    EXPECT_GT(o.loose, 300u) << horizon;
    late_total += late;
  }
  RecordProperty("late_crossings", static_cast<int>(late_total));
}

// The loose pass's estimate of how late a fall's crossing may be (crossing_delay_estimate)
// against the crossing measured at 1e-12, on the plate's unstable rotations from three
// initial tilts (where the tilt's amplitude grows from 1e-6, 1e-4 and 1e-2 rad), over 100 s:
// every fall it estimates is one at 1e-12 too, each crossing within 1/50 of its estimate
// (1/230 at worst when written).
TEST(DecidedVerdicts, TheCrossingDelayEstimateBoundsTheMeasuredDelay) {
  Body b;
  b.A = 0.010, b.B = 0.015, b.C = 0.020, b.mass = 1.0, b.length = 1.0193679918450561e-3;
  const double horizon = 100.0, low = 0.45, high = 0.55;
  Tolerances loose;
  loose.rtol = loose.atol = kLooseTolerance;
  for (double theta0 : {1e-6, 1e-4, 1e-2}) {
    InitialState s;
    s.spin = 1.3, s.theta0 = theta0;
    const Grid g = grid(b, s, {parse_sweep_axis("B/A=1.05:2.95:40"), parse_sweep_axis("spin=0.5:4:40")});
    std::vector<TiltBand> bands(g.bodies.size());
    batch_tilt_bands(g.bodies, g.states, horizon, low, high, loose, bands);
    std::vector<TiltVerdict> exact(g.bodies.size());
    batch_tilt_verdicts(g.bodies, g.states, horizon, high, Tolerances{}, exact);
    std::size_t estimated = 0;
    double worst = 0.0;  // the largest measured delay over its estimate
    for (std::size_t i = 0; i < bands.size(); ++i) {
      const double delay = crossing_delay_estimate(bands[i], theta0, high, loose);
      if (!std::isfinite(delay)) continue;
      ++estimated;
      ASSERT_TRUE(exact[i].exceeded) << theta0 << " point " << i;
      worst = std::max(worst, std::abs(exact[i].t_end - bands[i].t_end) / delay);
    }
    EXPECT_GT(estimated, theta0 < 1e-5 ? 100u : 500u) << theta0;
    EXPECT_LT(worst, 0.02) << theta0;
    RecordProperty("worst_" + std::to_string(theta0), std::to_string(worst));
  }
}

TEST(DecidedVerdicts, RefuseUnequalSpansAndABadMaxTilt) {
  const Body b = example_toy_top();
  InitialState s;
  s.spin = 200.0, s.theta0 = 0.05;
  std::vector<Body> bodies{b, b};
  std::vector<InitialState> states{s};
  std::vector<DecidedVerdict> out(2);
  try {
    decided_tilt_verdicts(bodies, states, 1.0, 0.5, Tolerances{}, out);
    FAIL() << "unequal spans accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "bodies");
  }
  states.push_back(s);
  try {
    decided_tilt_verdicts(bodies, states, 1.0, 0.0, Tolerances{}, out);
    FAIL() << "max_tilt 0 accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "max_tilt");
  }
}

}  // namespace
}  // namespace heavytop

namespace heavytop {
namespace {

// sweep_verdicts() takes its nonlinear column from decided_tilt_verdicts(): the default pass's
// verdicts, each with the tolerance that decided it; dopri5's one point at a time records the
// sweep's own.
TEST(DecidedVerdicts, SweepRecordsTheTolerancePerPoint) {
  const Body base = example_toy_top();
  InitialState state;
  state.spin = 200.0, state.theta0 = 0.05;
  const std::vector<SweepAxis> axes{parse_sweep_axis("B/A=1:1.2:3"), parse_sweep_axis("spin=60:300:8")};
  SweepOptions o;
  o.nonlinear = true, o.horizon = 5.0, o.max_tilt = 0.5, o.threads = 1;
  const std::vector<SweepVerdict> got = sweep_verdicts(base, state, axes, o, 0, grid_size(axes));
  const Grid g = grid(base, state, axes);
  std::vector<TiltVerdict> reference(g.bodies.size());
  batch_tilt_verdicts(g.bodies, g.states, o.horizon, o.max_tilt, o.integrator, reference);
  std::size_t closed = 0, loose = 0, tight = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_TRUE(got[i].nonlinear && got[i].nonlinear_tolerance);
    EXPECT_EQ(*got[i].nonlinear, !reference[i].exceeded) << i;
    const double t = *got[i].nonlinear_tolerance;
    closed += t == 0.0, loose += t == kLooseTolerance, tight += t == o.integrator.rtol;
  }
  EXPECT_EQ(closed + loose + tight, got.size());
  EXPECT_GT(closed, 0u);  // B/A = 1: symmetric tops that stay up
  EXPECT_GT(loose + tight, 0u);
  SweepOptions dopri5 = o;
  dopri5.nonlinear_integrator = Integrator::Adaptive;
  for (const SweepVerdict& v : sweep_verdicts(base, state, axes, dopri5, 0, 4)) EXPECT_EQ(*v.nonlinear_tolerance, 1e-12);
}

// `sweep --tolerance-column`: the CSV's nonlinear_tolerance column, read back by the resume's
// check (valid_journal_records) and past by read_map; MPI's packed records carry the tolerance
// as a class (0 none, 1 closed form, 2 loose, 3 the sweep's own), and so does an HDF5 sweep's
// journal with the column (one without has none).
TEST(DecidedVerdicts, TheToleranceColumnRoundTrips) {
  const std::vector<SweepAxis> axes{parse_sweep_axis("spin=100:300:3")};
  std::vector<SweepVerdict> v(3);
  v[0].nonlinear = true, v[0].nonlinear_tolerance = 0.0;
  v[1].nonlinear = true, v[1].nonlinear_tolerance = kLooseTolerance;
  v[2].nonlinear = false, v[2].nonlinear_tolerance = 1e-12;
  const std::string head = io::sweep_csv_header(axes, true, true), rows = io::sweep_csv_rows(axes, 0, v, true);
  EXPECT_TRUE(head.ends_with(",nonlinear,nonlinear_tolerance\n")) << head;
  EXPECT_EQ(rows.substr(rows.rfind(',', rows.size() - 2)), ",1e-12\n");
  EXPECT_EQ(io::valid_journal_records(rows, axes, true, false, true), 3u);
  EXPECT_EQ(io::valid_journal_records(rows, axes, true, false, false), 0u);  // a column too many
  EXPECT_EQ(io::sweep_csv_rows(axes, 0, v), io::sweep_csv_rows(axes, 0, v, false));  // the contract's rows
  EXPECT_EQ(io::sweep_csv_rows(axes, 0, v).find("e-"), std::string::npos);
  std::string packed;
  io::pack_verdicts(v, packed);
  const std::vector<SweepVerdict> back = io::unpack_verdicts(packed, 1e-12);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back[i].nonlinear, v[i].nonlinear) << i;
    EXPECT_EQ(back[i].nonlinear_tolerance, v[i].nonlinear_tolerance) << i;
  }
  EXPECT_EQ(io::valid_journal_records(packed, axes, true, true), 0u);  // a journal without the column has no tolerance bits
  EXPECT_EQ(io::valid_journal_records(packed, axes, true, true, true), 3u);  // one with it has them
  for (SweepVerdict& x : v) x.nonlinear_tolerance.reset();
  packed.clear();
  io::pack_verdicts(v, packed);
  EXPECT_EQ(io::valid_journal_records(packed, axes, true, true), 3u);
  EXPECT_EQ(io::valid_journal_records(packed, axes, true, true, true), 0u);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "heavytop-test-tolerance-column.csv";
  {
    std::ofstream out(file);
    out << head << rows;
  }
  const StabilityMap map = io::read_map(file.string(), "--map");
  std::filesystem::remove(file);
  EXPECT_TRUE(map.nonlinear);
  EXPECT_EQ(map.verdicts.size(), 3u);
  EXPECT_EQ(*map.verdicts[1].nonlinear, true);
}
// The rows of bodies that Arnold's theorem proves stable (kam, kam-markeev) are a resumed sweep's
// too, in CSV and packed records: the check knew only the first three certificates, and a resume
// recomputed everything from the first such row on. The property itself: the certificates that
// prove stability are exactly those lyapunov_stability gives with a Stable verdict.
TEST(DecidedVerdicts, ArnoldsCertificatesAreKeptByTheResume) {
  const std::vector<SweepAxis> axes{parse_sweep_axis("spin=100:300:3")};
  std::vector<SweepVerdict> v(3);
  const LyapunovCertificate certificates[] = {LyapunovCertificate::Kam, LyapunovCertificate::KamMarkeev,
                                              LyapunovCertificate::Resonance};
  for (std::size_t i = 0; i < 3; ++i) {
    v[i].lyapunov_certificate = certificates[i];
    v[i].lyapunov = proves_stability(certificates[i]);
    v[i].nonlinear = true;
  }
  EXPECT_TRUE(v[0].lyapunov && v[1].lyapunov && !v[2].lyapunov);
  EXPECT_EQ(io::valid_journal_records(io::sweep_csv_rows(axes, 0, v), axes, true, false), 3u);
  std::string packed;
  io::pack_verdicts(v, packed);
  EXPECT_EQ(io::valid_journal_records(packed, axes, true, true), 3u);
  // lyapunov_stability's Stable verdicts over asymmetric tops (index 2: C below A and B) carry exactly these.
  std::size_t arnold = 0;
  for (double b : {1.05, 1.2, 1.4})
    for (double spin = 0.5; spin < 200.0; spin *= 1.3) {
      const LyapunovVerdict verdict = lyapunov_stability(test_support::make_body(1.0, b, 0.6, 1.0), spin);
      EXPECT_EQ(verdict.verdict == LyapunovVerdictKind::Stable, proves_stability(verdict.certificate)) << b << " " << spin;
      arnold += verdict.certificate == LyapunovCertificate::Kam || verdict.certificate == LyapunovCertificate::KamMarkeev;
    }
  EXPECT_GT(arnold, 0u);
}

}  // namespace
}  // namespace heavytop

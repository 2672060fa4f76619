// The body on a table (table.hpp, SPEC section 16) against independent routes: the
// frictionless top's reduction to a quadrature (the tilt does not depend on the tip's radius;
// its turning points are the roots of the effective energy), the first integrals each contact
// keeps (energy, the vertical angular momentum about G, Jellett's integral), the closed forms of
// the spinning states' stability derived in docs/table.md (frictionless, rolling: Routh's
// criterion, viscous sliding: the spin at which the upright state changes stability, free of
// mu and slip_speed), and the published tippe top (Friedl 1997; Leine and Glocker 2003).

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <gtest/gtest.h>

#include "heavytop/simulate.hpp"
#include "heavytop/table.hpp"
#include "table_testing.hpp"

namespace heavytop {
namespace {

using table_testing::column;
using table_testing::start;
using table_testing::toy_top;

constexpr double kPi = 3.141592653589793;

// Friedl's tippe top on its ball (Leine and Glocker 2003): m = 6 g, A_G = 8e-7, C = 7e-7 kg m^2,
// r = 15 mm, the centre of mass 3 mm below the ball's centre.
Body tippe_top(double central_A = 8e-7) {
  Body b;
  b.mass = 0.006;
  b.length = -0.003;
  b.C = 7e-7;
  b.A = b.B = central_A + b.mass * b.length * b.length;
  b.tip_radius = 0.015;
  return b;
}

Table table_of(Contact contact, double friction = 0.0) {
  Table t;
  t.contact = contact;
  t.friction = friction;
  return t;
}

Tolerances tight() { return table_testing::tolerances(1e-13, 1e-14); }

// ---- frictionless ---------------------------------------------------------------------------

TEST(TableFrictionless, TheTiltDoesNotDependOnTheTipRadius) {
  const InitialState s = start(150.0, 0.3, 0.1, 2.0);
  const SampleGrid grid{1.0, 401};
  const TableRun sharp = simulate_on_table(toy_top(0.0), table_of(Contact::Frictionless), s, grid, tight());
  const TableRun round = simulate_on_table(toy_top(0.004), table_of(Contact::Frictionless), s, grid, tight());
  ASSERT_EQ(sharp.trajectory.size(), grid.count);
  ASSERT_EQ(round.trajectory.size(), grid.count);
  const auto& a = column(sharp, "tilt");
  const auto& b = column(round, "tilt");
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  EXPECT_LT(worst, 1e-9);
  // The height of O is the tip's radius, the normal force near m g on average.
  for (double h : column(round, "height")) EXPECT_DOUBLE_EQ(h, 0.004);
}

TEST(TableFrictionless, KeepsEnergyVerticalMomentumAboutGSpinAndGsVelocity) {
  const Body body = toy_top(0.002);
  const InitialState s = start(120.0, 0.4, -0.2, 3.0);
  const TableRun run = simulate_on_table(body, table_of(Contact::Frictionless), s, {2.0, 201}, tight());
  EXPECT_LT(run.summary.max_relative_energy_drift, 1e-10);
  EXPECT_LT(run.summary.max_relative_vertical_momentum_drift, 1e-10);
  const auto& spin = column(run, "spin");
  for (double w : spin) EXPECT_NEAR(w, spin.front(), 1e-10 * std::abs(spin.front()));
  // G = P + l k + r n: its horizontal position moves at the constant velocity it started with
  // (O at rest: l (w x k)_h, w = phi_rate0 (cos theta0, 0, -sin theta0) + spin k at phi0 ...).
  const auto& x = column(run, "x");
  const auto& y = column(run, "y");
  const Trajectory& tr = run.trajectory;
  auto G = [&](std::size_t i) {
    const double kx = std::sin(tr.theta[i]) * std::cos(tr.phi[i]), ky = -std::sin(tr.phi[i]);
    return std::array<double, 2>{x[i] + body.length * kx, y[i] + body.length * ky};
  };
  const std::size_t n = tr.size();
  const auto g0 = G(0), g1 = G(n - 1);
  const double vx = (g1[0] - g0[0]) / tr.t[n - 1], vy = (g1[1] - g0[1]) / tr.t[n - 1];
  for (std::size_t i = 0; i < n; ++i) {
    const auto g = G(i);
    EXPECT_NEAR(g[0], g0[0] + vx * tr.t[i], 1e-11);
    EXPECT_NEAR(g[1], g0[1] + vy * tr.t[i], 1e-11);
  }
}

// The frictionless symmetric top on a sphere: E' = (A_G + m l^2 sin^2)/2 tilt'^2 + V(tilt) with
// V = (L - C w3 cos)^2 / (2 A_G sin^2) + m g l cos (L the vertical momentum about G): the tilt
// turns where V = E', whatever the radius.
TEST(TableFrictionless, TheTiltTurnsAtTheRootsOfTheEffectiveEnergy) {
  const Body body = toy_top(0.003);
  const double Ag = central_moment_A(body), mgl = body.mass * body.gravity * body.length;
  const double theta0 = 0.5, spin = 100.0;
  const InitialState s = start(spin, theta0);
  // Started at rest but for the spin: tilt' = 0, so theta0 is a turning point; L = C w3 cos theta0.
  const double L = body.C * spin * std::cos(theta0);
  auto V = [&](double a) {
    const double d = L - body.C * spin * std::cos(a);
    return d * d / (2.0 * Ag * std::sin(a) * std::sin(a)) + mgl * std::cos(a);
  };
  const double E = V(theta0);
  boost::uintmax_t it = 200;
  const auto root = boost::math::tools::toms748_solve([&](double a) { return V(a) - E; }, theta0 + 1e-6, 3.0,
                                                      boost::math::tools::eps_tolerance<double>(50), it);
  const double other = 0.5 * (root.first + root.second);
  ASSERT_GT(other, theta0 + 0.01);
  const TableRun run = simulate_on_table(body, table_of(Contact::Frictionless), s, {0.5, 50001}, tight());
  const auto& tilt = column(run, "tilt");
  // The sampled maxima, each refined by the parabola through its three samples.
  int maxima = 0;
  for (std::size_t i = 1; i + 1 < tilt.size(); ++i) {
    if (!(tilt[i] > tilt[i - 1] && tilt[i] >= tilt[i + 1])) continue;
    const double a = tilt[i - 1], b = tilt[i], c = tilt[i + 1];
    const double peak = b + (a - c) * (a - c) / (8.0 * (2.0 * b - a - c));
    EXPECT_NEAR(peak, other, 1e-8);
    ++maxima;
  }
  EXPECT_GE(maxima, 3);
  for (double a : tilt) EXPECT_GE(a, theta0 - 1e-9);
}

// Without spin the frictionless top swings in a plane: E = (A_G + m l^2 sin^2) tilt'^2 / 2 + m g l cos,
// N = m (g + z_G''), z_G = r + l cos. Where N reaches 0 (TOMS 748 on N(tilt) along the energy) and
// when (the quadrature of dt = d tilt / tilt'), the body leaves the table.
TEST(TableFrictionless, LeavesTheTableWhereTheQuadratureSaysNVanishes) {
  const Body body = toy_top(0.0);
  const double Ag = central_moment_A(body), m = body.mass, l = body.length, g = body.gravity;
  const double a0 = 0.3, rate0 = -20.0;  // swinging up towards vertical: it hops near the top
  auto J = [&](double a) { return Ag + m * l * l * std::sin(a) * std::sin(a); };
  const double E = 0.5 * J(a0) * rate0 * rate0 + m * g * l * std::cos(a0);
  auto rate2 = [&](double a) { return 2.0 * (E - m * g * l * std::cos(a)) / J(a); };
  auto normal = [&](double a) {
    // tilt'' = (1/2) d(tilt'^2)/d tilt, differentiated by hand.
    const double dJ = 2.0 * m * l * l * std::sin(a) * std::cos(a);
    const double accel = (m * g * l * std::sin(a) - 0.5 * dJ * rate2(a)) / J(a);
    return m * (g - l * (std::cos(a) * rate2(a) + std::sin(a) * accel));
  };
  ASSERT_GT(normal(a0), 0.0);
  boost::uintmax_t it = 200;
  const auto root = boost::math::tools::toms748_solve(normal, 0.01, a0, boost::math::tools::eps_tolerance<double>(52), it);
  const double a_leave = 0.5 * (root.first + root.second);
  const double t_leave = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&](double a) { return 1.0 / std::sqrt(rate2(a)); }, a_leave, a0, 10, 1e-14);
  InitialState s;
  s.theta0 = a0;
  s.theta_rate0 = rate0;
  const TableRun run = simulate_on_table(body, table_of(Contact::Frictionless), s, {1.0, 11}, tight());
  EXPECT_EQ(run.summary.end, TableSummary::End::LeftTable);
  EXPECT_NEAR(run.summary.end_time, t_leave, 1e-9);
  EXPECT_NEAR(column(run, "tilt").back(), a_leave, 1e-9);
  EXPECT_NEAR(column(run, "normal_force").back(), 0.0, 1e-9);
}

// ---- stability of the spinning states: closed forms ------------------------------------------

// The numerical linearisation's largest real part (complex-step Jacobian, Eigen's eigenvalues),
// over the largest eigenvalue, among the eigenvalues that are not the spin family's zero.
double relative_growth(const Body& body, const Table& table, double spin, bool inverted = false) {
  const auto values = table_eigenvalues(body, table, spin, inverted);
  double largest = 0.0;
  for (auto v : values) largest = std::max(largest, std::abs(v));
  double growth = -HUGE_VAL;
  for (auto v : values)
    if (std::abs(v) > 1e-9 * largest) growth = std::max(growth, v.real());
  return growth / largest;
}

// The closed form's spin `w` is where the linearisation changes: unstable 1e-4 below, stable
// above (conservative: real parts zero to rounding; dissipative: negative).
void expect_change_at(const Body& body, const Table& table, double w, bool dissipative, bool inverted = false) {
  const double below = relative_growth(body, table, w * (1.0 - 1e-4), inverted);
  const double above = relative_growth(body, table, w * (1.0 + 1e-4), inverted);
  EXPECT_GT(below, dissipative ? 1e-9 : 1e-5) << "w = " << w;
  if (dissipative) EXPECT_LT(above, -1e-9) << "w = " << w;
  else EXPECT_LT(std::abs(above), 1e-12) << "w = " << w;
}

TEST(TableStability, FrictionlessUprightNeedsCSquaredOmegaSquaredAbove4AGmgl) {
  const Body body = toy_top(0.001);
  const double Ag = central_moment_A(body), mgl = body.mass * body.gravity * body.length;
  const double expected = std::sqrt(4.0 * Ag * mgl) / body.C;
  const TableStability s = table_stability(body, table_of(Contact::Frictionless), 2.0 * expected);
  ASSERT_TRUE(s.upright.critical_spin.has_value());
  EXPECT_NEAR(*s.upright.critical_spin, expected, 1e-12 * expected);
  EXPECT_TRUE(s.upright.stable);
  EXPECT_FALSE(s.upright.asymptotically);
  expect_change_at(body, table_of(Contact::Frictionless), expected, false);
}

// Rolling on a sphere of radius r (a = r + l the height of G above P): linearised,
// I_P e'' - i w (C + m r a) e' - m g l e = 0, I_P = A_G + m a^2 (docs/table.md), so the upright
// top is stable iff w^2 (C + m r a)^2 > 4 I_P m g l: Routh's criterion.
TEST(TableStability, RollingUprightIsRouthsCriterion) {
  for (double r : {0.0005, 0.003, 0.01}) {
    const Body body = toy_top(r);
    const double Ag = central_moment_A(body), m = body.mass, l = body.length, a = r + l;
    const double expected = std::sqrt(4.0 * (Ag + m * a * a) * m * body.gravity * l) / (body.C + m * r * a);
    const TableStability s = table_stability(body, table_of(Contact::Rolling), 1.5 * expected);
    ASSERT_TRUE(s.upright.critical_spin.has_value());
    EXPECT_NEAR(*s.upright.critical_spin, expected, 1e-12 * expected) << "r = " << r;
    EXPECT_TRUE(s.upright.stable);
    expect_change_at(body, table_of(Contact::Rolling), expected, false);
    // The linearisation itself, against the quadratic's roots (fixed frame; in the body frame,
    // turning at w, each root lambda is lambda - i w).
    const double w = 1.5 * expected, H = body.C + m * r * a, I = Ag + m * a * a;
    const std::complex<double> disc = std::sqrt(std::complex<double>(-w * w * H * H + 4.0 * I * m * body.gravity * l));
    const std::complex<double> lam(0.0, w * H / (2.0 * I));
    const auto values = table_eigenvalues(body, table_of(Contact::Rolling), w, false);
    for (std::complex<double> fixed : {lam + disc / (2.0 * I), lam - disc / (2.0 * I)}) {
      const std::complex<double> root = fixed - std::complex<double>(0.0, w);
      const bool found = std::any_of(values.begin(), values.end(), [&](std::complex<double> v) {
        return std::abs(v - root) < 1e-9 * std::abs(root) || std::abs(v - std::conj(root)) < 1e-9 * std::abs(root);
      });
      EXPECT_TRUE(found) << "root " << root.real() << " + " << root.imag() << " i";
    }
  }
}

// Viscous sliding: the upright state changes stability where a root is lambda = i w r / a, a
// motion without slip (docs/table.md), so w_c^2 = m g l a^2 / (r (C a - A_G r)) whatever mu
// and slip_speed; above it the round-tipped top is asymptotically stable: it rises.
TEST(TableStability, ViscousSlidingUprightChangesAtASpinFreeOfFriction) {
  const Body body = toy_top(0.002);
  const double Ag = central_moment_A(body), m = body.mass, l = body.length, r = body.tip_radius, a = r + l;
  const double expected = std::sqrt(m * body.gravity * l * a * a / (r * (body.C * a - Ag * r)));
  for (double mu : {0.05, 0.3, 2.0}) {
    for (double slip : {0.1, 1.0}) {
      Table t = table_of(Contact::Sliding, mu);
      t.slip_speed = slip;
      const TableStability s = table_stability(body, t, 1.2 * expected);
      ASSERT_TRUE(s.upright.critical_spin.has_value());
      EXPECT_NEAR(*s.upright.critical_spin, expected, 1e-12 * expected) << "mu " << mu << " slip " << slip;
      EXPECT_TRUE(s.upright.asymptotically);
      expect_change_at(body, t, expected, true);
      EXPECT_FALSE(table_stability(body, t, 0.8 * expected).upright.stable);
    }
  }
}

// The tippe top (alpha = -l / r): inverted asymptotically stable above a spin when
// 1 - alpha < A_G / C < 1 + alpha, upright unstable there (Bou-Rabee, Marsden and Romero 2004).
TEST(TableStability, TheTippeTopsWindow) {
  const Table viscous = table_of(Contact::Sliding, 0.3);
  const TableStability in_window = table_stability(tippe_top(8e-7), viscous, 180.0);
  EXPECT_FALSE(in_window.upright.stable);
  EXPECT_TRUE(in_window.inverted.asymptotically);
  // The inverted state's closed form: l -> -l, a = r (1 + alpha).
  const Body b = tippe_top(8e-7);
  const double Ag = central_moment_A(b), r = b.tip_radius, l = -b.length, a = r + l;
  const double expected = std::sqrt(b.mass * b.gravity * l * a * a / (r * (b.C * a - Ag * r)));
  ASSERT_TRUE(in_window.inverted.critical_spin.has_value());
  EXPECT_NEAR(*in_window.inverted.critical_spin, expected, 1e-12 * expected);
  expect_change_at(b, viscous, expected, true, /*inverted=*/true);
  // A_G / C above 1 + alpha = 1.2: the inverted state never stabilises.
  const TableStability above = table_stability(tippe_top(9e-7), viscous, 180.0);
  EXPECT_FALSE(above.inverted.stable);
  EXPECT_FALSE(above.inverted.critical_spin.has_value());
}

// A sharp tip sliding has no rising torque: the upright state is unstable at every spin, slowly
// at high spins (a real part like w^-4), which the closed form's missing change says exactly.
TEST(TableStability, ASharpTipSlidingIsNeverStable) {
  const TableStability s = table_stability(toy_top(0.0), table_of(Contact::Sliding, 0.3), 400.0);
  EXPECT_FALSE(s.upright.stable);
  EXPECT_TRUE(s.upright.stable_spin_intervals.empty());
  for (double w : {50.0, 500.0, 5000.0}) EXPECT_GT(relative_growth(toy_top(0.0), table_of(Contact::Sliding, 0.3), w), 1e-14);
}

// ---- sliding ----------------------------------------------------------------------------------

TEST(TableSliding, KeepsJellettsIntegralWhileTheEnergyFalls) {
  const TableRun run = simulate_on_table(tippe_top(), table_of(Contact::Sliding, 0.3), start(180.0, 0.1),
                                         {1.0, 101}, tight());
  EXPECT_LT(run.summary.max_relative_jellett_drift, 1e-9);
  const auto& energy = column(run, "energy");
  for (std::size_t i = 1; i < energy.size(); ++i) EXPECT_LE(energy[i], energy[i - 1] * (1.0 + 1e-13));
  EXPECT_LT(energy.back(), energy.front() * 0.999);
}

TEST(TableSliding, TheTippeTopTurnsOver) {
  const TableRun run = simulate_on_table(tippe_top(), table_of(Contact::Sliding, 0.3), start(180.0, 0.1),
                                         {20.0, 201}, tight());
  const auto& tilt = column(run, "tilt");
  EXPECT_GT(tilt.back(), kPi - 0.1);
  EXPECT_LT(run.summary.max_relative_jellett_drift, 1e-9);
}

TEST(TableSliding, ARoundTippedTopAboveItsCriticalSpinRisesToVertical) {
  const Body body = toy_top(0.002);
  const TableRun run = simulate_on_table(body, table_of(Contact::Sliding, 0.3), start(400.0, 0.1), {20.0, 2001});
  const auto& tilt = column(run, "tilt");
  EXPECT_LT(tilt.back(), 0.01);
}

// ---- Coulomb's law at a point -------------------------------------------------------------------

Table coulomb(double mu) {
  Table t = table_of(Contact::Sliding, mu);
  t.friction_law = FrictionLaw::Coulomb;
  return t;
}

// A uniform ball set down with topspin w0 and no speed: friction mu m g drives it (v = mu g t) and
// brakes the spin (w = w0 - 5 mu g t / (2 r)) until it rolls, v = w r: at t = 2 w0 r / (7 mu g),
// then at 2/7 w0 r for ever (the billiard ball's closed form).
TEST(TableCoulomb, ABallWithTopspinRollsAtTheBilliardBallsTime) {
  Body ball;
  ball.mass = 0.17;
  ball.length = 0.0;
  ball.tip_radius = 0.028;
  ball.A = ball.B = ball.C = 0.4 * ball.mass * ball.tip_radius * ball.tip_radius;
  const double mu = 0.2, w0 = 50.0, g = ball.gravity, r = ball.tip_radius;
  const double t_roll = 2.0 * w0 * r / (7.0 * mu * g);
  const TableRun run = simulate_on_table(ball, coulomb(mu), start(w0, kPi / 2.0), {2.0 * t_roll, 201}, tight());
  EXPECT_EQ(run.summary.switches, 1u);
  const auto& slip = column(run, "slip_speed");
  const auto& x = column(run, "x");
  const auto& y = column(run, "y");
  for (std::size_t i = 0; i < run.trajectory.size(); ++i) {
    const double t = run.trajectory.t[i];
    // P's distance: (1/2) mu g t^2 while it slides, then 2/7 w0 r a second more.
    const double d = t < t_roll ? 0.5 * mu * g * t * t : 0.5 * mu * g * t_roll * t_roll + 2.0 / 7.0 * w0 * r * (t - t_roll);
    EXPECT_NEAR(std::hypot(x[i], y[i]), d, 1e-9) << "t = " << t;
    if (t < t_roll * (1.0 - 1e-6)) EXPECT_NEAR(slip[i], w0 * r - 3.5 * mu * g * t, 1e-9) << "t = " << t;
    if (t > t_roll * (1.0 + 1e-6)) EXPECT_EQ(slip[i], 0.0) << "t = " << t;
  }
}

// Leine and Glocker's remark, the contract's research: at a point Coulomb's law sticks at once and
// the tippe top then rolls without losing energy, so it does not turn over.
TEST(TableCoulomb, TheTippeTopSticksAndRollsAndDoesNotTurnOver) {
  const TableRun run = simulate_on_table(tippe_top(), coulomb(0.3), start(180.0, 0.1), {10.0, 101}, tight());
  EXPECT_GE(run.summary.switches, 1u);
  EXPECT_LT(run.summary.max_relative_jellett_drift, 1e-9);
  const auto& tilt = column(run, "tilt");
  EXPECT_LT(*std::max_element(tilt.begin(), tilt.end()), 0.2);
  const auto& energy = column(run, "energy");
  const auto& slip = column(run, "slip_speed");
  for (std::size_t i = 1; i < energy.size(); ++i)
    if (slip[i] == 0.0 && slip[i - 1] == 0.0) EXPECT_NEAR(energy[i], energy[i - 1], 1e-11 * energy[0]);
  EXPECT_EQ(slip.back(), 0.0);
}

// A nutating round-tipped top whose contact sticks and slips in turn: every switch an event, the
// energy constant while it sticks and falling while it slips, Jellett's integral kept throughout.
TEST(TableCoulomb, SticksAndSlipsInTurn) {
  InitialState s = start(200.0, 0.3);
  s.theta_rate0 = 10.0;
  const TableRun run = simulate_on_table(toy_top(0.002), coulomb(0.2), s, {1.0, 2001}, tight());
  EXPECT_GE(run.summary.switches, 3u);
  EXPECT_LT(run.summary.max_relative_jellett_drift, 1e-9);
  const auto& energy = column(run, "energy");
  const auto& slip = column(run, "slip_speed");
  int stuck = 0, slipping = 0;
  for (std::size_t i = 1; i < energy.size(); ++i) {
    EXPECT_LE(energy[i], energy[i - 1] * (1.0 + 1e-12));
    if (slip[i] == 0.0 && slip[i - 1] == 0.0) {
      EXPECT_NEAR(energy[i], energy[i - 1], 1e-11 * energy[0]);
      ++stuck;
    } else if (slip[i] > 0.0 && slip[i - 1] > 0.0) {
      ++slipping;
    }
  }
  EXPECT_GT(stuck, 10);
  EXPECT_GT(slipping, 10);
}

// ---- the answer on a table --------------------------------------------------------------------

TEST(TableAnswer, TheTippeTopTurnsOverAllTheWay) {
  const TableAnalysis an = analyse_top_on_table(tippe_top(), table_of(Contact::Sliding, 0.3), start(180.0, 0.1));
  const TableAnswer& a = an.answer;
  EXPECT_EQ(a.verdict, AnswerVerdict::TurnsOver);
  EXPECT_TRUE(a.proven);
  ASSERT_TRUE(a.turns_over_at.has_value());
  EXPECT_GT(*a.turns_over_at, 2.0);
  EXPECT_LT(*a.turns_over_at, 10.0);
  EXPECT_TRUE(a.ends_upside_down);
  // Jellett's integral L . s, C w r (1 - alpha) at the start and -C w' r (1 + alpha) upside down
  // (w' = w . k), with the small start tilt's share: the spin falls to w (1 - alpha) / (1 + alpha).
  EXPECT_NEAR(a.final_spin, -180.0 * 0.8 / 1.2, 0.01 * 120.0);
}

// Above 1 + alpha the tippe top turns part way and spins tilted at the state where it rolls
// without slipping and precesses: w . k = W (cos - alpha) (no slip), and the torque about G,
// W (C w.k - A_G W cos) = m g l, give W^2 C ((gamma - 1) cos + alpha) = m g alpha r (docs/table.md).
TEST(TableAnswer, AboveTheWindowTheTippeTopSpinsTiltedAtItsSteadyState) {
  const Body b = tippe_top(9e-7);
  const TableAnalysis an = analyse_top_on_table(b, table_of(Contact::Sliding, 0.3), start(180.0, 0.1));
  const TableAnswer& a = an.answer;
  EXPECT_EQ(a.verdict, AnswerVerdict::TurnsOver);
  EXPECT_FALSE(a.ends_upside_down);
  const double alpha = 0.2, gamma = 9.0 / 7.0, c = std::cos(a.final_tilt), W = a.final_spin / (c - alpha);
  EXPECT_NEAR(W * W * b.C * ((gamma - 1.0) * c + alpha), b.mass * b.gravity * alpha * b.tip_radius,
              1e-6 * b.mass * b.gravity * alpha * b.tip_radius);
  EXPECT_GT(a.final_tilt, 1.6);
  EXPECT_LT(a.final_tilt, 3.0);
}

TEST(TableAnswer, BelowTheWindowTheTippeTopNeverPassesAQuarterTurn) {
  const TableAnalysis an = analyse_top_on_table(tippe_top(5e-7), table_of(Contact::Sliding, 0.3), start(180.0, 0.1));
  EXPECT_LT(an.answer.max_tilt, 1.5707963267948966);
  EXPECT_FALSE(an.answer.turns_over_at.has_value());
}

// The round-tipped toy top above its viscous critical spin rises and sleeps; its tilt's decay
// near upright is the linearisation's slowest rate.
TEST(TableAnswer, TheRisingTopSleepsAtTheRateOfItsSlowestMode) {
  const Body body = toy_top(0.002);
  const Table t = table_of(Contact::Sliding, 0.3);
  const TableAnalysis an = analyse_top_on_table(body, t, start(400.0, 0.1));
  EXPECT_EQ(an.answer.verdict, AnswerVerdict::StaysUp);
  ASSERT_TRUE(an.answer.upright_at.has_value());
  EXPECT_TRUE(an.answer.upright_attracts);
  // The decay of the tilt's envelope between two late windows against the least negative real part.
  const TableRun run = simulate_on_table(body, t, start(400.0, 0.1), {30.0, 30001}, tight());
  const auto& tilt = column(run, "tilt");
  auto envelope = [&](double from) {
    double top = 0.0;
    for (std::size_t i = 0; i < tilt.size(); ++i)
      if (run.trajectory.t[i] >= from && run.trajectory.t[i] < from + 1.0) top = std::max(top, tilt[i]);
    return top;
  };
  const double rate = std::log(envelope(25.0) / envelope(15.0)) / 10.0;
  const auto values = table_eigenvalues(body, t, column(run, "spin").back(), false);
  double slowest = -HUGE_VAL;
  for (auto v : values)
    if (std::abs(v) > 1e-9) slowest = std::max(slowest, v.real());
  ASSERT_LT(slowest, 0.0);
  EXPECT_NEAR(rate, slowest, 0.02 * std::abs(slowest));
}

TEST(TableAnswer, ASlowRoundTippedTopFalls) {
  const TableAnalysis an = analyse_top_on_table(toy_top(0.002), table_of(Contact::Sliding, 0.3), start(100.0, 0.1));
  EXPECT_EQ(an.answer.verdict, AnswerVerdict::Falls);
  ASSERT_TRUE(an.answer.falls_at.has_value());
  EXPECT_NEAR(an.answer.final_tilt, 1.0, 1e-8);
}

// ---- rolling ----------------------------------------------------------------------------------

TEST(TableRolling, KeepsEnergyAndJellett) {
  const TableRun run = simulate_on_table(toy_top(0.003), table_of(Contact::Rolling), start(150.0, 0.3, 0.1, 2.0),
                                         {1.0, 101}, tight());
  EXPECT_LT(run.summary.max_relative_energy_drift, 1e-10);
  EXPECT_LT(run.summary.max_relative_jellett_drift, 1e-10);
  for (double v : column(run, "slip_speed")) EXPECT_EQ(v, 0.0);
}

// A coin rolling upright on its rim (axis horizontal): it rolls straight, P moving at w rho
// along the table, O at rho above it, the tilt held at pi/2; energy kept.
TEST(TableRolling, ACoinRollsStraightOnItsRim) {
  Body coin;
  coin.mass = 0.01;
  coin.length = 0.0;
  coin.rim_radius = 0.0125;
  coin.A = coin.B = coin.mass * coin.rim_radius * coin.rim_radius / 4.0;
  coin.C = coin.mass * coin.rim_radius * coin.rim_radius / 2.0;
  const double w = 20.0;
  const TableRun run = simulate_on_table(coin, table_of(Contact::Rolling), start(w, kPi / 2.0), {2.0, 21}, tight());
  const auto& x = column(run, "x");
  const auto& y = column(run, "y");
  const auto& tilt = column(run, "tilt");
  for (std::size_t i = 0; i < run.trajectory.size(); ++i) {
    const double t = run.trajectory.t[i];
    EXPECT_NEAR(std::hypot(x[i], y[i]), w * coin.rim_radius * t, 1e-12);
    EXPECT_NEAR(tilt[i], kPi / 2.0, 1e-12);
    EXPECT_NEAR(column(run, "height")[i], coin.rim_radius, 1e-15);
    EXPECT_NEAR(column(run, "normal_force")[i], coin.mass * coin.gravity, 1e-12);
  }
  // Tilted, it wobbles and wanders, its energy kept.
  const TableRun wobble = simulate_on_table(coin, table_of(Contact::Rolling), start(w, kPi / 2.0 - 0.2), {2.0, 21}, tight());
  EXPECT_LT(wobble.summary.max_relative_energy_drift, 1e-10);
}

// A coin rolling steadily in a circle on its rim (no slip at P, G = O on a horizontal circle, the
// axis at tilt th precessing at W about the vertical): with w = W e_zeta + psi' k, no slip gives
// G's speed rho (W cos + psi'), and the torque about G, W sin (C w3 - A_G W cos) = -m rho (sin W
// rho w3 + g cos), fixes the spin w3 = w . k = (A_G W^2 sin cos - m g rho cos) / (W sin (C + m rho^2))
// (docs/table.md). Started there (phi_rate0 = -W sin, spin w3), the tilt holds to 1e-9 for 2 s.
TEST(TableRolling, ACoinRollsSteadilyInACircleAtItsClosedForm) {
  Body coin;
  coin.mass = 0.0075;
  coin.length = 0.0;
  coin.rim_radius = 0.011625;
  const double m = coin.mass, rho = coin.rim_radius;
  coin.A = coin.B = m * rho * rho / 4.0;
  coin.C = m * rho * rho / 2.0;
  for (double W : {5.0, 20.0, 60.0}) {
    const double th = 1.2, S = std::sin(th), c = std::cos(th);
    InitialState s;
    s.theta0 = th;
    s.phi_rate0 = -W * S;
    s.spin = (coin.A * W * W * S * c - m * coin.gravity * rho * c) / (W * S * (coin.C + m * rho * rho));
    const TableRun run = simulate_on_table(coin, table_of(Contact::Rolling), s, {2.0, 201}, tight());
    for (double tilt : column(run, "tilt")) EXPECT_NEAR(tilt, th, 1e-9) << "W = " << W;
    for (double w : column(run, "spin")) EXPECT_NEAR(w, s.spin, 1e-9 * std::max(1.0, std::abs(s.spin)));
    EXPECT_LT(run.summary.max_relative_energy_drift, 1e-12);
  }
}

// A run that cannot reach its horizon (max_steps) answers what it covered, as the pivot's does:
// nothing claimed, the horizon the time it reached.
TEST(TableAnswer, ARunThatStopsEarlyClaimsNothing) {
  AnswerOptions options;
  options.horizon = 8.0;
  options.integrator.max_steps = 200;
  const TableAnswer a =
      analyse_top_on_table(tippe_top(), table_of(Contact::Sliding, 0.3), start(180.0, 0.1), options).answer;
  EXPECT_EQ(a.verdict, AnswerVerdict::StaysUpForHorizon);
  EXPECT_FALSE(a.proven);
  EXPECT_NE(a.stopped.find("max_steps = 200"), std::string::npos) << a.stopped;
  EXPECT_GT(a.horizon, 0.0);
  EXPECT_LT(a.horizon, 1.0);  // 200 steps of a 180 rad/s spin: well under a second
  EXPECT_FALSE(a.upright_at || a.turns_over_at || a.falls_at || a.leaves_at);
}

// ---- stiff viscous sliding ----------------------------------------------------------------------

Table viscous(double slip_speed) {
  Table t = table_of(Contact::Sliding, 0.3);
  t.slip_speed = slip_speed;
  return t;
}

Tolerances both(double tolerance) {
  Tolerances t;
  t.rtol = t.atol = tolerance;
  return t;
}

// At slip_speed 1e-6 m/s the viscous law relaxes the tippe top's slip at about 1e7 1/s, 6e4 times
// its spin: DOP853's steps are held by its stability there, Rosenbrock 4's (implicit, its
// Jacobian the complex step's) by its accuracy only. Two methods of different kinds agree.
TEST(TableStiff, RosenbrockAndDop853AgreeWhereTheViscousLawIsStiff) {
  const SampleGrid grid{0.5, 6};
  const TableRun explicit_run =
      simulate_on_table(tippe_top(), viscous(1e-6), start(180.0, 0.1), grid, both(1e-10), {}, Integrator::Dop853);
  const TableRun implicit_run = simulate_on_table(tippe_top(), viscous(1e-6), start(180.0, 0.1), grid, both(1e-10),
                                                  {}, Integrator::Rosenbrock4);
  EXPECT_EQ(explicit_run.summary.integrator, Integrator::Dop853);
  EXPECT_EQ(implicit_run.summary.integrator, Integrator::Rosenbrock4);
  for (const char* name : {"tilt", "spin", "x", "y", "slip_speed"}) {
    const auto &a = column(explicit_run, name), &b = column(implicit_run, name);
    ASSERT_EQ(a.size(), b.size());
    double scale = 0.0;
    for (double v : a) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-7 * scale) << name << " at sample " << i;
  }
  EXPECT_LT(implicit_run.summary.max_relative_jellett_drift, 1e-9);
  // The point of the implicit method: several times fewer steps (measured 65e3 against 480e3).
  EXPECT_LT(5 * implicit_run.summary.steps, explicit_run.summary.steps);
}

// Auto takes Rosenbrock 4 where the stiffness ratio passes stiff_table_ratio(tolerance), DOP853
// elsewhere, and the contacts without the viscous law are never stiff.
TEST(TableStiff, AutoTakesTheImplicitMethodOnlyWhereItIsFaster) {
  EXPECT_EQ(table_integrator(tippe_top(), viscous(1.0), start(180.0, 0.1), both(1e-8)), Integrator::Dop853);
  EXPECT_EQ(table_integrator(tippe_top(), viscous(1e-6), start(180.0, 0.1), both(1e-8)), Integrator::Rosenbrock4);
  EXPECT_EQ(table_integrator(tippe_top(), viscous(1e-6), start(180.0, 0.1), both(1e-12)), Integrator::Dop853);
  Table coulomb = viscous(1e-9);
  coulomb.friction_law = FrictionLaw::Coulomb;
  EXPECT_EQ(table_integrator(tippe_top(), coulomb, start(180.0, 0.1), both(1e-8)), Integrator::Dop853);
  EXPECT_EQ(stiff_table_ratio(1e-8), 5e3);
}

// kIntegratorSupport is what the runs do: for every integrator and every kind of run, the run
// refuses it (InvalidInput, key "integrator") exactly where the table says it cannot.
TEST(IntegratorSupport, EveryRowIsWhatTheRunsDo) {
  Body pivot = toy_top(0.0);
  pivot.A *= 1.2;  // an asymmetric top: every integrator of the pivot applies
  const InitialState s = start(200.0, 0.1);
  Body damped = pivot;
  damped.damping.axial = 1e-7;
  Body general = pivot;
  general.general.offset_x = 1e-3;
  auto refused = [](auto&& run) {
    try {
      run();
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.key(), "integrator");
      return true;
    }
    return false;
  };
  for (Integrator i : kIntegrators) {
    SimulateOptions o;
    o.integrator = i;
    o.splitting.step = 1e-4;
    auto simulated = [&](const Body& b) {
      return [&] { simulate(Model::Nonlinear, b, s, {0.0, 0.01}, o); };
    };
    const bool pivot_ok = supports(i, IntegratorUse::Pivot);
    SCOPED_TRACE(std::string(name(i)));
    EXPECT_EQ(refused(simulated(pivot)), !pivot_ok);
    EXPECT_EQ(refused(simulated(damped)), !(pivot_ok && supports(i, IntegratorUse::Damped)));
    EXPECT_EQ(refused(simulated(general)), !(pivot_ok && supports(i, IntegratorUse::General)));
    EXPECT_EQ(refused([&] { tilt_extremes(i, pivot, s, 0.01, 1.0, Tolerances{}); }),
              !(pivot_ok && supports(i, IntegratorUse::Judging)));
    EXPECT_EQ(refused([&] {
                simulate_on_table(tippe_top(), viscous(1.0), start(180.0, 0.1), {0.01, 3}, {}, {}, i);
              }),
              !supports(i, IntegratorUse::Table));
  }
}

// ---- refusals ----------------------------------------------------------------------------------

TEST(TableInput, RefusesWhatTheTableCannotHold) {
  Table t = table_of(Contact::Sliding, -0.1);
  EXPECT_THROW(validate(t, toy_top(0.0)), InvalidInput);
  t.friction = 0.3;
  t.slip_speed = 0.0;
  try {
    validate(t, toy_top(0.0));
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "table.slip_speed");
  }
  Body b = toy_top(-1e-3);
  try {
    validate(table_of(Contact::Frictionless), b);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.tip_radius");
  }
  Body disc = toy_top(0.0);
  disc.rim_radius = 0.02;
  try {
    simulate_on_table(disc, table_of(Contact::Rolling), start(10.0, 0.0), {1.0, 3});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "motion.theta0");
  }
}

}  // namespace
}  // namespace heavytop

// A real top's losses (contact_losses.hpp, the table's Contensou law, rolling resistance and
// air; docs/table.md) against independent routes: Hertz's patch against the approach its own
// pressure makes (Boussinesq's integral), the drilling torque against that pressure's friction
// integrated over the patch, the disc's air torque against von Karman's similarity equations
// solved here by shooting, the sphere's against Stokes' law, the energy the run's losses book
// against the energy the body lost, and the spin-down's quadrature against the integrated motion.

#include <array>
#include <cmath>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/numeric/odeint.hpp>
#include <gtest/gtest.h>

#include "heavytop/contact_losses.hpp"
#include "heavytop/table.hpp"
#include "table_testing.hpp"

namespace heavytop {
namespace {

using table_testing::column;
using table_testing::start;

constexpr double kPi = 3.141592653589793;

// The built-in wooden toy top with a round steel tip of 0.5 mm.
Body toy_top() { return table_testing::toy_top(5e-4); }
using boost::math::quadrature::gauss_kronrod;

Table contensou_table(bool air, double rolling_resistance = 0.0) {
  Table t;
  t.contact = Contact::Sliding;
  t.friction = 0.3;
  t.friction_law = FrictionLaw::Contensou;
  t.tip_material = material_from_name("steel");
  t.material = material_from_name("oak");
  t.rolling_resistance = rolling_resistance;
  if (air) t.air = Air{};
  return t;
}

Tolerances tight() { return table_testing::tolerances(1e-12, 1e-13); }

TEST(HertzPatch, ItsPressureMakesTheApproachItsRadiusNeeds) {
  // Hertz's pressure p0 sqrt(1 - r^2/a^2) (p0 = 3 N / (2 pi a^2)) presses the two surfaces
  // together at the centre by u(0) = (2 / E*) int_0^a p dr (Boussinesq); the sphere meets the
  // flat over the patch only if u(0) = a^2 / R (Johnson 1985, 4.2). Steel on oak and steel on
  // glass, a light and a heavy load.
  for (const char* flat : {"oak", "glass"}) {
    const double E = contact_modulus(*material_from_name("steel"), *material_from_name(flat));
    for (double N : {0.05, 5.0}) {
      const double R = 5e-4, a = hertz_contact_radius(N, R, E), p0 = 3.0 * N / (2.0 * kPi * a * a);
      const double load = gauss_kronrod<double, 61>::integrate(
          [&](double r) { return p0 * std::sqrt(std::max(0.0, 1.0 - r * r / (a * a))) * 2.0 * kPi * r; }, 0.0, a, 15, 1e-14);
      const double approach = 2.0 / E *
                              gauss_kronrod<double, 61>::integrate(
                                  [&](double r) { return p0 * std::sqrt(std::max(0.0, 1.0 - r * r / (a * a))); }, 0.0, a,
                                  15, 1e-14);
      EXPECT_NEAR(load, N, 1e-9 * N) << flat;
      EXPECT_NEAR(approach, a * a / R, 1e-9 * a * a / R) << flat << " N = " << N;
    }
  }
  // 1 / E* from the two materials: steel on steel is E / (2 (1 - nu^2)).
  const Material steel = *material_from_name("steel");
  EXPECT_NEAR(contact_modulus(steel, steel), steel.modulus / (2.0 * (1.0 - steel.poisson * steel.poisson)), 1.0);
}

TEST(HertzPatch, TheDrillingTorqueIsTheFrictionOfItsPressureAboutTheCentre) {
  // M = int mu p(r) r dA over the patch: (3 pi / 16) mu N a for Hertz's pressure.
  const double N = 0.5886, mu = 0.3, a = 2.7e-5, p0 = 3.0 * N / (2.0 * kPi * a * a);
  const double torque = gauss_kronrod<double, 61>::integrate(
      [&](double r) { return mu * p0 * std::sqrt(std::max(0.0, 1.0 - r * r / (a * a))) * r * 2.0 * kPi * r; }, 0.0, a,
      15, 1e-14);
  EXPECT_NEAR(torque, kHertzDrillingArm * mu * N * a, 1e-10 * torque);
}

// von Karman's rotating disc: u = r w F(z*), v = r w G(z*), w_z = sqrt(nu w) H(z*) with
// F'' = F^2 - G^2 + H F', G'' = 2 F G + H G', H' = -2 F; F(0) = 0, G(0) = 1, H(0) = 0 and F, G -> 0
// far away. Returns G'(0), by shooting on (F'(0), G'(0)) with Newton's method, the far end
// moved out step by step (the equations grow away from the solution: each length starts from
// the last one's root).
double von_karman_shear() {
  using State = std::array<double, 5>;  // F, F', G, G', H
  double end = 3.0;
  auto far = [&end](double f1, double g1) {
    State y{0.0, f1, 1.0, g1, 0.0};
    auto rhs = [](const State& s, State& d, double) {
      d[0] = s[1];
      d[1] = s[0] * s[0] - s[2] * s[2] + s[4] * s[1];
      d[2] = s[3];
      d[3] = 2.0 * s[0] * s[2] + s[4] * s[3];
      d[4] = -2.0 * s[0];
    };
    boost::numeric::odeint::integrate_adaptive(
        boost::numeric::odeint::make_controlled<boost::numeric::odeint::runge_kutta_dopri5<State>>(1e-13, 1e-13), rhs, y,
        0.0, end, 1e-3);
    return std::array<double, 2>{y[0], y[2]};
  };
  double f1 = 0.5, g1 = -0.6;
  for (int k = 0; k < 60; ++k, end = std::min(end + 0.5, 12.0)) {
    const auto r = far(f1, g1);
    const double h = 1e-7;
    const auto rf = far(f1 + h, g1), rg = far(f1, g1 + h);
    const double j11 = (rf[0] - r[0]) / h, j12 = (rg[0] - r[0]) / h, j21 = (rf[1] - r[1]) / h, j22 = (rg[1] - r[1]) / h;
    const double det = j11 * j22 - j12 * j21;
    f1 -= (j22 * r[0] - j12 * r[1]) / det;
    g1 -= (-j21 * r[0] + j11 * r[1]) / det;
  }
  return g1;
}

TEST(AirTorque, ADiscsFacesFollowVonKarmansBoundaryLayer) {
  // Shear -mu r w sqrt(w / nu) G'(0) on each face: M = pi |G'(0)| rho sqrt(nu) w^(3/2) R^4 for both.
  const double shear = von_karman_shear();
  EXPECT_NEAR(shear, -0.6159, 1e-4);  // the classical value
  const Air air;
  const double nu = air.viscosity / air.density, R = 0.02;
  const std::vector<AirSurface> disc(2, AirSurface{AirSurface::Kind::Face, R, 0.0, 0.0});
  for (double reynolds : {1e3, 1e4, 1e5}) {
    const double w = reynolds * nu / (R * R);
    const double expected = kPi * std::abs(shear) * air.density * std::sqrt(nu) * std::pow(w, 1.5) * std::pow(R, 4);
    // Cochran's 3.87 against 2 pi 0.61592 = 3.8700: to 1e-4.
    EXPECT_NEAR(air_torque(disc, air, w), expected, 1e-4 * expected) << "Re = " << reynolds;
    EXPECT_EQ(air_torque(disc, air, -w), air_torque(disc, air, w));
  }
  // Above Re = 3e5 the turbulent layer, 0.146 Re^-1/5 (von Karman): larger than the laminar law.
  const double w = 1e6 * nu / (R * R);
  EXPECT_NEAR(air_torque(disc, air, w), 0.5 * 0.146 * std::pow(1e6, -0.2) * air.density * w * w * std::pow(R, 5),
              1e-12 * air_torque(disc, air, w));
}

TEST(AirTorque, ASlowSphereFollowsStokes) {
  const Air air;
  const double R = 1e-3, w = 0.5;  // Re = w R^2 / nu = 0.03
  const AirSurface sphere{AirSurface::Kind::Sphere, R, 0.0, 0.0};
  EXPECT_NEAR(air_torque(sphere, air, w), 8.0 * kPi * air.viscosity * R * R * R * w, 1e-12 * air_torque(sphere, air, w));
}

TEST(TableLosses, TheLossesBookedAreTheEnergyTheBodyLost) {
  // Contensou's sliding and drilling, rolling resistance and the air, on a wobbling top.
  const TableRun run = simulate_on_table(toy_top(), contensou_table(true, 2e-4), start(300.0, 0.2), {2.0, 201}, tight());
  const auto& energy = column(run, "energy");
  const auto& sliding = column(run, "loss_sliding");
  const auto& drilling = column(run, "loss_drilling");
  const auto& rolling = column(run, "loss_rolling");
  const auto& air = column(run, "loss_air");
  for (std::size_t i = 1; i < energy.size(); ++i) {
    const double lost = energy[0] - energy[i], booked = sliding[i] + drilling[i] + rolling[i] + air[i];
    ASSERT_GT(lost, 0.0);
    EXPECT_NEAR(booked, lost, 1e-8 * lost) << "t = " << run.trajectory.t[i];
  }
  for (const auto* loss : {&sliding, &drilling, &rolling, &air}) EXPECT_GT(loss->back(), 0.0);
  EXPECT_NEAR(run.summary.losses.total(), energy.front() - energy.back(), 1e-8 * (energy.front() - energy.back()));
}

TEST(TableLosses, AsleepTheDrillingTorqueIsCoulombsOverThePatch) {
  // Upright and not slipping, the patch only drills: C w' = -(3 pi / 16) mu m g a, a constant.
  const Body body = toy_top();
  const Table table = contensou_table(false);
  const TableRun run = simulate_on_table(body, table, start(400.0, 0.0), {1.0, 2}, tight());
  const double a = hertz_contact_radius(body.mass * body.gravity, body.tip_radius,
                                        contact_modulus(*table.tip_material, *table.material));
  const double rate = kHertzDrillingArm * 0.3 * body.mass * body.gravity * a / body.C;
  EXPECT_NEAR(column(run, "spin").back(), 400.0 - rate * 1.0, 1e-9 * 400.0);
  EXPECT_NEAR(table_spin_down(body, table, 400.0).drilling_torque, rate * body.C, 1e-12 * rate * body.C);
}

TEST(TableLosses, TheSpinDownsQuadratureIsTheIntegratedMotion) {
  // Asleep from 600 rad/s with drilling and air: after 10 s of the full motion, the quadrature
  // from the spin reached is 10 s shorter than from the start.
  const Body body = toy_top();
  const Table table = contensou_table(true);
  const TableRun run = simulate_on_table(body, table, start(600.0, 0.0), {10.0, 2}, tight());
  const TableSpinDown from_start = table_spin_down(body, table, 600.0);
  const TableSpinDown later = table_spin_down(body, table, column(run, "spin").back());
  ASSERT_TRUE(from_start.critical_spin && from_start.time_to_critical && later.time_to_critical);
  EXPECT_NEAR(*from_start.time_to_critical - *later.time_to_critical, 10.0, 1e-6);
  // Its energy: what the two losses take is the kinetic energy between the spins.
  const double taken = from_start.losses.drilling + from_start.losses.air;
  const double kinetic = 0.5 * body.C * (600.0 * 600.0 - *from_start.critical_spin * *from_start.critical_spin);
  EXPECT_NEAR(taken, kinetic, 1e-9 * kinetic);
  EXPECT_GT(from_start.losses.air, 0.0);
  EXPECT_GT(from_start.losses.drilling, 0.0);
}

TEST(TableLosses, BadSettingsAreRefusedByName) {
  const Body body = toy_top();
  Table t = contensou_table(false);
  t.tip_material.reset();
  EXPECT_THROW(
      {
        try {
          validate(t, body);
        } catch (const InvalidInput& e) {
          EXPECT_EQ(e.key(), "table.tip_material");
          throw;
        }
      },
      InvalidInput);
  t = contensou_table(false);
  EXPECT_THROW(
      {
        try {
          validate(t, table_testing::toy_top(0.0));
        } catch (const InvalidInput& e) {
          EXPECT_EQ(e.key(), "body.tip_radius");
          throw;
        }
      },
      InvalidInput);
  t.friction_law = FrictionLaw::Coulomb;
  t.rolling_resistance = 1e-4;
  EXPECT_THROW(validate(t), InvalidInput);
  t = contensou_table(true);
  t.air->density = -1.0;
  EXPECT_THROW(validate(t), InvalidInput);
}

}  // namespace
}  // namespace heavytop

namespace heavytop {
namespace {

TEST(TableLosses, TheUprightChangesStabilityWhereTheViscousClosedFormSays) {
  // Linearised, Contensou's law is viscous with slip_speed eps w and the air acts on the spin
  // alone, so the eigenvalues (computed, not the closed form) change sign at
  // w^2 = m g l a^2 / (r (C a - A_G r)), whatever mu, with the air or without.
  const Body body = toy_top();
  const double m = body.mass, g = body.gravity, l = body.length, r = body.tip_radius, a = r + l;
  const double closed = std::sqrt(m * g * l * a * a / (r * (body.C * a - central_moment_A(body) * r)));
  for (bool air : {false, true})
    for (double mu : {0.05, 0.3}) {
      Table t = contensou_table(air);
      t.friction = mu;
      auto growth = [&](double w) {
        double largest = -1e300;
        for (const auto& e : table_eigenvalues(body, t, w, false)) largest = std::max(largest, e.real());
        return largest;
      };
      EXPECT_GT(growth(0.999 * closed), 1e-9) << "mu " << mu << " air " << air;
      EXPECT_LT(growth(1.001 * closed), 1e-12) << "mu " << mu << " air " << air;
      EXPECT_NEAR(*table_stability(body, t, 2.0 * closed).upright.critical_spin, closed, 1e-12 * closed);
    }
}

}  // namespace
}  // namespace heavytop

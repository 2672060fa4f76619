// The general body (SPEC section 11) in the nonlinear model, against oracles that could fail:
// the Kovalevskaya and Goryachev-Chaplygin integrals (docs/general-body.md derives both), the
// existing principal-axes integrators for an ordinary body and for a body given in rotated
// axes, and an independent integration of the textbook equations (rotation matrix, Boost's
// Bulirsch-Stoer) for a body with every general term nonzero.

#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <boost/numeric/odeint.hpp>
#include <gtest/gtest.h>

#include "heavytop/general_body.hpp"
#include "heavytop/simulate.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {

using test_support::column;
using test_support::make_state;
using test_support::sci;

constexpr double kPi = 3.141592653589793;

double angle_difference(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

Tolerances tight() {
  Tolerances o;
  o.rtol = 1e-13;
  o.atol = 1e-13;
  return o;
}

// A body with principal-looking diagonal (A, B, C), mass 1 and gravity g.
Body body_with(double A, double B, double C, double gravity) {
  Body b;
  b.A = A;
  b.B = B;
  b.C = C;
  b.mass = 1.0;
  b.gravity = gravity;
  return b;
}

// An attitude off every symmetry: body axes tilted 0.6 rad from the vertical, turned.
RigidBodyState generic_state(const Eigen::Vector3d& omega) {
  RigidBodyState x;
  x.attitude = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(-0.8, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  x.omega = omega;
  return x;
}

std::vector<double> times_to(double t_end, std::size_t n) { return sample_times(t_end, n); }

// Kovalevskaya (1889): A = B = 2C, c = (a, 0, 0). With n = m g a / C,
// K = (w1^2 - w2^2 - n g1)^2 + (2 w1 w2 - n g2)^2 (docs/general-body.md).
double kovalevskaya(const RigidBodyState& x, double n) {
  const Eigen::Vector3d& w = x.omega;
  const Eigen::Vector3d g = x.attitude.row(2).transpose();
  const double re = w.x() * w.x() - w.y() * w.y() - n * g.x(), im = 2.0 * w.x() * w.y() - n * g.y();
  return re * re + im * im;
}

// Goryachev-Chaplygin (1900): A = B = 4C, c = (a, 0, 0), on (I w).gamma = 0. With n = m g a / C,
// G = w3 (w1^2 + w2^2) - n w1 g3 (docs/general-body.md).
double goryachev_chaplygin(const RigidBodyState& x, double n) {
  const Eigen::Vector3d& w = x.omega;
  const Eigen::Vector3d g = x.attitude.row(2).transpose();
  return w.z() * (w.x() * w.x() + w.y() * w.y()) - n * w.x() * g.z();
}

struct Drift {
  double integral = 0.0, energy = 0.0;
};

template <class Integral>
Drift drifts(const Body& body, const RigidBodyState& x0, const Integral& integral) {
  const auto states = integrate_general_body(body, x0, times_to(100.0, 2001), tight());
  const double k0 = integral(x0), e0 = general_conserved_quantities(body, x0).energy;
  Drift d;
  for (const RigidBodyState& x : states) {
    d.integral = std::max(d.integral, std::abs(integral(x) - k0) / std::abs(k0));
    d.energy = std::max(d.energy, std::abs(general_conserved_quantities(body, x).energy - e0) / std::abs(e0));
  }
  return d;
}

TEST(GeneralBody, KovalevskayaIntegralAndEnergyConservedTo1e10Over100s) {
  Body top = body_with(2.0, 2.0, 1.0, 9.81);  // A = B = 2C
  top.general.offset_x = 0.05;                // centre of mass in the equatorial plane
  top.length = 0.0;
  const double n = top.mass * top.gravity * top.general.offset_x / top.C;
  const RigidBodyState x0 = generic_state({0.7, -0.4, 1.3});
  ASSERT_GT(kovalevskaya(x0, n), 0.1);  // a state far from K = 0 (a relative error means something)
  const Drift d = drifts(top, x0, [n](const RigidBodyState& x) { return kovalevskaya(x, n); });
  RecordProperty("kovalevskaya_K_E_drift", sci(d.integral) + " " + sci(d.energy));
  EXPECT_LT(d.integral, 1e-10);
  EXPECT_LT(d.energy, 1e-10);

  // The oracle has teeth: 10% off the Kovalevskaya ratio, K moves at the percent level.
  Body off = top;
  off.A = off.B = 2.2;
  const Drift wrong = drifts(off, x0, [n](const RigidBodyState& x) { return kovalevskaya(x, n); });
  EXPECT_GT(wrong.integral, 1e-3);
  EXPECT_LT(wrong.energy, 1e-10);
}

TEST(GeneralBody, GoryachevChaplyginIntegralConservedTo1e10Over100sAtZeroVerticalMomentum) {
  Body top = body_with(4.0, 4.0, 1.0, 9.81);  // A = B = 4C
  top.general.offset_x = 0.04;
  top.length = 0.0;
  const double n = top.mass * top.gravity * top.general.offset_x / top.C;
  RigidBodyState x0 = generic_state({0.9, -0.5, 0.0});
  const Eigen::Vector3d g = x0.attitude.row(2).transpose();
  // w3 such that L_zeta = (I w).gamma = 4 C (w1 g1 + w2 g2) + C w3 g3 = 0.
  x0.omega.z() = -4.0 * (x0.omega.x() * g.x() + x0.omega.y() * g.y()) / g.z();
  ASSERT_LT(std::abs(general_conserved_quantities(top, x0).vertical_momentum), 1e-15);
  ASSERT_GT(std::abs(goryachev_chaplygin(x0, n)), 0.1);
  const Drift d = drifts(top, x0, [n](const RigidBodyState& x) { return goryachev_chaplygin(x, n); });
  RecordProperty("goryachev_chaplygin_G_E_drift", sci(d.integral) + " " + sci(d.energy));
  EXPECT_LT(d.integral, 1e-10);
  EXPECT_LT(d.energy, 1e-10);

  // Off the constraint L_zeta = 0 it is no integral: G moves.
  RigidBodyState spun = x0;
  spun.omega.z() += 0.5;
  const Drift wrong = drifts(top, spun, [n](const RigidBodyState& x) { return goryachev_chaplygin(x, n); });
  EXPECT_GT(wrong.integral, 1e-3);
}

// The general path on an ordinary body (general terms zero) against simulate()'s own
// principal-axes integrators (Taylor under auto; spin-factored variables), 1e-9 rad.
TEST(GeneralBody, OrdinaryBodyAgreesWithTheNonlinearModelTo1e9Rad) {
  struct Case {
    Body body;
    InitialState state;
    double t_end;
  };
  const Case cases[] = {{example_toy_top(), example_motion(), 2.0},
                        {test_support::make_body(1.0, 1.5, 2.0, 0.981), make_state(10.0, 0.05, 0.02, 0.1, -0.2), 20.0}};
  for (const Case& c : cases) {
    const auto times = times_to(c.t_end, 401);
    const Trajectory general = simulate_general_body(c.body, c.state, times, tight());
    const Simulation reference = simulate(Model::Nonlinear, c.body, c.state, times);
    ASSERT_TRUE(reference.summary.ok());
    double worst = 0.0;
    for (std::size_t i = 0; i < times.size(); ++i)
      worst = std::max({worst, angle_difference(general.theta[i], reference.trajectory.theta[i]),
                        angle_difference(general.phi[i], reference.trajectory.phi[i])});
    RecordProperty("ordinary_body_angle_difference", sci(worst));
    EXPECT_LT(worst, 1e-9);
    // The same energy column: one formula for E.
    EXPECT_NEAR(column(general, "energy").back(), column(reference.trajectory, "energy").front(),
                1e-11 * std::abs(column(reference.trajectory, "energy").front()) + 1e-18);
  }
}

// A body given in axes x', y', z' that are not principal (products of inertia, the centre of
// mass off z') is the principal body seen in other axes: its motion, run through the general
// integrator, is the principal body's run through simulate() (the Taylor path), 1e-9 rad.
TEST(GeneralBody, ProductsOfInertiaEqualTheSameBodyInItsPrincipalAxes) {
  const Body principal = test_support::make_body(1.0, 1.5, 2.0, 0.981);  // c = (0, 0, 0.981)
  const Eigen::Matrix3d P =
      (Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, -0.5).normalized())).toRotationMatrix();  // columns: principal axes in x', y', z'
  const Eigen::Matrix3d I = P * Eigen::Vector3d(principal.A, principal.B, principal.C).asDiagonal() * P.transpose();
  const Eigen::Vector3d c = P * Eigen::Vector3d(0.0, 0.0, principal.length);
  Body rotated = principal;
  rotated.A = I(0, 0);
  rotated.B = I(1, 1);
  rotated.C = I(2, 2);
  rotated.general.Ixy = -I(0, 1);
  rotated.general.Ixz = -I(0, 2);
  rotated.general.Iyz = -I(1, 2);
  rotated.general.offset_x = c.x();
  rotated.general.offset_y = c.y();
  rotated.length = c.z();
  ASSERT_NO_THROW(validate(rotated));
  ASSERT_TRUE(is_general(rotated));

  const InitialState state = make_state(10.0, 0.05, 0.02, 0.1, -0.2);
  const RigidBodyState x2 = initial_rigid_body_state(state);  // the principal axes' start
  const RigidBodyState x1{x2.attitude * P.transpose(), P * x2.omega};
  const auto times = times_to(20.0, 401);
  const auto states = integrate_general_body(rotated, x1, times, tight());
  const Simulation reference = simulate(Model::Nonlinear, principal, state, times);
  ASSERT_TRUE(reference.summary.ok());
  double worst = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Vector3d k = states[i].attitude * P.col(2);  // the principal z axis
    const Eigen::Vector3d k_ref = test_support::axis_of(reference.trajectory.theta[i], reference.trajectory.phi[i]);
    worst = std::max(worst, (k - k_ref).norm());  // the chord: the angle to 1e-18 (acos is not, near 0)
  }
  RecordProperty("rotated_body_axis_difference", sci(worst));
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT((states.back().attitude.col(2) - reference.trajectory.size() * 0.0 * Eigen::Vector3d::Ones() -
             test_support::axis_of(reference.trajectory.theta.back(), reference.trajectory.phi.back()))
                .norm(),
            1e-3);  // body z' itself is not the principal axis: the comparison is not trivial
}

// The two integrators of the general body: dopri5 (general_body.cpp) and the Taylor series
// (taylor.cpp's General variables), each against the same oracles.
class GeneralBodyIntegrators : public ::testing::TestWithParam<Integrator> {
 protected:
  SimulateOptions options() const {
    SimulateOptions o;
    o.adaptive = tight();
    o.integrator = GetParam();
    return o;
  }
  std::string solver() const {
    return GetParam() == Integrator::Taylor ? "Taylor, order 24, plain variables, general body"
                                            : "Dormand-Prince 5(4), general body";
  }
};
INSTANTIATE_TEST_SUITE_P(Both, GeneralBodyIntegrators, ::testing::Values(Integrator::Adaptive, Integrator::Taylor),
                         [](const auto& info) { return std::string(name(info.param)); });

// The textbook equations, written out independently: R' = R [w]x, I w' = (I w) x w + c x F,
// F = -m g R^T e_zeta, on (R, w) (12 variables), by Boost's Bulirsch-Stoer.
TEST_P(GeneralBodyIntegrators, AgreeWithAnIndependentBulirschStoerIntegrationTo1e9Rad) {
  Body body = body_with(1.2, 1.6, 0.9, 9.81);
  body.general = {0.05, -0.08, 0.03, 0.04, -0.03};  // Ixy, Ixz, Iyz, offset_x, offset_y
  body.length = 0.1;
  ASSERT_NO_THROW(validate(body));
  const Eigen::Matrix3d I = inertia_tensor(body);
  const Eigen::Matrix3d Iinv = I.inverse();
  const Eigen::Vector3d c(0.04, -0.03, 0.1);
  const InitialState state = make_state(8.0, 0.2, -0.1, 0.3, 0.5);

  using X = std::array<double, 12>;
  auto rhs = [&](const X& x, X& dxdt, double) {
    Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(x.data());
    const Eigen::Vector3d w(x[9], x[10], x[11]);
    Eigen::Matrix3d W;
    W << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> dR(dxdt.data());
    dR = R * W;
    const Eigen::Vector3d force = -body.mass * body.gravity * R.transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d dw = Iinv * ((I * w).cross(w) + c.cross(force));
    for (int i = 0; i < 3; ++i) dxdt[9 + i] = dw[i];
  };
  const RigidBodyState x0 = initial_rigid_body_state(state);
  X x{};
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(x.data()) = x0.attitude;
  for (int i = 0; i < 3; ++i) x[9 + i] = x0.omega[i];
  const auto times = times_to(10.0, 201);
  std::vector<Eigen::Vector3d> axes;
  boost::numeric::odeint::integrate_times(
      boost::numeric::odeint::bulirsch_stoer<X>(1e-14, 1e-14), rhs, x, times.begin(), times.end(), 1e-3,
      [&axes](const X& s, double) { axes.emplace_back(s[2], s[5], s[8]); });  // R e3

  const Simulation run = simulate(Model::Nonlinear, body, state, times, options());
  ASSERT_TRUE(run.summary.ok()) << run.summary.message;
  EXPECT_EQ(run.summary.solver, solver());
  double worst = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const AxisAngles a = axis_angles(axes[i].normalized(), Eigen::Vector3d::Zero());
    worst = std::max({worst, angle_difference(run.trajectory.theta[i], a.theta),
                      angle_difference(run.trajectory.phi[i], a.phi)});
  }
  RecordProperty("bulirsch_stoer_angle_difference", sci(worst));
  EXPECT_LT(worst, 1e-9);
  // The motion is not small: the axis wanders by tenths of a radian.
  double range = 0.0;
  for (double theta : run.trajectory.theta) range = std::max(range, std::abs(theta - run.trajectory.theta[0]));
  EXPECT_GT(range, 0.05);
  // Its energy column is conserved (E with m g c.gamma).
  EXPECT_LT(*run.summary.max_relative_energy_drift, 1e-11);
}

TEST(GeneralBody, RefusesABodyThatCannotExist) {
  Body body = body_with(1.0, 1.0, 1.5, 9.81);
  body.general.Ixy = 1.2;  // |Ixy| > sqrt(A B): not positive definite
  try {
    validate(body);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.Ixy");
  }
  // Positive definite, diagonal within the triangle inequalities, principal moments not:
  // A = B = 1, C = 1.9, Ixy = 0.5: principal moments 0.5, 1.5, 1.9 (0.5 + 1.5 >= 1.9 holds),
  // Ixy = 0.6: 0.4 + 1.6 >= 1.9 holds; Iyz with Ixy makes it fail.
  body = body_with(1.0, 1.0, 1.9, 9.81);
  body.general.Ixz = 0.3;
  body.general.Iyz = 0.3;
  const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_tensor(body)).eigenvalues();
  ASSERT_GT(l[0], 0.0);
  ASSERT_LT(l[0] + l[1], l[2]);  // the case really breaks the principal triangle inequality
  try {
    validate(body);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.Ixz");
  }
}

TEST(GeneralBody, OnlyTheNonlinearModelByDopri5OrTaylorTakesIt) {
  Body body = example_toy_top();
  body.general.offset_x = 1e-4;
  const InitialState state = example_motion();
  const auto times = times_to(0.01, 3);
  for (Model m : {Model::FirstOrder, Model::BodyFixed, Model::Linearized, Model::LagrangeExact}) {
    try {
      simulate(m, body, state, times);
      FAIL() << name(m) << " accepted the general body";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.key(), "body.offset_x") << name(m);
    }
  }
  for (Integrator i : {Integrator::Dop853, Integrator::Splitting}) {
    SimulateOptions o;
    o.integrator = i;
    EXPECT_THROW(
        {
          try {
            simulate(Model::Nonlinear, body, state, times, o);
          } catch (const InvalidInput& e) {
            EXPECT_EQ(e.key(), "integrator");
            throw;
          }
        },
        InvalidInput);
  }
  EXPECT_THROW(simulate_nonlinear(body, state, times), InvalidInput);  // the principal-axes path
  Body damped = body;
  damped.damping.axial = 1e-7;
  try {
    simulate(Model::Nonlinear, damped, state, times);
    FAIL() << "accepted a damped general body";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "damping.axial");
  }
  for (Integrator i : {Integrator::Auto, Integrator::Adaptive, Integrator::Taylor}) {
    SimulateOptions o;
    o.integrator = i;
    EXPECT_TRUE(simulate(Model::Nonlinear, body, state, times, o).summary.ok());
  }
}

}  // namespace
}  // namespace heavytop

namespace heavytop {
namespace {

// An unbalanced gyroscope (docs/general-body.md, "Coning"): a symmetric top (A = B) whose centre of
// mass is e off its axis. Near the vertical, with u = k_xi + i k_eta, the first-order equation is
//     i A u'' + C w0 u' - i m g R u = i m g e exp(i w0 t),
// the offset's weight a torque turning with the body; its forced solution is the coning
//     u = U exp(i w0 t),  U = m g e / ((C - A) w0^2 - m g R).
// Started on it, the axis cones at the spin frequency with amplitude |U|.
TEST_P(GeneralBodyIntegrators, UnbalancedGyroscopeConesAtTheSpinFrequencyWithTheFirstOrderAmplitude) {
  Body top = example_toy_top();
  top.general.offset_x = 1e-4;  // m, the ISO 1940 scale of a poorly balanced small rotor
  const double w0 = 200.0;
  const double U = top.mass * top.gravity * top.general.offset_x / ((top.C - top.A) * w0 * w0 - top.mgR());
  const InitialState state = make_state(w0, U, 0.0, 0.0, -w0 * U);  // u(0) = U, u'(0) = i w0 U
  const double period = 2.0 * kPi / w0;
  const auto times = times_to(50.0 * period, 5001);
  const SimulateOptions options = this->options();
  const Simulation run = simulate(Model::Nonlinear, top, state, times, options);
  ASSERT_TRUE(run.summary.ok()) << run.summary.message;
  double amplitude_error = 0.0, phase_error = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Vector3d k = test_support::axis_of(run.trajectory.theta[i], run.trajectory.phi[i]);
    const std::complex<double> u(k.x(), k.y()), expected = U * std::exp(std::complex<double>(0.0, w0 * times[i]));
    amplitude_error = std::max(amplitude_error, std::abs(std::abs(u) - std::abs(U)) / std::abs(U));
    phase_error = std::max(phase_error, std::abs(std::arg(u / expected)));
  }
  RecordProperty("coning_amplitude_rad", sci(std::abs(U)));
  RecordProperty("coning_relative_amplitude_and_phase_error", sci(amplitude_error) + " " + sci(phase_error));
  EXPECT_LT(amplitude_error, 1e-3);
  EXPECT_LT(phase_error, 1e-3);  // rad, over 50 turns: the coning keeps the spin's frequency

  // Started upright instead, the first-order motion adds the free modes exp(i l t), l the roots of
  // A l^2 - C w0 l + m g R = 0 (slow and fast precession), sized so that u(0) = u'(0) = 0:
  // u = U e^{i w0 t} + a1 e^{i l1 t} + a2 e^{i l2 t}, a1 + a2 = -U, l1 a1 + l2 a2 = -w0 U.
  const double root = std::sqrt(top.C * top.C * w0 * w0 - 4.0 * top.A * top.mgR());
  const double l1 = (top.C * w0 - root) / (2.0 * top.A), l2 = (top.C * w0 + root) / (2.0 * top.A);
  const double a2 = -U * (w0 - l1) / (l2 - l1), a1 = -U - a2;
  const Simulation upright = simulate(Model::Nonlinear, top, make_state(w0, 0.0), times, options);
  ASSERT_TRUE(upright.summary.ok());
  double largest = 0.0, error = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Eigen::Vector3d k = test_support::axis_of(upright.trajectory.theta[i], upright.trajectory.phi[i]);
    const double t = times[i];
    const std::complex<double> I(0.0, 1.0);
    const std::complex<double> linear = U * std::exp(I * w0 * t) + a1 * std::exp(I * l1 * t) + a2 * std::exp(I * l2 * t);
    largest = std::max(largest, std::abs(linear));
    error = std::max(error, std::abs(std::complex<double>(k.x(), k.y()) - linear));
  }
  RecordProperty("upright_start_first_order_relative_error", sci(error / largest));
  EXPECT_GT(largest, 5.0 * std::abs(U));  // the free modes dominate: the check is not the coning alone
  EXPECT_LT(error / largest, 1e-3);
}

}  // namespace
}  // namespace heavytop

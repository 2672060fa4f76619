// The report's 3D view: the attitude it animates (spin_angles: R = Q(phi, theta) Rz(psi)) against
// two independent routes, the Lagrange top's closed form and Boost.Odeint on RigidBodySystem
// (quaternion and body rates, no angles at all); the equivalent ellipsoid's moments; the
// display decimation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <boost/numeric/odeint.hpp>

#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/report/animation.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/rigid_body.hpp"
#include "test_support.hpp"

namespace heavytop {
namespace {
using test_support::make_body;
using test_support::make_state;

// rad, the angle of the rotation that takes `a` to `b`.
double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.transpose() * b)).angle();
}

// The report's attitude at sample i.
Eigen::Matrix3d report_attitude(const Trajectory& tr, const std::vector<double>& psi, std::size_t i) {
  return axis_frame(tr.phi[i], tr.theta[i]) * Eigen::AngleAxisd(psi[i], Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// Largest attitude error of the report's route against `exact` over `samples` samples of [0, T].
template <class Exact>
double attitude_error(const Body& body, const InitialState& s, double T, std::size_t samples, Exact exact) {
  const std::vector<double> times = sample_times(T, samples);
  const Trajectory tr = simulate_nonlinear(body, s, times);
  const std::vector<double> psi = report::spin_angles(body, tr);
  EXPECT_EQ(psi.front(), 0.0);  // SPEC section 2: psi = 0 at t = 0
  double worst = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i)
    worst = std::max(worst, rotation_angle(exact(i, times[i]), report_attitude(tr, psi, i)));
  return worst;
}

// A symmetric body with large tilts and rates (theta' sin phi, the term that couples the
// spin to the axis's motion, is of order 1 rad/s): against the closed form. A sign slip in
// psi' = w3 + theta' sin(phi) would be off by radians; the trapezoid rule's error falls 4x
// per doubling of the samples (second order).
TEST(ReportAttitude, MatchesTheLagrangeTopsClosedForm) {
  const Body body = make_body(1.0, 1.0, 0.6, 1.0);
  const InitialState s = make_state(6.0, 0.4, -0.2, 0.3, 0.6);
  const LagrangeTop top = lagrange_top(body, s);
  auto exact = [&](std::size_t, double t) { return lagrange_rigid_body_state(top, t).attitude; };
  const double coarse = attitude_error(body, s, 10.0, 2001, exact);
  const double fine = attitude_error(body, s, 10.0, 4001, exact);
  RecordProperty("attitude_error_2001_4001", test_support::sci(coarse) + " " + test_support::sci(fine));
  EXPECT_LT(fine, 5e-6);  // measured 2.4e-6 rad (9.6e-6 at 2001 samples)
  EXPECT_GT(coarse / fine, 3.5);
  EXPECT_LT(coarse / fine, 4.5);
}

// An asymmetric body (w3 itself varies): against Bulirsch-Stoer on RigidBodySystem.
TEST(ReportAttitude, MatchesOdeintOnTheRigidBody) {
  namespace odeint = boost::numeric::odeint;
  const Body body = make_body(1.0, 1.5, 2.0, 1.0);
  const InitialState s = make_state(8.0, 0.3, 0.1, -0.4, 0.5);
  for (std::size_t samples : {2001, 4001}) {
    std::vector<Eigen::Matrix3d> expected;
    RigidBodyVector x = to_vector(initial_rigid_body_state(s));
    const std::vector<double> times = sample_times(5.0, samples);
    odeint::integrate_times(odeint::bulirsch_stoer<RigidBodyVector>(1e-13, 1e-13), RigidBodySystem{body}, x,
                            times.begin(), times.end(), 1e-3,
                            [&](const RigidBodyVector& y, double) { expected.push_back(from_vector(y).attitude); });
    const double error = attitude_error(body, s, 5.0, samples, [&](std::size_t i, double) { return expected[i]; });
    RecordProperty("attitude_error_" + std::to_string(samples), test_support::sci(error));
    EXPECT_LT(error, samples == 2001 ? 2e-6 : 5e-7) << samples;  // measured 1.0e-6, 2.5e-7 rad
  }
}

// The report's asymmetric example, which falls over (the axis passes the horizontal): the angles
// of Q(phi, theta) are singular where the axis lies along eta (phi = +-pi/2), and psi' spikes
// there; the attitude the page shows must still be the body's.
TEST(ReportAttitude, FollowsABodyThatFallsOver) {
  namespace odeint = boost::numeric::odeint;
  const Body body = make_body(1.0, 1.5, 2.0, 1.0);
  const InitialState s = make_state(1.3, 0.01);
  const std::vector<double> times = sample_times(24.6, 4001);
  std::vector<Eigen::Matrix3d> expected;
  RigidBodyVector x = to_vector(initial_rigid_body_state(s));
  odeint::integrate_times(odeint::bulirsch_stoer<RigidBodyVector>(1e-13, 1e-13), RigidBodySystem{body}, x, times.begin(),
                          times.end(), 1e-3, [&](const RigidBodyVector& y, double) { expected.push_back(from_vector(y).attitude); });
  const double error = attitude_error(body, s, 24.6, 4001, [&](std::size_t i, double) { return expected[i]; });
  // The two integrations agree on the axis (3.0e-8 rad): what remains (6.5e-4 rad) is the
  // trapezoid rule's error on psi where psi' spikes, near phi = +-pi/2. Invisible on screen,
  // but the one place the quadrature is not at 1e-6.
  const Trajectory tr = simulate_nonlinear(body, s, times);
  double axis = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i)
    axis = std::max(axis, std::acos(std::min(1.0, axis_frame(tr.phi[i], tr.theta[i]).col(2).dot(expected[i].col(2)))));
  RecordProperty("attitude_error_falling", test_support::sci(error) + " axis " + test_support::sci(axis));
  EXPECT_LT(axis, 1e-7);
  EXPECT_LT(error, 1e-3);
}

TEST(ReportAttitude, NeedsTheAxialMomentumColumn) {
  Trajectory tr;
  tr.t = tr.theta = tr.phi = tr.theta_rate = tr.phi_rate = {0.0};
  EXPECT_THROW(report::spin_angles(make_body(1, 1, 1, 1), tr), InvalidInput);
}

// The equivalent uniform ellipsoid has the body's mass and moments about O (parallel axes).
TEST(ReportShape, EllipsoidHasTheBodysMoments) {
  Body body = make_body(2e-4, 2.4e-4, 1e-4, 0.0);
  body.mass = 0.1;
  body.length = 0.03;
  const auto e = report::equivalent_ellipsoid(body);
  const double a = e.semi_axes[0], b = e.semi_axes[1], c = e.semi_axes[2], m = body.mass, shift = m * body.length * body.length;
  EXPECT_TRUE(e.note.empty()) << e.note;
  EXPECT_NEAR(m * (b * b + c * c) / 5 + shift, body.A, 1e-15);
  EXPECT_NEAR(m * (a * a + c * c) / 5 + shift, body.B, 1e-15);
  EXPECT_NEAR(m * (a * a + b * b) / 5, body.C, 1e-15);
  EXPECT_DOUBLE_EQ(e.centre, 0.03);
  // The toy top's disc: its central moments are planar (A_c + B_c = C), a zero thickness,
  // drawn at kMinThickness of the radius and said so.
  const auto disc = report::equivalent_ellipsoid(example_toy_top());
  EXPECT_NEAR(disc.semi_axes[2], report::kMinThickness * disc.semi_axes[0], 1e-12);
  EXPECT_NE(disc.note.find("z semi-axis (0: a flat body)"), std::string::npos) << disc.note;
  // Moments no body has (A_c = 0 here: A = m R^2) are said to be so.
  EXPECT_NE(report::equivalent_ellipsoid(make_body(1.0, 1.5, 2.0, 1.0)).note.find("no real body"), std::string::npos);
  // (1/2) m r^2 = C of a disc of r = 20 mm is (1/5) m (a^2 + b^2) of an elliptic one of a = b = sqrt(5/2) r / sqrt 2.
  EXPECT_NEAR(disc.semi_axes[0], 0.020 * std::sqrt(1.25), 1e-9);
}

TEST(ReportDisplay, DecimatesToAtMostDisplaySamplesKeepingTheEnds) {
  for (std::size_t n : {1, 2, 1000, 1001, 1002, 4001, 10007}) {
    const auto shown = report::display_samples(n);
    EXPECT_LE(shown.size(), report::kDisplaySamples + 1) << n;
    EXPECT_EQ(shown.front(), 0u);
    EXPECT_EQ(shown.back(), n - 1);
    if (n <= report::kDisplaySamples) { EXPECT_EQ(shown.size(), n); }
  }
  EXPECT_EQ(report::display_samples(4001).size(), 1001u);  // the report's 4001: every 4th
}

}  // namespace
}  // namespace heavytop

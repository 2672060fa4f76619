// The body's rules (SPEC section 1) and the frames and angles of SPEC section 2.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/rigid_body.hpp"

namespace heavytop {
namespace {

Body valid_body() { return Body{.A = 1.0, .B = 1.2, .C = 0.7, .mass = 2.0, .gravity = 9.81, .length = 0.1}; }

struct BrokenRule {
  const char* name;
  void (*break_it)(Body&);
  const char* key;
};

class BodyRule : public ::testing::TestWithParam<BrokenRule> {};

TEST_P(BodyRule, IsRefusedNamingTheKey) {
  Body body = valid_body();
  GetParam().break_it(body);
  try {
    validate(body);
    FAIL() << "accepted a body breaking " << GetParam().name;
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), GetParam().key);
    EXPECT_FALSE(e.rule().empty());
  }
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

INSTANTIATE_TEST_SUITE_P(
    Spec, BodyRule,
    ::testing::Values(
        BrokenRule{"A>0", [](Body& b) { b.A = 0.0; }, "body.A"},
        BrokenRule{"A finite", [](Body& b) { b.A = kNaN; }, "body.A"},
        BrokenRule{"B>0", [](Body& b) { b.B = -1.0; }, "body.B"},
        BrokenRule{"B finite", [](Body& b) { b.B = kInf; }, "body.B"},
        BrokenRule{"C>0", [](Body& b) { b.C = 0.0; }, "body.C"},
        BrokenRule{"mass>0", [](Body& b) { b.mass = -1.0; }, "body.mass"},
        BrokenRule{"mass finite", [](Body& b) { b.mass = kNaN; }, "body.mass"},
        BrokenRule{"gravity>=0", [](Body& b) { b.gravity = -9.81; }, "body.gravity"},
        BrokenRule{"gravity finite", [](Body& b) { b.gravity = kInf; }, "body.gravity"},
        BrokenRule{"length finite", [](Body& b) { b.length = kNaN; }, "body.length"},
        BrokenRule{"A+B>=C", [](Body& b) { b.C = 2.3; }, "body.C"},
        BrokenRule{"B+C>=A", [](Body& b) { b.A = 2.0; }, "body.A"},
        BrokenRule{"C+A>=B", [](Body& b) { b.B = 1.8; }, "body.B"}),
    [](const auto& info) {
      std::string n = info.param.name;
      for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(Body, FlatBodyOnTheTriangleBoundaryIsAccepted) {
  // A + B = C exactly (a flat disc about its centre) and in rounded decimal arithmetic.
  EXPECT_NO_THROW(validate(Body{.A = 1.0, .B = 1.0, .C = 2.0, .mass = 1.0, .length = 0.0}));
  EXPECT_NO_THROW(validate(Body{.A = 0.1, .B = 0.2, .C = 0.3, .mass = 1.0, .length = 0.0}));
  EXPECT_NO_THROW(validate(Body{.A = 1.0, .B = 1.0, .C = 1.0, .mass = 1.0, .gravity = 0.0, .length = -1.0}));
}

TEST(Body, ExampleTopIsValidAndRealistic) {
  const Body top = example_toy_top();
  EXPECT_NO_THROW(validate(top));
  // A toy top: tens of grams, a few centimetres, critical spin of the order of 1000 rpm.
  const double critical = 2.0 * std::sqrt(top.A * top.mgR()) / top.C;
  EXPECT_GT(critical * 30.0 / M_PI, 500.0);
  EXPECT_LT(critical * 30.0 / M_PI, 3000.0);
}

TEST(InitialStateRules, NonFiniteIsRefused) {
  InitialState s;
  s.theta_rate0 = kNaN;
  try {
    validate(s);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "motion.theta_rate0");
  }
}

TEST(Frames, AxisFrameThirdColumnIsSpecAxis) {
  const double phi = 0.3, theta = -0.7;
  const Eigen::Vector3d k = axis_frame(phi, theta).col(2);
  EXPECT_NEAR(k.x(), std::sin(theta) * std::cos(phi), 1e-15);
  EXPECT_NEAR(k.y(), -std::sin(phi), 1e-15);
  EXPECT_NEAR(k.z(), std::cos(theta) * std::cos(phi), 1e-15);
  const AxisAngles a = axis_angles(k, Eigen::Vector3d::Zero());
  EXPECT_NEAR(a.phi, phi, 1e-15);
  EXPECT_NEAR(a.theta, theta, 1e-15);
}

TEST(Frames, RatesOfTheAxisInvertTheAxisFrameRate) {
  // k' = w x k with w the axis frame's angular velocity must give back phi', theta'.
  const double phi = -0.4, theta = 1.1, phi_rate = 0.25, theta_rate = -1.5;
  const Eigen::Vector3d k = axis_frame(phi, theta).col(2);
  const Eigen::Vector3d k_rate = axis_frame_rate(phi, theta, phi_rate, theta_rate).cross(k);
  const AxisAngles a = axis_angles(k, k_rate);
  EXPECT_NEAR(a.phi_rate, phi_rate, 1e-14);
  EXPECT_NEAR(a.theta_rate, theta_rate, 1e-14);
  // And against a finite difference of the exact angles.
  const double h = 1e-6;
  const Eigen::Vector3d k_next = axis_frame(phi + h * phi_rate, theta + h * theta_rate).col(2);
  EXPECT_NEAR((k_next - k).norm() / h, k_rate.norm(), 1e-5);
}

// tilt_of_axis: asin below 45 degrees, atan2 above (frames.hpp). Against the tilt each axis was
// built from, at any length of the axis, across the switch, near 0 and near the underflow guard:
// within a few units in the last place of the tilt (the axis's own rounding is one of them).
TEST(Frames, TiltOfAxisIsTheAngleFromTheVerticalAtEveryTiltAndLength) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const double quarter = std::atan(1.0);
  std::vector<double> tilts = {0.0, 1e-300, 1e-150, 1e-12, 1e-6, 0.05, 0.5, 1.0, 2.0, 3.0, 3.14159};
  for (double d : {-1e-9, -1e-13, 0.0, 1e-13, 1e-9}) tilts.push_back(quarter + d);
  for (int i = 1; i < 200; ++i) tilts.push_back(3.14159265 * i / 200.0);
  for (double tilt : tilts)
    for (double azimuth : {0.0, 0.7, 2.5, -1.9})
      for (double length : {1.0, 3.7, 1e-3}) {
        const double kx = length * std::sin(tilt) * std::cos(azimuth), ky = length * std::sin(tilt) * std::sin(azimuth);
        const double kz = length * std::cos(tilt);
        EXPECT_NEAR(tilt_of_axis(kx, ky, kz), tilt, 6.0 * kEps * tilt)
            << "tilt " << tilt << ", azimuth " << azimuth << ", length " << length;
      }
  EXPECT_EQ(tilt_of_axis(0.0, 0.0, 1.0), 0.0);
  EXPECT_EQ(tilt_of_axis(0.0, 0.0, -2.0), std::acos(-1.0));
  EXPECT_NEAR(tilt_of_axis(1.0, 0.0, 0.0), 2.0 * quarter, kEps);
}

// azimuth_of_axis (atan2_in_octant) against std::atan2 at every direction, lengths down to
// near underflow, the octants' borders, and SPEC's (-pi, pi] where atan2 gives -pi (a -0 k_eta).
TEST(Frames, AzimuthOfAxisIsAtan2InEveryOctant) {
  constexpr double kEps = std::numeric_limits<double>::epsilon(), kPi = 3.141592653589793;
  std::vector<double> angles;
  for (int i = -1000; i <= 1000; ++i) angles.push_back(kPi * i / 1000.0 * (1.0 - 1e-12));
  for (int k = -3; k <= 4; ++k)
    for (double d : {-1e-12, 0.0, 1e-12}) angles.push_back(kPi * k / 4.0 + d);
  for (double angle : angles)
    for (double length : {1.0, 0.3, 2e-140, 7.0}) {
      const double kx = length * std::cos(angle), ky = length * std::sin(angle);
      EXPECT_NEAR(azimuth_of_axis(kx, ky), std::atan2(ky, kx), 4.0 * kEps * std::max(std::abs(angle), 1.0))
          << "angle " << angle << ", length " << length;
    }
  EXPECT_EQ(azimuth_of_axis(0.0, 0.0), 0.0);
  EXPECT_EQ(azimuth_of_axis(-1.0, 0.0), kPi);
  EXPECT_EQ(azimuth_of_axis(-1.0, -0.0), kPi);  // atan2 gives -pi here, outside (-pi, pi]
  EXPECT_EQ(azimuth_of_axis(0.0, 2.0), kPi / 2);
  EXPECT_EQ(azimuth_of_axis(0.0, -2.0), -kPi / 2);
  EXPECT_NEAR(azimuth_of_axis(-1e-160, 1e-160), 0.75 * kPi, kEps);  // near underflow: atan2's route
}

// ContinuousAzimuth keeps the last multiple of 2 pi while it fits (frames.cpp): every sample the
// same bits as SPEC's rule, the wrapped azimuth plus 2 pi round((previous - wrapped) / 2 pi),
// over walks of small, large (near pi) and huge steps, through many turns, and at zero.
TEST(Frames, ContinuousAzimuthIsTheRoundingRuleBitForBit) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  std::mt19937_64 random(31);
  for (double largest : {0.1, 3.0, 3.2, 40.0}) {
    std::uniform_real_distribution<double> step(-largest, largest);
    ContinuousAzimuth continuous;
    double angle = 0.0, previous = 0.0;
    bool started = false;
    for (int i = 0; i < 20000; ++i) {
      angle += (i % 500 == 7) ? 0.0 : step(random) + 0.05;  // drifts through many turns
      const double kx = i % 997 == 3 ? 1.0 : std::cos(angle), ky = i % 997 == 3 ? -0.0 : std::sin(angle);
      const double wrapped = azimuth_of_axis(kx, ky);
      const double expected = started ? wrapped + kTwoPi * std::round((previous - wrapped) / kTwoPi) : wrapped;
      started = true;
      const double got = continuous.of_axis(kx, ky);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(expected))
          << "largest step " << largest << ", sample " << i;
      previous = expected;
    }
  }
}

// from_vector: the rotation of q / |q| from q of any length (one division, frames of every
// integrator's samples), against Eigen's own route (AngleAxis of the unit quaternion), and
// axis_angles' theta (atan2_in_octant, every octant) against the theta
// the axis was built from.
TEST(Frames, AttitudeOfAQuaternionOfAnyLengthAndThetaOfEveryAxis) {
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d axis = Eigen::Vector3d(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(0.31 * i + 1)).normalized();
    const Eigen::Quaterniond unit(Eigen::AngleAxisd(0.05 * i - 4.0, axis));
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(unit).toRotationMatrix();
    for (double length : {1.0, 1.0 + 1e-7, 0.37, 12.0}) {
      const RigidBodyState r = from_vector({length * unit.w(), length * unit.x(), length * unit.y(), length * unit.z(), 1, 2, 3});
      EXPECT_LT((r.attitude - expected).cwiseAbs().maxCoeff(), 2e-15) << i << " " << length;
      EXPECT_LT((r.attitude.transpose() * r.attitude - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 2e-15);
    }
  }
  EXPECT_EQ(from_vector({0, 0, 0, 0, 1, 2, 3}).attitude, Eigen::Matrix3d::Identity());
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  for (int i = -300; i <= 300; ++i)
    for (double phi : {0.0, 0.4, -1.2}) {
      const double theta = 3.14159 * i / 300.0;
      const AxisAngles a = axis_angles(axis_frame(phi, theta).col(2), Eigen::Vector3d::Zero());
      EXPECT_NEAR(a.theta, theta, 8.0 * kEps * std::max(std::abs(theta), 1e-300)) << theta << " " << phi;
    }
}

TEST(Frames, InitialRigidBodyStateFollowsSpec) {
  InitialState s{.spin = 10.0, .theta0 = 0.2, .phi0 = -0.1, .theta_rate0 = 0.3, .phi_rate0 = 0.4};
  const RigidBodyState x = initial_rigid_body_state(s);
  EXPECT_NEAR((x.attitude.transpose() * x.attitude - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
  // The spin component along the body axis: w0 plus the axis frame's own rate along k.
  const Eigen::Vector3d k = x.attitude.col(2);
  const Eigen::Vector3d frame_rate = axis_frame_rate(s.phi0, s.theta0, s.phi_rate0, s.theta_rate0);
  EXPECT_NEAR(x.omega.z(), s.spin + frame_rate.dot(k), 1e-14);
  EXPECT_NEAR(frame_rate.dot(k), -s.theta_rate0 * std::sin(s.phi0), 1e-15);
}

}  // namespace
}  // namespace heavytop

// The comparison's numbers against direct calls of the models, the frequency measurement
// against a motion with known frequencies, and the sweep against single stability calls.
#include <optional>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "heavytop/compare.hpp"
#include "heavytop/linear_motion.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop {
namespace {

Body body_with(double A, double B, double C, double mgR) {
  return Body{.A = A, .B = B, .C = C, .mass = 1.0, .gravity = 1.0, .length = mgR};
}

TEST(Compare, NumbersEqualDirectCallsOfTheModels) {
  const Body b = body_with(1.0, 1.5, 2.0, 1.0);
  const InitialState s{.spin = 1.6, .theta0 = 0.01};
  const auto times = sample_times(20.0, 2001);
  const Comparison c = compare_models(b, s, times);
  const Trajectory truth = simulate_nonlinear(b, s, times);
  ASSERT_EQ(c.models.size(), 3u);
  for (const ModelComparison& m : c.models) {
    const Trajectory direct = simulate_linear(linear_model(*linear_model_from_name(m.model), b), s, times, LinearMethod::Analytic);
    double max_error = 0.0, final_error = 0.0;
    std::optional<double> diverged_at;  // where its angles first pass kDivergedAngle
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (std::max(std::abs(direct.theta[i]), std::abs(direct.phi[i])) > kDivergedAngle) {
        diverged_at = times[i];
        break;
      }
      final_error = std::max(std::abs(direct.theta[i] - truth.theta[i]), std::abs(direct.phi[i] - truth.phi[i]));
      max_error = std::max(max_error, final_error);
    }
    EXPECT_EQ(m.diverged_at, diverged_at) << m.model;
    EXPECT_EQ(m.max_angle_error, max_error) << m.model;
    if (!diverged_at) {
      EXPECT_EQ(m.final_angle_error, final_error) << m.model;
    }
  }
  // The body-fixed model (5) is unstable at this spin (its critical spin is above 1.6 rad/s):
  // it grows past any small-motion meaning within the horizon, and is reported as diverged.
  EXPECT_FALSE(linear_stability(linear_model(LinearModelKind::BodyFixed, b), s.spin).stable);
  EXPECT_TRUE(c.models[1].diverged_at.has_value());
  EXPECT_FALSE(c.models[0].diverged_at || c.models[2].diverged_at);
  // The exact linearisation is close at this small amplitude, the paper's (4) is not (E3).
  EXPECT_LT(c.models[2].max_angle_error, 1e-4);
  EXPECT_GT(c.models[0].max_angle_error, 1e-3);
  ASSERT_TRUE(c.models[2].nutation_relative_error);
  EXPECT_LT(*c.models[2].nutation_relative_error, 1e-3);
}

TEST(Compare, FrequenciesOfAKnownMotion) {
  // z = theta - i phi = r1 exp(i w1 t) + r2 exp(i w2 t), r1 > r2: the tilt |z| beats at
  // |w1 - w2| (nutation) and the azimuth turns on average at w1 (precession). SPEC's
  // azimuth is atan2(k_eta, k_xi) = atan2(-sin phi, ...), so it turns with arg z.
  const double r1 = 0.02, r2 = 0.005, w1 = 0.7, w2 = 9.3;
  Trajectory tr;
  for (double t : sample_times(30.0, 30001)) {
    const std::complex<double> z = r1 * std::polar(1.0, w1 * t) + r2 * std::polar(1.0, w2 * t);
    // Exact angles of the axis k = (Re z, Im z, sqrt(1 - |z|^2)).
    const double kx = z.real(), ky = z.imag(), kz = std::sqrt(1.0 - std::norm(z));
    tr.t.push_back(t);
    tr.theta.push_back(std::atan2(kx, kz));
    tr.phi.push_back(-std::asin(ky));
    tr.theta_rate.push_back(0.0);
    tr.phi_rate.push_back(0.0);
  }
  const MotionFrequencies f = measure_frequencies(tr);
  ASSERT_TRUE(f.nutation && f.precession);
  EXPECT_NEAR(*f.nutation, w2 - w1, 1e-4 * (w2 - w1));
  EXPECT_NEAR(*f.precession, w1, 1e-3 * w1);
}

TEST(Sweep, VerdictsEqualSingleStabilityCallsAndDoNotDependOnThreads) {
  const Body base = body_with(1.0, 1.0, 1.5, 1.0);
  const InitialState state{.spin = 0.0};
  const std::vector<SweepAxis> axes{parse_sweep_axis("B/A=0.6:2.4:37"), parse_sweep_axis("spin=0:4:41")};
  ASSERT_EQ(grid_size(axes), 37u * 41u);
  SweepOptions serial, parallel;
  serial.threads = 1;
  parallel.threads = 3;
  const auto one = sweep_verdicts(base, state, axes, serial, 0, grid_size(axes));
  const auto two = sweep_verdicts(base, state, axes, parallel, 0, grid_size(axes));
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].linear, two[i].linear) << i;
    const double ratio = 0.6 + 1.8 * static_cast<double>(i / 41) / 36.0, spin = 4.0 * static_cast<double>(i % 41) / 40.0;
    Body b = base;
    b.B = ratio * base.A;
    for (std::size_t m = 0; m < kLinearModels.size(); ++m)
      EXPECT_EQ(one[i].linear[m], linear_stability(linear_model(kLinearModels[m], b), spin).stable) << i;
  }
}

TEST(Sweep, NonlinearVerdictFollowsTheTilt) {
  // Erratum E3's body: the nonlinear body falls at 1.3 and stays up at 1.45 rad/s.
  const Body b = body_with(1.0, 1.5, 2.0, 1.0);
  const InitialState state{.theta0 = 1e-4};
  SweepOptions o;
  o.nonlinear = true;
  o.horizon = 300.0;
  o.max_tilt = 0.5;
  o.integrator.rtol = o.integrator.atol = 1e-9;
  const std::vector<SweepAxis> axes{parse_sweep_axis("spin=1.3:1.45:2")};
  const auto v = sweep_verdicts(b, state, axes, o, 0, 2);
  EXPECT_FALSE(*v[0].nonlinear);
  EXPECT_TRUE(*v[1].nonlinear);
  EXPECT_FALSE(v[0].linear[2]);
  EXPECT_TRUE(v[0].linear[0]);  // (4) promises it stands up at 1.3
}

TEST(Sweep, BadGridsAreRefusedNamingVary) {
  const Body base = body_with(1.0, 1.0, 1.5, 1.0);
  for (const char* text : {"B/A=0.1:3:10" /* breaks the triangle rule */, "mass=-1:1:3"}) {
    try {
      validate_sweep(base, InitialState{}, {parse_sweep_axis(text)}, SweepOptions{});
      FAIL() << text;
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.key(), "vary") << e.what();
    }
  }
  for (const char* text : {"D=0:1:3", "spin=0:1", "spin=0:1:0", "spin=a:1:3", "spin=0:1:3.5"})
    EXPECT_THROW(parse_sweep_axis(text), InvalidInput) << text;
  SweepOptions o;
  o.nonlinear = true;
  EXPECT_THROW(validate_sweep(base, InitialState{}, {parse_sweep_axis("spin=0:1:3")}, o), InvalidInput);
}

}  // namespace
}  // namespace heavytop

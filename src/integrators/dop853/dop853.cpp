#include "heavytop/dop853.hpp"
#include "heavytop/frames.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "heavytop/rigid_body.hpp"

#include "integrators/dop853/stepper.hpp"
#include "integrators/integration.hpp"
#include "integrators/monitor.hpp"
#include "integrators/sampling.hpp"
#include "integrators/tilt_scan.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

namespace {

using State = RigidBodyVector;
constexpr std::size_t kN = 7;

// The rigid body's part of DOP853 (stepper.hpp): |q| = 1 at each step's start (its rate
// scaled too), the first integrals' drifts and the work into the summary, if one is asked for.
struct RigidBodyHooks {
  const Body* body;
  NonlinearSummary* summary;
  StepMonitor<NonlinearSummary> monitor;

  void project(State& y, State& dydt) { monitor.note_norm(renormalise_quaternion(y, dydt)); }
  void rejected() {
    if (summary) ++summary->rejected_steps;
  }
  void accepted(double t, const State& y, std::size_t evaluations) {
    if (!summary) return;
    summary->rhs_evaluations = evaluations;
    monitor.note_step(t, conserved_quantities(*body, from_vector(y)));
  }
  void evaluated(std::size_t evaluations) {
    if (summary) summary->rhs_evaluations = evaluations;
  }
};

class Dop853 : public Dop853Stepper<kN, RigidBodySystem, RigidBodyHooks> {
 public:
  Dop853(const Body& body, const State& x0, double horizon, const Tolerances& options, NonlinearSummary* summary)
      : Dop853Stepper(RigidBodySystem{body}, x0, horizon, options,
                      RigidBodyHooks{&body, summary, StepMonitor<NonlinearSummary>(summary)}) {
    if (hooks().monitor)
      hooks().monitor.start(body.A == body.B, scales_of(body, from_vector(x0)),
                            conserved_quantities(body, from_vector(x0)));
  }
};

// Tilt acos(k_zeta) and d(k_zeta)/dt of the plain state: k_zeta = gamma_3, with gamma = R(q)^T
// e_zeta in body axes and gamma' = gamma x w, so d(gamma_3)/dt = gamma_1 w2 - gamma_2 w1.
struct TiltOf {
  double g1, g2, g3;
  explicit TiltOf(const State& x) {
    const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
    const double inv = 1.0 / (qw * qw + qx * qx + qy * qy + qz * qz);
    g1 = 2.0 * (qx * qz - qw * qy) * inv, g2 = 2.0 * (qy * qz + qw * qx) * inv;
    g3 = (qw * qw - qx * qx - qy * qy + qz * qz) * inv;
  }
  double tilt() const { return tilt_of_axis(g1, g2, g3); }
  double rate(const State& x) const { return g1 * x[5] - g2 * x[4]; }
};

// nonlinear.cpp's scan_tilt on DOP853's dense output: extrema at the roots of d(k_zeta)/dt,
// the crossing of stop_above located by TOMS 748.
TiltExtremes scan_tilt(const Body& body, const State& x0, double horizon, double stop_above,
                       const Tolerances& options, const Progress& progress) {
  const TiltRecord start = start_tilt_scan(TiltOf(x0).tilt(), x0[6], stop_above);
  if (start.e.exceeded || horizon == 0.0) return start.e;
  Dop853 integrator(body, x0, horizon, options, nullptr);
  auto tilt = [](const State& x) { return TiltOf(x).tilt(); };
  auto rate = [](const State& x) { return TiltOf(x).rate(x); };
  return scan_tilt_extremes(integrator, horizon, start, DenseOutputEvents<State, decltype(tilt), decltype(rate)>(x0, tilt, rate),
                            [](const State& x) { return x[6]; }, progress);
}

}  // namespace

TiltExtremes dop853_tilt_extremes(const Body& body, const InitialState& initial, double horizon, double stop_above,
                                  const Tolerances& options, const Progress& progress) {
  validate(body);
  refuse_general(body, "dop853 (use dopri5 or auto)");
  detail::refuse_damping(body, "dop853");
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  return scan_tilt(body, to_vector(initial_rigid_body_state(initial)), horizon, stop_above, options, progress);
}

void detail::stream_dop853(const Body& body, const InitialState& initial, const SampleStream& samples,
                           const Tolerances& options, NonlinearSummary* summary) {
  validate(body);
  refuse_general(body, "dop853 (use dopri5 or auto)");
  detail::refuse_damping(body, "dop853");
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  const double horizon = samples.horizon();
  Dop853 integrator(body, to_vector(rb0), horizon, options, summary);
  write_samples(integrator, body, rb0, conserved_quantities(body, rb0), false, samples,
                [&body](const State& x) {
                  const RigidBodyState rb = from_vector(x);
                  return sample_of(rb, conserved_quantities(body, rb));
                });
}

Trajectory simulate_dop853(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const Tolerances& options, NonlinearSummary* summary, const Progress& progress) {
  return gathered(times, progress, [&](const SampleStream& samples) {
    detail::stream_dop853(body, initial, samples, options, summary);
  });
}

}  // namespace heavytop

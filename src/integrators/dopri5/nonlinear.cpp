#include "heavytop/nonlinear.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "integrators/dopri5/driver.hpp"
#include "integrators/dopri5/spin_factored.hpp"
#include "integrators/integration.hpp"
#include "integrators/sampling.hpp"
#include "integrators/tilt_scan.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

namespace {

using namespace detail::spin_factored;

// ---- Options --------------------------------------------------------------------------------

Violation first_violation(const Tolerances& o) {
  if (!(std::isfinite(o.rtol) && o.rtol >= 1e-15 && o.rtol <= 1.0))
    return std::pair{"rtol", "must be a finite number in [1e-15, 1]"};
  if (!(std::isfinite(o.atol) && o.atol > 0.0))
    return std::pair{"atol", "must be a finite number > 0"};
  if (o.max_steps == 0) return std::pair{"max_steps", "must be > 0"};
  return std::nullopt;
}

// ---- The integrator ---------------------------------------------------------------------------

// The spin-factored variables for the dopri5 driver (driver.hpp).
template <bool Symmetric, bool Damped>
struct SpinFactoredVariables {
  using State = StateOf<Damped>;
  using Equations = spin_factored::Equations<Symmetric, Damped>;
  static constexpr bool kSymmetric = Symmetric, kDamped = Damped;
  static constexpr int kW3 = spin_factored::kW3;

  static Equations equations(const Body& body) { return Equations(body); }

  // Back onto the manifold before the next step: |p| = 1 (its rate scales with p), psi
  // reduced to [-pi, pi] (the equations are 2 pi periodic in psi). p is multiplied by 1/|p|
  // where renormalise_quaternion() (the plain state's) divides by |p|: the two differ in the
  // last bit, and dividing here would change 70 of tests/record_outputs.sh's 262 runs (every
  // dopri5 run of a principal-axes body; by up to 2e-9 rad on the horizontal gyroscope's fast
  // phase, within its tolerance), so this set keeps its own rounding.
  static double project(State& x, State& dxdt) {
    const double norm = std::sqrt(x[kPw] * x[kPw] + x[kPx] * x[kPx] + x[kPy] * x[kPy] + x[kPz] * x[kPz]);
    const double inv = 1.0 / norm;
    for (int i = kPw; i <= kPz; ++i) {
      x[i] *= inv;
      dxdt[i] *= inv;
    }
    constexpr double kTwoPi = 6.283185307179586;
    if (std::abs(x[kPsi]) > 3.141592653589793) x[kPsi] -= kTwoPi * std::nearbyint(x[kPsi] / kTwoPi);
    return norm;
  }

  static State state_of(const RigidBodyState& rb0) { return to_state<State>(rb0); }
  static Scales scales(const Body& body, const RigidBodyState&, const State& x0) {
    return scales_of(body, to_rigid_body(x0));
  }
  static ConservedQuantities initial(const Body& body, const RigidBodyState&, const State& x0) {
    return conserved(body, x0);
  }
  static ConservedQuantities conserved(const Body& body, const State& x) {
    return conserved_of_state(body, x, Symmetric);
  }
  // (A - B) w1 w2 in the state x (N m): the gyroscopic torque on the spin.
  static double gyroscopic(const Body& body, const State& x) {
    if constexpr (Symmetric) return 0.0;
    const RigidBodyState rb = to_rigid_body(x);
    return (body.A - body.B) * rb.omega.x() * rb.omega.y();
  }
};

template <bool Symmetric, bool Damped = false>
using Integrator = Dopri5Driver<SpinFactoredVariables<Symmetric, Damped>>;

template <bool Symmetric, bool Damped>
void simulate(const Body& body, const RigidBodyState& rb0, const SampleStream& samples,
              const Tolerances& options, NonlinearSummary* summary) {
  using State = StateOf<Damped>;
  const double horizon = samples.horizon();
  Integrator<Symmetric, Damped> integrator(body, rb0, horizon, options, summary);
  // Angles from p itself (k' = R (w x e3) as in angles_of()), E, L_zeta, C w3 from the body.
  write_samples(integrator, body, rb0, conserved_quantities(body, rb0), Damped, samples,
                [&body](const State& x) {
                  SampleValues v{angles_of(x), to_rigid_body(x), {}, {}};
                  v.conserved = conserved_quantities(body, v.body);
                  if constexpr (Damped) v.taken = {x[kWork], x[kVerticalLoss], x[kAxialLoss]};
                  return v;
                });
}

template <bool Symmetric, bool Damped>
TiltExtremes scan_tilt(const Body& body, const RigidBodyState& rb0, double horizon, double stop_above,
                       const Tolerances& options, NonlinearSummary* summary, const Progress& progress) {
  using State = StateOf<Damped>;
  const State x0 = to_state<State>(rb0);
  if (summary) *summary = NonlinearSummary{};
  const TiltRecord start = start_tilt_scan(tilt_of(x0), x0[kW3], stop_above);
  if (start.e.exceeded || horizon == 0.0) return start.e;

  Integrator<Symmetric, Damped> integrator(body, rb0, horizon, options, summary);
  auto tilt = [](const State& x) { return tilt_of(x); };
  auto rate = [](const State& x) { return tilt_cos_rate(x); };
  return scan_tilt_extremes(integrator, horizon, start, DenseOutputEvents<State, decltype(tilt), decltype(rate)>(x0, tilt, rate),
                            [](const State& x) { return x[kW3]; }, progress);
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------

bool Tolerances::IsValid(std::string* why) const {
  return is_valid(first_violation(*this), why);
}

void validate(const Tolerances& options) { throw_if_invalid(first_violation(options)); }

std::string NonlinearSummary::BriefReport() const {
  return fmt::format("nonlinear: {} steps ({} rejected), {} evaluations, t = {:.6g} s, {}", steps,
                     rejected_steps, rhs_evaluations, final_time, drift_report(*this));
}

ConservedQuantities conserved_quantities(const Body& body, const RigidBodyState& x) {
  const Eigen::Vector3d gamma = x.attitude.row(2).transpose();  // R^T e_zeta
  return conserved_from(body, x.omega.x(), x.omega.y(), x.omega.z(), gamma.x(), gamma.y(), gamma.z());
}

Trajectory simulate_nonlinear(const Body& body, const InitialState& initial,
                              const std::vector<double>& times, const Tolerances& options,
                              NonlinearSummary* summary, const Progress& progress) {
  return gathered(times, progress, [&](const SampleStream& samples) {
    detail::stream_nonlinear(body, initial, samples, options, summary);
  });
}

void detail::stream_nonlinear(const Body& body, const InitialState& initial, const SampleStream& samples,
                              const Tolerances& options, NonlinearSummary* summary) {
  validate(body);
  refuse_general(body, "this principal-axes integrator (simulate() and simulate_general_body() take it)");
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  // Exact equality picks the cheaper right-hand side whose transverse inertia is isotropic
  // (a body symmetric only to kSymmetryTolerance takes the general one).
  const bool damped = !body.damping.conservative();
  if (body.A == body.B) {
    if (damped) simulate<true, true>(body, rb0, samples, options, summary);
    else simulate<true, false>(body, rb0, samples, options, summary);
  } else {
    if (damped) simulate<false, true>(body, rb0, samples, options, summary);
    else simulate<false, false>(body, rb0, samples, options, summary);
  }
}

TiltExtremes tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                           double stop_above, const Tolerances& options,
                           NonlinearSummary* summary, const Progress& progress) {
  validate(body);
  refuse_general(body, "the tilt scan (sweep, lifetime, the wander)");
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0))
    throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  const bool damped = !body.damping.conservative();
  if (body.A == body.B)
    return damped ? scan_tilt<true, true>(body, rb0, horizon, stop_above, options, summary, progress)
                  : scan_tilt<true, false>(body, rb0, horizon, stop_above, options, summary, progress);
  return damped ? scan_tilt<false, true>(body, rb0, horizon, stop_above, options, summary, progress)
                : scan_tilt<false, false>(body, rb0, horizon, stop_above, options, summary, progress);
}

double max_tilt(const Body& body, const InitialState& initial, double horizon, double stop_above,
                const Tolerances& options) {
  const TiltExtremes e = tilt_extremes(body, initial, horizon, stop_above, options);
  // Past the threshold the tilt was seen above it: the largest tilt is beyond stop_above, even
  // where the crossing's own tilt rounds to it.
  return e.exceeded ? std::max(e.max_tilt, std::nextafter(stop_above, HUGE_VAL)) : e.max_tilt;
}

}  // namespace heavytop

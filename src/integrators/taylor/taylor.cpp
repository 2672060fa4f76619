// The Taylor integrator's entry points: its samples (the one sample loop over the stepper of
// integrator.hpp), its tilt scan on the series, and the choice of the set of variables.
// series.hpp: the series arithmetic; variables.hpp: the sets; recurrence.hpp: their
// coefficients; integrator.hpp: the stepper.
#include "heavytop/taylor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "heavytop/general_body.hpp"
#include "heavytop/rigid_body.hpp"

#include "integrators/integration.hpp"
#include "integrators/sampling.hpp"
#include "integrators/streams.hpp"
#include "integrators/taylor/integrator.hpp"

namespace heavytop {

using namespace detail;

namespace {

using namespace detail::taylor;

template <class System>
void simulate(const Body& body, const RigidBodyState& rb0, const SampleStream& samples,
              const Tolerances& options, TaylorSummary* summary) {
  using State = typename TaylorIntegrator<System>::State;
  const double horizon = samples.horizon();
  TaylorIntegrator<System> integrator(body, System(body), System::state_of(rb0), horizon, options, summary);
  write_samples(integrator, body, rb0, System::conserved(body, rb0), System::kDamped, samples, options.progress,
                [&body](const State& x) {
                  const RigidBodyState rb = System::rigid_body(x);
                  SampleValues v = sample_of(rb, System::conserved(body, rb));
                  if constexpr (System::kDamped) v.taken = {x[System::kWork], x[System::kVerticalLoss], x[System::kAxialLoss]};
                  return v;
                });
}

// ---- Events on the series ---------------------------------------------------------------------------

// Tilt acos(k_zeta) of a state, as atan2(|k_horizontal|, k_zeta) (accurate near 0).
template <class State>
double tilt_of(const State& x) {
  const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
  const double g1 = 2.0 * (qx * qz - qw * qy), g2 = 2.0 * (qy * qz + qw * qx);
  return std::atan2(std::hypot(g1, g2), qw * qw - qx * qx - qy * qy + qz * qz);
}

// A root of the polynomial s on [a, b] where s(a), s(b) have opposite signs, to ~1e-15 of
// the step (TOMS 748; the polynomial is cheap, so it is solved to rounding).
double polynomial_root(const Coefficients& s, int p, double a, double b, double fa, double fb, double h) {
  return root([&](double tau) { return horner(s, p, tau); }, a, b, fa, fb, h);
}

template <class System>
TiltExtremes scan_tilt(const Body& body, const RigidBodyState& rb0, double horizon, double stop_above,
                       const Tolerances& options, TaylorSummary* summary) {
  using Integrator = TaylorIntegrator<System>;
  TiltExtremes e;
  if (summary) *summary = TaylorSummary{};
  const auto x0 = System::state_of(rb0);
  const double tilt0 = tilt_of(x0);
  e.min_tilt = e.max_tilt = tilt0;
  e.exceeded = tilt0 > stop_above;
  if (e.exceeded || horizon == 0.0) return e;

  Integrator integrator(body, System(body), x0, horizon, options, summary);
  const int p = integrator.order();
  const bool threshold = stop_above < 3.141592653589793;  // a tilt above pi cannot be reached
  const double cos_stop = std::cos(stop_above);
  auto note = [&](double t, double tilt) {
    if (tilt < e.min_tilt) e.min_tilt = tilt, e.t_min = t;
    if (tilt > e.max_tilt) e.max_tilt = tilt, e.t_max = t;
  };

  Coefficients rate{}, kz{};
  Gamma g;
  typename Integrator::State y;
  constexpr int kPieces = 8;
  while (integrator.time() < horizon) {
    integrator.step();
    const double t0 = integrator.previous_time(), h = integrator.time() - t0;
    const auto& x = integrator.series();
    // The series of d(k_zeta)/dt = gamma_1 u_2 - gamma_2 u_1 and of k_zeta = qw^2 - qx^2 - qy^2 + qz^2,
    // to order p (gamma to order p first: the recurrence stopped at p - 1).
    g = integrator.gamma();
    std::array<Coefficients, 4> q;
    for (int i = 0; i < 4; ++i) q[i] = series_of(x, i, p);
    const Coefficients u1 = series_of(x, System::kU1, p), u2 = series_of(x, System::kU2, p);
    g.g1[p] = 2.0 * (cauchy(q[1], q[3], p) - cauchy(q[0], q[2], p));
    g.g2[p] = 2.0 * (cauchy(q[2], q[3], p) + cauchy(q[0], q[1], p));
    for (int n = 0; n <= p; ++n) {
      rate[n] = cauchy(g.g1, u2, n) - cauchy(g.g2, u1, n);
      kz[n] = cauchy(q[0], q[0], n) - cauchy(q[1], q[1], n) - cauchy(q[2], q[2], n) + cauchy(q[3], q[3], n);
    }
    kz[0] -= cos_stop;  // k_zeta - cos(stop): negative once the tilt passes stop_above

    double a = 0.0, ra = horner(rate, p, 0.0), ka = horner(kz, p, 0.0);
    for (int k = 1; k <= kPieces; ++k) {
      const double b = h * k / kPieces, rb = horner(rate, p, b), kb = horner(kz, p, b);
      double crossing = -1.0;
      if (threshold && ka >= 0.0 && kb < 0.0) crossing = polynomial_root(kz, p, a, b, ka, kb, h);
      if ((ra < 0.0 && rb > 0.0) || (ra > 0.0 && rb < 0.0)) {
        const double extremum = polynomial_root(rate, p, a, b, ra, rb, h);
        if (crossing < 0.0 || extremum < crossing) {
          integrator.interpolate(t0 + extremum, y);
          note(t0 + extremum, tilt_of(y));
        }
      }
      if (crossing >= 0.0) {
        integrator.interpolate(t0 + crossing, y);
        note(t0 + crossing, tilt_of(y));
        e.exceeded = true;
        e.t_end = t0 + crossing;
        if constexpr (System::kDamped) e.spin_at_end = y[6];
        return e;
      }
      a = b, ra = rb, ka = kb;
    }
    integrator.interpolate(integrator.time(), y);
    note(integrator.time(), tilt_of(y));
  }
  e.t_end = horizon;
  if constexpr (System::kDamped) e.spin_at_end = y[6];
  return e;
}

// The set of variables for a body; a damped general body is refused (SPEC section 11 is
// integrated undamped), naming its damping key.
enum class Set { SpinFactored, Plain, General, DampedSpinFactored, DampedPlain };
Set taylor_set(const Body& body) {
  const bool damped = !body.damping.conservative();
  switch (taylor_variables(body)) {
    case TaylorVariables::General: refuse_damped_general(body); return Set::General;
    case TaylorVariables::SpinFactored: return damped ? Set::DampedSpinFactored : Set::SpinFactored;
    case TaylorVariables::Plain: return damped ? Set::DampedPlain : Set::Plain;
  }
  return Set::Plain;
}

}  // namespace

// ---- Public API -------------------------------------------------------------------------------------

TaylorVariables taylor_variables(const Body& body) {
  if (is_general(body)) return TaylorVariables::General;
  return body.A == body.B ? TaylorVariables::SpinFactored : TaylorVariables::Plain;
}

int taylor_order(const Tolerances& options, TaylorVariables variables) {
  // Jorba & Zou's ceil(-ln(eps)/2 + 1) is optimal for a series with a fixed radius of
  // convergence; here the coefficients fall faster (the steps grew about as the order did), and
  // at equal error on five bodies (docs/integrators.md, "Order and step") higher orders were
  // 1.4-1.6x faster for the spin-factored variables (twice Jorba-Zou's -ln(eps)/2) and up to
  // 1.45x for the plain ones (1.5 times it; neutral to 0.8x at some levels).
  const double eps = std::min(options.rtol, options.atol);
  const double factor = variables == TaylorVariables::SpinFactored ? 1.0 : 0.75;
  const int p = static_cast<int>(std::ceil(-factor * std::log(eps) + 1.0));
  return std::clamp(p, 2, kTaylorMaxOrder);
}

void detail::stream_taylor(const Body& body, const InitialState& initial, const SampleStream& samples,
                           const Tolerances& options, TaylorSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  switch (taylor_set(body)) {
    case Set::SpinFactored: return simulate<SpinFactored>(body, rb0, samples, options, summary);
    case Set::Plain: return simulate<Plain>(body, rb0, samples, options, summary);
    case Set::General: return simulate<General>(body, rb0, samples, options, summary);
    case Set::DampedSpinFactored: return simulate<DampedSpinFactored>(body, rb0, samples, options, summary);
    case Set::DampedPlain: return simulate<DampedPlain>(body, rb0, samples, options, summary);
  }
}

Trajectory simulate_taylor(const Body& body, const InitialState& initial, const std::vector<double>& times,
                           const Tolerances& options, TaylorSummary* summary) {
  return gathered(times, [&](const SampleStream& samples) {
    detail::stream_taylor(body, initial, samples, options, summary);
  });
}

TiltExtremes taylor_tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                                  double stop_above, const Tolerances& options, TaylorSummary* summary) {
  validate(body);
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  switch (taylor_set(body)) {
    case Set::SpinFactored: return scan_tilt<SpinFactored>(body, rb0, horizon, stop_above, options, summary);
    case Set::Plain: return scan_tilt<Plain>(body, rb0, horizon, stop_above, options, summary);
    case Set::General: return scan_tilt<General>(body, rb0, horizon, stop_above, options, summary);
    case Set::DampedSpinFactored: return scan_tilt<DampedSpinFactored>(body, rb0, horizon, stop_above, options, summary);
    case Set::DampedPlain: return scan_tilt<DampedPlain>(body, rb0, horizon, stop_above, options, summary);
  }
  return {};
}

}  // namespace heavytop

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
#include "heavytop/frames.hpp"
#include "heavytop/rigid_body.hpp"

#include "integrators/integration.hpp"
#include "integrators/sampling.hpp"
#include "integrators/streams.hpp"
#include "integrators/taylor/integrator.hpp"
#include "integrators/tilt_scan.hpp"

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
  write_samples(integrator, body, rb0, System::conserved(body, rb0), System::kDamped, samples,
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
  return tilt_of_axis(g1, g2, qw * qw - qx * qx - qy * qy + qz * qz);  // |(g1, g2)| = sin(tilt), as |(k_xi, k_eta)|
}

// A step's events on its own series, the Taylor integrator's capability in the one tilt scan
// (tilt_scan.hpp): the series of d(k_zeta)/dt = gamma_1 u_2 - gamma_2 u_1 and of
// k_zeta - cos(stop_above) to order p (gamma to order p first: the recurrence stopped at p - 1),
// k_zeta = qw^2 - qx^2 - qy^2 + qz^2 taken as 1 - 2 (qx^2 + qy^2): |q| = 1 at the step's start,
// and every set's attitude rate q (x) (0, w) / 2 keeps |q|^2, so its series is 1 order by order
// (to rounding); two squares instead of four. Their sign changes in 8 pieces of the step, each
// root by Newton in its bracket (polynomial_root). An extremum before the crossing is noted,
// then the crossing itself, which ends the scan; without one, the step's end.
template <class System>
class SeriesEvents {
 public:
  using Integrator = TaylorIntegrator<System>;

  explicit SeriesEvents(double stop_above)
      : threshold_(stop_above < 3.141592653589793),  // a tilt above pi cannot be reached
        one_minus_cos_stop_(2.0 * std::sin(0.5 * stop_above) * std::sin(0.5 * stop_above)) {}

  double operator()(Integrator& integrator, double t0, double /*t1*/, TiltRecord& record) {
    const int p = integrator.order();
    const double h = integrator.time() - t0;
    const auto& x = integrator.series();
    g_ = integrator.gamma();
    std::array<Coefficients, 4> q;
    for (int i = 0; i < 4; ++i) q[i] = series_of(x, i, p);
    const Coefficients u1 = series_of(x, System::kU1, p), u2 = series_of(x, System::kU2, p);
    g_.g1[p] = 2.0 * (cauchy(q[1], q[3], p) - cauchy(q[0], q[2], p));
    g_.g2[p] = 2.0 * (cauchy(q[2], q[3], p) + cauchy(q[0], q[1], p));
    for (int n = 0; n <= p; ++n) {
      rate_[n] = cauchy(g_.g1, u2, n) - cauchy(g_.g2, u1, n);
      kz_[n] = -2.0 * sum_of_squares(q[1], q[2], n);
    }
    kz_[0] += one_minus_cos_stop_;  // k_zeta - cos(stop): negative once the tilt passes stop_above

    constexpr int kPieces = 8;
    double a = 0.0, ra = horner(rate_, p, 0.0), ka = horner(kz_, p, 0.0);
    for (int k = 1; k <= kPieces; ++k) {
      const double b = h * k / kPieces, rb = horner(rate_, p, b), kb = horner(kz_, p, b);
      double crossing = -1.0;
      if (threshold_ && ka >= 0.0 && kb < 0.0) crossing = polynomial_root(kz_.data(), p, a, b, ka, kb, h);
      if ((ra < 0.0 && rb > 0.0) || (ra > 0.0 && rb < 0.0)) {
        const double extremum = polynomial_root(rate_.data(), p, a, b, ra, rb, h);
        if (crossing < 0.0 || extremum < crossing) {
          integrator.interpolate(t0 + extremum, y_);
          record.note(t0 + extremum, tilt_of(y_));
        }
      }
      if (crossing >= 0.0) {
        integrator.interpolate(t0 + crossing, y_);
        record.note(t0 + crossing, tilt_of(y_));
        return t0 + crossing;
      }
      a = b, ra = rb, ka = kb;
    }
    integrator.interpolate(integrator.time(), y_);
    record.note(integrator.time(), tilt_of(y_));
    return -1.0;
  }

 private:
  bool threshold_;
  double one_minus_cos_stop_;  // 2 sin^2(stop / 2): no cancellation at a small stop_above
  Coefficients rate_{}, kz_{};
  Gamma g_;
  typename Integrator::State y_;
};

template <class System>
TiltExtremes scan_tilt(const Body& body, const RigidBodyState& rb0, double horizon, double stop_above,
                       const Tolerances& options, TaylorSummary* summary, const Progress& progress) {
  if (summary) *summary = TaylorSummary{};
  const auto x0 = System::state_of(rb0);
  const TiltRecord start = start_tilt_scan(tilt_of(x0), x0[6], stop_above);
  if (start.e.exceeded || horizon == 0.0) return start.e;

  TaylorIntegrator<System> integrator(body, System(body), x0, horizon, options, summary);
  // spin_at_end: w.k = w3, slot 6 of every set (constant in the conservative symmetric one).
  return scan_tilt_extremes(integrator, horizon, start, SeriesEvents<System>(stop_above),
                            [](const auto& x) { return x[6]; }, progress);
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
                           const Tolerances& options, TaylorSummary* summary, const Progress& progress) {
  return gathered(times, progress, [&](const SampleStream& samples) {
    detail::stream_taylor(body, initial, samples, options, summary);
  });
}

TiltExtremes taylor_tilt_extremes(const Body& body, const InitialState& initial, double horizon,
                                  double stop_above, const Tolerances& options, TaylorSummary* summary,
                                  const Progress& progress) {
  validate(body);
  validate(initial);
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
  const RigidBodyState rb0 = initial_rigid_body_state(initial);
  switch (taylor_set(body)) {
    case Set::SpinFactored: return scan_tilt<SpinFactored>(body, rb0, horizon, stop_above, options, summary, progress);
    case Set::Plain: return scan_tilt<Plain>(body, rb0, horizon, stop_above, options, summary, progress);
    case Set::General: return scan_tilt<General>(body, rb0, horizon, stop_above, options, summary, progress);
    case Set::DampedSpinFactored: return scan_tilt<DampedSpinFactored>(body, rb0, horizon, stop_above, options, summary, progress);
    case Set::DampedPlain: return scan_tilt<DampedPlain>(body, rb0, horizon, stop_above, options, summary, progress);
  }
  return {};
}

}  // namespace heavytop

#include "heavytop/lifetime.hpp"

#include <cmath>
#include <numbers>

#include "heavytop/linear_models.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/stability.hpp"

#include "integrators/integration.hpp"

namespace heavytop {
namespace {

detail::Violation first_violation(const LifetimeOptions& o) {
  if (o.horizon && !(std::isfinite(*o.horizon) && *o.horizon > 0.0))
    return std::pair{"horizon", "must be a finite number > 0"};
  if (!(o.max_tilt > 0.0 && o.max_tilt <= std::numbers::pi)) return std::pair{"max_tilt", "must be in (0, pi]"};
  return std::nullopt;
}

}  // namespace

bool LifetimeOptions::IsValid(std::string* why) const {
  return detail::is_valid(first_violation(*this), why) && integrator.IsValid(why);
}

void validate(const LifetimeOptions& options) {
  detail::throw_if_invalid(first_violation(options));
  validate(options.integrator);
}

Lifetime spin_decay(const Body& body, const InitialState& initial, const LifetimeOptions& options) {
  validate(body);
  refuse_general(body, "lifetime");
  validate(initial);
  validate(options);

  Lifetime life;
  Body conservative = body;
  conservative.damping = {};
  life.critical_spin = critical_spin(stable_spin_intervals(linear_model(LinearModelKind::Linearized, conservative)));
  const Damping& d = body.damping;
  life.law_exact = is_symmetric(body);
  if (life.critical_spin && *life.critical_spin > 0.0 && !d.driven) {
    if (std::abs(initial.spin) <= *life.critical_spin) life.time_to_critical = 0.0;
    else life.time_to_critical = SpinDecayLaw{body.C, d.axial, d.friction}.time_to(initial.spin, *life.critical_spin);
  }
  // A horizon given beyond what a double resolves is refused before the run, as simulate's
  // --t-end is (1e300 s ran until --max-steps gave up).
  if (options.horizon) validate_horizon(body, initial, *options.horizon, "horizon");
  life.max_tilt = fall_tilt(tilt(initial.theta0, initial.phi0), options.max_tilt);
  life.limit_given = options.max_tilt;
  life.horizon = options.horizon ? *options.horizon
                 : life.time_to_critical && *life.time_to_critical > 0.0 ? 10.0 * *life.time_to_critical
                                                                          : kDefaultLifetimeHorizon;
  // The default horizon too: at 1.8e19 rad/s its 1000 s ran for minutes towards max_steps.
  if (const double longest = longest_meaningful_time(body, initial); !options.horizon && life.horizon > longest)
    throw InvalidInput("horizon", fmt::format("the default {:.3g} s is too long at this motion: beyond {:.3g} s a double "
                                              "no longer resolves its phase to 1e-3 rad (give a shorter horizon)",
                                              life.horizon, longest));
  return life;
}

Lifetime lifetime(const Body& body, const InitialState& initial, const LifetimeOptions& options,
                  const Progress& progress) {
  Lifetime life = spin_decay(body, initial, options);
  const TiltExtremes e = tilt_extremes(options.method, body, initial, life.horizon, life.max_tilt, options.integrator,
                                        &life.summary, progress);
  life.largest_tilt = e.max_tilt;
  if (e.exceeded) {
    life.fall_time = e.t_end;
    life.fall_spin = e.spin_at_end;
    life.largest_tilt = life.max_tilt;
  }
  return life;
}

}  // namespace heavytop

#include "heavytop/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "heavytop/frames.hpp"
#include "heavytop/dop853.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/taylor.hpp"

#include "integrators/integration.hpp"
#include "integrators/streams.hpp"

namespace heavytop {
namespace {

constexpr std::array<std::string_view, 5> kModelNames = {"first-order", "body-fixed", "linearized", "nonlinear",
                                                         "lagrange-exact"};

/// The closed forms sample by sample: each sample is computed on its own, so a piece of the
/// times at a time gives the same numbers.
template <class Evaluate>
void closed_form_in_chunks(const detail::SampleStream& samples, const Evaluate& evaluate) {
  std::vector<double> times;
  for (std::size_t begin = 0; begin < samples.count; begin += samples.chunk) {
    const std::size_t end = std::min(samples.count, begin + std::min(samples.chunk, samples.count - begin));
    times.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i) times[i - begin] = samples.time(i);
    Trajectory part = evaluate(times);
    samples.flush(part);
    if (samples.progress) samples.progress(times.back());
    if (samples.chunk == static_cast<std::size_t>(-1)) break;
  }
}

/// Throws std::runtime_error naming the column and the time of the first value of `part`
/// that is not finite.
void check_finite(Model model, const Trajectory& part) {
  for (std::size_t c = 0; c < kTrajectoryColumns.size() + part.extra.size(); ++c) {
    const auto& column = part.column(c);
    // First whether all are finite, in integer operations the compiler vectorises (SSE2 has
    // them all): a value is not finite where its exponent bits are all ones, and only then does
    // adding 1 to that field carry into the sign bit. Then, only if one is not, which is first.
    constexpr std::uint64_t kExponent = 0x7ff0000000000000, kExponentOne = 0x0010000000000000;
    std::uint64_t carries = 0;
    for (const double v : column) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);  // std::bit_cast, which the web build's library lacks
      carries |= (bits & kExponent) + kExponentOne;
    }
    if (!(carries >> 63)) continue;
    for (std::size_t i = 0; i < column.size(); ++i)
      if (!std::isfinite(column[i]))
        throw std::runtime_error(fmt::format(
            "{}: {} is not a finite number at t = {:.6g} s: the motion has grown beyond the range of a "
            "double{}", name(model), part.column_names()[c], part.t[i],
            linear_kind(model) ? " (the linear model is unstable here; see `stability`)" : ""));
  }
}

}  // namespace

std::string_view name(Model model) { return kModelNames[static_cast<std::size_t>(model)]; }

std::optional<Model> model_from_name(std::string_view name) {
  for (Model m : kModels)
    if (heavytop::name(m) == name) return m;
  return std::nullopt;
}

std::string model_names(std::string_view separator) {
  std::string names;
  for (Model m : kModels) names += fmt::format("{}{}", names.empty() ? "" : separator, name(m));
  return names;
}

std::optional<LinearModelKind> linear_kind(Model model) {
  switch (model) {
    case Model::FirstOrder: return LinearModelKind::FirstOrder;
    case Model::BodyFixed: return LinearModelKind::BodyFixed;
    case Model::Linearized: return LinearModelKind::Linearized;
    default: return std::nullopt;
  }
}

Model model_of(LinearModelKind kind) {
  switch (kind) {
    case LinearModelKind::FirstOrder: return Model::FirstOrder;
    case LinearModelKind::BodyFixed: return Model::BodyFixed;
    case LinearModelKind::Linearized: break;
  }
  return Model::Linearized;
}

std::string_view name(Integrator integrator) {
  switch (integrator) {
    case Integrator::Dopri5: return "dopri5";
    case Integrator::Splitting: return "splitting";
    case Integrator::Taylor: return "taylor";
    case Integrator::Dop853: return "dop853";
    case Integrator::Rosenbrock4: return "rosenbrock4";
    case Integrator::Auto: break;
  }
  return "auto";
}

std::optional<Integrator> integrator_from_name(std::string_view name) {
  if (name == "adaptive") return Integrator::Dopri5;
  for (Integrator i : kIntegrators)
    if (name == heavytop::name(i)) return i;
  return std::nullopt;
}

bool supports(Integrator integrator, IntegratorUse use) {
  for (const IntegratorSupport& row : kIntegratorSupport)
    if (row.integrator == integrator) {
      switch (use) {
        case IntegratorUse::Pivot: return row.pivot;
        case IntegratorUse::Damped: return row.damped;
        case IntegratorUse::General: return row.general;
        case IntegratorUse::Judging: return row.judging;
        case IntegratorUse::Table: return row.table;
      }
    }
  return false;
}

std::string integrator_names(std::string_view separator, std::string_view last,
                             std::initializer_list<IntegratorUse> uses) {
  std::vector<std::string_view> names;
  for (Integrator i : kIntegrators)
    if (std::all_of(uses.begin(), uses.end(), [i](IntegratorUse use) { return supports(i, use); }))
      names.push_back(name(i));
  std::string joined;
  for (std::size_t k = 0; k < names.size(); ++k)
    joined += fmt::format("{}{}", k == 0 ? "" : k + 1 == names.size() ? last : separator, names[k]);
  return joined;
}

std::optional<std::string> integrator_refusal(Integrator integrator, const Body& body, bool on_table, bool judging) {
  using U = IntegratorUse;
  const std::string_view who = name(integrator);
  // The names that would do, for the run as asked.
  auto instead = [&](std::initializer_list<U> uses) { return integrator_names(", ", " or ", uses); };
  const U place = on_table ? U::Table : U::Pivot;
  if (on_table && !supports(integrator, U::Table))
    return fmt::format("on a table (SPEC section 16) the body is integrated by {}", instead({U::Table}));
  if (!on_table && !supports(integrator, U::Pivot))
    return fmt::format("{} integrates a body on a table (SPEC section 16): on a pivot use {}", who, instead({U::Pivot}));
  if (is_general(body) && !supports(integrator, U::General))
    return fmt::format("{} integrates the ordinary body only: the general body (SPEC section 11) is integrated by {}",
                       who, instead({place, U::General}));
  if (!body.damping.conservative() && !supports(integrator, U::Damped))
    return fmt::format("{} integrates the conservative body only: with damping, friction or a motor use {}", who,
                       instead({place, U::Damped}));
  if (judging && !supports(integrator, U::Judging))
    return fmt::format("must be {} ({} has no error control to judge a run by)", instead({place, U::Judging}), who);
  return std::nullopt;
}

void check_integrator(Integrator integrator, const Body& body, bool on_table, bool judging) {
  if (auto why = integrator_refusal(integrator, body, on_table, judging)) throw InvalidInput("integrator", *why);
}

Integrator choose_integrator(const Body& body, const Tolerances& tolerances) {
  // Measured at equal error (docs/integrators.md, "Choosing"): the Taylor integrator (with
  // taylor_order()'s rule) is the fastest at every error level from 1e-3 down on both benchmark
  // bodies; only for a symmetric body at tolerances above 1e-2 (errors of ~5e-3 and more) is
  // dopri5 as fast or faster, its steps there being cheaper than a Taylor step whose length
  // the nutation bounds.
  // A damped body (SPEC section 6) follows the same rule: at equal error the Taylor integrator
  // was 1.2, 1.9 and 6.2 times faster than dopri5 on the damped toy top at 1e-4, 1e-6, 1e-9
  // (dopri5 does not reach 1e-12), 2.0, 3.1, 12 and 44 times on the asymmetric body with a
  // friction stop at 1e-4 ... 1e-12 (bench_integrators, docs/integrators.md; Jorba-Zou's orders).
  // The general body (SPEC section 11) takes the Taylor integrator at every tolerance: over 10 s
  // it took 1.1-1.5x less time than dopri5 at 1e-6, 2.4-4.7x at 1e-9, 6.4-13x at 1e-12, with
  // errors 1-40 times smaller (docs/integrators.md); damped, it goes to dopri5, which refuses it.
  if (is_general(body) && !body.damping.conservative()) return Integrator::Dopri5;
  const double eps = std::min(tolerances.rtol, tolerances.atol);
  return eps > kAutoTaylorBelow && body.A == body.B && !is_general(body) ? Integrator::Dopri5 : Integrator::Taylor;
}

Integrator resolve_integrator(Integrator asked, const Body& body, const Tolerances& tolerances) {
  return asked == Integrator::Auto ? choose_integrator(body, tolerances) : asked;
}

TiltExtremes tilt_extremes(Integrator integrator, const Body& body, const InitialState& initial, double horizon,
                           double stop_above, const Tolerances& tolerances, NonlinearSummary* summary,
                           const Progress& progress) {
  check_integrator(integrator, body, false, true);
  switch (resolve_integrator(integrator, body, tolerances)) {
    case Integrator::Taylor: {
      TaylorSummary taylor;
      const TiltExtremes e =
          taylor_tilt_extremes(body, initial, horizon, stop_above, tolerances, summary ? &taylor : nullptr, progress);
      if (summary) *summary = taylor.work;
      return e;
    }
    case Integrator::Dop853: return dop853_tilt_extremes(body, initial, horizon, stop_above, tolerances, progress);
    default: return tilt_extremes(body, initial, horizon, stop_above, tolerances, summary, progress);
  }
}

void validate(const SimulateOptions& options) {
  validate(options.adaptive);
  if (options.integrator == Integrator::Splitting) validate(options.splitting);
}

bool SimulateOptions::IsValid(std::string* why) const {
  if (!adaptive.IsValid(why)) return false;
  return integrator != Integrator::Splitting || splitting.IsValid(why);
}

std::string SimulationSummary::BriefReport() const {
  std::string line = fmt::format("{} ({}): {} samples", name(model), solver, samples);
  if (steps) line += fmt::format(", {} steps ({} rejected), {} evaluations", steps, rejected_steps, rhs_evaluations);
  if (drifts)
    line += fmt::format(", relative drift: energy {:.2e}, vertical momentum {:.2e}", drifts->max_relative_energy_drift,
                        drifts->max_relative_vertical_momentum_drift);
  if (!ok()) line += ": FAILED: " + message;
  return line;
}

double longest_meaningful_time(const Body& body, const InitialState& initial) {
  const double gravity_rate = 1.0 / gravity_time(body);
  const double rate = std::max({std::abs(initial.spin), std::abs(initial.theta_rate0), std::abs(initial.phi_rate0),
                                std::isfinite(gravity_rate) ? gravity_rate : 0.0});
  return rate > 0.0 ? 1e-3 / (std::numeric_limits<double>::epsilon() * rate) : std::numeric_limits<double>::infinity();
}

void validate_horizon(const Body& body, const InitialState& initial, double horizon, const std::string& key) {
  if (const double longest = longest_meaningful_time(body, initial); horizon > longest)
    throw InvalidInput(key, fmt::format("too long: beyond {:.3g} s a double no longer resolves the phase of this "
                                        "motion to 1e-3 rad", longest));
}

void validate_damping(Model model, const Body& body, const SimulateOptions& options) {
  const Damping& d = body.damping;
  if (d.conservative()) return;
  if (model == Model::LagrangeExact)
    throw InvalidInput("model", "lagrange-exact is the conservative symmetric top: with damping use nonlinear");
  if (model == Model::Nonlinear) check_integrator(options.integrator, body, false, false);
  if (linear_kind(model) && d.transverse > 0.0 && options.method == LinearMethod::Analytic)
    throw InvalidInput("method", "the closed form covers the undamped linear models: with transverse damping "
                                 "use numeric (the matrix exponential)");
}

namespace {

/// Everything simulate() and simulate_streaming() do, over any stream of samples.
SimulationSummary run(Model model, const Body& body, const InitialState& initial, const detail::SampleStream& stream,
                      const SimulateOptions& options, const char* time_key, NonlinearSummary* adaptive_out) {
  validate(body);
  validate(initial);
  validate(options);
  if (model == Model::LagrangeExact) validate_symmetric(body);
  validate_damping(model, body, options);
  const bool general = is_general(body);
  if (general) {  // SPEC section 11: the nonlinear model by dopri5 or the Taylor integrator only
    if (model != Model::Nonlinear) refuse_general(body, fmt::format("the {} model", name(model)).c_str());
  }
  if (model == Model::Nonlinear) check_integrator(options.integrator, body, false, false);
  validate_horizon(body, initial, stream.count ? stream.time(stream.count - 1) : 0.0, time_key);

  SimulationSummary s;
  s.model = model;
  // Every piece is checked before it is handed on: a failure never passes a NaN along.
  detail::SampleStream samples = stream;
  // Here, once for every model and integrator, the people's columns tilt and azimuth follow
  // SPEC's five: the nonlinear model's writer puts them there from the axis k itself; for the
  // closed forms they are put in from theta and phi, and taken out again after the piece is
  // handed on (the closed forms reuse the piece).
  samples.axis_direction = true;
  ContinuousAzimuth azimuth;
  samples.flush = [&](Trajectory& part) {
    check_finite(model, part);
    s.samples += part.size();
    const bool written = !part.extra.empty() && part.extra.front().first == kAxisDirectionColumns[0];
    if (!written) insert_axis_direction_columns(part, azimuth);
    stream.flush(part);
    // (a sink that took the piece by move left it empty)
    if (!written && part.extra.size() >= kAxisDirectionColumns.size() &&
        part.extra.front().first == kAxisDirectionColumns[0])
      part.extra.erase(part.extra.begin(), part.extra.begin() + kAxisDirectionColumns.size());
  };
  try {
    if (const auto kind = linear_kind(model)) {
      s.solver = options.method == LinearMethod::Analytic ? "closed form" : "matrix exponential";
      if (body.damping.axial > 0.0 || body.damping.friction > 0.0 || body.damping.driven)
        s.warnings.push_back("the linear models hold the spin constant: only the transverse damping enters them "
                             "(the axial damping, friction and motor act in nonlinear)");
      const LinearModel linear = linear_model(*kind, body);
      closed_form_in_chunks(samples, [&](const std::vector<double>& t) {
        return simulate_linear(linear, initial, t, options.method);
      });
    } else if (model == Model::LagrangeExact) {
      s.solver = "elliptic functions";
      closed_form_in_chunks(samples, [&](const std::vector<double>& t) {
        return simulate_lagrange_exact(body, initial, t);
      });
    } else if (options.integrator == Integrator::Splitting) {
      s.solver = fmt::format("splitting, order {}, step {:g} s", options.splitting.order, options.splitting.step);
      SplittingSummary summary;
      detail::stream_splitting(body, initial, samples, options.splitting, &summary);
      s.steps = summary.steps + summary.partial_steps;
      s.rhs_evaluations = summary.kicks;
      s.drifts = static_cast<const Drifts&>(summary);
      if (summary.max_relative_energy_drift > kSplittingEnergyWarning)
        s.warnings.push_back(fmt::format(
            "the splitting's relative energy error reached {:.3g}, above {:g}: the step {:g} s is too large for "
            "this motion (halve it, or use the adaptive integrator)",
            summary.max_relative_energy_drift, kSplittingEnergyWarning, options.splitting.step));
    } else {
      const Tolerances& adaptive = options.adaptive;
      NonlinearSummary summary;
      const Integrator chosen = resolve_integrator(options.integrator, body, adaptive);
      if (chosen == Integrator::Taylor) {
        TaylorSummary taylor;
        detail::stream_taylor(body, initial, samples, adaptive, &taylor);
        summary = taylor.work;
        s.solver = fmt::format("Taylor, order {}, {}{}", taylor.order,
                               taylor.variables == TaylorVariables::SpinFactored ? "spin-factored variables"
                               : taylor.variables == TaylorVariables::Plain      ? "plain variables"
                                                                                 : "plain variables, general body",
                               taylor.damped ? ", damped" : "");
      } else if (general) {
        s.solver = "Dormand-Prince 5(4), general body";
        detail::stream_general(body, initial, samples, adaptive, &summary);
      } else if (chosen == Integrator::Dop853) {
        s.solver = "Dormand-Prince 8(5,3)";
        detail::stream_dop853(body, initial, samples, adaptive, &summary);
      } else {
        s.solver = "Dormand-Prince 5(4)";
        detail::stream_nonlinear(body, initial, samples, adaptive, &summary);
      }
      s.steps = summary.steps;
      s.rejected_steps = summary.rejected_steps;
      s.rhs_evaluations = summary.rhs_evaluations;
      s.drifts = static_cast<const Drifts&>(summary);
      if (adaptive_out) *adaptive_out = summary;
    }
  } catch (const std::runtime_error& e) {
    s.termination = Termination::Failure;
    s.message = e.what();
  }
  return s;
}

}  // namespace

SimulationSummary simulate_streaming(Model model, const Body& body, const InitialState& initial,
                                     const SampleGrid& grid, const SimulateOptions& options,
                                     const TrajectorySink& sink, std::size_t chunk, NonlinearSummary* adaptive,
                                     const Progress& progress) {
  if (!(std::isfinite(grid.t_end) && grid.t_end >= 0.0)) throw InvalidInput("t_end", "must be finite and >= 0");
  const detail::SampleStream stream{grid.count, [&grid](std::size_t i) { return grid.time(i); },
                                    std::max<std::size_t>(chunk, 1), [&sink](Trajectory& part) { sink(part); },
                                    progress};
  return run(model, body, initial, stream, options, "t_end", adaptive);
}

Simulation simulate(Model model, const Body& body, const InitialState& initial, const std::vector<double>& times,
                    const SimulateOptions& options, const Progress& progress) {
  detail::validate_times(times);
  Simulation result;
  NonlinearSummary adaptive;
  result.summary =
      run(model, body, initial, detail::gather(times, result.trajectory, progress), options, "times", &adaptive);
  if (model == Model::Nonlinear && options.integrator != Integrator::Splitting) result.adaptive = adaptive;
  return result;
}

}  // namespace heavytop

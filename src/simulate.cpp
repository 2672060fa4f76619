#include "heavytop/simulate.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "heavytop/lagrange_exact.hpp"

namespace heavytop {
namespace {

constexpr std::array<std::string_view, 5> kModelNames = {"first-order", "body-fixed", "linearized", "nonlinear",
                                                         "lagrange-exact"};

/// The linear models sample by sample, in chunks so that a long run reports its progress (each
/// sample is computed on its own, so chunking changes nothing).
Trajectory linear_in_chunks(const LinearModel& model, const InitialState& initial, const std::vector<double>& times,
                            LinearMethod method, const std::function<void(double)>& progress) {
  constexpr std::size_t kChunk = 1 << 16;
  if (times.size() <= kChunk || !progress) return simulate_linear(model, initial, times, method);
  Trajectory out;
  out.reserve(times.size());
  for (std::size_t begin = 0; begin < times.size(); begin += kChunk) {
    const auto first = times.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = times.begin() + static_cast<std::ptrdiff_t>(std::min(times.size(), begin + kChunk));
    out.append(simulate_linear(model, initial, std::vector<double>(first, last), method));
    progress(*(last - 1));
  }
  return out;
}

template <class Summary>
void copy_drifts(const Summary& from, SimulationSummary& to) {
  to.max_relative_energy_drift = from.max_relative_energy_drift;
  to.max_relative_vertical_momentum_drift = from.max_relative_vertical_momentum_drift;
  to.max_relative_axial_momentum_drift = from.max_relative_axial_momentum_drift;
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
  return integrator == Integrator::Adaptive ? "adaptive" : "splitting";
}

std::optional<Integrator> integrator_from_name(std::string_view name) {
  if (name == "adaptive") return Integrator::Adaptive;
  if (name == "splitting") return Integrator::Splitting;
  return std::nullopt;
}

bool SimulateOptions::IsValid(std::string* why) const {
  if (!adaptive.IsValid(why)) return false;
  return integrator != Integrator::Splitting || splitting.IsValid(why);
}

std::string SimulationSummary::BriefReport() const {
  std::string line = fmt::format("{} ({}): {} samples", name(model), solver, samples);
  if (steps) line += fmt::format(", {} steps ({} rejected), {} evaluations", steps, rejected_steps, rhs_evaluations);
  if (max_relative_energy_drift)
    line += fmt::format(", relative drift: energy {:.2e}, vertical momentum {:.2e}", *max_relative_energy_drift,
                        max_relative_vertical_momentum_drift.value_or(0.0));
  if (!ok()) line += ": FAILED: " + message;
  return line;
}

Simulation simulate(Model model, const Body& body, const InitialState& initial, const std::vector<double>& times,
                    const SimulateOptions& options) {
  validate(body);
  validate(initial);
  if (std::string why; !options.IsValid(&why)) {
    const auto colon = why.find(": ");
    throw InvalidInput(why.substr(0, colon), colon == std::string::npos ? why : why.substr(colon + 2));
  }
  if (model == Model::LagrangeExact) validate_symmetric(body);

  Simulation result;
  SimulationSummary& s = result.summary;
  s.model = model;
  try {
    if (const auto kind = linear_kind(model)) {
      s.solver = options.method == LinearMethod::Analytic ? "closed form" : "matrix exponential";
      result.trajectory =
          linear_in_chunks(linear_model(*kind, body), initial, times, options.method, options.progress);
    } else if (model == Model::LagrangeExact) {
      s.solver = "elliptic functions";
      result.trajectory = simulate_lagrange_exact(body, initial, times);
    } else if (options.integrator == Integrator::Splitting) {
      s.solver = fmt::format("splitting, order {}, step {:g} s", options.splitting.order, options.splitting.step);
      SplittingSummary summary;
      result.trajectory = simulate_splitting(body, initial, times, options.splitting, &summary);
      s.steps = summary.steps + summary.partial_steps;
      s.rhs_evaluations = summary.kicks;
      copy_drifts(summary, s);
    } else {
      s.solver = "Dormand-Prince 5(4)";
      NonlinearOptions adaptive = options.adaptive;
      if (options.progress) adaptive.progress = options.progress;
      NonlinearSummary summary;
      result.trajectory = simulate_nonlinear(body, initial, times, adaptive, &summary);
      s.steps = summary.steps;
      s.rejected_steps = summary.rejected_steps;
      s.rhs_evaluations = summary.rhs_evaluations;
      copy_drifts(summary, s);
      result.adaptive = summary;
    }
  } catch (const std::runtime_error& e) {
    s.termination = Termination::Failure;
    s.message = e.what();
  }
  s.samples = result.trajectory.size();
  return result;
}

}  // namespace heavytop

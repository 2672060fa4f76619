// simulate: every model through the core's one entry point, heavytop::simulate(Model, ...).
#include <algorithm>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/io/formats.hpp"
#include "docs.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/simulate.hpp"
#include "interrupt.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

py::dict summary_dict(const SimulationSummary& s) {
  auto drift = [&s](double Drifts::*field) { return s.drifts ? py::object(py::float_((*s.drifts).*field)) : py::none(); };
  return py::dict("model"_a = std::string(name(s.model)), "solver"_a = s.solver,
                  "termination"_a = s.ok() ? "success" : "failure", "message"_a = s.message,
                  "samples"_a = s.samples, "steps"_a = s.steps, "rejected_steps"_a = s.rejected_steps,
                  "rhs_evaluations"_a = s.rhs_evaluations,
                  "max_relative_energy_drift"_a = drift(&Drifts::max_relative_energy_drift),
                  "max_relative_vertical_momentum_drift"_a = drift(&Drifts::max_relative_vertical_momentum_drift),
                  "max_relative_axial_momentum_drift"_a = drift(&Drifts::max_relative_axial_momentum_drift),
                  "report"_a = s.BriefReport());
}

/// The command line's checks of `heavytop simulate`, in its order, with the keyword
/// arguments' names as keys; then the core's simulate() (which checks rtol, atol, step,
/// order and max_steps). Returns (columns, summary): a failed run is reported in the summary.
py::tuple simulate(const Body& body, const std::string& model_name, double spin, double theta0, double phi0,
                   double theta_rate0, double phi_rate0, double t_end, long long samples,
                   const std::optional<std::string>& method, const std::optional<std::string>& integrator,
                   std::optional<double> rtol, std::optional<double> atol, std::optional<double> step,
                   std::optional<int> order, std::optional<long long> max_steps) {
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  const auto model = model_from_name(model_name);
  if (!model) throw InvalidInput("model", "must be one of " + model_names(", "));
  const bool linear = linear_kind(*model).has_value(), nonlinear = *model == Model::Nonlinear;
  if (!nonlinear) io::refuse_general_in(body, "simulate --model " + model_name);  // as the command line
  if (*model == Model::LagrangeExact) validate_symmetric(body);
  // Unasked, a damped linear model takes the route that covers it (the closed form does not).
  const std::string how = method.value_or(body.damping.transverse > 0.0 ? "numeric" : "analytic");
  if (how != "analytic" && how != "numeric") throw InvalidInput("method", "must be analytic or numeric");
  require_positive("t_end", t_end);
  require_count("samples", samples, 2, 100'000'000);
  if (method && !linear) throw InvalidInput("method", "applies to the linear models only");
  const auto chosen = integrator_from_name(integrator.value_or("auto"));  // the command line's default
  if (!chosen) throw InvalidInput("integrator", "must be auto, taylor, dop853, dopri5 (adaptive) or splitting");
  const std::pair<const char*, bool> nonlinear_only[] = {
      {"integrator", integrator.has_value()}, {"step", step.has_value()}, {"order", order.has_value()},
      {"max_steps", max_steps.has_value()}};
  for (const auto& [key, given] : nonlinear_only)
    if (given && !nonlinear) throw InvalidInput(key, "applies to model=\"nonlinear\" only");
  if (*chosen != Integrator::Splitting && (step || order))
    throw InvalidInput(step ? "step" : "order", "applies to integrator=\"splitting\" only");

  SimulateOptions options;
  options.method = how == "numeric" ? LinearMethod::Numeric : LinearMethod::Analytic;
  options.integrator = *chosen;
  if (rtol) options.adaptive.rtol = *rtol;
  if (atol) options.adaptive.atol = *atol;
  if (step) options.splitting.step = *step;
  if (order) options.splitting.order = *order;
  if (max_steps) {
    const auto steps = static_cast<std::size_t>(std::max(0LL, *max_steps));  // < 1: the core's "must be > 0"
    (*chosen == Integrator::Splitting ? options.splitting.max_steps : options.adaptive.max_steps) = steps;
  }
  options.progress = poll_signals();

  Simulation run = without_gil([&] {
    return heavytop::simulate(*model, body, state, sample_times(t_end, static_cast<std::size_t>(samples)), options);
  });
  Trajectory& tr = run.trajectory;
  const auto names = tr.column_names();
  py::dict columns;
  for (std::size_t c = 0; c < names.size(); ++c) columns[py::str(names[c])] = to_numpy(std::move(tr.column(c)));
  return py::make_tuple(columns, summary_dict(run.summary));
}

}  // namespace

void bind_simulate(py::module_& m) {
  m.def("simulate", &simulate, docs::kCoreSimulate, "body"_a, "model"_a, py::kw_only(), "spin"_a, "theta0"_a,
        "phi0"_a, "theta_rate0"_a, "phi_rate0"_a, "t_end"_a, "samples"_a, "method"_a = py::none(),
        "integrator"_a = py::none(), "rtol"_a = py::none(), "atol"_a = py::none(), "step"_a = py::none(),
        "order"_a = py::none(), "max_steps"_a = py::none());
  py::list models;
  for (Model model : kModels) models.append(std::string(name(model)));
  m.attr("MODELS") = py::tuple(models);
}

}  // namespace heavytop::python

// simulate: every model through the core's one entry point, heavytop::simulate(Model, ...).
#include <algorithm>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/io/formats.hpp"
#include "docs.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/table.hpp"
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

/// The core's resolve() of the request (the rules `heavytop simulate` applies, in its order),
/// the keyword arguments' names as keys; then the core's simulate() (which checks rtol, atol,
/// step, order and max_steps). Returns (columns, summary, None): a failed run is reported in the
/// summary. On a table (SPEC section 16) the same rules, then the table's (simulate_table):
/// (columns, the JSON's "summary", the JSON's "table").
py::tuple simulate(const Body& body, const std::string& model_name, double spin, double theta0, double phi0,
                   double theta_rate0, double phi_rate0, double t_end, long long samples,
                   const std::optional<std::string>& method, const std::optional<std::string>& integrator,
                   std::optional<double> rtol, std::optional<double> atol, std::optional<double> step,
                   std::optional<int> order, std::optional<long long> max_steps, const std::optional<Table>& table) {
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  const bool on_table = table && table->on_table();
  if (on_table) validate(*table, body);  // as the command line checks [table] with the body, first
  // The core's rules (resolve()); here only its keys spelled as keyword arguments and the
  // general body's refusal in the command line's words.
  SimulateRequest request;
  request.model = Requested<std::string>::of(model_name);
  request.method = Requested<std::string>::of(method);
  request.integrator = Requested<std::string>::of(integrator);
  request.t_end = t_end;
  request.samples = samples;
  request.rtol = Requested<double>::of(rtol);
  request.atol = Requested<double>::of(atol);
  request.step = Requested<double>::of(step);
  request.order = Requested<int>::of(order);
  request.max_steps = Requested<long long>::of(max_steps);
  ResolvedSimulate resolved;
  try {
    resolved = resolve(request, body, [&](Model m) {
      if (m != Model::Nonlinear) io::refuse_general_in(body, "simulate --model " + model_name);  // as the command line
    });
  } catch (const InvalidInput& e) {
    throw spelled(e, Spelling{[](std::string_view key) { return std::string(key); },
                              [](std::string_view key, std::string_view value) {
                                return fmt::format("{}=\"{}\"", key, value);
                              },
                              "auto, taylor, dop853, dopri5 (adaptive), splitting or rosenbrock4"});
  }
  const std::optional<Model> model = resolved.model;
  if (on_table)
    return simulate_table(body, *table, state, model_name, integrator, resolved.t_end, resolved.samples,
                          resolved.options.adaptive);
  Simulation run = without_gil([&] {
    return heavytop::simulate(*model, body, state, sample_times(resolved.t_end, resolved.samples), resolved.options,
                              poll_signals());
  });
  Trajectory& tr = run.trajectory;
  const auto names = tr.column_names();
  py::dict columns;
  for (std::size_t c = 0; c < names.size(); ++c) columns[py::str(names[c])] = to_numpy(std::move(tr.column(c)));
  return py::make_tuple(columns, summary_dict(run.summary), py::none());
}

}  // namespace

void bind_simulate(py::module_& m) {
  m.def("simulate", &simulate, docs::kCoreSimulate, "body"_a, "model"_a, py::kw_only(), "spin"_a, "theta0"_a,
        "phi0"_a, "theta_rate0"_a, "phi_rate0"_a, "t_end"_a, "samples"_a, "method"_a = py::none(),
        "integrator"_a = py::none(), "rtol"_a = py::none(), "atol"_a = py::none(), "step"_a = py::none(),
        "order"_a = py::none(), "max_steps"_a = py::none(), "table"_a = py::none());
  py::list models;
  for (Model model : kModels) models.append(std::string(name(model)));
  m.attr("MODELS") = py::tuple(models);
}

}  // namespace heavytop::python

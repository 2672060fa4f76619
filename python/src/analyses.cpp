// stability and compare: json.loads of the very JSON the command line prints (heavytop_io).
#include <cmath>
#include <optional>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "docs.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/lifetime.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/table.hpp"
#include "interrupt.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

/// (json.loads of `stability --format json`, the answer's paragraph in words): the words are
/// io's, the same the command line's text opens with. On a table (SPEC section 16) those of
/// `stability --config` with [table] (stability_on_table).
py::tuple stability(const Body& body, double spin, double theta0, double phi0, double theta_rate0,
                    double phi_rate0, double horizon, double max_tilt, std::optional<double> lifetime_horizon,
                    const std::optional<Table>& table) {
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  const bool on_table = table && table->on_table();
  if (on_table) validate(*table, body);  // as the command line checks [table] with the body, first
  AnswerOptions options;
  options.horizon = horizon;
  options.max_tilt = max_tilt;
  options.damped_horizon = lifetime_horizon;
  validate(options);  // the command line's checks, under the keys horizon, max_tilt, lifetime_horizon
  if (on_table) return stability_on_table(body, *table, state, options);  // SPEC section 16
  std::string json, words;
  without_gil([&] {
    const TopAnalysis analysis = analyse_top(body, state, options, poll_signals());
    json = io::stability_json(body, analysis);
    words = io::answer_text(analysis.answer);
    return 0;
  });
  return py::make_tuple(from_json(json), words);
}

py::object compare(const Body& body, double spin, double theta0, double phi0, double theta_rate0,
                   double phi_rate0, double t_end, long long samples, std::optional<double> rtol,
                   std::optional<double> atol) {
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  require_positive("t_end", t_end);
  require_count("samples", samples, 3, static_cast<long long>(kMaxComparisonSamples));
  validate_horizon(body, state, t_end, "t_end");
  const Tolerances options = tolerances(rtol, atol);
  return from_json(without_gil([&] {
    return io::comparison_json(
        compare_models(body, state, sample_times(t_end, static_cast<std::size_t>(samples)), options, poll_signals()));
  }));
}

py::object lifetime(const Body& body, double spin, double theta0, double phi0, double theta_rate0,
                    double phi_rate0, std::optional<double> horizon, double max_tilt, std::optional<double> rtol,
                    std::optional<double> atol, std::optional<long long> max_steps) {
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  LifetimeOptions options;
  options.horizon = horizon;
  options.max_tilt = max_tilt;
  options.integrator = tolerances(rtol, atol);
  if (max_steps) options.integrator.max_steps = static_cast<std::size_t>(std::max(0LL, *max_steps));
  return from_json(without_gil([&] { return io::lifetime_json(heavytop::lifetime(body, state, options, poll_signals())); }));
}

}  // namespace

void bind_analyses(py::module_& m) {
  m.def("lifetime", &lifetime, docs::kCoreLifetime, "body"_a, py::kw_only(), "spin"_a, "theta0"_a, "phi0"_a,
        "theta_rate0"_a, "phi_rate0"_a, "horizon"_a = py::none(), "max_tilt"_a = 1.0, "rtol"_a = py::none(),
        "atol"_a = py::none(), "max_steps"_a = py::none());
  m.def("stability", &stability, docs::kCoreStability, "body"_a, "spin"_a, py::kw_only(), "theta0"_a = 0.0,
        "phi0"_a = 0.0, "theta_rate0"_a = 0.0, "phi_rate0"_a = 0.0, "horizon"_a = 100.0, "max_tilt"_a = 1.0,
        "lifetime_horizon"_a = py::none(), "table"_a = py::none());
  m.def("compare", &compare, docs::kCoreCompare, "body"_a, py::kw_only(), "spin"_a, "theta0"_a, "phi0"_a,
        "theta_rate0"_a, "phi_rate0"_a, "t_end"_a, "samples"_a, "rtol"_a = py::none(), "atol"_a = py::none());
}

}  // namespace heavytop::python

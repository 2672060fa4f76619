// Shared by the binding files of heavytop._core: conversions between the core's types and
// Python's, and the functions that bind each topic (one file per topic).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "heavytop/answer.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"
#include "heavytop/table.hpp"

namespace heavytop::python {

namespace py = pybind11;

/// JSON text, exactly as the command line prints it (heavytop_io, heavytop_symbolic), as
/// Python dicts and lists (json.loads keeps the order of the keys).
py::object from_json(const std::string& text);

/// A column as a float64 NumPy array that takes the vector over (no copy).
py::array_t<double> to_numpy(std::vector<double>&& column);

/// The body checked as every command but `body` and `simulate --model nonlinear` checks a
/// [body] section: SPEC section 1's rules, then SPEC section 11's terms refused with the command
/// line's message (io::refuse_general_keys: "body.Ixy: is 1e-06: the general body ...").
void validate_ordinary(const Body& body);

/// The user's initial state, validated as the command line validates it (keys "motion.*").
InitialState motion(double spin, double theta0, double phi0, double theta_rate0, double phi_rate0);

/// The nonlinear integrator's tolerances; None keeps the core's default (keys "rtol", "atol").
Tolerances tolerances(std::optional<double> rtol, std::optional<double> atol);

/// `value` must be finite and > 0 (key `key`: a keyword argument's name).
void require_positive(const char* key, double value);
/// `value` must be in [lo, hi] (key `key`: a keyword argument's name).
void require_count(const char* key, long long value, long long lo, long long hi);

/// The body on `table` (SPEC section 16; table.on_table(), validate(table, body) done) as
/// `heavytop simulate` runs it once its options are resolved: `model` "nonlinear" and
/// `integrator` auto or dop853 (InvalidInput otherwise, keys "table.contact", "integrator").
/// Returns (columns, the JSON's "summary", the JSON's "table").
py::tuple simulate_table(const Body& body, const Table& table, const InitialState& state, const std::string& model,
                         const std::optional<std::string>& integrator, double t_end, std::size_t samples,
                         const Tolerances& tolerances);
/// (json.loads of `stability --format json` on `table`, table_answer_text's words).
py::tuple stability_on_table(const Body& body, const Table& table, const InitialState& state,
                             const AnswerOptions& options);

// One per topic: each adds its classes and functions to the module.
void bind_errors(py::module_& m);
void bind_body(py::module_& m);
void bind_simulate(py::module_& m);
void bind_analyses(py::module_& m);
void bind_sweep(py::module_& m);
void bind_derive(py::module_& m);
void bind_parts(py::module_& m);
void bind_fit_decay(py::module_& m);
void bind_chaos(py::module_& m);
void bind_config(py::module_& m);
void bind_report(py::module_& m);
void bind_table(py::module_& m);

}  // namespace heavytop::python

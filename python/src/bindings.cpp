#include "bindings.hpp"

#include <cmath>

#include <fmt/format.h>

#include "heavytop/body.hpp"
#include "heavytop/io/formats.hpp"

namespace heavytop::python {

py::object from_json(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

py::array_t<double> to_numpy(std::vector<double>&& column) {
  auto* owner = new std::vector<double>(std::move(column));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owner->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             owner->data(), free_when_done);
}

void validate_ordinary(const Body& body) {
  Body ordinary = body;  // as cli/common.cpp: the body's own rules first, then its general terms
  ordinary.general = {};
  validate(ordinary);
  io::refuse_general_keys(body);
}

InitialState motion(double spin, double theta0, double phi0, double theta_rate0, double phi_rate0) {
  const InitialState state{.spin = spin, .theta0 = theta0, .phi0 = phi0, .theta_rate0 = theta_rate0,
                           .phi_rate0 = phi_rate0};
  validate(state);
  return state;
}

Tolerances tolerances(std::optional<double> rtol, std::optional<double> atol) {
  Tolerances options;
  if (rtol) options.rtol = *rtol;
  if (atol) options.atol = *atol;
  validate(options);
  return options;
}

void require_positive(const char* key, double value) {
  if (!(std::isfinite(value) && value > 0.0)) throw InvalidInput(key, "must be finite and > 0");
}

void require_count(const char* key, long long value, long long lo, long long hi) {
  if (value < lo || value > hi) throw InvalidInput(key, fmt::format("must be an integer in [{}, {}]", lo, hi));
}

}  // namespace heavytop::python

// A configuration file (SPEC section 4) read by the command line's own reader (heavytop_io), so
// that its errors are the command line's: heavytop.load("examples/toy-top.toml").
#include <map>
#include <string>
#include <variant>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/body_parts.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/mass_properties.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

// (Body, {motion key: value}, {"section.key": value}, [given keys], parts?) of the file `path`;
// the body and the motion checked as `heavytop stability --config` checks them.
py::tuple load_configuration(const std::string& path) {
  const io::Configuration config = io::read_configuration(path, "path");
  Body body = config.body;
  if (config.parts.empty()) {
    for (const std::string& key : io::required_body_keys())
      if (!config.given.count(key))
        throw InvalidInput(key, "is required in [body], unless [[body.part]] describe the body");
    for (const auto& [key, value] : config.general)
      if (value != 0.0)
        throw InvalidInput(key, fmt::format("is {:g}: the general body (SPEC section 11: the centre of mass off "
                                            "the z axis, products of inertia) is integrated by `simulate --model "
                                            "nonlinear` only (`heavytop body` reports it)",
                                            value));
  } else {
    const Damping damping = body.damping;
    const io::AssembledBody assembled = io::assemble_parts(config.parts);
    body = body_of(assembled.assembly, config.body.gravity, assembled.names);
    body.damping = damping;
  }
  validate(body);
  validate(config.motion);
  const InitialState& s = config.motion;
  py::dict motion("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0, "theta_rate0"_a = s.theta_rate0,
                  "phi_rate0"_a = s.phi_rate0);
  py::dict settings;
  for (const auto& [key, value] : config.settings)
    std::visit([&](const auto& v) { settings[py::str(key)] = py::cast(v); }, value);
  py::list given;
  for (const std::string& key : config.given) given.append(key);
  return py::make_tuple(body, motion, settings, given, !config.parts.empty());
}

}  // namespace

void bind_config(py::module_& m) {
  m.def("load_configuration", &load_configuration,
        "(Body, motion, settings, given keys, made of parts) of a configuration file", "path"_a);
}

}  // namespace heavytop::python

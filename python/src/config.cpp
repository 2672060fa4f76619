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

// (Body, {motion key: value}, {"section.key": value}, [given keys], parts?, Table) of the file `path`;
// the body and the motion checked as `heavytop simulate --config` checks them: a general body
// (SPEC section 11) is kept (the analyses that cannot take it refuse it).
py::tuple load_configuration(const std::string& path) {
  const io::Configuration config = io::read_configuration(path, "path");
  // [table] checked as the command line checks it (SPEC section 16): the pivot when absent.
  const Table table = io::table_of(config);
  Body body = config.body;
  if (config.parts.empty()) {
    for (const std::string& key : io::required_body_keys())
      if (!config.given.count(key))
        throw InvalidInput(key, "is required in [body], unless [[body.part]] describe the body");
    const auto given = [&](const char* key) {
      const auto it = config.general.find(key);
      return it == config.general.end() ? 0.0 : it->second;
    };
    body.general = {given("body.Ixy"), given("body.Ixz"), given("body.Iyz"), given("body.offset_x"),
                    given("body.offset_y")};
  } else {  // as cli/common.cpp makes it for `simulate --model nonlinear`: a general assembly as it is
    const io::AssembledBody assembled = io::assemble_parts(config.parts);
    const BodyAssembly& a = assembled.assembly;
    if (!a.general()) {
      const Damping damping = body.damping;
      body = body_of(a, config.body.gravity, assembled.names);
      body.damping = damping;
      body.tip_radius = config.body.tip_radius;
      body.rim_radius = config.body.rim_radius;
    } else {
      body = io::as_given(a, body);
    }
  }
  if (table.on_table()) body.touch_tilt = io::touch_tilt(config.parts, body);  // where a body of parts falls
  validate(body);
  validate(config.motion);
  if (table.on_table()) validate(table, body);  // a general or damped body on a table: refused naming its key
  const InitialState& s = config.motion;
  py::dict motion("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0, "theta_rate0"_a = s.theta_rate0,
                  "phi_rate0"_a = s.phi_rate0);
  py::dict settings;
  for (const auto& [key, value] : config.settings)
    std::visit([&](const auto& v) { settings[py::str(key)] = py::cast(v); }, value);
  py::list given;
  for (const std::string& key : config.given) given.append(key);
  return py::make_tuple(body, motion, settings, given, !config.parts.empty(), table);
}

}  // namespace

void bind_config(py::module_& m) {
  m.def("load_configuration", &load_configuration,
        "(Body, motion, settings, given keys, made of parts, Table) of a configuration file", "path"_a);
}

}  // namespace heavytop::python

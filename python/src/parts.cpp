// A body from its parts (SPEC section 10), steady precessions, rpm: json.loads of the very
// JSON `heavytop body` and `heavytop precession` print (heavytop_io).
#include <map>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/io/body_formats.hpp"
#include "heavytop/io/body_parts.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/precession.hpp"
#include "heavytop/units.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

// `text` is a configuration holding [[body.part]] tables (heavytop._api writes it from the
// parts' dicts), read by the configuration's own parser so that Python checks what the file does.
// A general body is refused as the command line's analyses refuse it unless `allow_general`
// (then the Body holds SPEC section 11's terms, as `simulate --model nonlinear` takes it).
py::tuple assemble_parts(const std::string& text, const std::string& source, double gravity, bool allow_general) {
  const io::Configuration config = io::parse_configuration(text, source, "parts");
  if (config.parts.empty()) throw InvalidInput("parts", "give at least one part");
  const io::AssembledBody assembled = io::assemble_parts(config.parts);
  Body body;
  body.gravity = gravity;
  if (!allow_general || !assembled.assembly.general()) {
    body = body_of(assembled.assembly, gravity, assembled.names);
  } else {  // as `simulate --model nonlinear --config` makes it: the tensor about the body axes as it is
    body = io::as_given(assembled.assembly, body);
  }
  validate(body);
  return py::make_tuple(from_json(io::body_json(assembled, gravity)), py::cast(body));
}

// `heavytop body` of a body given by its keys ([body] A, B, C, mass, length and SPEC section 11's).
py::object body_json_of(const Body& body) {
  validate(body);
  const std::map<std::string, double> general = {
      {"body.offset_x", body.general.offset_x}, {"body.offset_y", body.general.offset_y},
      {"body.Ixy", body.general.Ixy}, {"body.Ixz", body.general.Ixz}, {"body.Iyz", body.general.Iyz}};
  return from_json(io::body_json(io::assemble_moments(body, general), body.gravity));
}

py::object precession(const Body& body, double tilt, double spin) {
  validate_ordinary(body);
  if (!body.damping.conservative() && PyErr_WarnEx(PyExc_UserWarning, io::kPrecessionIgnoresDamping, 1) != 0)
    throw py::error_already_set();
  std::optional<PrecessionAnalysis> steady;
  if (is_symmetric(body)) steady = analyse_precession(body, tilt, spin);
  const auto rotations = permanent_rotations(body, tilt);
  return from_json(io::precession_json(body, tilt, spin, steady ? &*steady : nullptr, rotations));
}

}  // namespace

void bind_parts(py::module_& m) {
  m.def("assemble_parts", &assemble_parts, "(body JSON, Body or None) of [[body.part]] tables in TOML text",
        "text"_a, "source"_a, "gravity"_a, "allow_general"_a);
  m.def("body_json", &body_json_of, "json.loads of `heavytop body --format json` for a body given by its keys",
        "body"_a);
  m.def("precession", &precession, "json.loads of `heavytop precession --format json`", "body"_a, "tilt"_a,
        "spin"_a);
  m.def("rad_per_s_from_rpm", &rad_per_s_from_rpm, "rad/s of a spin in rpm (SPEC section 9)", "rpm"_a);
}

}  // namespace heavytop::python

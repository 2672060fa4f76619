// heavytop.Body and the built-in example.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "docs.hpp"
#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

Body make_body(double A, double B, double C, double mass, double length, double gravity) {
  const Body body{.A = A, .B = B, .C = C, .mass = mass, .gravity = gravity, .length = length};
  validate(body);
  return body;
}

}  // namespace

void bind_body(py::module_& m) {
  py::class_<Body>(m, "Body", docs::kBody)
      .def(py::init(&make_body), "A"_a, "B"_a, "C"_a, "mass"_a, "length"_a, "gravity"_a = 9.81, docs::kBodyInit)
      .def_readonly("A", &Body::A, "kg m^2, moment of inertia about body x through O")
      .def_readonly("B", &Body::B, "kg m^2, moment of inertia about body y through O")
      .def_readonly("C", &Body::C, "kg m^2, moment of inertia about the spin axis z through O")
      .def_readonly("mass", &Body::mass, "kg, m")
      .def_readonly("length", &Body::length, "m, R: signed distance O to the centre of mass along z")
      .def_readonly("gravity", &Body::gravity, "m/s^2, g")
      .def_property_readonly("mgR", &Body::mgR, "N m, the gravitational moment m g R (signed like R)")
      .def("to_dict", [](const Body& b) {
             return py::dict("A"_a = b.A, "B"_a = b.B, "C"_a = b.C, "mass"_a = b.mass, "gravity"_a = b.gravity,
                             "length"_a = b.length);
           }, "The body as the JSON outputs' \"body\" object: {A, B, C, mass, gravity, length}.")
      .def("__eq__", [](const Body& a, const Body& b) {
             return a.A == b.A && a.B == b.B && a.C == b.C && a.mass == b.mass && a.gravity == b.gravity &&
                    a.length == b.length;
           }, py::is_operator())
      .def("__hash__", [](const Body& b) {  // immutable: hashes like its tuple
             return py::hash(py::make_tuple(b.A, b.B, b.C, b.mass, b.length, b.gravity));
           })
      .def("__repr__", [](const Body& b) {
             return fmt::format("heavytop.Body(A={}, B={}, C={}, mass={}, length={}, gravity={})", b.A, b.B, b.C,
                                b.mass, b.length, b.gravity);
           })
      .def(py::pickle(
          [](const Body& b) { return py::make_tuple(b.A, b.B, b.C, b.mass, b.length, b.gravity); },
          [](const py::tuple& t) {
            return make_body(t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(),
                             t[4].cast<double>(), t[5].cast<double>());
          }));

  m.def("example_toy_top", &example_toy_top, docs::kExampleToyTop);
  m.def("example_motion", [] {
        const InitialState s = example_motion();
        return py::dict("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0,
                        "theta_rate0"_a = s.theta_rate0, "phi_rate0"_a = s.phi_rate0);
      }, docs::kExampleMotion);
}

}  // namespace heavytop::python

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

Body make_body(double A, double B, double C, double mass, double length, double gravity, double transverse_damping,
               double axial_damping, double friction, bool driven) {
  const Body body{.A = A, .B = B, .C = C, .mass = mass, .gravity = gravity, .length = length,
                  .damping = {.transverse = transverse_damping, .axial = axial_damping, .friction = friction,
                              .driven = driven}};
  validate(body);
  return body;
}

py::tuple state_of(const Body& b) {
  return py::make_tuple(b.A, b.B, b.C, b.mass, b.length, b.gravity, b.damping.transverse, b.damping.axial,
                        b.damping.friction, b.damping.driven);
}

}  // namespace

void bind_body(py::module_& m) {
  py::class_<Body>(m, "Body", docs::kBody)
      .def(py::init(&make_body), "A"_a, "B"_a, "C"_a, "mass"_a, "length"_a, "gravity"_a = 9.81, py::kw_only(),
           "transverse_damping"_a = 0.0, "axial_damping"_a = 0.0, "friction"_a = 0.0, "driven"_a = false,
           docs::kBodyInit)
      .def_readonly("A", &Body::A, "kg m^2, moment of inertia about body x through O")
      .def_readonly("B", &Body::B, "kg m^2, moment of inertia about body y through O")
      .def_readonly("C", &Body::C, "kg m^2, moment of inertia about the spin axis z through O")
      .def_readonly("mass", &Body::mass, "kg, m")
      .def_readonly("length", &Body::length, "m, R: signed distance O to the centre of mass along z")
      .def_readonly("gravity", &Body::gravity, "m/s^2, g")
      .def_property_readonly("mgR", &Body::mgR, "N m, the gravitational moment m g R (signed like R)")
      .def_property_readonly("transverse_damping", [](const Body& b) { return b.damping.transverse; },
                             "N m s, d_t: the drag torque -d_t w_perp on the axis's motion (SPEC section 6)")
      .def_property_readonly("axial_damping", [](const Body& b) { return b.damping.axial; },
                             "N m s, d_a: the drag torque -d_a (w.k) k on the spin")
      .def_property_readonly("friction", [](const Body& b) { return b.damping.friction; },
                             "N m, tau0: the dry friction torque -tau0 sign(w.k) k at the tip")
      .def_property_readonly("driven", [](const Body& b) { return b.damping.driven; },
                             "True: a motor holds the spin w.k at its value at t = 0")
      .def("to_dict", [](const Body& b) {
             return py::dict("A"_a = b.A, "B"_a = b.B, "C"_a = b.C, "mass"_a = b.mass, "gravity"_a = b.gravity,
                             "length"_a = b.length);
           }, "The body as the JSON outputs' \"body\" object: {A, B, C, mass, gravity, length}.")
      .def("__eq__", [](const Body& a, const Body& b) {
             return state_of(a).equal(state_of(b));
           }, py::is_operator())
      .def("__hash__", [](const Body& b) { return py::hash(state_of(b)); })  // immutable: like its tuple
      .def("__repr__", [](const Body& b) {
             std::string damping;
             if (b.damping.transverse) damping += fmt::format(", transverse_damping={}", b.damping.transverse);
             if (b.damping.axial) damping += fmt::format(", axial_damping={}", b.damping.axial);
             if (b.damping.friction) damping += fmt::format(", friction={}", b.damping.friction);
             if (b.damping.driven) damping += ", driven=True";
             return fmt::format("heavytop.Body(A={}, B={}, C={}, mass={}, length={}, gravity={}{})", b.A, b.B, b.C,
                                b.mass, b.length, b.gravity, damping);
           })
      .def(py::pickle(&state_of, [](const py::tuple& t) {
        return make_body(t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(),
                         t[4].cast<double>(), t[5].cast<double>(), t[6].cast<double>(), t[7].cast<double>(),
                         t[8].cast<double>(), t[9].cast<bool>());
      }));

  m.def("example_toy_top", &example_toy_top, docs::kExampleToyTop);
  m.def("example_motion", [] {
        const InitialState s = example_motion();
        return py::dict("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0,
                        "theta_rate0"_a = s.theta_rate0, "phi_rate0"_a = s.phi_rate0);
      }, docs::kExampleMotion);
}

}  // namespace heavytop::python

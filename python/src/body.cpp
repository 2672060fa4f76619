// heavytop.Body and the built-in example.
#include <string>
#include <utility>

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
               double axial_damping, double friction, bool driven, double offset_x, double offset_y, double Ixy,
               double Ixz, double Iyz, double tip_radius, double rim_radius) {
  const Body body{.A = A, .B = B, .C = C, .mass = mass, .gravity = gravity, .length = length,
                  .damping = {.transverse = transverse_damping, .axial = axial_damping, .friction = friction,
                              .driven = driven},
                  .general = {.Ixy = Ixy, .Ixz = Ixz, .Iyz = Iyz, .offset_x = offset_x, .offset_y = offset_y},
                  .tip_radius = tip_radius, .rim_radius = rim_radius};
  validate(body);
  return body;
}

py::tuple state_of(const Body& b) {
  const GeneralInertia& g = b.general;
  return py::make_tuple(b.A, b.B, b.C, b.mass, b.length, b.gravity, b.damping.transverse, b.damping.axial,
                        b.damping.friction, b.damping.driven, g.offset_x, g.offset_y, g.Ixy, g.Ixz, g.Iyz,
                        b.tip_radius, b.rim_radius);
}

// The general body's keyword arguments (SPEC section 11), after those of docs::kBodyInit.
const std::string& init_doc() {
  static const std::string doc = std::string(docs::kBodyInit) +
      "\noffset_x, offset_y: m (default 0), the centre of mass's x and y in the body axes: the centre of mass\n"
      "        is (offset_x, offset_y, length)\n"
      "Ixy, Ixz, Iyz: kg m^2 (default 0), the products of inertia about O in the body axes (the tensor\n"
      "        [[A, -Ixy, -Ixz], [-Ixy, B, -Iyz], [-Ixz, -Iyz, C]], positive definite)\n"
      "A body with any of these nonzero is SPEC section 11's general body: simulate(body, \"nonlinear\")\n"
      "integrates it (integrator \"auto\" or \"dopri5\"); every other analysis refuses it (InvalidInput).\n"
      "tip_radius: m (>= 0, default 0), the radius of the sphere centred at O with which the body touches a table\n"
      "        (SPEC section 16; 0: a sharp point)\n"
      "rim_radius: m (>= 0, default 0), or the radius of a ring about the axis through O, thickened by tip_radius\n"
      "        (a coin, a disc). Both matter only on a table (simulate(..., table=Table(...))).";
  return doc;
}

}  // namespace

void bind_body(py::module_& m) {
  py::class_<Body>(m, "Body", docs::kBody)
      .def(py::init(&make_body), "A"_a, "B"_a, "C"_a, "mass"_a, "length"_a, "gravity"_a = 9.81, py::kw_only(),
           "transverse_damping"_a = 0.0, "axial_damping"_a = 0.0, "friction"_a = 0.0, "driven"_a = false,
           "offset_x"_a = 0.0, "offset_y"_a = 0.0, "Ixy"_a = 0.0, "Ixz"_a = 0.0, "Iyz"_a = 0.0, "tip_radius"_a = 0.0,
           "rim_radius"_a = 0.0, init_doc().c_str())
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
      .def_property_readonly("offset_x", [](const Body& b) { return b.general.offset_x; },
                             "m, the centre of mass's x in the body axes (SPEC section 11; 0: on the z axis)")
      .def_property_readonly("offset_y", [](const Body& b) { return b.general.offset_y; },
                             "m, the centre of mass's y in the body axes (SPEC section 11)")
      .def_property_readonly("Ixy", [](const Body& b) { return b.general.Ixy; },
                             "kg m^2, the product of inertia integral of x y dm about O (SPEC section 11)")
      .def_property_readonly("Ixz", [](const Body& b) { return b.general.Ixz; },
                             "kg m^2, the product of inertia integral of x z dm about O (SPEC section 11)")
      .def_property_readonly("Iyz", [](const Body& b) { return b.general.Iyz; },
                             "kg m^2, the product of inertia integral of y z dm about O (SPEC section 11)")
      .def_readonly("tip_radius", &Body::tip_radius,
                    "m, the radius of the sphere centred at O that touches a table (SPEC section 16; 0: a sharp point)")
      .def_readonly("rim_radius", &Body::rim_radius,
                    "m, the radius of the ring about the axis through O that touches a table (SPEC section 16; 0: none)")
      .def_property_readonly("general", [](const Body& b) { return is_general(b); },
                             "True for SPEC section 11's general body (an offset or a product of inertia nonzero)")
      .def("to_dict", [](const Body& b) {
             py::dict d("A"_a = b.A, "B"_a = b.B, "C"_a = b.C, "mass"_a = b.mass, "gravity"_a = b.gravity,
                        "length"_a = b.length);
             if (b.tip_radius != 0.0) d["tip_radius"] = b.tip_radius;  // as the JSON's "body", when given
             if (b.rim_radius != 0.0) d["rim_radius"] = b.rim_radius;
             if (is_general(b)) {
               d["offset_x"] = b.general.offset_x;
               d["offset_y"] = b.general.offset_y;
               d["Ixy"] = b.general.Ixy;
               d["Ixz"] = b.general.Ixz;
               d["Iyz"] = b.general.Iyz;
             }
             return d;
           }, "The body as the JSON outputs' \"body\" object: {A, B, C, mass, gravity, length}, tip_radius and\n"
              "rim_radius when not 0 (SPEC section 16), and for a general body (SPEC section 11) offset_x, offset_y,\n"
              "Ixy, Ixz, Iyz.")
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
             const GeneralInertia& g = b.general;
             for (const auto& [name, value] : {std::pair{"offset_x", g.offset_x}, std::pair{"offset_y", g.offset_y},
                                               std::pair{"Ixy", g.Ixy}, std::pair{"Ixz", g.Ixz}, std::pair{"Iyz", g.Iyz}})
               if (value != 0.0) damping += fmt::format(", {}={}", name, value);
             for (const auto& [name, value] : {std::pair{"tip_radius", b.tip_radius}, std::pair{"rim_radius", b.rim_radius}})
               if (value != 0.0) damping += fmt::format(", {}={}", name, value);
             return fmt::format("heavytop.Body(A={}, B={}, C={}, mass={}, length={}, gravity={}{})", b.A, b.B, b.C,
                                b.mass, b.length, b.gravity, damping);
           })
      .def(py::pickle(&state_of, [](const py::tuple& t) {
        // 10 items: a pickle made before the general body's terms (all 0); 15: before the radii (0).
        const auto general = [&](std::size_t i) { return t.size() > i ? t[i].cast<double>() : 0.0; };
        return make_body(t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(),
                         t[4].cast<double>(), t[5].cast<double>(), t[6].cast<double>(), t[7].cast<double>(),
                         t[8].cast<double>(), t[9].cast<bool>(), general(10), general(11), general(12), general(13),
                         general(14), general(15), general(16));
      }));

  m.def("example_toy_top", &example_toy_top, docs::kExampleToyTop);
  m.def("example_motion", [] {
        const InitialState s = example_motion();
        return py::dict("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0,
                        "theta_rate0"_a = s.theta_rate0, "phi_rate0"_a = s.phi_rate0);
      }, docs::kExampleMotion);
}

}  // namespace heavytop::python

// heavytop._core: the compiled half of the Python package heavytop, thin pybind11 bindings
// over heavytop_core, heavytop_io and heavytop_symbolic (one file per topic). The package's
// Python half (heavytop/__init__.py, results.py) turns what these return into typed results.
#include "bindings.hpp"
#include "docs.hpp"
#include "heavytop/body.hpp"

#ifndef HEAVYTOP_VERSION
#error "HEAVYTOP_VERSION (the CMake project's version) must be defined"
#endif

namespace heavytop::python {

void bind_errors(py::module_& m) {
  // heavytop::InvalidInput -> heavytop.InvalidInput(ValueError), with .key and .rule. The
  // core names its fields as the Python keyword arguments do ("rtol", "max_tilt", "vary"),
  // and the body and motion as the configuration file does ("body.A", "motion.spin"): the
  // message is shown as it is (the command line maps the fields to its flags instead).
  static py::handle invalid_input = py::exception<InvalidInput>(m, "InvalidInput", PyExc_ValueError).release();
  invalid_input.attr("__doc__") = docs::kInvalidInput;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InvalidInput& e) {
      py::object error = invalid_input(e.what());
      error.attr("key") = e.key();
      error.attr("rule") = e.rule();
      PyErr_SetObject(invalid_input.ptr(), error.ptr());
    }
  });
}

}  // namespace heavytop::python

PYBIND11_MODULE(_core, m) {
  using namespace heavytop::python;
  m.doc() = docs::kCoreModule;
  m.attr("__version__") = HEAVYTOP_VERSION;
  bind_errors(m);
  bind_body(m);
  bind_table(m);
  bind_simulate(m);
  bind_analyses(m);
  bind_sweep(m);
  bind_derive(m);
  bind_parts(m);
  bind_fit_decay(m);
  bind_chaos(m);
  bind_config(m);
  bind_report(m);
}

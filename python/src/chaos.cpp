// heavytop.chaos() (SPEC 17): json.loads of the very JSON `heavytop chaos --format json` prints,
// and of its Poincare section (`chaos --section --format json`), from the core's analyse_chaos().
#include <optional>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "interrupt.hpp"
#include "heavytop/chaos.hpp"
#include "heavytop/io/chaos_formats.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

py::object chaos(const Body& body, double spin, double theta0, double phi0, double theta_rate0, double phi_rate0,
                 double horizon, std::optional<double> precision, double renormalisation_interval, bool section) {
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  ChaosOptions options;
  options.horizon = horizon;
  options.precision = precision;
  options.renormalisation_interval = renormalisation_interval;
  validate(options);
  std::string json = without_gil([&] {
    return section ? io::section_json(poincare_section(body, state, options, poll_signals()))
                   : io::chaos_json(analyse_chaos(body, state, options, poll_signals()));
  });
  return from_json(json);
}

}  // namespace

void bind_chaos(py::module_& m) {
  m.def("chaos", &chaos, "json.loads of `heavytop chaos --format json` (section: of `chaos --section`)", "body"_a,
        "spin"_a, "theta0"_a, "phi0"_a, "theta_rate0"_a, "phi_rate0"_a, "horizon"_a, "precision"_a,
        "renormalisation_interval"_a, "section"_a);
}

}  // namespace heavytop::python

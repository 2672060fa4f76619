// fit_decay: d_a, tau0 and w0 fitted to a measured spin decay, as json.loads of the JSON that
// `heavytop fit-decay --format json` prints (heavytop_io).
#include <cmath>
#include <optional>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/fit_decay.hpp"
#include "heavytop/io/formats.hpp"
#include "interrupt.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

py::object fit_decay(std::vector<double> t, std::vector<double> spin, const Body& body, std::optional<double> spin0) {
  validate_ordinary(body);
  FitDecayOptions options;
  if (spin0) {
    if (!(std::isfinite(*spin0) && *spin0 > 0.0)) throw InvalidInput("spin0", "must be a finite number > 0");
    options.fit_spin0 = false;
    options.spin0 = *spin0;
  }
  const DecayData data{std::move(t), std::move(spin)};
  return from_json(without_gil([&] { return io::fit_decay_json(fit_spin_decay(body, data, options)); }));
}

}  // namespace

void bind_fit_decay(py::module_& m) {
  m.def("fit_decay", &fit_decay,
        "d_a, tau0 (and w0 unless spin0 is given) fitted to spins (rad/s) at times (s): the JSON of "
        "`heavytop fit-decay --format json` as a dict. Use heavytop.fit_decay.",
        "t"_a, "spin"_a, "body"_a, py::kw_only(), "spin0"_a = py::none());
}

}  // namespace heavytop::python

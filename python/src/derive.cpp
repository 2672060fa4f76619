// derive, derive_rotations, derive_check: json.loads of `heavytop derive --format json`
// (heavytop_symbolic renders both), or RuntimeError when built without GiNaC.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "docs.hpp"
#include "heavytop/body.hpp"

#ifdef HEAVYTOP_HAVE_SYMBOLIC
#include "heavytop/symbolic/derive.hpp"
#include "heavytop/symbolic/json.hpp"
#include "heavytop/symbolic/kinematics.hpp"
#endif

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

#ifdef HEAVYTOP_HAVE_SYMBOLIC
void check_order(int order) {
  if (order != 1 && order != 2) throw InvalidInput("order", "must be 1 or 2");
}

// GiNaC is not thread-safe: the GIL stays held, so derivations never run concurrently.
py::object derive(const std::string& method, const std::string& sequence, int order) {
  check_order(order);
  const auto m = symbolic::method_from_name(method);
  if (!m) throw InvalidInput("method", "must be euler-moving, euler-fixed, euler-body or lagrange");
  const auto s = symbolic::sequence_from_name(sequence);
  if (!s) throw InvalidInput("sequence", "must be phi-theta or theta-phi");
  return from_json(symbolic::derivation_json(symbolic::derive(*m, *s, order)));
}

py::object derive_rotations(int order) {
  check_order(order);
  return from_json(symbolic::rotations_json(symbolic::rotations(order)));
}

py::object derive_check(std::optional<int> order) {
  if (order) check_order(*order);
  return from_json(symbolic::check_json(symbolic::check(order ? std::vector<int>{*order} : std::vector<int>{1, 2})));
}
#else
[[noreturn]] void no_symbolic() {
  throw std::runtime_error("derive: heavytop was built without HEAVYTOP_BUILD_SYMBOLIC");
}
py::object derive(const std::string&, const std::string&, int) { no_symbolic(); }
py::object derive_rotations(int) { no_symbolic(); }
py::object derive_check(std::optional<int>) { no_symbolic(); }
#endif

}  // namespace

void bind_derive(py::module_& m) {
  m.def("derive", &derive, docs::kCoreDerive, "method"_a, "sequence"_a, "order"_a);
  m.def("derive_rotations", &derive_rotations, docs::kCoreDeriveRotations, "order"_a);
  m.def("derive_check", &derive_check, docs::kCoreDeriveCheck, "order"_a = py::none());
#ifdef HEAVYTOP_HAVE_SYMBOLIC
  m.attr("HAS_DERIVE") = true;
#else
  m.attr("HAS_DERIVE") = false;  // built without HEAVYTOP_BUILD_SYMBOLIC (GiNaC): derive*() raise RuntimeError
#endif
}

}  // namespace heavytop::python

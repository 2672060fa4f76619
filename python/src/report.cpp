// The report folder (heavytop_report): heavytop.report(...) writes what `heavytop report` writes.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/report/report.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

// As cli/report_command.cpp: `map` a sweep's file (CSV or HDF5), `held` and `values` its
// slices; `source` the configuration file named in the title ("" for none).
void write_report(const std::string& folder, const Body& body, double spin, double theta0, double phi0,
                  double theta_rate0, double phi_rate0, std::optional<double> t_end, const std::string& map_file,
                  const std::string& held, const std::vector<double>& values, const std::string& source) {
  if (folder.empty()) throw InvalidInput("folder", "give the report's folder, e.g. \"report\"");
  if (t_end) require_positive("t_end", *t_end);
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  std::optional<report::ReportMap> map;
  if (!map_file.empty()) {
    map = report::ReportMap{.file = map_file, .map = io::read_map(map_file, "map"), .held = held, .values = values};
  } else if (!held.empty()) {
    throw InvalidInput("slice", "needs map=FILE");
  }
  py::gil_scoped_release release;
  report::write_report(folder, body, state, t_end, map, source);
}

}  // namespace

void bind_report(py::module_& m) {
  m.def("write_report", &write_report, "the folder of `heavytop report`", "folder"_a, "body"_a, "spin"_a, "theta0"_a,
        "phi0"_a, "theta_rate0"_a, "phi_rate0"_a, "t_end"_a, "map"_a, "held"_a, "values"_a, "source"_a);
}

}  // namespace heavytop::python

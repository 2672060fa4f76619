// The report folder (heavytop_report): heavytop.report(...) writes what `heavytop report` writes.
#include <cmath>
#include <fstream>
#include <numbers>
#include <string_view>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "interrupt.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/animation.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/report/report.hpp"
#include "web_assets.hpp"  // report/src: the page script the report writes (three.js, uPlot), embedded

#include <nlohmann/json.hpp>

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
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  std::optional<report::ReportMap> map;
  if (!map_file.empty()) {
    map = report::ReportMap{.file = map_file, .map = io::read_map(map_file, "map"), .held = held, .values = values};
  } else if (!held.empty()) {
    throw InvalidInput("slice", "needs map=FILE");
  }
  // The report names its folder "--output", the command line's option: here it is `folder`. A
  // file that cannot be written is an OSError, as write_file's.
  try {
    const py::gil_scoped_release release;
    report::write_report(folder, body, state, t_end, map, source, {}, poll_signals());
  } catch (const Interrupted&) {
    throw py::error_already_set();  // Ctrl-C: KeyboardInterrupt, the folder as it was
  } catch (const InvalidInput& e) {
    if (e.key() != "--output") throw;
    throw InvalidInput("folder", e.rule());
  } catch (const io::Failure& e) {
    const std::string_view what = e.what(), option = "--output: ";
    const std::string message = what.starts_with(option) ? "folder: " + std::string(what.substr(option.size())) : std::string(what);
    PyErr_SetString(PyExc_OSError, message.c_str());
    throw py::error_already_set();
  }
}

// As cli/explore_command.cpp: the built page at `page_file` ("" when there is none) with its
// inputs starting at `body` and `state`, checked as the command line checks them.
py::bytes explorer_page(const std::string& page_file, const Body& body, double spin, double theta0, double phi0,
                          double theta_rate0, double phi_rate0) {
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  if (page_file.empty()) throw InvalidInput("explore", io::kExplorerPageMissing);
  std::ifstream in(page_file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  auto page = io::explorer_page(text.str(), body, state);
  if (!in || !page) throw std::runtime_error("explore: '" + page_file + "' is not the explorer page");
  return py::bytes(*page);
}

// Writes `content` to `path` as the command line writes --output (io::write_output): a regular
// file, or a new one, through a unique temporary name beside it and a rename, so that a failed
// write (a full disk, a file-size limit) leaves the old file as it was and no partial one; a
// device or pipe written directly, never replaced; a folder refused. `key` names the argument
// in messages ("path: 'out' is a folder"). A path is a file's name here: "-" is the file "-",
// not stdout. An InvalidInput for what the path is, OSError for a write that fails.
void write_file(const std::string& path, const py::bytes& content, const std::string& key) {
  if (path.empty()) throw InvalidInput(key, "give a file's name, e.g. \"page.html\"");
  const std::string text = content;
  try {
    const py::gil_scoped_release unlocked;  // a pipe may wait for its reader
    io::write_output(path == "-" ? "./-" : path, text, key);
  } catch (const io::Failure& e) {
    PyErr_SetString(PyExc_OSError, e.what());
    throw py::error_already_set();
  }
}

std::vector<double> as_vector(const py::handle& column) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(column);
  if (!a || a.ndim() != 1) throw InvalidInput("trajectory", "its columns must be 1-D float arrays");
  return std::vector<double>(a.data(), a.data() + a.size());
}

// window.HEAVYTOP_REPORT for the report's page script (report/web/src/main.js) drawing one
// trajectory in its 3D view: what report.cpp's page_data_js() gives its 3D view, for this motion
// (no other model, no map). psi from the model's spin w3: the nonlinear model's axial_momentum
// column (C w3), or for the linear models the constant spin `spin`.
std::string motion_view_data(const Body& body, double spin, py::dict columns) {
  Trajectory tr;
  tr.t = as_vector(columns["t"]);
  tr.theta = as_vector(columns["theta"]);
  tr.phi = as_vector(columns["phi"]);
  tr.theta_rate = as_vector(columns["theta_rate"]);
  tr.phi_rate = as_vector(columns["phi_rate"]);
  std::vector<double> cw3 = columns.contains("axial_momentum") ? as_vector(columns["axial_momentum"])
                                                                : std::vector<double>(tr.size(), body.C * spin);
  tr.extra.emplace_back("axial_momentum", std::move(cw3));
  if (tr.size() < 2) throw InvalidInput("trajectory", "needs at least 2 samples to move");
  const std::vector<double> psi = report::spin_angles(body, tr);
  const std::vector<std::size_t> shown = report::display_samples(tr.size());
  auto pick = [&](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i : shown) a.push_back(std::isfinite(v[i]) ? nlohmann::json(v[i]) : nlohmann::json(nullptr));
    return a;
  };
  // Playback as the report's (report.cpp): the fastest of these speeds at which the spin turns at
  // most 30 degrees a frame (60 frames a second) and the motion lasts at least 8 s; else the slowest.
  double spin_rate = 0.0;
  for (std::size_t i = 1; i < tr.size(); ++i)
    if (tr.t[i] > tr.t[i - 1]) spin_rate = std::max(spin_rate, std::abs(psi[i] - psi[i - 1]) / (tr.t[i] - tr.t[i - 1]));
  const std::vector<double> speeds{1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0};
  double speed = speeds.front();
  for (double s : speeds)
    if (s * spin_rate / 60.0 <= std::numbers::pi / 6.0 && tr.t.back() / s >= 8.0) speed = s;
  const report::EquivalentEllipsoid shape = report::equivalent_ellipsoid(body);
  const nlohmann::json data = {
      {"body", {{"A", body.A}, {"B", body.B}, {"C", body.C}, {"mass", body.mass}, {"gravity", body.gravity},
                {"length", body.length}}},
      {"spin", spin},
      {"t", pick(tr.t)},
      {"display", {{"samples", shown.size()}, {"computed_samples", tr.size()}}},
      {"nonlinear", {{"theta", pick(tr.theta)}, {"phi", pick(tr.phi)}, {"psi", pick(psi)}}},
      {"models", nlohmann::json::array()},
      {"angle_scale", 1.0},
      {"angle_unit", "rad"},
      {"shape", {{"semi_axes", shape.semi_axes}, {"centre", shape.centre}, {"note", shape.note}}},
      {"parts", nlohmann::json::array()},
      {"playback", {{"speed", speed}, {"speeds", speeds}, {"spin_rate", spin_rate}}},
  };
  return "window.HEAVYTOP_REPORT = " + data.dump() + ";\n";
}

// The report's page script (heavytop-report.js: three.js, uPlot and the page's code, bundled), or
// None and why this build has none.
py::tuple page_script() {
  if (const char* why = report::detail::web_assets_missing()) return py::make_tuple(py::none(), std::string(why));
  for (const auto& asset : report::detail::web_assets())
    if (std::string_view(asset.name) == "heavytop-report.js")
      return py::make_tuple(py::bytes(reinterpret_cast<const char*>(asset.data), asset.size), py::none());
  return py::make_tuple(py::none(), std::string("the build embedded no heavytop-report.js"));
}

}  // namespace

void bind_report(py::module_& m) {
  m.def("write_report", &write_report, "the folder of `heavytop report`", "folder"_a, "body"_a, "spin"_a, "theta0"_a,
        "phi0"_a, "theta_rate0"_a, "phi_rate0"_a, "t_end"_a, "map"_a, "held"_a, "values"_a, "source"_a);
  m.def("explorer_page", &explorer_page, "the page of `heavytop explore` (SPEC section 15)", "page_file"_a, "body"_a,
        "spin"_a, "theta0"_a, "phi0"_a, "theta_rate0"_a, "phi_rate0"_a);
  m.def("write_file", &write_file,
        "writes bytes to a file as the command line writes --output: a temporary name beside it and a rename",
        "path"_a, "content"_a, "key"_a);
  m.def("motion_view_data", &motion_view_data, "window.HEAVYTOP_REPORT for one trajectory's 3D view", "body"_a,
        "spin"_a, "columns"_a);
  m.def("page_script", &page_script, "(the report's page script as bytes, or None and why)");
  // Where this build wrote the explorer page (web/, Emscripten), or "" when it was not configured.
#ifdef HEAVYTOP_BUILT_EXPLORER_PAGE
  m.attr("BUILT_EXPLORER_PAGE") = HEAVYTOP_BUILT_EXPLORER_PAGE;
#else
  m.attr("BUILT_EXPLORER_PAGE") = "";
#endif
}

}  // namespace heavytop::python

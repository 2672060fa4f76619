// sweep and grid_values: the command line's stability maps, on every core, the GIL released.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "docs.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/units.hpp"
#include "interrupt.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

struct VariedKey {
  std::string key;
  Values values;
  const double* data() const { return values.data(); }
  std::size_t size() const { return static_cast<std::size_t>(values.size()); }
};

/// True if `v` are exactly the command line's KEY=v[0]:v[n-1]:n values (SweepAxis::value).
bool is_cli_grid(const VariedKey& v, SweepAxis& axis) {
  axis = SweepAxis{v.key, v.data()[0], v.data()[v.size() - 1], v.size()};
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!(axis.value(i) == v.data()[i])) return false;
  return true;
}

/// The one-point axes that put grid point `index` (first key slowest) at its exact values.
std::vector<SweepAxis> point_axes(const std::vector<VariedKey>& keys, std::size_t index) {
  std::vector<SweepAxis> axes(keys.size());
  for (std::size_t k = keys.size(); k-- > 0;) {
    const double v = keys[k].data()[index % keys[k].size()];
    index /= keys[k].size();
    axes[k] = SweepAxis{keys[k].key, v, v, 1};
  }
  return axes;
}

/// The varied keys and their values, checked as the command line checks --vary (key "vary").
std::vector<VariedKey> varied_keys(const py::dict& vary) {
  if (vary.size() < 1 || vary.size() > kMaxSweepAxes)
    throw InvalidInput("vary", fmt::format("give 1 to {} parameters", kMaxSweepAxes));
  std::vector<VariedKey> keys;
  for (const auto& [k, v] : vary) {
    if (!py::isinstance<py::str>(k))
      throw InvalidInput("vary", "the keys must be strings (A, B, C, mass, gravity, length, spin, B/A, C/A)");
    const std::string key = k.cast<std::string>();
    if (key.find_first_of("=:") != std::string::npos) throw InvalidInput("vary", fmt::format("unknown key '{}'", key));
    parse_sweep_axis(key + "=0:0:1");  // the command line's check of the key
    Values values;
    try {
      values = Values::ensure(v);
    } catch (const py::error_already_set&) {
    }
    if (!values || values.ndim() != 1 || values.size() < 1 || values.size() > 100'000'000)
      throw InvalidInput("vary", fmt::format("the values of '{}' must be a 1-D array of 1 to 100000000 numbers", key));
    if (key == "spin_rpm") {  // as the command line's spin_rpm=START:STOP:COUNT: the axis "spin", in rad/s
      Values spins(values.size());
      for (py::ssize_t i = 0; i < values.size(); ++i) spins.mutable_data()[i] = rad_per_s_from_rpm(values.data()[i]);
      keys.push_back({"spin", std::move(spins)});
      continue;
    }
    keys.push_back({key, std::move(values)});
  }
  return keys;
}

/// The CLI's columns of a map: each varied key's value at every grid point, each linear model,
/// `lyapunov` (proven Lyapunov stable), `lyapunov_certificate` (names), `nonlinear` if held.
py::dict map_columns(const StabilityMap& map) {
  const std::size_t total = map.verdicts.size();
  py::dict out;
  std::vector<std::size_t> counts;
  for (const auto& a : map.axes) counts.push_back(a.values.size());
  std::vector<double*> value_columns;
  for (const auto& a : map.axes) {
    py::array_t<double> column(static_cast<py::ssize_t>(total));
    value_columns.push_back(column.mutable_data());
    out[py::str(a.key)] = column;
  }
  const std::size_t model_count = kLinearModels.size() + 1 + (map.nonlinear ? 1 : 0);
  std::vector<bool*> verdict_columns;
  for (std::size_t m = 0; m < model_count; ++m) {
    py::array_t<bool> column(static_cast<py::ssize_t>(total));
    verdict_columns.push_back(column.mutable_data());
    out[py::str(m < kLinearModels.size() ? std::string(name(kLinearModels[m]))
                : m == kLinearModels.size() ? "lyapunov" : "nonlinear")] = column;
    if (m == kLinearModels.size()) out["lyapunov_certificate"] = py::none();  // its place; filled below
  }
  without_gil([&] {
    for (std::size_t i = 0; i < total; ++i) {
      const std::vector<std::size_t> at = grid_indices(counts, i);
      for (std::size_t k = 0; k < map.axes.size(); ++k) value_columns[k][i] = map.axes[k].values[at[k]];
      const SweepVerdict& v = map.verdicts[i];
      for (std::size_t m = 0; m < kLinearModels.size(); ++m) verdict_columns[m][i] = v.linear[m];
      verdict_columns[kLinearModels.size()][i] = v.lyapunov;
      if (map.nonlinear) verdict_columns.back()[i] = v.nonlinear.value_or(false);
    }
  });
  // The certificates' names, as a NumPy array of strings (the CLI's column): the names
  // indexed by each point's code (one Python string per name, not per point).
  py::list names;
  for (int c = 0; c <= static_cast<int>(kLastLyapunovCertificate); ++c)
    names.append(py::str(std::string(name(static_cast<LyapunovCertificate>(c)))));
  py::array_t<std::uint8_t> codes(static_cast<py::ssize_t>(total));
  std::uint8_t* code = codes.mutable_data();
  for (std::size_t i = 0; i < total; ++i) code[i] = static_cast<std::uint8_t>(map.verdicts[i].lyapunov_certificate);
  out["lyapunov_certificate"] = py::module_::import("numpy").attr("array")(names, "dtype"_a = "U")[codes];
  return out;
}

py::dict sweep(const Body& body, const py::dict& vary, double spin, double theta0, double phi0,
               double theta_rate0, double phi_rate0, bool nonlinear, double horizon, double max_tilt,
               std::optional<double> rtol, std::optional<double> atol,
               const std::optional<std::string>& integrator) {
  validate_ordinary(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  const std::vector<VariedKey> keys = varied_keys(vary);
  SweepOptions options;
  options.nonlinear = nonlinear;
  options.horizon = horizon;
  options.max_tilt = max_tilt;
  options.integrator = tolerances(rtol, atol);
  // The command line's --integrator: auto (batched Taylor) unless asked.
  const auto chosen = integrator_from_name(integrator.value_or("auto"));
  if (!chosen || *chosen == Integrator::Splitting)
    throw InvalidInput("integrator", "must be auto, taylor, dopri5 (adaptive) or dop853");
  options.nonlinear_integrator = *chosen;

  // When every array is the command line's START:STOP:COUNT grid (bit for bit), its very calls.
  std::vector<SweepAxis> axes(keys.size());
  bool cli_grid = true;
  for (std::size_t k = 0; k < keys.size(); ++k) cli_grid = is_cli_grid(keys[k], axes[k]) && cli_grid;
  // Every point is checked before anything is computed, as the command line does. The grid's
  // size first, by the command line's own check (validate_sweep: at most kMaxSweepPoints,
  // counted in floating point, so that no product of the counts wraps around): for any values,
  // with axes of their counts at their first values (its corners then are grid point 0, which
  // the check of every point below starts with anyway).
  without_gil([&] {
    if (cli_grid) {
      validate_sweep(body, state, axes, options);
    } else {
      std::vector<SweepAxis> counts;
      for (const auto& k : keys) counts.push_back(SweepAxis{k.key, k.data()[0], k.data()[0], k.size()});
      validate_sweep(body, state, counts, options);
      const std::size_t total = grid_size(counts);
      // A few microseconds a point: minutes for the largest grids, so Ctrl-C is heard here too.
      const auto poll = poll_signals();
      for (std::size_t i = 0; i < total; ++i) {
        validate_sweep(body, state, point_axes(keys, i), options);
        poll(0.0);
      }
    }
  });
  const std::size_t total = grid_size(axes);  // at most kMaxSweepPoints, checked above

  StabilityMap map{.axes = {}, .nonlinear = nonlinear, .verdicts = std::vector<SweepVerdict>(total)};
  for (const auto& k : keys) map.axes.push_back(MapAxis{.key = k.key, .values = {k.data(), k.data() + k.size()}});
  without_gil([&] {
    SweepOptions one_thread = options;
    one_thread.threads = 1;  // the blocks are spread over the threads here
    if (cli_grid) {
      // The command line's own grid: the calls it makes, block by block.
      parallel_blocks(total, 16, [&](std::size_t begin, std::size_t end) {
        std::ranges::copy(sweep_verdicts(body, state, axes, one_thread, begin, end), map.verdicts.begin() + begin);
      });
    } else {
      // Any values: each point is a grid of one point at its exact values, judged by the same call.
      parallel_blocks(total, 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
          map.verdicts[i] = sweep_verdicts(body, state, point_axes(keys, i), one_thread, 0, 1)[0];
      });
    }
  });
  return map_columns(map);
}

/// A map file's columns and its grid's shape.
py::tuple read_map(const std::string& path) {
  StabilityMap map;
  without_gil([&] { map = io::read_map(path, "path"); });
  py::list shape;
  for (const auto& a : map.axes) shape.append(a.values.size());
  return py::make_tuple(map_columns(map), py::tuple(shape));
}

py::array_t<double> grid_values(double start, double stop, long long count) {
  if (!std::isfinite(start)) throw InvalidInput("start", "must be a finite number");
  if (!std::isfinite(stop)) throw InvalidInput("stop", "must be a finite number");
  require_count("count", count, 1, 100'000'000);
  const SweepAxis axis{"", start, stop, static_cast<std::size_t>(count)};
  std::vector<double> values(axis.count);
  for (std::size_t i = 0; i < axis.count; ++i) values[i] = axis.value(i);
  return to_numpy(std::move(values));
}

}  // namespace

void bind_sweep(py::module_& m) {
  m.def("sweep", &sweep, docs::kCoreSweep, "body"_a, "vary"_a, py::kw_only(), "spin"_a, "theta0"_a, "phi0"_a,
        "theta_rate0"_a, "phi_rate0"_a, "nonlinear"_a, "horizon"_a, "max_tilt"_a, "rtol"_a = py::none(),
        "atol"_a = py::none(), "integrator"_a = py::none());
  m.def("read_map", &read_map, docs::kCoreReadMap, "path"_a);
  m.def("grid_values", &grid_values, docs::kGridValues, "start"_a, "stop"_a, "count"_a);
}

}  // namespace heavytop::python

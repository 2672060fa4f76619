// The Python module `heavytop`: thin pybind11 bindings over the C++ core.
//
// Every result a command prints as JSON (stability, compare, derive) is returned here as
// json.loads of the very string the command prints (heavytop_formats, heavytop_symbolic), so
// Python and the command line cannot drift apart. Trajectories and sweeps come back as NumPy
// arrays filled in C++, with the GIL released while the core computes. Bad input raises
// heavytop.InvalidInput, a ValueError whose message is the command line's "<key>: <rule>".
#include <algorithm>
#include <map>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "heavytop/io/formats.hpp"
#include "heavytop/body.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/linear_motion.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/state.hpp"
#include "heavytop/sweep.hpp"

#ifdef HEAVYTOP_HAVE_SYMBOLIC
#include "heavytop/symbolic/derive.hpp"
#include "heavytop/symbolic/json.hpp"
#include "heavytop/symbolic/kinematics.hpp"
#endif

namespace py = pybind11;
using namespace pybind11::literals;

namespace heavytop::python {
namespace {

// ---- conversions -----------------------------------------------------------------------------

/// JSON text, exactly as the command line prints it, as Python dicts and lists.
py::object from_json(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

/// A column as a float64 NumPy array that takes the vector over (no copy).
py::array_t<double> to_numpy(std::vector<double>&& column) {
  auto* owner = new std::vector<double>(std::move(column));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owner->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             owner->data(), free_when_done);
}

/// The user's initial state, validated as the command line validates it (keys "motion.*").
InitialState motion(double spin, double theta0, double phi0, double theta_rate0, double phi_rate0) {
  const InitialState state{.spin = spin, .theta0 = theta0, .phi0 = phi0, .theta_rate0 = theta_rate0,
                           .phi_rate0 = phi_rate0};
  validate(state);
  return state;
}

/// The nonlinear integrator's tolerances; None keeps the default (keys "--rtol", "--atol").
NonlinearOptions tolerances(std::optional<double> rtol, std::optional<double> atol) {
  NonlinearOptions options;
  if (rtol) options.rtol = *rtol;
  if (atol) options.atol = *atol;
  validate(options);
  return options;
}

// ---- interruption ----------------------------------------------------------------------------

/// Thrown (not a std::exception, so nothing on the way catches it) when Python has a pending
/// signal, e.g. KeyboardInterrupt from Ctrl-C or a Jupyter interrupt; the error is set.
struct Interrupted {};

/// True if Python has a pending signal (its error indicator is then set). Takes the GIL briefly;
/// called with it released.
bool signalled() {
  const py::gil_scoped_acquire gil;
  return PyErr_CheckSignals() != 0;
}

/// A nonlinear integrator's progress callback that polls signals at most every 0.1 s.
std::function<void(double)> poll_signals() {
  auto next = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [next](double) {
    const auto now = std::chrono::steady_clock::now();
    if (now < *next) return;
    *next = now + std::chrono::milliseconds(100);
    if (signalled()) throw Interrupted{};
  };
}

/// Runs `compute` with the GIL released; an interruption becomes the pending Python error.
template <class Compute>
auto without_gil(Compute&& compute) {
  try {
    const py::gil_scoped_release unlocked;
    return compute();
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
}

// ---- simulate: the models by name --------------------------------------------------------------

struct RunSettings {
  LinearMethod method = LinearMethod::Analytic;
  NonlinearOptions integrator;
};

using Runner = std::function<Trajectory(const Body&, const InitialState&, const std::vector<double>&, const RunSettings&)>;

struct SimulatedModel {
  std::string name;                       ///< SPEC name
  bool linear;                            ///< takes `method` (analytic | numeric)
  std::function<void(const Body&)> check; ///< what the model needs of the body beyond validate()
  Runner run;
};

void any_body(const Body&) {}

Runner linear_runner(LinearModelKind kind) {
  return [kind](const Body& body, const InitialState& state, const std::vector<double>& times, const RunSettings& s) {
    return simulate_linear(linear_model(kind, body), state, times, s.method);
  };
}

/// Every model simulate() knows, in SPEC order. A model is one line here.
const std::vector<SimulatedModel>& simulated_models() {
  static const std::vector<SimulatedModel> models = {
      {"first-order", true, any_body, linear_runner(LinearModelKind::FirstOrder)},
      {"body-fixed", true, any_body, linear_runner(LinearModelKind::BodyFixed)},
      {"linearized", true, any_body, linear_runner(LinearModelKind::Linearized)},
      {"nonlinear", false, any_body,
       [](const Body& b, const InitialState& s, const std::vector<double>& t, const RunSettings& o) {
         return simulate_nonlinear(b, s, t, o.integrator);
       }},
      {"lagrange-exact", false, validate_symmetric,
       [](const Body& b, const InitialState& s, const std::vector<double>& t, const RunSettings&) {
         return simulate_lagrange_exact(b, s, t);
       }},
  };
  return models;
}

std::string model_names(const char* separator) {
  std::string names;
  for (const auto& m : simulated_models()) names += (names.empty() ? "" : separator) + m.name;
  return names;
}

py::dict simulate(const Body& body, const std::string& model, double spin, double theta0, double phi0,
                  double theta_rate0, double phi_rate0, double t_end, long long samples,
                  std::optional<std::string> method, std::optional<double> rtol, std::optional<double> atol) {
  // In the command line's order: body and motion, then the command's own options.
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  const SimulatedModel* chosen = nullptr;
  for (const auto& m : simulated_models())
    if (m.name == model) chosen = &m;
  if (!chosen) throw InvalidInput("--model", "must be one of " + model_names(", "));
  chosen->check(body);
  const std::string how = method.value_or("analytic");
  if (how != "analytic" && how != "numeric") throw InvalidInput("--method", "must be analytic or numeric");
  if (!(std::isfinite(t_end) && t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
  if (samples < 2 || samples > 100'000'000) throw InvalidInput("--samples", "must be an integer in [2, 100000000]");
  if (!chosen->linear && method) throw InvalidInput("--method", "applies to the linear models only");
  RunSettings settings;
  settings.method = how == "numeric" ? LinearMethod::Numeric : LinearMethod::Analytic;
  settings.integrator = tolerances(rtol, atol);

  settings.integrator.progress = poll_signals();
  Trajectory tr = without_gil(
      [&] { return chosen->run(body, state, sample_times(t_end, static_cast<std::size_t>(samples)), settings); });
  const auto names = tr.column_names();
  py::dict out;
  std::vector<double>* base[] = {&tr.t, &tr.theta, &tr.phi, &tr.theta_rate, &tr.phi_rate};
  for (std::size_t c = 0; c < names.size(); ++c)
    out[py::str(names[c])] = to_numpy(std::move(c < 5 ? *base[c] : tr.extra[c - 5].second));
  return out;
}

// ---- stability, compare --------------------------------------------------------------------

py::object stability(const Body& body, double spin) {
  validate(body);
  motion(spin, 0, 0, 0, 0);
  return from_json(without_gil([&] { return io::stability_json(body, spin, analyse_stability(body, spin)); }));
}

py::object compare(const Body& body, double spin, double theta0, double phi0, double theta_rate0,
                   double phi_rate0, double t_end, long long samples, std::optional<double> rtol,
                   std::optional<double> atol) {
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  if (!(std::isfinite(t_end) && t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
  if (samples < 3 || samples > 100'000'000) throw InvalidInput("--samples", "must be an integer in [3, 100000000]");
  NonlinearOptions options = tolerances(rtol, atol);
  options.progress = poll_signals();
  return from_json(without_gil([&] {
    return io::comparison_json(compare_models(body, state, sample_times(t_end, static_cast<std::size_t>(samples)), options));
  }));
}

// ---- sweep ------------------------------------------------------------------------------------

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

/// f(begin, end) over [0, count) in blocks of `block`, handed out from an atomic counter to one
/// worker per core (as the core's sweep does). The calling thread, the GIL released, polls
/// Python's signals meanwhile: on Ctrl-C (a Jupyter interrupt) the workers stop at their next
/// block and Interrupted is thrown. Otherwise rethrows the first failure once all have ended.
void parallel_blocks(std::size_t count, std::size_t block, const std::function<void(std::size_t, std::size_t)>& f) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::once_flag failed;
  std::mutex mutex;
  std::condition_variable finished;
  const std::size_t threads =
      std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), (count + block - 1) / block);
  std::size_t running = threads;
  auto work = [&] {
    for (std::size_t first; !stop && (first = next.fetch_add(block)) < count;) {
      try {
        f(first, std::min(count, first + block));
      } catch (...) {
        std::call_once(failed, [&] { failure = std::current_exception(); });
        stop = true;
      }
    }
    const std::lock_guard lock(mutex);
    if (--running == 0) finished.notify_one();
  };
  bool interrupted = false;
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(work);
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) {
      lock.unlock();
      if (!interrupted && signalled()) {
        interrupted = true;
        stop = true;
      }
      lock.lock();
    }
  }
  if (interrupted) throw Interrupted{};
  if (failure) std::rethrow_exception(failure);
}

py::dict sweep(const Body& body, const py::dict& vary, double spin, double theta0, double phi0,
               double theta_rate0, double phi_rate0, bool nonlinear, double horizon, double max_tilt,
               std::optional<double> rtol, std::optional<double> atol) {
  validate(body);
  const InitialState state = motion(spin, theta0, phi0, theta_rate0, phi_rate0);
  if (vary.size() < 1 || vary.size() > 2) throw InvalidInput("--vary", "give one or two parameters");
  std::vector<VariedKey> keys;
  for (const auto& [k, v] : vary) {
    if (!py::isinstance<py::str>(k)) throw InvalidInput("--vary", "the keys must be strings (A, B, C, mass, gravity, length, spin, B/A, C/A)");
    const std::string key = k.cast<std::string>();
    if (key.find_first_of("=:") != std::string::npos) throw InvalidInput("--vary", fmt::format("unknown key '{}'", key));
    parse_sweep_axis(key + "=0:0:1");  // the command line's check of the key
    Values values;
    try {
      values = Values::ensure(v);
    } catch (const py::error_already_set&) {
    }
    if (!values || values.ndim() != 1 || values.size() < 1 || values.size() > 100'000'000)
      throw InvalidInput("--vary", fmt::format("the values of '{}' must be a 1-D array of 1 to 100000000 numbers", key));
    keys.push_back({key, std::move(values)});
  }
  SweepOptions options;
  options.nonlinear = nonlinear;
  options.horizon = horizon;
  options.max_tilt = max_tilt;
  options.integrator = tolerances(rtol, atol);

  // When every array is the command line's START:STOP:COUNT grid (bit for bit), its very calls.
  std::vector<SweepAxis> axes(keys.size());
  bool cli_grid = true;
  for (std::size_t k = 0; k < keys.size(); ++k) cli_grid = is_cli_grid(keys[k], axes[k]) && cli_grid;
  std::size_t total = 1;
  for (const auto& k : keys) total *= k.size();
  if (total > 100'000'000) throw InvalidInput("--vary", "the grid must have at most 100000000 points");
  // Every point is checked before anything is computed, as the command line does.
  without_gil([&] {
    if (cli_grid) {
      validate_sweep(body, state, axes, options);
    } else {
      validate_sweep(body, state, {}, options);
      for (std::size_t i = 0; i < total; ++i) validate_sweep(body, state, point_axes(keys, i), options);
    }
  });

  py::dict out;
  std::vector<double*> value_columns;
  for (const auto& k : keys) {
    py::array_t<double> column(static_cast<py::ssize_t>(total));
    value_columns.push_back(column.mutable_data());
    out[py::str(k.key)] = column;
  }
  const std::size_t model_count = kLinearModels.size() + (nonlinear ? 1 : 0);
  std::vector<bool*> verdict_columns;
  for (std::size_t m = 0; m < model_count; ++m) {
    py::array_t<bool> column(static_cast<py::ssize_t>(total));
    verdict_columns.push_back(column.mutable_data());
    out[py::str(m < kLinearModels.size() ? std::string(name(kLinearModels[m])) : "nonlinear")] = column;
  }

  without_gil([&] {
    std::vector<SweepVerdict> verdicts(total);
    SweepOptions one_thread = options;
    one_thread.threads = 1;  // the blocks are spread over the threads here
    if (cli_grid) {
      // The command line's own grid: the calls it makes, block by block.
      parallel_blocks(total, 16, [&](std::size_t begin, std::size_t end) {
        std::ranges::copy(sweep_verdicts(body, state, axes, one_thread, begin, end), verdicts.begin() + begin);
      });
    } else {
      // Any values: each point is a grid of one point at its exact values, judged by the same call.
      parallel_blocks(total, 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
          verdicts[i] = sweep_verdicts(body, state, point_axes(keys, i), one_thread, 0, 1)[0];
      });
    }
    for (std::size_t i = 0; i < total; ++i) {
      for (std::size_t k = 0, index = i; k < keys.size(); ++k) {
        std::size_t stride = 1;
        for (std::size_t j = k + 1; j < keys.size(); ++j) stride *= keys[j].size();
        value_columns[k][i] = keys[k].data()[index / stride % keys[k].size()];
      }
      for (std::size_t m = 0; m < kLinearModels.size(); ++m) verdict_columns[m][i] = verdicts[i].linear[m];
      if (nonlinear) verdict_columns.back()[i] = verdicts[i].nonlinear.value_or(false);
    }
  });
  return out;
}

py::array_t<double> grid_values(double start, double stop, long long count) {
  if (!std::isfinite(start) || !std::isfinite(stop)) throw InvalidInput("--vary", "START and STOP must be finite numbers");
  if (count < 1 || count > 100'000'000) throw InvalidInput("--vary", "COUNT must be an integer in [1, 100000000]");
  const SweepAxis axis{"", start, stop, static_cast<std::size_t>(count)};
  std::vector<double> values(axis.count);
  for (std::size_t i = 0; i < axis.count; ++i) values[i] = axis.value(i);
  return to_numpy(std::move(values));
}

// ---- derive -----------------------------------------------------------------------------------

#ifdef HEAVYTOP_HAVE_SYMBOLIC
void check_order(int order) {
  if (order != 1 && order != 2) throw InvalidInput("--order", "must be 1 or 2");
}

// GiNaC is not thread-safe: the GIL stays held, so derivations never run concurrently.
py::object derive(const std::string& method, const std::string& sequence, int order) {
  check_order(order);
  const auto m = symbolic::method_from_name(method);
  if (!m) throw InvalidInput("--method", "must be euler-moving, euler-fixed, euler-body or lagrange");
  const auto s = symbolic::sequence_from_name(sequence);
  if (!s) throw InvalidInput("--sequence", "must be phi-theta or theta-phi");
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

// ---- documentation ------------------------------------------------------------------------------

constexpr const char* kModuleDoc = R"doc(heavytop: the heavy top (a rigid body turning about a fixed point O in uniform gravity,
spinning fast about its axis), its approximate models, their stability and motion.

Units are SI everywhere: kg, m, s, rad (rates rad/s). The conventions are SPEC.md's:

  Fixed frame (xi, eta, zeta), zeta vertical and up. Body frame: principal axes x, y, z
  through O, z the spin axis. k = the unit vector of the spin axis, and the paper's angles are
      phi   = -asin(k_eta)   (tilt about xi)
      theta = atan2(k_xi, k_zeta)   (tilt towards xi)
  so k = (sin theta cos phi, -sin phi, cos theta cos phi). The initial state (spin w0,
  theta0, phi0, theta_rate0, phi_rate0) starts the body with its axes the columns of
  Q(phi0, theta0) and angular velocity phi_rate0 (cos theta0, 0, -sin theta0)
  + theta_rate0 (0, 1, 0) + spin k0 in the fixed frame (the linear models take
  (phi, theta, phi', theta') as given).

Models (MODELS): "first-order" (the paper's (4)), "body-fixed" (the paper's (5)), "linearized"
(the exact linearisation about the upright rotation), "nonlinear" (the full body, the truth),
"lagrange-exact" (a symmetric body, A = B, only: the nonlinear motion in closed form).

Functions return what the command line prints: stability(), compare() and derive() give
json.loads of `heavytop stability|compare|derive --format json`; simulate() and sweep() give
dicts of NumPy arrays, one per CSV column of `heavytop simulate|sweep`. Bad input raises
heavytop.InvalidInput (a ValueError) with the command line's one-line "<key>: <rule>".

    import heavytop
    top = heavytop.example_toy_top()
    heavytop.stability(top, 200.0)["models"]["linearized"]["critical_spin"]   # rad/s
    m = heavytop.simulate(top, "nonlinear", spin=200.0, theta0=0.05, t_end=1.0, samples=2001)
    m["t"], m["theta"]                                                        # s, rad
)doc";

constexpr const char* kSimulateDoc = R"doc(The motion of one model: t, theta, phi and their rates (SI units), as NumPy arrays.

The same computation as `heavytop simulate --format csv`, column for column:

    body          Body: A, B, C (kg m^2), mass (kg), length R (m), gravity (m/s^2)
    model         "first-order" | "body-fixed" | "linearized" | "nonlinear" (default)
                  | "lagrange-exact" (A = B)                                  [--model]

  Motion (keyword only):
    spin          rad/s, spin w0 about the body axis (default 0)
    theta0        rad, initial theta (tilt towards xi)
    phi0          rad, initial phi (tilt about xi)
    theta_rate0   rad/s, initial theta'
    phi_rate0     rad/s, initial phi'

  Options (keyword only):
    t_end         s, end of the simulated interval (> 0; default 10)          [--t-end]
    samples       rows, at t_i = i t_end / (samples - 1) (>= 2; default 1001)  [--samples]
    method        linear models: "analytic" (closed form, the default) |
                  "numeric" (matrix exponential); linear models only          [--method]
    rtol          nonlinear: relative tolerance per step (default 1e-12)      [--rtol]
    atol          nonlinear: absolute tolerance per step (default 1e-12)      [--atol]

Returns a dict of float64 arrays of length `samples`, in the CSV's column order:
    t (s), theta (rad), phi (rad), theta_rate (rad/s), phi_rate (rad/s),
and for "nonlinear" also energy (J), vertical_momentum (kg m^2/s, about zeta),
axial_momentum (kg m^2/s, C w3; conserved only when A == B), energy_drift,
vertical_momentum_drift, axial_momentum_drift (each minus its value at t = 0).
theta, phi are SPEC section 2's exact angles of the spin axis for every model.

The arrays are filled in C++ with the GIL released; Ctrl-C (a Jupyter interrupt) stops a
nonlinear run within 0.1 s and raises KeyboardInterrupt. Bad input raises InvalidInput (a
ValueError) naming the key as the command line does: "motion.spin: must be a finite number",
"--samples: must be an integer in [2, 100000000]"; an integrator that cannot meet its
tolerance raises RuntimeError.
)doc";

constexpr const char* kStabilityDoc = R"doc(Linear stability of the first-order, body-fixed and linearized models at spin w0.

    body   Body (SI units)
    spin   rad/s, the spin w0 about the body axis

Returns json.loads of `heavytop stability --format json` for the same input:
{"body": {...}, "spin": w0, "models": {"first-order": {"stable": bool,
"critical_spin": rad/s or None, "stable_spin_intervals": [[lo, hi or None], ...] (rad/s),
"eigenvalues": [[re, im], ...] (1/s), "frequencies": [...] (rad/s, when stable),
"reason": str}, "body-fixed": {...}, "linearized": {...}}}. The linearized model's
eigenvalues are those of its body-frame system. Bad input raises InvalidInput (ValueError).
)doc";

constexpr const char* kCompareDoc = R"doc(Every approximate model against the full nonlinear body, from one state over one horizon.

    body                      Body (SI units)
    spin, theta0, phi0,       the initial state (rad/s, rad, rad, rad/s, rad/s; keyword only,
    theta_rate0, phi_rate0    default 0)
    t_end                     s, horizon (> 0; default 10)                     [--t-end]
    samples                   samples over the horizon (>= 3; default 10001)   [--samples]
    rtol, atol                nonlinear: tolerances per step (default 1e-12)   [--rtol, --atol]

Returns json.loads of `heavytop compare --format json`: {"nonlinear": {"nutation_frequency",
"precession_rate" (rad/s), "steps", "max_relative_energy_drift"}, "models": {NAME (first-order,
body-fixed, linearized, and lagrange-exact when A = B):
{"max_angle_error", "final_angle_error" (rad, the larger of |d theta| and |d phi|),
"nutation_frequency", "precession_rate" (rad/s), "nutation_relative_error",
"precession_relative_error"}}}. Runs with the GIL released.
)doc";

constexpr const char* kSweepDoc = R"doc(A stability map: each model's verdict over a grid of one or two parameters.

The computation of `heavytop sweep --vary KEY=START:STOP:COUNT [--vary ...]`, in C++ on every
core with the GIL released.

    body        Body (SI units): the base the grid varies
    vary        {KEY: values} with one or two keys, each a body key (A, B, C, mass, gravity,
                length), "spin", or a ratio "B/A" or "C/A" (the numerator changes, the
                denominator is held at the body's value); values a 1-D array (SI units).
                The grid is the product of the arrays, the first key slowest (dict order).
  Motion (keyword only): spin (rad/s), theta0, phi0 (rad), theta_rate0, phi_rate0 (rad/s),
                the base state (default 0)
  Options (keyword only):
    nonlinear   also judge each point by a nonlinear simulation (needs a tilted start)
    horizon     s, simulated time of each nonlinear run (> 0; default 100)   [--horizon]
    max_tilt    rad, a nonlinear run is stable if its tilt stays <= this
                (default 0.5)                                                [--max-tilt]
    rtol, atol  nonlinear: tolerances per step (default 1e-12)              [--rtol, --atol]

Returns a dict, one array per CSV column, one element per grid point (row-major, the first
key slowest): each key's values (float64), then "first-order", "body-fixed", "linearized" and,
when asked, "nonlinear" (bool: stable). Reshape with .reshape(len(values1), len(values2)).

Any values are judged exactly as given. When every array is the command line's
START:STOP:COUNT grid (grid_values(start, stop, count), bit for bit) the sweep makes the
command line's own calls (heavytop::sweep_verdicts over blocks of the grid); otherwise each
point is judged by that same routine as a grid of one point. Either way the points run in
parallel, one thread per core, and the verdicts are the same at the same values. Ctrl-C (a
Jupyter interrupt) stops it within a block and raises KeyboardInterrupt.
Bad input raises InvalidInput (ValueError) with the command line's message ("--vary: ...").
)doc";

constexpr const char* kGridValuesDoc = R"doc(The values of the command line's --vary KEY=START:STOP:COUNT, bit for bit:
start + i (stop - start) / (count - 1), i = 0..count-1 (float64 array). Pass them to sweep()
to reproduce a command-line sweep exactly.
)doc";

constexpr const char* kDeriveDoc = R"doc(The paper's linear model derived symbolically (GiNaC): M q'' + G q' + K q = 0, q = (phi, theta).

    method     "euler-moving" (default) | "euler-fixed" | "euler-body" | "lagrange"
    sequence   "phi-theta" (default) | "theta-phi": the order of the small rotations
    order      1 | 2: order of smallness kept in the kinematics

Returns json.loads of `heavytop derive --method M --sequence S --order N --format json`:
{"M": [[..],[..]], "G": .., "K": .., "characteristic_polynomial": "..",
"stability_condition": ".."}, every entry a string in A, B, C, m, g, R, omega0 (and lambda),
`^` for powers (sympy reads them after ^ -> **). Bad input raises InvalidInput (ValueError).
)doc";

constexpr const char* kRotationsDoc = R"doc(The paper's small-rotation matrices to `order` (1 or 2), as `heavytop derive --rotations --format json`:
{"A1", "A2", "A3", "A1A2", "A2A1", "commutator"}, 3x3 arrays of strings in phi, theta, psi
(rows i, j, k in terms of l, m, n); commutator = A1A2 - A2A1.
)doc";

constexpr const char* kCheckDoc = R"doc(Every route and rotation sequence at `order` (1, 2, or None for both), as `heavytop derive --check --format json`:
{"rows": [{"method", "sequence", "order", "M", "G", "K", "model", "expected",
"as_expected", "why"}, ...], "all_as_expected": bool}.
)doc";

}  // namespace
}  // namespace heavytop::python

PYBIND11_MODULE(heavytop, m) {
  using namespace heavytop;
  using namespace heavytop::python;
  m.doc() = kModuleDoc;
  m.attr("__version__") = HEAVYTOP_VERSION;

  // heavytop::InvalidInput -> heavytop.InvalidInput(ValueError), with .key and .rule.
  static py::handle invalid_input =
      py::exception<InvalidInput>(m, "InvalidInput", PyExc_ValueError).release();
  invalid_input.attr("__doc__") =
      "Bad input: a ValueError whose message is the command line's '<key>: <rule>'; "
      "the attributes key and rule hold the two parts.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InvalidInput& e) {
      // The command line's spelling of the library's field names, as the tests expect.
      static const std::map<std::string, std::string> flags = {
          {"rtol", "--rtol"}, {"atol", "--atol"}, {"max_steps", "--max-steps"}, {"horizon", "--horizon"},
          {"max_tilt", "--max-tilt"}, {"vary", "--vary"}, {"step", "--step"}, {"order", "--order"}};
      const auto it = flags.find(e.key());
      const InvalidInput shown(it == flags.end() ? e.key() : it->second, e.rule());
      py::object error = invalid_input(shown.what());
      error.attr("key") = shown.key();
      error.attr("rule") = shown.rule();
      PyErr_SetObject(invalid_input.ptr(), error.ptr());
    }
  });

  py::class_<Body>(m, "Body", R"doc(A rigid body turning about a fixed point O in uniform gravity (SPEC section 1). Immutable.

    Body(A, B, C, mass, length, gravity=9.81)

A, B, C (kg m^2): principal moments of inertia about the body axes x, y, z through O; mass (kg);
length (m): R, signed distance from O to the centre of mass along z (> 0: a top on its tip,
< 0: a hanging gyroscope); gravity (m/s^2): g, acting along -zeta. mgR (N m): m g R.

Body frame: principal axes x, y, z through O, z the spin (symmetry) axis. Validated exactly as
the command line validates [body]: A, B, C, mass finite and > 0, gravity finite and >= 0,
length finite, and A + B >= C, B + C >= A, C + A >= B; else InvalidInput (a ValueError),
e.g. "body.mass: must be > 0".
)doc")
      .def(py::init([](double A, double B, double C, double mass, double length, double gravity) {
             const Body body{.A = A, .B = B, .C = C, .mass = mass, .gravity = gravity, .length = length};
             validate(body);
             return body;
           }),
           "A"_a, "B"_a, "C"_a, "mass"_a, "length"_a, "gravity"_a = 9.81,
           R"doc(A, B: kg m^2, moments of inertia about the body's transverse axes x, y through O
C: kg m^2, moment of inertia about the spin axis z through O
mass: kg
length: m, R: signed distance from O to the centre of mass along z (> 0: a top on its tip,
        < 0: a hanging gyroscope)
gravity: m/s^2, g (default 9.81), acting along -zeta)doc")
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
            const Body body{.A = t[0].cast<double>(), .B = t[1].cast<double>(), .C = t[2].cast<double>(),
                            .mass = t[3].cast<double>(), .gravity = t[5].cast<double>(), .length = t[4].cast<double>()};
            validate(body);
            return body;
          }));
  m.def("example_toy_top", &example_toy_top,
        "The built-in example (the command line's base without --config): a wooden toy top, 60 g,\n"
        "a 40 mm disc on a spindle, the centre of mass 25 mm above the tip (SI units).");
  m.def("example_motion", [] {
        const InitialState s = example_motion();
        return py::dict("spin"_a = s.spin, "theta0"_a = s.theta0, "phi0"_a = s.phi0,
                        "theta_rate0"_a = s.theta_rate0, "phi_rate0"_a = s.phi_rate0);
      },
      "The built-in example's motion as keyword arguments: spin 200 rad/s, theta0 0.05 rad, the\n"
      "rest 0. E.g. heavytop.simulate(heavytop.example_toy_top(), **heavytop.example_motion()).");

  m.def("stability", &stability, kStabilityDoc, "body"_a, "spin"_a);
  m.def("simulate", &heavytop::python::simulate, kSimulateDoc, "body"_a, "model"_a = "nonlinear", py::kw_only(), "spin"_a = 0.0,
        "theta0"_a = 0.0, "phi0"_a = 0.0, "theta_rate0"_a = 0.0, "phi_rate0"_a = 0.0, "t_end"_a = 10.0,
        "samples"_a = 1001, "method"_a = py::none(), "rtol"_a = py::none(), "atol"_a = py::none());
  m.def("compare", &compare, kCompareDoc, "body"_a, py::kw_only(), "spin"_a = 0.0, "theta0"_a = 0.0,
        "phi0"_a = 0.0, "theta_rate0"_a = 0.0, "phi_rate0"_a = 0.0, "t_end"_a = 10.0, "samples"_a = 10001,
        "rtol"_a = py::none(), "atol"_a = py::none());
  m.def("sweep", &sweep, kSweepDoc, "body"_a, "vary"_a, py::kw_only(), "spin"_a = 0.0, "theta0"_a = 0.0,
        "phi0"_a = 0.0, "theta_rate0"_a = 0.0, "phi_rate0"_a = 0.0, "nonlinear"_a = false, "horizon"_a = 100.0,
        "max_tilt"_a = 0.5, "rtol"_a = py::none(), "atol"_a = py::none());
  m.def("grid_values", &heavytop::python::grid_values, kGridValuesDoc, "start"_a, "stop"_a, "count"_a);
  m.def("derive", &derive, kDeriveDoc, "method"_a = "euler-moving", "sequence"_a = "phi-theta", "order"_a = 1);
  m.def("derive_rotations", &derive_rotations, kRotationsDoc, "order"_a = 1);
  m.def("derive_check", &derive_check, kCheckDoc, "order"_a = py::none());

#ifdef HEAVYTOP_HAVE_SYMBOLIC
  m.attr("HAS_DERIVE") = true;
#else
  m.attr("HAS_DERIVE") = false;  // built without HEAVYTOP_BUILD_SYMBOLIC (GiNaC): derive*() raise RuntimeError
#endif
  py::list models;
  for (const auto& model : simulated_models()) models.append(model.name);
  m.attr("MODELS") = py::tuple(models);
}

#include "heavytop/sweep.hpp"

#include "heavytop/batch.hpp"
#include "heavytop/dop853.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/taylor.hpp"
#include "heavytop/verdicts.hpp"

#include "heavytop/frames.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <exception>
#include <atomic>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "heavytop/stability.hpp"
#include "heavytop/units.hpp"

#include "integrators/integration.hpp"

namespace heavytop {
namespace {

constexpr std::string_view kKeys[] = {"A", "B", "C", "mass", "gravity", "length", "spin", "spin_rpm", "B/A", "C/A"};

double parse_number(std::string_view text, const char* what) {
  double value = 0.0;
#if defined(__EMSCRIPTEN__)  // its libc++ has no floating-point from_chars (the core in WebAssembly, web/)
  const std::string copy(text);
  char* stop = nullptr;
  value = copy.empty() || std::isspace(static_cast<unsigned char>(copy[0])) ? NAN : std::strtod(copy.c_str(), &stop);
  if (stop != copy.c_str() + copy.size() || !std::isfinite(value))
#else
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
#endif
    throw InvalidInput("vary", fmt::format("{} '{}' must be a finite number", what, text));
  return value;
}

// ---- The nonlinear verdict (issue 14: batched) ----

// True if the point goes to the batched Taylor integrator (batch.hpp): with auto or taylor, a
// conservative body on principal axes. Damped and general bodies, and dopri5 or dop853, go
// one point at a time (a damped one with taylor through taylor_tilt_extremes).
bool batched(const SweepOptions& o, const Body& body) {
  return (o.nonlinear_integrator == Integrator::Auto || o.nonlinear_integrator == Integrator::Taylor) && batchable(body);
}

// One point's verdict with the integrator asked for (auto: choose_integrator's for a body
// the batch does not take, i.e. dopri5), through the one dispatch of simulate.hpp.
bool sweep_tilt_verdict(const Body& body, const InitialState& state, const SweepOptions& o) {
  return !tilt_extremes(o.nonlinear_integrator, body, state, o.horizon, o.max_tilt, o.integrator).exceeded;
}

// Each verdict at the tolerance that decides it (verdicts.hpp): the same verdicts as the
// batch at the sweep's tolerance, most of them from a closed form or a loose pass.
struct SweepBatch {
  std::vector<Body> bodies;
  std::vector<InitialState> states;
  std::vector<std::size_t> slots;  // their places in the block's output
  std::vector<DecidedVerdict> results;

  void clear() { bodies.clear(), states.clear(), slots.clear(); }
  void judge(const SweepOptions& o, std::vector<SweepVerdict>& out) {
    results.resize(bodies.size());
    decided_tilt_verdicts(bodies, states, o.horizon, o.max_tilt, o.integrator, results);
    for (std::size_t k = 0; k < slots.size(); ++k) {
      out[slots[k]].nonlinear = !results[k].exceeded;
      out[slots[k]].nonlinear_tolerance = results[k].tolerance;
    }
  }
};

}  // namespace

double SweepAxis::value(std::size_t i) const {
  if (count <= 1) return start;
  return start + (stop - start) * static_cast<double>(i) / static_cast<double>(count - 1);
}

bool is_sweep_key(std::string_view key) {
  return std::find(std::begin(kKeys), std::end(kKeys), key) != std::end(kKeys);
}

std::string sweep_keys_text() {
  std::string text;
  for (std::string_view key : kKeys) text += fmt::format("{}{}", text.empty() ? "" : ", ", key);
  return text;
}

SweepAxis parse_sweep_axis(std::string_view text) {
  const auto eq = text.find('=');
  const std::string rule = "must be KEY=START:STOP:COUNT with KEY one of " + sweep_keys_text();
  if (eq == std::string_view::npos) throw InvalidInput("vary", rule);
  SweepAxis axis;
  axis.key = std::string(text.substr(0, eq));
  if (!is_sweep_key(axis.key)) throw InvalidInput("vary", fmt::format("unknown key '{}': {}", axis.key, rule));
  const std::string_view range = text.substr(eq + 1);
  const auto c1 = range.find(':'), c2 = range.find(':', c1 == std::string_view::npos ? c1 : c1 + 1);
  if (c1 == std::string_view::npos || c2 == std::string_view::npos) throw InvalidInput("vary", rule);
  axis.start = parse_number(range.substr(0, c1), "START");
  axis.stop = parse_number(range.substr(c1 + 1, c2 - c1 - 1), "STOP");
  const std::string_view count = range.substr(c2 + 1);
  long long n = 0;
  const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), n);
  if (error != std::errc() || end != count.data() + count.size() || n < 1 || n > 100'000'000)
    throw InvalidInput("vary", fmt::format("COUNT '{}' must be an integer in [1, 100000000]", count));
  axis.count = static_cast<std::size_t>(n);
  if (axis.key == "spin_rpm") {  // SPEC section 9: the grid in rpm, the sweep (and its CSV) in rad/s
    axis.key = "spin";
    axis.start = rad_per_s_from_rpm(axis.start);
    axis.stop = rad_per_s_from_rpm(axis.stop);
  }
  return axis;
}

std::size_t grid_size(const std::vector<SweepAxis>& axes) {
  std::size_t n = 1;
  for (const auto& a : axes) n *= a.count;
  return n;
}

std::vector<std::size_t> grid_indices(const std::vector<std::size_t>& counts, std::size_t index) {
  std::vector<std::size_t> indices(counts.size());
  for (std::size_t k = counts.size(); k-- > 0;) {
    indices[k] = index % counts[k];
    index /= counts[k];
  }
  return indices;
}

std::vector<double> grid_values(const std::vector<SweepAxis>& axes, std::size_t index) {
  std::vector<std::size_t> counts;
  for (const auto& a : axes) counts.push_back(a.count);
  const auto indices = grid_indices(counts, index);
  std::vector<double> values(axes.size());
  for (std::size_t k = 0; k < axes.size(); ++k) values[k] = axes[k].value(indices[k]);
  return values;
}

std::pair<double, double> realizable_ratio_range(const Body& body) {
  return {std::abs(body.C - body.A) / body.A, (body.C + body.A) / body.A};
}

void apply_grid_point(const std::vector<SweepAxis>& axes, std::size_t index, Body& body,
                      InitialState& state) {
  const Body base = body;
  const std::vector<double> values = grid_values(axes, index);
  for (std::size_t k = axes.size(); k-- > 0;) {
    const SweepAxis& a = axes[k];
    const double v = values[k];
    if (a.key == "A") body.A = v;
    else if (a.key == "B") body.B = v;
    else if (a.key == "C") body.C = v;
    else if (a.key == "mass") body.mass = v;
    else if (a.key == "gravity") body.gravity = v;
    else if (a.key == "length") body.length = v;
    else if (a.key == "spin") state.spin = v;
    else if (a.key == "B/A") body.B = v * base.A;
    else if (a.key == "C/A") body.C = v * base.A;
  }
}

bool SweepOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (!(std::isfinite(horizon) && horizon > 0.0)) return fail("horizon: must be finite and > 0");
  if (!(std::isfinite(max_tilt) && max_tilt > 0.0 && max_tilt <= M_PI)) return fail("max_tilt: must be in (0, pi] rad");
  if (!supports(nonlinear_integrator, IntegratorUse::Pivot) || !supports(nonlinear_integrator, IntegratorUse::Judging)) {
    if (why)
      *why = fmt::format("integrator: must be {} (a sweep's points are on a pivot, each judged by its run's error "
                         "control)", integrator_names(", ", " or ", {IntegratorUse::Pivot, IntegratorUse::Judging}));
    return false;
  }
  return integrator.IsValid(why);
}

void validate_sweep(const Body& base, const InitialState& base_state,
                    const std::vector<SweepAxis>& axes, const SweepOptions& options) {
  if (std::string why; !options.IsValid(&why)) {
    const auto colon = why.find(':');
    throw InvalidInput(why.substr(0, colon), why.substr(colon == std::string::npos ? 0 : colon + 2));
  }
  if (axes.size() > kMaxSweepAxes) throw InvalidInput("vary", fmt::format("give 1 to {} parameters", kMaxSweepAxes));
  for (std::size_t i = 0; i < axes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (axes[i].key == axes[j].key) throw InvalidInput("vary", fmt::format("'{}' is varied twice", axes[i].key));
  double points = 1.0;  // in floating point: the product of the counts may not fit an integer
  for (const auto& a : axes) points *= static_cast<double>(a.count);
  if (points > static_cast<double>(kMaxSweepPoints))
    throw InvalidInput("vary", fmt::format("the grid has {:g} points, more than the {} a sweep may have", points,
                                           kMaxSweepPoints));
  // Every rule of a body (positive and finite values, the triangle inequalities, a finite
  // m g R) and the range of the spin the analysis can hold are linear or monotone in each
  // varied value along an axis, and the values of an axis lie between its START and STOP, so
  // if the corners of the grid pass, every point does: 2^axes checks, not one per point.
  for (std::size_t corner = 0; corner < (std::size_t{1} << axes.size()); ++corner) {
    std::size_t i = 0;
    for (std::size_t k = 0; k < axes.size(); ++k) i = i * axes[k].count + ((corner >> k & 1) ? axes[k].count - 1 : 0);
    Body body = base;
    InitialState state = base_state;
    apply_grid_point(axes, i, body, state);
    try {
      validate(body);
      validate(state);
      for (LinearModelKind kind : kLinearModels) linear_stability(linear_model(kind, body), state.spin);
    } catch (const InvalidInput& e) {
      std::string where;
      const std::vector<double> values = grid_values(axes, i);
      for (std::size_t k = 0; k < axes.size(); ++k) where += fmt::format("{}{}={}", k ? ", " : "", axes[k].key, values[k]);
      throw InvalidInput("vary", fmt::format("at {} the body breaks {}: {}", where, e.key(), e.rule()));
    }
  }
  if (options.nonlinear) {
    const double start_tilt = tilt(base_state.theta0, base_state.phi0);
    if (start_tilt == 0.0 && base_state.theta_rate0 == 0.0 && base_state.phi_rate0 == 0.0)
      throw InvalidInput("motion.theta0", "a nonlinear sweep needs a tilted start (e.g. theta0 = 1e-3): the upright body never moves");
    if (start_tilt >= options.max_tilt)
      throw InvalidInput("max_tilt", "must exceed the initial tilt");
    // What the integrator cannot hold (the grid varies no damping: the base body's say); a damped
    // body goes to the Taylor integrator one point at a time (batchable() is false for it).
    check_integrator(options.nonlinear_integrator, base, false, true);
  }
}

StabilityMap stability_map(const std::vector<SweepAxis>& axes, bool nonlinear, std::vector<SweepVerdict> verdicts) {
  StabilityMap map{.axes = {}, .nonlinear = nonlinear, .verdicts = std::move(verdicts)};
  for (const auto& a : axes) {
    MapAxis& axis = map.axes.emplace_back(MapAxis{.key = a.key, .values = {}});
    for (std::size_t i = 0; i < a.count; ++i) axis.values.push_back(a.value(i));
  }
  return map;
}

std::size_t nearest_index(const std::vector<double>& values, double value) {
  return static_cast<std::size_t>(
      std::min_element(values.begin(), values.end(),
                       [&](double a, double b) { return std::abs(a - value) < std::abs(b - value); }) -
      values.begin());
}

StabilityMap slice(const StabilityMap& map, std::string_view key, double value) {
  const auto held = std::find_if(map.axes.begin(), map.axes.end(), [&](const MapAxis& a) { return a.key == key; });
  if (held == map.axes.end()) throw InvalidInput("slice", fmt::format("'{}' is not a varied key of the map", key));
  if (!std::isfinite(value)) throw InvalidInput("slice", fmt::format("the value of '{}' must be finite", key));
  const std::vector<double>& values = held->values;
  const std::size_t nearest = nearest_index(values, value);
  const std::size_t k = static_cast<std::size_t>(held - map.axes.begin());
  StabilityMap out{.axes = {}, .nonlinear = map.nonlinear, .verdicts = {}};
  for (std::size_t j = 0; j < map.axes.size(); ++j)
    if (j != k) out.axes.push_back(map.axes[j]);
  // Row-major: index = (outer * size_k + i_k) * inner + rest, `inner` the size of the axes after k.
  std::size_t inner = 1;
  for (std::size_t j = k + 1; j < map.axes.size(); ++j) inner *= map.axes[j].values.size();
  const std::size_t outer = map.verdicts.size() / (inner * values.size());
  out.verdicts.reserve(outer * inner);
  for (std::size_t o = 0; o < outer; ++o)
    for (std::size_t r = 0; r < inner; ++r) out.verdicts.push_back(map.verdicts[(o * values.size() + nearest) * inner + r]);
  return out;
}

std::vector<SweepVerdict> sweep_verdicts(const Body& base, const InitialState& base_state,
                                         const std::vector<SweepAxis>& axes,
                                         const SweepOptions& options, std::size_t begin,
                                         std::size_t end) {
  std::vector<SweepVerdict> out(end - begin);
  std::exception_ptr failure;
  std::once_flag failed;
  // Work is handed out in small blocks from an atomic counter; each point's verdict lands in
  // its own slot, so the result does not depend on the threads. Threads end with the call
  // (no pool left spinning while the caller writes the rows).
  std::atomic<std::size_t> next{0};
  const std::size_t cores = options.threads > 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  // A nonlinear point costs far more than the rest and is batched: blocks of up to 64 keep the
  // lanes full, but every thread gets about 8 blocks (a call may be as small as 8 points).
  const std::size_t kBlock = !options.nonlinear ? 16 : cores == 1 ? 64 : std::clamp<std::size_t>(out.size() / (8 * cores), 8, 64);
  auto work = [&] {
    SweepBatch batch;  // this block's nonlinear points that the batched Taylor integrator takes
    for (std::size_t first; (first = next.fetch_add(kBlock)) < out.size();) {
      batch.clear();
      for (std::size_t i = first; i < std::min(out.size(), first + kBlock); ++i) {
        try {
          Body body = base;
          InitialState state = base_state;
          apply_grid_point(axes, begin + i, body, state);
          SweepVerdict& v = out[i];
          for (std::size_t m = 0; m < kLinearModels.size(); ++m)
            v.linear[m] = linear_stability(linear_model(kLinearModels[m], body), state.spin).stable;
          const LyapunovVerdict lyapunov = lyapunov_stability(body, state.spin);
          v.lyapunov = lyapunov.verdict == LyapunovVerdictKind::Stable;
          v.lyapunov_certificate = lyapunov.certificate;
          if (options.nonlinear && batched(options, body)) {
            batch.bodies.push_back(body), batch.states.push_back(state), batch.slots.push_back(i);
          } else if (options.nonlinear) {
            v.nonlinear = sweep_tilt_verdict(body, state, options);
            v.nonlinear_tolerance = options.integrator.rtol;
          }
        } catch (...) {
          std::call_once(failed, [&] { failure = std::current_exception(); });
        }
      }
      try {
        batch.judge(options, out);
      } catch (...) {
        std::call_once(failed, [&] { failure = std::current_exception(); });
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>(cores, (out.size() + kBlock - 1) / kBlock);
  {
#if defined(__EMSCRIPTEN__)  // no threads in the page (web/): one worker
    (void)threads;
#else
    std::vector<std::jthread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
#endif
    work();
  }
  if (failure) std::rethrow_exception(failure);
  return out;
}

}  // namespace heavytop

#include "heavytop/batch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "heavytop/frames.hpp"
#include "heavytop/rigid_body.hpp"
#include "heavytop/taylor.hpp"

#include "integrators/batch/batch.hpp"
#include "integrators/batch/points.hpp"
#include "integrators/integration.hpp"
#include "integrators/taylor/series.hpp"

namespace heavytop {

static_assert(detail::kBatchMaxOrder == kTaylorMaxOrder, "the batch kernel's jet must hold the Taylor orders");

// ---- Helpers the kernels call (baseline code) ---------------------------------------------------

double detail::series_root(const double* s, int p, double a, double b, double fa, double fb, double h) {
  return detail::taylor::polynomial_root(s, p, a, b, fa, fb, h);  // taylor.cpp's roots
}

// The kernels' failures (batch.hpp), as the scalar Taylor integrator's.
void detail::fail_max_steps(std::size_t max_steps, double t) { fail("taylor", StepOutcome::MaxSteps, t, max_steps); }

void detail::fail_underflow(double t) { fail("taylor", StepOutcome::StepUnderflow, t); }

void detail::fail_not_finite(double t) { fail("taylor", StepOutcome::NotFinite, t); }

// ---- Instruction sets ---------------------------------------------------------------------------

bool batch_isa_supported(BatchIsa isa) {
  switch (isa) {
    case BatchIsa::Sse2: return true;  // the x86-64 baseline
#if defined(__x86_64__) || defined(__i386__)
    case BatchIsa::Avx2: return __builtin_cpu_supports("avx2");
    case BatchIsa::Avx512: return __builtin_cpu_supports("avx512f");
#else  // WebAssembly (web/): the portable kernel only
    case BatchIsa::Avx2: return false;
    case BatchIsa::Avx512: return false;
#endif
  }
  return false;
}

BatchIsa best_batch_isa() {
  static const BatchIsa best = batch_isa_supported(BatchIsa::Avx512) ? BatchIsa::Avx512
                               : batch_isa_supported(BatchIsa::Avx2) ? BatchIsa::Avx2
                                                                      : BatchIsa::Sse2;
  return best;
}

std::size_t batch_lanes(BatchIsa isa) {
  switch (isa) {
    case BatchIsa::Sse2: return 2;
    case BatchIsa::Avx2: return 4;
    case BatchIsa::Avx512: return 8;
  }
  return 1;
}

const char* name(BatchIsa isa) {
  switch (isa) {
    case BatchIsa::Sse2: return "sse2";
    case BatchIsa::Avx2: return "avx2";
    case BatchIsa::Avx512: return "avx512";
  }
  return "?";
}

bool batchable(const Body& body) noexcept { return body.damping.conservative() && !is_general(body); }

// ---- The batch ----------------------------------------------------------------------------------

detail::BatchPoint detail::batch_point(const Body& b, const RigidBodyState& x0, std::size_t index) {
  refuse_general(b, "the Taylor integrator (use dopri5 or auto)");
  refuse_damping(b, "the batched Taylor integrator");
  BatchPoint point;
  point.index = index;
  const RigidBodyVector x = to_vector(x0);
  std::copy(x.begin(), x.end(), point.x0);
  const double qw = point.x0[0], qx = point.x0[1], qy = point.x0[2], qz = point.x0[3];
  const double g1 = 2.0 * (qx * qz - qw * qy), g2 = 2.0 * (qy * qz + qw * qx);
  point.tilt0 = tilt_of_axis(g1, g2, qw * qw - qx * qx - qy * qy + qz * qz);  // as taylor.cpp's tilt_of
  point.symmetric = b.A == b.B;
  const double mgr = b.mgR();
  point.e1 = (b.B - b.C) / b.A, point.e2 = (b.C - b.A) / b.B, point.e3 = (b.A - b.B) / b.C;
  point.ka = mgr / b.A, point.kb = mgr / b.B;
  point.c_over_a = b.C / b.A;
  return point;
}

void detail::check_run(double horizon, double stop_above, const Tolerances& options, BatchIsa isa) {
  if (!batch_isa_supported(isa))
    throw InvalidInput("isa", fmt::format("this processor does not run {}", name(isa)));
  validate(options);
  if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("horizon", "must be a finite number >= 0");
  if (std::isnan(stop_above)) throw InvalidInput("max_tilt", "must be a number");
}

void detail::run_batch(const BatchPoints& points, double horizon, double stop_above, double band_low,
                       const Tolerances& options, BatchIsa isa, bool extremes, BatchResult* results) {
  check_run(horizon, stop_above, options, isa);
  BatchSettings settings{taylor_order(options, TaylorVariables::Plain), options.rtol, options.atol,
                         horizon, stop_above, options.max_steps, extremes, band_low};
#if defined(__x86_64__) || defined(__i386__)
  auto kernel = isa == BatchIsa::Avx512 ? batch_scan_avx512
                : isa == BatchIsa::Avx2 ? batch_scan_avx2
                                        : batch_scan_sse2;
#else  // WebAssembly: the portable kernel only (the wide ones are not built, batch_isa_supported)
  auto kernel = batch_scan_sse2;
#endif
  if (!points.plain.empty()) kernel(false, points.plain.data(), points.plain.size(), settings, results);
  settings.order = taylor_order(options, TaylorVariables::SpinFactored);
  if (!points.symmetric.empty()) kernel(true, points.symmetric.data(), points.symmetric.size(), settings, results);
}

TiltBand detail::tilt_band(const BatchResult& r) {
  return TiltBand{r.exceeded, r.t_end,     r.touched_low, std::acos(std::clamp(r.peak_cos, -1.0, 1.0)),
                  r.steps,    r.inverse_tilt_sum};
}

namespace {

// Every entry point: the points in grid order, validated as taylor_tilt_extremes() validates
// one; results in grid order.
std::vector<detail::BatchResult> scan(std::span<const Body> bodies, std::span<const InitialState> initials,
                                      std::size_t outputs, double horizon, double stop_above, double band_low,
                                      const Tolerances& options, BatchIsa isa, bool extremes) {
  if (bodies.size() != initials.size() || bodies.size() != outputs)
    throw InvalidInput("bodies", "bodies, initial states and results must be as many");
  detail::check_run(horizon, stop_above, options, isa);  // before any point's error
  detail::BatchPoints points;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    validate(bodies[i]);  // the body's error before its state's, as taylor_tilt_extremes()
    validate(initials[i]);
    points.add(detail::batch_point(bodies[i], initial_rigid_body_state(initials[i]), i));
  }
  std::vector<detail::BatchResult> results(bodies.size());
  detail::run_batch(points, horizon, stop_above, band_low, options, isa, extremes, results.data());
  return results;
}

}  // namespace

void batch_tilt_extremes(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                         double stop_above, const Tolerances& options, std::span<TiltExtremes> out) {
  batch_tilt_extremes(bodies, initials, horizon, stop_above, options, out, best_batch_isa());
}

void batch_tilt_extremes(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                         double stop_above, const Tolerances& options, std::span<TiltExtremes> out,
                         BatchIsa isa) {
  const auto results = scan(bodies, initials, out.size(), horizon, stop_above, 0.0, options, isa, true);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const detail::BatchResult& r = results[i];
    out[i] = TiltExtremes{};  // spin_at_end 0, as taylor_tilt_extremes leaves it
    out[i].min_tilt = r.min_tilt, out[i].t_min = r.t_min, out[i].max_tilt = r.max_tilt, out[i].t_max = r.t_max;
    out[i].t_end = r.t_end, out[i].exceeded = r.exceeded;
  }
}

void batch_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                         double stop_above, const Tolerances& options, std::span<TiltVerdict> out) {
  batch_tilt_verdicts(bodies, initials, horizon, stop_above, options, out, best_batch_isa());
}

void batch_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                         double stop_above, const Tolerances& options, std::span<TiltVerdict> out,
                         BatchIsa isa) {
  const auto results = scan(bodies, initials, out.size(), horizon, stop_above, 0.0, options, isa, false);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = TiltVerdict{results[i].exceeded, results[i].t_end};
}

void batch_tilt_bands(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                      double low, double high, const Tolerances& options, std::span<TiltBand> out) {
  batch_tilt_bands(bodies, initials, horizon, low, high, options, out, best_batch_isa());
}

void batch_tilt_bands(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                      double low, double high, const Tolerances& options, std::span<TiltBand> out,
                      BatchIsa isa) {
  if (!(low > 0.0 && low < high)) throw InvalidInput("max_tilt", "the band's low tilt must be in (0, high)");
  const auto results = scan(bodies, initials, out.size(), horizon, high, low, options, isa, false);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = detail::tilt_band(results[i]);
}

}  // namespace heavytop

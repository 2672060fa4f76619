#include "heavytop/compare.hpp"

#include <cmath>
#include <numbers>

#include "heavytop/frames.hpp"
#include "heavytop/lagrange_exact.hpp"
#include "heavytop/linear_motion.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/stability.hpp"

namespace heavytop {
namespace {

ModelComparison against(const std::string& model, Trajectory tr, const Trajectory& truth,
                        const MotionFrequencies& truth_frequencies) {
  ModelComparison c;
  c.model = model;
  const bool linear = linear_model_from_name(model).has_value();
  for (std::size_t i = 0; i < tr.size(); ++i) {
    if (linear && !(std::max(std::abs(tr.theta[i]), std::abs(tr.phi[i])) <= kDivergedAngle)) {
      c.diverged_at = tr.t[i];
      break;
    }
    const double e = std::max(std::abs(tr.theta[i] - truth.theta[i]), std::abs(tr.phi[i] - truth.phi[i]));
    c.max_angle_error = std::max(c.max_angle_error, e);
    c.final_angle_error = e;
  }
  if (c.diverged_at) {
    c.trajectory = std::move(tr);
    return c;
  }
  c.frequencies = measure_frequencies(tr);
  auto relative = [](std::optional<double> x, std::optional<double> truth) -> std::optional<double> {
    if (!x || !truth || *truth == 0.0) return std::nullopt;
    return std::abs(*x - *truth) / std::abs(*truth);
  };
  c.nutation_relative_error = relative(c.frequencies.nutation, truth_frequencies.nutation);
  c.precession_relative_error = relative(c.frequencies.precession, truth_frequencies.precession);
  c.trajectory = std::move(tr);
  return c;
}

}  // namespace

double natural_horizon(const Body& body, double spin) {
  const StabilityVerdict v = linear_stability(linear_model(LinearModelKind::FirstOrder, body), spin);
  std::vector<double> f;
  for (double x : v.frequencies)
    if (x > 0.0) f.push_back(x);
  if (v.stable && !f.empty())
    return std::min(2.0 * 2.0 * std::numbers::pi / f.front(), 40.0 * 2.0 * std::numbers::pi / f.back());
  const double scale = gravity_time(body);
  return std::isfinite(scale) ? 20.0 * scale : 10.0;
}

MotionFrequencies measure_frequencies(const Trajectory& tr) {
  const std::size_t n = tr.size();
  MotionFrequencies f;
  if (n < 3) return f;
  std::vector<double> tau(n), az(n);
  double lo = INFINITY, hi = -INFINITY;
  ContinuousAzimuth azimuth;
  for (std::size_t i = 0; i < n; ++i) {
    tau[i] = tilt(tr.theta[i], tr.phi[i]);
    az[i] = azimuth(tr.theta[i], tr.phi[i]);
    lo = std::min(lo, tau[i]);
    hi = std::max(hi, tau[i]);
  }
  std::vector<double> maxima;  // times of tilt maxima
  if (hi - lo > 1e-9 * std::max(hi, 1e-300)) {
    for (std::size_t i = 1; i + 1 < n; ++i) {
      if (!(tau[i] > tau[i - 1] && tau[i] >= tau[i + 1])) continue;
      const double h = tr.t[i + 1] - tr.t[i];
      const double curvature = tau[i - 1] - 2.0 * tau[i] + tau[i + 1];
      const double shift = curvature != 0.0 ? 0.5 * (tau[i - 1] - tau[i + 1]) / curvature : 0.0;
      maxima.push_back(tr.t[i] + shift * h);
    }
  }
  auto azimuth_at = [&](double t) {  // linear interpolation of the unwrapped azimuth
    const auto it = std::upper_bound(tr.t.begin(), tr.t.end(), t);
    const std::size_t j = std::clamp<std::size_t>(static_cast<std::size_t>(it - tr.t.begin()), 1, n - 1);
    const double w = (t - tr.t[j - 1]) / (tr.t[j] - tr.t[j - 1]);
    return az[j - 1] + w * (az[j] - az[j - 1]);
  };
  if (maxima.size() >= 2) {
    const double span = maxima.back() - maxima.front();
    f.nutation = 2.0 * std::numbers::pi * static_cast<double>(maxima.size() - 1) / span;
    if (lo > 0.0) f.precession = (azimuth_at(maxima.back()) - azimuth_at(maxima.front())) / span;
  } else if (lo > 0.0) {
    f.precession = (az.back() - az.front()) / (tr.t.back() - tr.t.front());
  }
  return f;
}

Comparison compare_models(const Body& body, const InitialState& state,
                          const std::vector<double>& times, const Tolerances& options, const Progress& progress) {
  Comparison c;
  c.nonlinear = simulate_nonlinear(body, state, times, options, &c.summary, progress);
  c.nonlinear_frequencies = measure_frequencies(c.nonlinear);
  for (LinearModelKind kind : kLinearModels) {
    const LinearModel model = linear_model(kind, body);
    // The closed form covers the undamped models; a damped one takes the matrix exponential.
    const LinearMethod method = model.damped() ? LinearMethod::Numeric : LinearMethod::Analytic;
    c.models.push_back(against(std::string(name(kind)), simulate_linear(model, state, times, method), c.nonlinear,
                               c.nonlinear_frequencies));
  }
  if (is_symmetric(body) && body.damping.conservative())
    c.models.push_back(against("lagrange-exact", simulate_lagrange_exact(body, state, times), c.nonlinear,
                               c.nonlinear_frequencies));
  return c;
}

}  // namespace heavytop

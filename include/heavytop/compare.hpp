#pragma once
/// \file
/// Every approximate model against the full nonlinear body, from one state over one horizon.

#include <optional>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The two frequencies a person sees in the axis's motion, measured from a trajectory.
struct MotionFrequencies {
  std::optional<double> nutation;    ///< rad/s, 2 pi / mean time between tilt maxima (none if the tilt is constant)
  std::optional<double> precession;  ///< rad/s, mean rate of the axis's azimuth atan2(k_eta, k_xi) over whole nutation periods
};

/// Measures the nutation and precession of a sampled motion (needs >= 2 tilt maxima for the
/// nutation; interior maxima are refined by a parabola through three samples).
MotionFrequencies measure_frequencies(const Trajectory& trajectory);

/// The most samples a comparison may have: it holds every model's whole trajectory (it
/// measures frequencies over all of it), about 200 bytes a sample.
inline constexpr std::size_t kMaxComparisonSamples = 2'000'000;

/// rad, the tilt angle beyond which a linear (small-motion) model counts as diverged.
inline constexpr double kDivergedAngle = 1.0;

/// One approximate model against `nonlinear`.
struct ModelComparison {
  std::string model;                ///< SPEC model name
  Trajectory trajectory;            ///< its motion at the common times
  double max_angle_error = 0.0;     ///< rad, max over the samples of max(|d theta|, |d phi|)
                                    ///< (up to diverged_at, when it diverged)
  double final_angle_error = 0.0;   ///< rad, the same at the last sample (meaningless if diverged)
  /// s, when a linear model's angles first passed kDivergedAngle: from there on it has left
  /// any small-motion meaning (it grows exponentially, to 1e300 and beyond), and its errors
  /// and frequencies are not reported.
  std::optional<double> diverged_at;
  MotionFrequencies frequencies;    ///< measured from its own trajectory
  std::optional<double> nutation_relative_error;    ///< |nutation - truth| / truth
  std::optional<double> precession_relative_error;  ///< |precession - truth| / |truth|
};

/// The truth and every approximate model: first-order, body-fixed, linearized, and
/// lagrange-exact when A = B (a check of the integrator: its error should be ~1e-9 rad).
struct Comparison {
  Trajectory nonlinear;                 ///< the truth
  MotionFrequencies nonlinear_frequencies;
  NonlinearSummary summary;             ///< what the integrator did
  std::vector<ModelComparison> models;  ///< in SPEC order
};

/// s, a horizon that shows a few precession periods and tens of nutation loops of `body` at
/// spin w0 (rad/s) when model (4) is stable there, else 20 gravity times (10 s without gravity).
double natural_horizon(const Body& body, double spin);

/// Runs every model from `state` at `times` (s) and compares it with `nonlinear`; `progress` is
/// the nonlinear run's.
Comparison compare_models(const Body& body, const InitialState& state,
                          const std::vector<double>& times, const Tolerances& options = {},
                          const Progress& progress = {});

}  // namespace heavytop

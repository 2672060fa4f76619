#pragma once
/// \file
/// The progress callback of a run: an argument of the run (simulate, simulate_streaming, each
/// integrator's simulate_* and tilt scan, compare_models, lifetime), never a field of its options,
/// so options stay plain values that can be copied, compared and validated; and how a run that
/// cannot go on says so (RunFailure), with how far it got.

#include <functional>
#include <stdexcept>
#include <string>

namespace heavytop {

/// Called with the simulated time (s) as a run proceeds: after each output sample, and every few
/// dozen steps between samples (every few thousand grid steps for the splitting). An empty one is
/// never called. It may throw to stop the run: simulate() then reports the exception's message as
/// its failure and keeps the samples before it; every other run lets the exception through.
using Progress = std::function<void(double t)>;

/// An error-controlled run that could not go on: more than max_steps steps, a step size lost in
/// the rounding of t (the tolerance cannot be met), or a state no longer finite. what() is the one
/// line saying which and where; reached() is the time (s) up to which the motion was computed, so
/// an answer built on the run can state the horizon it really covered.
class RunFailure : public std::runtime_error {
 public:
  RunFailure(const std::string& what, double reached) : std::runtime_error(what), reached_(reached) {}
  double reached() const noexcept { return reached_; }

 private:
  double reached_;
};

}  // namespace heavytop

#pragma once
/// \file
/// The progress callback of a run: an argument of the run (simulate, simulate_streaming, each
/// integrator's simulate_* and tilt scan, compare_models, lifetime), never a field of its options,
/// so options stay plain values that can be copied, compared and validated.

#include <functional>

namespace heavytop {

/// Called with the simulated time (s) as a run proceeds: after each output sample, and every few
/// dozen steps between samples (every few thousand grid steps for the splitting). An empty one is
/// never called. It may throw to stop the run: simulate() then reports the exception's message as
/// its failure and keeps the samples before it; every other run lets the exception through.
using Progress = std::function<void(double t)>;

}  // namespace heavytop

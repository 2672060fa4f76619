#pragma once
// The batch's points prepared once (baseline code, private to src/): batch.cpp's entry points
// and decided_tilt_verdicts (analyses/verdicts.cpp), which sorts a map's points between passes
// without copying bodies or recomputing their initial states.

#include <cstddef>
#include <vector>

#include "heavytop/batch.hpp"
#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

#include "integrators/batch/batch.hpp"

namespace heavytop::detail {

// A batch's points by set of variables (taylor.hpp's spin-factored for A == B, plain
// otherwise): each set runs in its own kernel.
struct BatchPoints {
  std::vector<BatchPoint> symmetric, plain;
  void add(const BatchPoint& p) { (p.symmetric ? symmetric : plain).push_back(p); }
  std::size_t size() const { return symmetric.size() + plain.size(); }
};

// The point of a validated `body` from the rigid-body state x0 (initial_rigid_body_state of a
// validated initial state), its result to go to results[index]. Refuses a general or damped
// body (InvalidInput) as taylor_tilt_extremes() does.
BatchPoint batch_point(const Body& body, const RigidBodyState& x0, std::size_t index);

// Refuses a bad isa, options, horizon (s, finite >= 0) or stop_above (rad, a number), as
// taylor_tilt_extremes() does.
void check_run(double horizon, double stop_above, const Tolerances& options, BatchIsa isa);

// The tilt scan of every point (results[p.index], as many as the largest index needs) with
// the Tolerances' order and steps, up to `horizon` (s) or the tilt `stop_above` (rad); the
// band below it from `band_low` (rad, 0: none; verdicts only), the extremes or the verdicts
// only, in the kernel of `isa`. Checks its run first (check_run).
void run_batch(const BatchPoints& points, double horizon, double stop_above, double band_low,
               const Tolerances& options, BatchIsa isa, bool extremes, BatchResult* results);

// The band fields of a banded result (batch_tilt_bands).
TiltBand tilt_band(const BatchResult& r);

}  // namespace heavytop::detail

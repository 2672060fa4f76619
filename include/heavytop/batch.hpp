#pragma once
/// \file
/// The nonlinear tilt question of a sweep ("does the tilt stay <= max_tilt over [0, horizon]?")
/// for many bodies at once: the Taylor-series integrator of taylor.hpp run on several bodies
/// side by side in structure-of-arrays form, one body per SIMD lane (docs/integrators.md,
/// "Batched sweeps"; the batch mode of heyoka, Biscani & Izzo 2021).
///
/// Each lane has its own step size, its own events and its own stop, and a lane that stops
/// takes the next body at once; nothing is reduced across lanes. Every operation on a lane is
/// the elementwise IEEE operation the unbatched integrator does, in the same order, with no
/// fused multiply-add, so a body's result is bit for bit the same whichever bodies share its
/// batch, whatever the lane width, and equal to taylor_tilt_extremes()'s (both built without
/// floating-point contraction, as the project builds them). A sweep's output therefore does not
/// depend on threads, chunks or MPI ranks.
///
/// Bodies with A == B take the spin-factored variables, the others the plain ones, as in
/// taylor.hpp (two groups, each batched on its own). Damped (SPEC section 6) and general
/// (SPEC section 11) bodies are not taken (batchable() is false): their torques are in
/// dopri5's equations only.

#include <cstddef>
#include <span>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The instruction sets the batch kernel is compiled for, one translation unit each; the
/// results are bit-identical on all of them.
enum class BatchIsa {
  Sse2,    ///< x86-64 baseline: 2 lanes (one 128-bit register of doubles)
  Avx2,    ///< AVX2 without FMA: 4 lanes
  Avx512,  ///< AVX-512F without FMA: 8 lanes
};

/// The widest instruction set this processor (and its operating system) runs.
BatchIsa best_batch_isa();

/// True if this processor runs `isa`.
bool batch_isa_supported(BatchIsa isa);

/// Bodies integrated side by side with `isa` (dimensionless: 2, 4 or 8).
std::size_t batch_lanes(BatchIsa isa);

/// "sse2" | "avx2" | "avx512".
const char* name(BatchIsa isa);

/// True if batch_tilt_extremes() takes `body`: conservative (SPEC section 6's torques all
/// zero, not driven) and not general (SPEC section 11).
bool batchable(const Body& body) noexcept;

/// taylor_tilt_extremes(bodies[i], initials[i], horizon, stop_above, options) into out[i] for
/// every i, the bodies integrated batch_lanes(isa) at a time with best_batch_isa() (or `isa`).
/// Each out[i] equals the unbatched call's result bit for bit (min_tilt, t_min, max_tilt,
/// t_max, t_end, exceeded; spin_at_end is left 0). Units: horizon s (finite, >= 0), stop_above
/// rad (not NaN; the tilt from the upward vertical). Throws InvalidInput with the unbatched
/// call's keys ("body.*", "motion.*", "rtol", "atol", "max_steps", "horizon", "max_tilt"),
/// "integrator" for a body that is not batchable(), "bodies" when the three spans' sizes
/// differ, "isa" for an instruction set this processor lacks; std::runtime_error
/// ("taylor: ...") as the unbatched call on max_steps, a step lost in the rounding of t, or a
/// state that stops being finite (the whole call then fails).
void batch_tilt_extremes(std::span<const Body> bodies, std::span<const InitialState> initials,
                         double horizon, double stop_above, const Tolerances& options,
                         std::span<TiltExtremes> out);
void batch_tilt_extremes(std::span<const Body> bodies, std::span<const InitialState> initials,
                         double horizon, double stop_above, const Tolerances& options,
                         std::span<TiltExtremes> out, BatchIsa isa);

/// The sweep's question alone: did the tilt pass stop_above, and when.
struct TiltVerdict {
  bool exceeded = false;  ///< the tilt passed stop_above within the horizon
  double t_end = 0.0;     ///< s, the crossing, or the horizon
};

/// batch_tilt_extremes()'s `exceeded` and `t_end` (the same bits, and so
/// taylor_tilt_extremes()'s) without the tilt's extrema, which a verdict does not need: no
/// series of d(k_zeta)/dt, no root-finding of the extrema, no tilt at each step end (a third
/// less work; the crossing is found by the same test on the same series). Same units, keys and
/// failures as batch_tilt_extremes().
void batch_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials,
                         double horizon, double stop_above, const Tolerances& options,
                         std::span<TiltVerdict> out);
void batch_tilt_verdicts(std::span<const Body> bodies, std::span<const InitialState> initials,
                         double horizon, double stop_above, const Tolerances& options,
                         std::span<TiltVerdict> out, BatchIsa isa);

/// A verdict with a band around its threshold (the sweep's loose first pass, verdicts.hpp).
struct TiltBand {
  bool exceeded = false;     ///< the tilt passed `high` (batch_tilt_verdicts' verdict at stop_above = high)
  double t_end = 0.0;        ///< s, that crossing, or the horizon (the same bits as there)
  bool touched_low = false;  ///< the tilt passed `low` at one of the points the crossing test looks at
  double peak_tilt = 0.0;    ///< rad, the largest tilt at those points (`high` once exceeded)
  std::size_t steps = 0;     ///< Taylor steps taken (dimensionless)
  /// 1/rad: the sum over the steps of 1 / (the tilt's amplitude in that step): the largest tilt
  /// at the points the crossing test looks at in the step and the step before, each taken as
  /// its chord 2 sin(tilt / 2), at most the tilt (infinite while the tilt is 0). What the steps'
  /// errors weigh relative to the motion they perturb (decided_tilt_verdicts).
  double inverse_tilt_sum = 0.0;
};

/// batch_tilt_verdicts() at stop_above = `high`, also watching a lower tilt `low` (rad, 0 <
/// low < high) and the largest tilt at the points where the crossing is tested (the 9 piece
/// ends of each step, as taylor.cpp splits it); same units, keys and failures, and the
/// verdicts are the same bits.
void batch_tilt_bands(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                      double low, double high, const Tolerances& options, std::span<TiltBand> out);
void batch_tilt_bands(std::span<const Body> bodies, std::span<const InitialState> initials, double horizon,
                      double low, double high, const Tolerances& options, std::span<TiltBand> out,
                      BatchIsa isa);

}  // namespace heavytop

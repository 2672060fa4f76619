#pragma once
// Private to batch*.cpp: what the baseline translation unit (batch.cpp) hands the kernel of
// each instruction set (batch_kernel.hpp, compiled once per set), and the out-of-line helpers
// the kernels call back. The kernels use no inline function or template shared with other
// translation units (no fmt, no std::string, no Boost): a copy compiled for AVX-512 must never
// be the one the linker keeps for baseline code.

#include <cstddef>

// No heavytop header here: they bring in Eigen, whose inline code must not be compiled for
// AVX-512 in a translation unit the baseline links against.

namespace heavytop::detail {

// kTaylorMaxOrder (taylor.hpp; batch.cpp checks they agree).
inline constexpr int kBatchMaxOrder = 24;

// TiltExtremes' fields (nonlinear.hpp) as the kernel fills them; batch.cpp copies them over.
struct BatchResult {
  double min_tilt, t_min, max_tilt, t_max, t_end;  // rad, s, rad, s, s
  bool exceeded;
  // With BatchSettings::band_low (verdicts only): the tilt passed band_low at one of the
  // steps' piece points (or its crossing of stop_above); the largest tilt at those points (rad,
  // as cos: peak_cos = min k_zeta); the steps taken.
  bool touched_low = false;
  double peak_cos = 1.0;
  std::size_t steps = 0;
  // With band_low: TiltBand::inverse_tilt_sum (1/rad).
  double inverse_tilt_sum = 0.0;
};

// One body of a batch, prepared in batch.cpp.
struct BatchPoint {
  std::size_t index;           // where its result goes
  double x0[7];                // to_vector(initial_rigid_body_state(initial)): q (w, x, y, z), w (rad/s)
  double tilt0;                // rad, the tilt of x0 (taylor.cpp's tilt_of)
  bool symmetric;              // A == B: the spin-factored variables
  // The right-hand side's coefficients, as taylor/variables.hpp's Plain and SpinFactored hold them:
  double e1, e2, e3;           // (B - C)/A, (C - A)/B, (A - B)/C (dimensionless)
  double ka, kb;               // m g R / A, m g R / B (1/s^2)
  double c_over_a;             // C / A (dimensionless)
};

struct BatchSettings {
  int order;                   // taylor_order(options)
  double rtol, atol;
  double horizon;              // s
  double stop_above;           // rad
  std::size_t max_steps;
  bool extremes;               // false: only `exceeded` and `t_end` are wanted (batch_tilt_verdicts)
  // Verdicts only: > 0 also watches this lower tilt (rad, < stop_above) and the peak (the
  // band fields of BatchResult; batch_tilt_bands). 0: off.
  double band_low = 0.0;
};

// A root of the polynomial s[0..p] on [a, b] (s(a), s(b) of opposite signs): the scalar scan's
// polynomial_root (taylor/series.hpp, to 1e-15 of the step h), compiled at the baseline.
double series_root(const double* s, int p, double a, double b, double fa, double fb, double h);

// The unbatched integrator's failures, word for word.
[[noreturn]] void fail_max_steps(std::size_t max_steps, double t);
[[noreturn]] void fail_underflow(double t);
[[noreturn]] void fail_not_finite(double t);

// The kernels: the tilt scan of points[0..count) with the spin-factored (symmetric) or the
// plain variables, results into out[points[i].index].
void batch_scan_sse2(bool symmetric, const BatchPoint* points, std::size_t count, const BatchSettings& s,
                     BatchResult* out);
void batch_scan_avx2(bool symmetric, const BatchPoint* points, std::size_t count, const BatchSettings& s,
                     BatchResult* out);
void batch_scan_avx512(bool symmetric, const BatchPoint* points, std::size_t count, const BatchSettings& s,
                       BatchResult* out);

}  // namespace heavytop::detail

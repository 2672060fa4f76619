#pragma once
/// \file
/// A measured spin decay as input (issue 18, item 4): the axial damping d_a and the dry
/// friction tau0 of SPEC section 6 fitted by nonlinear least squares (Eigen's Levenberg-
/// Marquardt, MINPACK's lmder) to a stopwatch's spins w_i at times t_i, through the law of
/// damping.hpp, C w' = -d_a w - tau0 sign(w) (SpinDecayLaw: exact for a free symmetric body,
/// A = B; C comes from the body). The spin at t = 0, w0, is fitted too unless it is known.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "heavytop/body.hpp"

namespace heavytop {

/// A measured spin decay: spin magnitudes (rad/s, >= 0) at times (s, >= 0, non-decreasing).
/// Points after dry friction has stopped the body are 0 (the law holds it there).
struct DecayData {
  std::vector<double> t;     ///< s, from the start of the stopwatch
  std::vector<double> spin;  ///< rad/s, |w.k| at t[i]
};

/// Settings of fit_spin_decay().
struct FitDecayOptions {
  /// Fit w0, the spin at t = 0, as a third parameter (a stopwatch user rarely knows it
  /// exactly); false: w0 is `spin0`.
  bool fit_spin0 = true;
  /// rad/s, the known spin at t = 0 when !fit_spin0 (finite, > 0); ignored otherwise.
  double spin0 = 0.0;
  /// Relative tolerance of the least-squares solver on the sum of squares and on the
  /// parameters (MINPACK's ftol = xtol; dimensionless), in [1e-15, 1e-3].
  double tolerance = 1e-13;
  /// Largest number of evaluations of the residuals per solver run (> 0).
  std::size_t max_evaluations = 10'000;

  /// True if every setting is in range; otherwise false, and `why` (if not null) receives a
  /// one-line "key: rule" message (key "spin0", "tolerance" or "max_evaluations").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput (key "spin0", "tolerance" or "max_evaluations") unless options.IsValid().
void validate(const FitDecayOptions& options);

/// One fitted parameter.
struct FittedParameter {
  double value = 0.0;        ///< the estimate (unit of the parameter)
  /// Its standard uncertainty (same unit): sqrt of the diagonal of s^2 (J^T J)^-1 at the
  /// optimum, s^2 = RSS / (n' - p), p the number of parameters fitted, n' the points where the
  /// data or the fitted law are above 0 (a top read as stopped where the law has stopped it
  /// carries neither noise nor information); NaN when J^T J is singular (the data do not
  /// determine the parameters) or n' <= p. 0 for a parameter not fitted.
  /// For a parameter held at its bound 0 it is the spread it would have if it were free
  /// (from the Jacobian of every parameter at the optimum), a scale for how large it may be.
  double uncertainty = 0.0;
  bool fitted = true;        ///< false: given, not fitted (w0 with !fit_spin0)
  /// True if the data prefer a value below the bound 0 and the estimate is held at 0 (the
  /// constrained least-squares optimum; the parameter is then not identified from the data).
  bool at_bound = false;
};

/// What fit_spin_decay() did (Ceres style: what happened, not only the answer).
struct FitDecaySummary {
  bool converged = false;          ///< the solver met its tolerances (or double precision)
  std::string termination;         ///< one line: why the solver stopped
  std::size_t solver_runs = 0;     ///< solver runs: one per set of parameters held at 0
  std::size_t evaluations = 0;     ///< residual evaluations, every run
  std::size_t jacobian_evaluations = 0;  ///< Jacobian evaluations, every run
  /// One line each: a parameter at its bound or within its uncertainty of 0, parameters
  /// strongly correlated, a singular Jacobian, A != B (the law is then approximate), ...
  std::vector<std::string> warnings;

  /// One line: convergence, runs, evaluations and the number of warnings.
  std::string BriefReport() const;
};

/// The result of fit_spin_decay().
struct DecayFit {
  FittedParameter axial;     ///< d_a, N m s (>= 0)
  FittedParameter friction;  ///< tau0, N m (>= 0)
  FittedParameter spin0;     ///< w0, rad/s: the spin at t = 0
  /// Correlation coefficient of d_a and tau0 (dimensionless, in [-1, 1]) from the covariance
  /// of every parameter at the optimum; NaN when that covariance is singular. Near -1 the data
  /// cannot tell viscous drag from dry friction (a decay seen over too narrow a range of spins).
  double correlation = 0.0;
  double rms_residual = 0.0;  ///< rad/s, sqrt(RSS / n), the residuals through SpinDecayLaw
  std::size_t points = 0;     ///< n, the number of data points
  double C = 0.0;             ///< kg m^2, the body's axial moment the fit assumed
  /// s, when the fitted dry friction stops the spin (SpinDecayLaw::stop_time); nullopt
  /// without friction.
  std::optional<double> stop_time;
  FitDecaySummary summary;
};

/// Fits d_a, tau0 (both >= 0) and, with options.fit_spin0, w0 to `data` by unweighted least
/// squares on the spin (rad/s), the model SpinDecayLaw{body.C, d_a, tau0}.spin(w0, t).
/// Bounds: every combination of d_a and tau0 free or held at 0 is solved (Levenberg-Marquardt,
/// the law continued analytically to negative coefficients so the solver is unconstrained),
/// and the feasible one with the smallest sum of squares is the constrained optimum.
/// Throws InvalidInput: key "data" (sizes differ; fewer than p + 1 points, p the number of
/// parameters fitted; a time or spin not finite; t < 0 or decreasing; spin < 0; every spin 0;
/// no time span), a body rule (validate(body)), or an option's key. Numerical trouble is
/// reported in the summary (converged = false, warnings), not thrown.
DecayFit fit_spin_decay(const Body& body, const DecayData& data, const FitDecayOptions& options = {});

}  // namespace heavytop

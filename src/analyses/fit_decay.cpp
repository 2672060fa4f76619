#include "heavytop/fit_decay.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>
#include <fmt/format.h>

#include "integrators/integration.hpp"
#include "heavytop/damping.hpp"

namespace heavytop {
namespace {

// The solver works in dimensionless units, so that its parameters, residuals and Jacobian
// columns are all of order 1 whatever the body (C = 1e-5 or 1e3 kg m^2) and the data's units:
// tau = t / T, y = w / W (T the last time, W the largest spin), and
//   a = d_a T / C,   b = tau0 T / (C W),   c = w0 / W.
// The law C w' = -d_a w - tau0 (w > 0) is then y' = -a y - b, solved by
//   g(tau) = c exp(-a tau) - b tau phi(a tau),   phi(x) = (1 - exp(-x)) / x,
// SpinDecayLaw's closed form, here also for a < 0 or b < 0 (the analytic continuation), so
// that Levenberg-Marquardt may step outside the bounds and a negative optimum shows that a
// bound is active. For c > 0 the spin stops where g first reaches 0 and stays there (dry
// friction holds it): g < 0 only after a crossing with b > 0, so the model is max(g, 0).
constexpr int kA = 0, kB = 1, kC = 2;
using Params = std::array<double, 3>;

double phi(double x) { return x == 0.0 ? 1.0 : -std::expm1(-x) / x; }

// phi'(x) = (exp(-x) - phi(x)) / x, by its series sum_{k>=1} (-1)^k k x^(k-1) / (k+1)! where
// the difference cancels (|x| < 0.5: 24 terms reach 1e-30).
double phi_prime(double x) {
  if (std::abs(x) >= 0.5) return (std::exp(-x) - phi(x)) / x;
  double sum = 0.0, power = 1.0, factorial = 2.0;  // x^(k-1), (k+1)!
  for (int k = 1; k <= 24; ++k) {
    sum += (k % 2 ? -1.0 : 1.0) * k * power / factorial;
    power *= x;
    factorial *= k + 2;
  }
  return sum;
}

// The model y(tau) and its gradient in (a, b, c).
struct ModelPoint {
  double y;
  Params gradient;
};

ModelPoint model(const Params& p, double tau) {
  const double x = p[kA] * tau, e = std::exp(-x), f = phi(x);
  const double g = p[kC] * e - p[kB] * tau * f;
  if (!(g > 0.0)) return {0.0, {0.0, 0.0, 0.0}};  // stopped: held at 0, whatever the parameters
  return {g, {-p[kC] * tau * e - p[kB] * tau * tau * phi_prime(x), -tau * f, e}};
}

// The least-squares problem of one solver run: the parameters with free[j] are the solver's
// unknowns, the others held at `fixed`.
struct Problem {
  std::vector<double> tau, y;
  std::array<bool, 3> free{};
  Params fixed{};

  int unknowns() const { return static_cast<int>(std::count(free.begin(), free.end(), true)); }
  Params full(const Eigen::VectorXd& x) const {
    Params p = fixed;
    for (int j = 0, i = 0; j < 3; ++j)
      if (free[j]) p[j] = x[i++];
    return p;
  }
};

// Eigen's MINPACK functor: residuals model - data, analytic Jacobian (lmder). A value that is
// not finite (exp overflowing far outside any sensible decay) stops the run (UserAsked).
struct Residuals {
  const Problem& problem;
  int inputs() const { return problem.unknowns(); }
  int values() const { return static_cast<int>(problem.y.size()); }

  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    const Params p = problem.full(x);
    for (std::size_t i = 0; i < problem.y.size(); ++i) {
      r[static_cast<Eigen::Index>(i)] = model(p, problem.tau[i]).y - problem.y[i];
      if (!std::isfinite(r[static_cast<Eigen::Index>(i)])) return -1;
    }
    return 0;
  }
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jacobian) const {
    const Params p = problem.full(x);
    for (std::size_t i = 0; i < problem.y.size(); ++i) {
      const ModelPoint m = model(p, problem.tau[i]);
      for (int j = 0, col = 0; j < 3; ++j)
        if (problem.free[j]) {
          jacobian(static_cast<Eigen::Index>(i), col++) = m.gradient[j];
          if (!std::isfinite(m.gradient[j])) return -1;
        }
    }
    return 0;
  }
};

// The Jacobian of the parameters marked in `columns`, at p (n x count).
Eigen::MatrixXd jacobian_of(const Problem& problem, const Params& p, const std::array<bool, 3>& columns) {
  const int count = static_cast<int>(std::count(columns.begin(), columns.end(), true));
  Eigen::MatrixXd J(static_cast<Eigen::Index>(problem.y.size()), count);
  for (std::size_t i = 0; i < problem.y.size(); ++i) {
    const ModelPoint m = model(p, problem.tau[i]);
    for (int j = 0, col = 0; j < 3; ++j)
      if (columns[j]) J(static_cast<Eigen::Index>(i), col++) = m.gradient[j];
  }
  return J;
}

// (J^T J)^-1 by the SVD of J (better conditioned than forming J^T J); nullopt when J is
// numerically rank-deficient (a singular value below 1e-10 of the largest: the dimensionless
// columns are of order 1, so this is a parameter the data do not determine).
std::optional<Eigen::MatrixXd> inverse_normal_matrix(const Eigen::MatrixXd& J) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  if (s.size() == 0 || !(s.minCoeff() > 1e-10 * s.maxCoeff())) return std::nullopt;
  const Eigen::MatrixXd V = svd.matrixV();
  return V * s.cwiseInverse().cwiseAbs2().asDiagonal() * V.transpose();
}

// A starting point from the law in integral form, linear in its unknowns: over the points
// before the spin first reads 0, y_i = y_s - a int_{tau_0}^{tau_i} y - b (tau_i - tau_0)
// (trapezoid rule), solved for the free ones of (y_s, a, b) by least squares (QR), then
// carried back to tau = 0 for c. Exact for dense noiseless data up to the quadrature error.
Params starting_point(const Problem& problem, bool fit_c) {
  std::size_t m = 0;
  while (m < problem.y.size() && problem.y[m] > 0.0) ++m;
  Params p = problem.fixed;
  const int unknowns = 1 + problem.free[kA] + problem.free[kB];
  if (m >= static_cast<std::size_t>(unknowns) + 1) {
    Eigen::MatrixXd M(static_cast<Eigen::Index>(m), unknowns);
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(m));
    double integral = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      if (i > 0) integral += 0.5 * (problem.y[i] + problem.y[i - 1]) * (problem.tau[i] - problem.tau[i - 1]);
      int col = 0;
      const auto row = static_cast<Eigen::Index>(i);
      M(row, col++) = 1.0;
      if (problem.free[kA]) M(row, col++) = -integral;
      if (problem.free[kB]) M(row, col++) = -(problem.tau[i] - problem.tau[0]);
      rhs[row] = problem.y[i];
    }
    const Eigen::VectorXd z = M.colPivHouseholderQr().solve(rhs);
    int col = 1;
    if (problem.free[kA]) p[kA] = z[col++];
    if (problem.free[kB]) p[kB] = z[col++];
    if (fit_c) {
      const double tau0 = problem.tau[0], x = p[kA] * tau0;
      p[kC] = z[0] * std::exp(x) + p[kB] * tau0 * phi(-x);  // the law run back from tau_0 to 0
    }
    if (z.allFinite() && std::isfinite(p[kC])) return p;
    p = problem.fixed;
  }
  // Too few points before the stop for that: a straight line through the first and the last
  // positive point.
  const std::size_t last = m > 1 ? m - 1 : 0;
  const double span = problem.tau[last] - problem.tau[0];
  if (problem.free[kB]) p[kB] = span > 0.0 ? (problem.y[0] - problem.y[last]) / span : 1.0;
  if (fit_c) p[kC] = problem.y[0] + p[kB] * problem.tau[0];
  return p;
}

struct Run {
  Params p{};
  double rss = 0.0;
  bool feasible = false;
  bool converged = false;
  std::string termination;
};

std::string termination_of(int status) {
  using namespace Eigen::LevenbergMarquardtSpace;
  switch (status) {
    case RelativeReductionTooSmall: return "converged: relative reduction of the sum of squares below the tolerance";
    case RelativeErrorTooSmall: return "converged: relative change of the parameters below the tolerance";
    case RelativeErrorAndReductionTooSmall: return "converged: sum of squares and parameters both within the tolerance";
    case CosinusTooSmall: return "converged: the residuals are orthogonal to the Jacobian (a zero gradient)";
    case FtolTooSmall:
    case XtolTooSmall:
    case GtolTooSmall: return "converged to double precision (no further reduction possible)";
    case TooManyFunctionEvaluation: return "not converged: max_evaluations reached";
    case UserAsked: return "not converged: the model overflowed (a decay far outside the data's scale)";
    default: return "not converged: the solver refused its input";
  }
}

bool converged_status(int status) {
  using namespace Eigen::LevenbergMarquardtSpace;
  return (status >= RelativeReductionTooSmall && status <= CosinusTooSmall) ||
         (status >= FtolTooSmall && status <= GtolTooSmall);
}

Run solve(Problem& problem, bool fit_c, const FitDecayOptions& options, FitDecaySummary& summary) {
  Run run;
  const Params start = starting_point(problem, fit_c);
  Eigen::VectorXd x(problem.unknowns());
  for (int j = 0, i = 0; j < 3; ++j)
    if (problem.free[j]) x[i++] = start[j];
  Residuals residuals{problem};
  Eigen::LevenbergMarquardt<Residuals> lm(residuals);
  lm.parameters.ftol = options.tolerance;
  lm.parameters.xtol = options.tolerance;
  lm.parameters.maxfev = static_cast<Eigen::DenseIndex>(options.max_evaluations);
  const int status = lm.minimize(x);
  summary.solver_runs += 1;
  summary.evaluations += static_cast<std::size_t>(lm.nfev);
  summary.jacobian_evaluations += static_cast<std::size_t>(lm.njev);
  run.p = problem.full(x);
  Eigen::VectorXd r(residuals.values());
  run.converged = converged_status(status) && residuals(x, r) == 0;
  run.rss = run.converged ? r.squaredNorm() : std::numeric_limits<double>::infinity();
  run.feasible = run.p[kA] >= 0.0 && run.p[kB] >= 0.0;
  run.termination = termination_of(status);
  return run;
}

detail::Violation first_violation(const FitDecayOptions& o) {
  if (!o.fit_spin0 && !(std::isfinite(o.spin0) && o.spin0 > 0.0))
    return std::pair{"spin0", "must be a finite number > 0 (the known spin at t = 0, rad/s)"};
  if (!(std::isfinite(o.tolerance) && o.tolerance >= 1e-15 && o.tolerance <= 1e-3))
    return std::pair{"tolerance", "must be a finite number in [1e-15, 1e-3]"};
  if (o.max_evaluations == 0) return std::pair{"max_evaluations", "must be > 0"};
  return std::nullopt;
}

void validate_data(const DecayData& data, std::size_t parameters) {
  if (data.t.size() != data.spin.size())
    throw InvalidInput("data", fmt::format("{} times but {} spins", data.t.size(), data.spin.size()));
  if (data.t.size() < parameters + 1)
    throw InvalidInput("data", fmt::format("needs at least {} points to fit {} parameters and estimate their "
                                           "uncertainties (has {})",
                                           parameters + 1, parameters, data.t.size()));
  double previous = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < data.t.size(); ++i) {
    const double t = data.t[i], w = data.spin[i];
    if (!std::isfinite(t) || !std::isfinite(w))
      throw InvalidInput("data", fmt::format("point {}: t and spin must be finite numbers", i));
    if (t < previous) throw InvalidInput("data", fmt::format("point {}: t must be >= 0 and non-decreasing", i));
    if (w < 0.0) throw InvalidInput("data", fmt::format("point {}: spin must be >= 0 (its magnitude)", i));
    previous = t;
    largest = std::max(largest, w);
  }
  if (!(data.t.back() > data.t.front()))
    throw InvalidInput("data", "the times must span an interval (the first and the last differ)");
  if (!(largest > 0.0)) throw InvalidInput("data", "every spin is 0: there is no decay to fit");
}

}  // namespace

bool FitDecayOptions::IsValid(std::string* why) const { return detail::is_valid(first_violation(*this), why); }

void validate(const FitDecayOptions& options) { detail::throw_if_invalid(first_violation(options)); }

std::string FitDecaySummary::BriefReport() const {
  return fmt::format("fit-decay: {}; {} solver runs, {} evaluations, {} Jacobians; {} warnings",
                     converged ? "converged" : "NOT converged", solver_runs, evaluations, jacobian_evaluations,
                     warnings.size());
}

DecayFit fit_spin_decay(const Body& body, const DecayData& data, const FitDecayOptions& options) {
  validate(body);
  refuse_general(body, "fit-decay");
  validate(options);
  const bool fit_c = options.fit_spin0;
  validate_data(data, fit_c ? 3 : 2);

  const double T = data.t.back(), W = *std::max_element(data.spin.begin(), data.spin.end());
  Problem problem;
  for (std::size_t i = 0; i < data.t.size(); ++i) {
    problem.tau.push_back(data.t[i] / T);
    problem.y.push_back(data.spin[i] / W);
  }
  const std::array<bool, 3> all{true, true, fit_c};
  problem.fixed = {0.0, 0.0, fit_c ? 0.0 : options.spin0 / W};

  // The bounds a, b >= 0: each of the four combinations of a and b free or held at 0; the
  // feasible converged run with the least sum of squares is the constrained optimum.
  const std::size_t n = data.t.size();
  DecayFit fit;
  Run best;
  best.rss = std::numeric_limits<double>::infinity();
  std::array<bool, 3> best_free{};
  std::string last_termination;
  for (const auto& [free_a, free_b] : {std::pair{true, true}, {false, true}, {true, false}, {false, false}}) {
    problem.free = {free_a, free_b, fit_c};
    Run run;
    if (problem.unknowns() == 0) {  // w0 known and both held: nothing to solve, a constant spin
      Eigen::VectorXd r(static_cast<Eigen::Index>(n)), none;
      Residuals{problem}(none, r);
      run = {problem.fixed, r.squaredNorm(), true, true, "nothing to fit: w0 known, axial and friction 0"};
    } else {
      run = solve(problem, fit_c, options, fit.summary);
    }
    last_termination = run.termination;
    if (run.feasible && run.converged && run.rss < best.rss) {
      best = run;
      best_free = problem.free;
    }
  }
  auto& warnings = fit.summary.warnings;
  fit.summary.converged = std::isfinite(best.rss);
  if (!fit.summary.converged) {  // nothing usable: say why the last run stopped
    fit.summary.termination = last_termination;
    best.p = problem.fixed;
    best_free = {false, false, false};
    warnings.push_back("the least-squares solver did not converge: the values are not a fit");
  } else {
    fit.summary.termination = best.termination;
  }
  problem.free = best_free;

  // Uncertainties: s^2 (J^T J)^-1 over the parameters fitted; a parameter held at its bound
  // gets its spread from the covariance of every parameter at the optimum.
  // The degrees of freedom count only the points that say something: a stopped top read as 0
  // where the law has stopped it too has neither a residual nor a Jacobian row (no noise, no
  // information); counting them would shrink s^2 (by 20% where 12 of 61 points read 0 after the stop).
  const int p_fitted = problem.unknowns();
  std::size_t informative = 0;
  for (std::size_t i = 0; i < n; ++i) informative += problem.y[i] > 0.0 || model(best.p, problem.tau[i]).y > 0.0;
  const auto p_count = static_cast<std::size_t>(p_fitted);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double s2 = p_fitted == 0 ? 0.0 : informative > p_count ? best.rss / static_cast<double>(informative - p_count) : nan;
  if (fit.summary.converged && p_fitted > 0 && !(informative > p_count))
    warnings.push_back(fmt::format("only {} points before the spin stops, for {} parameters: no uncertainties",
                                   informative, p_fitted));
  const auto fitted_inverse = p_fitted > 0 ? inverse_normal_matrix(jacobian_of(problem, best.p, best_free))
                                           : std::optional<Eigen::MatrixXd>(Eigen::MatrixXd());
  const auto all_inverse = inverse_normal_matrix(jacobian_of(problem, best.p, all));
  std::array<double, 3> sigma{nan, nan, 0.0};
  for (int j = 0, i = 0, k = 0; j < 3; ++j) {
    if (best_free[j]) {
      if (fitted_inverse) sigma[j] = std::sqrt(s2 * (*fitted_inverse)(i, i));
      ++i;
    } else if (all[j] && fit.summary.converged) {
      if (all_inverse) sigma[j] = std::sqrt(s2 * (*all_inverse)(k, k));
    }
    if (all[j]) ++k;
  }
  fit.correlation = all_inverse ? (*all_inverse)(kA, kB) / std::sqrt((*all_inverse)(kA, kA) * (*all_inverse)(kB, kB))
                                : nan;

  // Back to SI units.
  const double C = body.C;
  const std::array<double, 3> scale{C / T, C * W / T, W};
  auto parameter = [&](int j) {
    FittedParameter out;
    out.value = best_free[j] ? best.p[j] * scale[j] : (j == kC ? (fit_c ? best.p[j] * scale[j] : options.spin0) : 0.0);
    out.uncertainty = sigma[j] * scale[j];
    out.fitted = all[j];
    out.at_bound = j != kC && fit.summary.converged && !best_free[j];
    return out;
  };
  fit.axial = parameter(kA);
  fit.friction = parameter(kB);
  fit.spin0 = parameter(kC);
  fit.points = n;
  fit.C = C;

  // The residuals through the physical law itself (one place for it: damping.hpp).
  const SpinDecayLaw law{C, fit.axial.value, fit.friction.value};
  // Scaled by the largest residual: r^2 overflows a double for spins near 1e300.
  std::vector<double> residual(n);
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    residual[i] = law.spin(fit.spin0.value, data.t[i]) - data.spin[i];
    largest = std::max(largest, std::abs(residual[i]));
  }
  double rss = 0.0;
  if (largest > 0.0 && std::isfinite(largest))
    for (double r : residual) rss += (r / largest) * (r / largest);
  fit.rms_residual = std::isfinite(largest) ? largest * std::sqrt(rss / static_cast<double>(n)) : largest;
  fit.stop_time = law.stop_time(fit.spin0.value);

  // What the user should know about these numbers.
  if (!is_symmetric(body))
    warnings.push_back("the law is exact for a symmetric body (A = B); for this one (A != B) it neglects the "
                       "torque (A - B) w1 w2 on the spin, small only while the axis stays near upright");
  if (body.damping.driven)
    warnings.push_back("the body is driven (a motor holds its spin); the fit describes a free spin-down, with "
                       "the motor off");
  if (!fit.summary.converged) return fit;
  if (fit.axial.value == 0.0 && fit.friction.value == 0.0) {
    warnings.push_back("axial and friction are both 0: the data show no decay");
  } else {
    if (fit.axial.at_bound)
      warnings.push_back("axial is held at its bound 0 (the data prefer a negative value): no viscous drag is "
                         "seen, the decay is linear in time (dry friction alone); axial is not identified");
    if (fit.friction.at_bound)
      warnings.push_back("friction is held at its bound 0 (the data prefer a negative value): no dry friction is "
                         "seen, the decay is exponential (viscous drag alone); friction is not identified");
  }
  const auto negligible = [&](const FittedParameter& q, const char* name, const char* unit) {
    if (!q.at_bound && std::isfinite(q.uncertainty) && q.value < 2.0 * q.uncertainty)
      warnings.push_back(fmt::format("{} = {:.3g} +- {:.2g} {} is within 2 uncertainties of 0: the data do not "
                                     "show it clearly",
                                     name, q.value, q.uncertainty, unit));
  };
  negligible(fit.axial, "axial", "N m s");
  negligible(fit.friction, "friction", "N m");
  if (!fitted_inverse || !all_inverse)
    warnings.push_back("the Jacobian is singular at the optimum: the data do not determine every parameter "
                       "(uncertainties shown as NaN/null)");
  else if (const double worst = std::max(fit.axial.uncertainty / fit.axial.value,
                                         fit.friction.uncertainty / fit.friction.value);
           !fit.axial.at_bound && !fit.friction.at_bound && std::abs(fit.correlation) > 0.99 && worst > 0.2)
    // The two torques are always correlated (both slow the spin; r near -0.99 even for a record
    // down to the stop); it matters when it leaves one of them poorly known.
    warnings.push_back(fmt::format("axial and friction are strongly correlated (r = {:.4f}) and one is known to "
                                   "only {:.0f}%: the data hardly separate viscous drag from dry friction; a record "
                                   "over a wider range of spins would",
                                   fit.correlation, 100.0 * worst));
  if (!(fit.spin0.value > 0.0)) warnings.push_back("the fitted spin at t = 0 is not > 0: the data do not look like a decay");
  if (fit_c && data.t.front() > 0.1 * (data.t.back() - data.t.front()))
    warnings.push_back(fmt::format("spin0 is the spin extrapolated back to t = 0, {:g} s before the first point; "
                                   "shift the times to start at 0 if that is not meant",
                                   data.t.front()));
  return fit;
}

}  // namespace heavytop

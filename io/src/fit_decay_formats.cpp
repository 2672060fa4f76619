// The forms of fit_spin_decay()'s result (formats.hpp): JSON for scripts, text for people
// ending with the [damping] section to paste.
#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "heavytop/io/formats.hpp"

namespace heavytop::io {
namespace {

using Json = nlohmann::ordered_json;

Json finite_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

Json parameter_json(const FittedParameter& p) {
  return {{"value", p.value}, {"uncertainty", finite_or_null(p.uncertainty)}, {"fitted", p.fitted},
          {"at_bound", p.at_bound}};
}

// "2.013e-07 +- 3.1e-09", "0 (held at its bound; +- 4e-09 if free)", "200 (given)".
std::string with_uncertainty(const FittedParameter& p) {
  const std::string sigma = std::isfinite(p.uncertainty) ? fmt::format("{:.2g}", p.uncertainty) : "?";
  if (!p.fitted) return fmt::format("{:.6g} (given)", p.value);
  if (p.at_bound) return fmt::format("0 (held at its bound; +- {} if it were free)", sigma);
  return fmt::format("{:.5g} +- {}", p.value, sigma);
}

}  // namespace

std::string fit_decay_json(const DecayFit& fit) {
  Json j;
  j["axial"] = parameter_json(fit.axial);
  j["friction"] = parameter_json(fit.friction);
  j["spin0"] = parameter_json(fit.spin0);
  j["rms_residual"] = fit.rms_residual;
  j["points"] = fit.points;
  j["converged"] = fit.summary.converged;
  j["correlation"] = finite_or_null(fit.correlation);
  j["C"] = fit.C;
  j["stop_time"] = fit.stop_time ? Json(*fit.stop_time) : Json(nullptr);
  j["termination"] = fit.summary.termination;
  j["warnings"] = fit.summary.warnings;
  return j.dump(2) + "\n";
}

std::string fit_decay_text(const DecayFit& fit, const Damping& configured) {
  std::ostringstream out;
  out << fmt::format("Spin decay fitted to {} points (C = {:g} kg m^2 from the body):\n", fit.points, fit.C);
  out << fmt::format("  axial damping  d_a  = {} N m s\n", with_uncertainty(fit.axial));
  out << fmt::format("  dry friction   tau0 = {} N m\n", with_uncertainty(fit.friction));
  out << fmt::format("  spin at t = 0  w0   = {} rad/s ({:.0f} rpm)\n", with_uncertainty(fit.spin0),
                     fit.spin0.value * 30.0 / std::numbers::pi);
  out << fmt::format("  residual RMS {:.3g} rad/s; correlation of d_a and tau0 {}; ", fit.rms_residual,
                     std::isfinite(fit.correlation) ? fmt::format("{:.3f}", fit.correlation) : "undetermined");
  out << (fit.stop_time ? fmt::format("the spin stops at t = {:.4g} s\n", *fit.stop_time)
                        : std::string("the spin never stops (no dry friction)\n"));
  out << fmt::format("  solver: {} ({} runs, {} evaluations)\n", fit.summary.termination, fit.summary.solver_runs,
                     fit.summary.evaluations);
  for (const std::string& w : fit.summary.warnings) out << "warning: " << w << "\n";
  out << "Assumed: the law C w' = -d_a w - tau0 sign(w) of a free spin (no motor) of a symmetric body (A = B), "
         "C from the body, unweighted least squares on the spin.\n";
  if (!fit.summary.converged) {
    out << "No [damping] section: the fit did not converge.\n";
    return out.str();
  }
  out << "\n# Paste into the configuration:\n[damping]\n";
  out << "transverse = " << number(configured.transverse) << "\n";
  out << "axial = " << number(fit.axial.value) << "\n";
  out << "friction = " << number(fit.friction.value) << "\n";
  return out.str();
}

}  // namespace heavytop::io

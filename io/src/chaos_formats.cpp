// The forms of the chaos command's results (chaos_formats.hpp): SPEC section 17's JSON, its
// sentence, the Poincare section's CSV.
#include "heavytop/io/chaos_formats.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "heavytop/io/formats.hpp"

namespace heavytop::io {
namespace {

using Json = nlohmann::ordered_json;

Json finite_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

// "1e-15", "2.5e-07", "0.01": the precision as people write it.
std::string short_number(double x) { return fmt::format("{:.3g}", x); }

// "1196", "12.3", "0.05": a time in s, whole seconds from 100 s on.
std::string seconds(double t) { return t >= 100.0 ? fmt::format("{:.0f}", t) : fmt::format("{:.3g}", t); }

}  // namespace

std::string chaos_json(const ChaosResult& r) {
  Json j;
  j["lyapunov_exponent"] = finite_or_null(r.lyapunov_exponent);
  j["lyapunov_error"] = finite_or_null(r.lyapunov_error);
  Json history = Json::array();
  for (const auto& row : r.history) history.push_back(Json::array({row[0], finite_or_null(row[1])}));
  j["history"] = std::move(history);
  Json spectrum = Json::array();
  for (double l : r.spectrum) spectrum.push_back(finite_or_null(l));
  j["spectrum"] = std::move(spectrum);
  j["megno"] = finite_or_null(r.megno);
  j["prediction_horizon"] = r.prediction_horizon ? finite_or_null(*r.prediction_horizon) : Json(nullptr);
  j["precision"] = r.precision;
  j["chaotic"] = r.chaotic;
  return j.dump(2) + "\n";
}

std::string chaos_text(const ChaosResult& r) {
  std::string out;
  if (r.chaotic) {
    const double horizon = r.prediction_horizon.value_or(0.0);
    out = fmt::format("Chaotic: the largest Lyapunov exponent is {:.3g} +- {:.2g} 1/s; a start known to {} is "
                      "predictable to 1 % for the first {} s{}.\n",
                      r.lyapunov_exponent, r.lyapunov_error, short_number(r.precision), seconds(horizon),
                      horizon == 0.0 ? " (not even at the start: it is known to worse than 1 %)" : "");
  } else {
    // Each of SPEC's two conditions that failed, in words.
    std::string why;
    if (!(r.lyapunov_exponent > r.regular_bound + 3.0 * r.lyapunov_error))
      why = fmt::format("the largest Lyapunov exponent, {:.3g} +- {:.2g} 1/s, does not stand above the {:.3g} 1/s "
                        "(4 ln T / T) a regular motion still shows at this horizon by three times its error",
                        r.lyapunov_exponent, r.lyapunov_error, r.regular_bound);
    if (!(r.megno > 4.0))
      why += fmt::format("{}MEGNO is {:.3g}, not above 4 (2 on a torus)", why.empty() ? "" : ", and ", r.megno);
    out = fmt::format("Not chaotic over {} s: {}; no prediction horizon is stated.\n", seconds(r.horizon), why);
    // MEGNO sees a slow divergence before the exponent stands out of its own error.
    if (r.megno > 4.0)
      out += fmt::format("  MEGNO {:.3g} > 4 suggests chaos that this horizon cannot yet establish: try a longer "
                         "--horizon.\n",
                         r.megno);
  }
  out += fmt::format("  spectrum (1/s): {:.3g}, {:.3g}, {:.3g}, {:.3g}, {:.3g}, {:.3g}; MEGNO <Y> = {:.4g}; "
                     "{} DOP853 steps, energy kept to {:.1e} relative\n",
                     r.spectrum[0], r.spectrum[1], r.spectrum[2], r.spectrum[3], r.spectrum[4], r.spectrum[5],
                     r.megno, r.steps, r.max_relative_energy_drift);
  return out;
}

std::string section_csv(const PoincareSection& section) {
  std::string out = "t,tilt,tilt_rate\n";
  for (const SectionCrossing& c : section.crossings)
    out += number(c.t) + "," + number(c.tilt) + "," + number(c.tilt_rate) + "\n";
  return out;
}

std::string section_text(const PoincareSection& section, double horizon) {
  std::string out = fmt::format("Poincare section psi = 0 (psi' > 0) over {:.4g} s: {} crossings; energy kept to "
                                "{:.1e} relative\n",
                                horizon, section.crossings.size(), section.max_relative_energy_drift);
  out += fmt::format("{:>16} {:>16} {:>16}\n", "t (s)", "tilt (rad)", "tilt_rate (rad/s)");
  for (const SectionCrossing& c : section.crossings)
    out += fmt::format("{:>16.9g} {:>16.9g} {:>16.9g}\n", c.t, c.tilt, c.tilt_rate);
  return out;
}

std::string section_json(const PoincareSection& section) {
  Json j;
  j["columns"] = Json::array({"t", "tilt", "tilt_rate"});
  Json rows = Json::array();
  for (const SectionCrossing& c : section.crossings) rows.push_back(Json::array({c.t, c.tilt, c.tilt_rate}));
  j["rows"] = std::move(rows);
  j["max_relative_energy_drift"] = section.max_relative_energy_drift;
  return j.dump(2) + "\n";
}

}  // namespace heavytop::io

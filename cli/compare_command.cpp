// heavytop compare: every approximate model against the nonlinear body, one state, one horizon.
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "formats.hpp"
#include "heavytop/compare.hpp"

namespace heavytop::cli {
namespace {
using Json = nlohmann::ordered_json;
Json optional_number(const std::optional<double>& x) { return x ? Json(*x) : Json(nullptr); }
}  // namespace

std::string comparison_json(const Comparison& c) {
  Json out;
  out["nonlinear"] = {{"nutation_frequency", optional_number(c.nonlinear_frequencies.nutation)},
                      {"precession_rate", optional_number(c.nonlinear_frequencies.precession)},
                      {"steps", c.summary.steps},
                      {"max_relative_energy_drift", c.summary.max_relative_energy_drift}};
  Json models = Json::object();
  for (const auto& m : c.models) {
    models[m.model] = {{"max_angle_error", m.max_angle_error},
                       {"final_angle_error", m.final_angle_error},
                       {"nutation_frequency", optional_number(m.frequencies.nutation)},
                       {"precession_rate", optional_number(m.frequencies.precession)},
                       {"nutation_relative_error", optional_number(m.nutation_relative_error)},
                       {"precession_relative_error", optional_number(m.precession_relative_error)}};
  }
  out["models"] = models;
  return out.dump(2) + "\n";
}

std::string comparison_csv(const Comparison& c) {
  std::string out = "model,max_angle_error,final_angle_error,nutation_frequency,precession_rate,"
                    "nutation_relative_error,precession_relative_error\n";
  auto cell = [](const std::optional<double>& x) { return x ? number(*x) : std::string(); };
  out += fmt::format("nonlinear,0,0,{},{},0,0\n", cell(c.nonlinear_frequencies.nutation),
                     cell(c.nonlinear_frequencies.precession));
  for (const auto& m : c.models)
    out += fmt::format("{},{},{},{},{},{},{}\n", m.model, number(m.max_angle_error), number(m.final_angle_error),
                       cell(m.frequencies.nutation), cell(m.frequencies.precession),
                       cell(m.nutation_relative_error), cell(m.precession_relative_error));
  return out;
}

std::string comparison_text(const Comparison& c, double t_end) {
  auto freq = [](const std::optional<double>& x) { return x ? fmt::format("{:.6g}", *x) : std::string("-"); };
  auto rel = [](const std::optional<double>& x) { return x ? fmt::format("{:.2e}", *x) : std::string("-"); };
  std::ostringstream out;
  out << fmt::format("Every model against the full nonlinear body over {:g} s (angles in rad, frequencies in rad/s)\n\n", t_end);
  out << fmt::format("{:<15} {:>12} {:>12} {:>12} {:>10} {:>12} {:>10}\n", "model", "max error", "final error",
                     "nutation", "rel. err", "precession", "rel. err");
  out << fmt::format("{:<15} {:>12} {:>12} {:>12} {:>10} {:>12} {:>10}\n", "nonlinear", "(truth)", "",
                     freq(c.nonlinear_frequencies.nutation), "", freq(c.nonlinear_frequencies.precession), "");
  for (const auto& m : c.models)
    out << fmt::format("{:<15} {:>12.3e} {:>12.3e} {:>12} {:>10} {:>12} {:>10}\n", m.model, m.max_angle_error,
                       m.final_angle_error, freq(m.frequencies.nutation), rel(m.nutation_relative_error),
                       freq(m.frequencies.precession), rel(m.precession_relative_error));
  out << fmt::format("\nIntegrator: {} steps, energy drift {:.1e} (relative).\n", c.summary.steps,
                     c.summary.max_relative_energy_drift);
  return out.str();
}

Action add_compare_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "Every approximate model against the nonlinear body: angle errors, frequencies");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json", "csv"});
  auto t_end = std::make_shared<double>(10.0);
  auto samples = std::make_shared<long long>(10001);
  auto tol = std::make_shared<NonlinearOptions>();
  cmd->add_option("--t-end", *t_end, "s, horizon (> 0)")->default_str("10");
  cmd->add_option("--samples", *samples, "samples over the horizon (>= 3)")->default_str("10001");
  cmd->add_option("--rtol", tol->rtol, "nonlinear: relative tolerance per step")->default_str(fmt::format("{}", tol->rtol));
  cmd->add_option("--atol", tol->atol, "nonlinear: absolute tolerance per step")->default_str(fmt::format("{}", tol->atol));
  return [inputs, t_end, samples, tol] {
    inputs->resolve();
    if (!(std::isfinite(*t_end) && *t_end > 0.0)) throw InvalidInput("--t-end", "must be finite and > 0");
    if (*samples < 3 || *samples > 100'000'000) throw InvalidInput("--samples", "must be an integer in [3, 100000000]");
    validate(*tol);
    const Comparison c = compare_models(inputs->body(), inputs->state(),
                                        sample_times(*t_end, static_cast<std::size_t>(*samples)), *tol);
    const std::string& f = inputs->format();
    write_output(inputs->output(), f == "json" ? comparison_json(c) : f == "csv" ? comparison_csv(c) : comparison_text(c, *t_end));
  };
}

}  // namespace heavytop::cli

// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues.
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "formats.hpp"
#include "heavytop/stability.hpp"

namespace heavytop::cli {
namespace {

using Json = nlohmann::ordered_json;


}  // namespace

std::vector<ModelReport> analyse(const Body& body, double spin) {
  std::vector<ModelReport> reports;
  for (LinearModelKind kind : kLinearModels) {
    const LinearModel model = linear_model(kind, body);
    auto intervals = stable_spin_intervals(model);
    auto critical = critical_spin(intervals);
    reports.push_back({kind, linear_stability(model, spin), std::move(intervals), critical});
  }
  return reports;
}

namespace {

Json optional_number(const std::optional<double>& x) { return x ? Json(*x) : Json(nullptr); }

}  // namespace

std::string stability_json(const Body& body, double spin, const std::vector<ModelReport>& reports) {
  Json out;
  out["body"] = {{"A", body.A},       {"B", body.B},
                 {"C", body.C},       {"mass", body.mass},
                 {"gravity", body.gravity}, {"length", body.length}};
  out["spin"] = spin;
  Json models = Json::object();
  for (const auto& r : reports) {
    Json m;
    m["stable"] = r.verdict.stable;
    m["critical_spin"] = optional_number(r.critical);
    m["stable_spin_intervals"] = Json::array();
    for (const auto& i : r.intervals)
      m["stable_spin_intervals"].push_back({i.lo, optional_number(i.hi)});
    m["eigenvalues"] = Json::array();
    for (const auto& l : r.verdict.eigenvalues) m["eigenvalues"].push_back({l.real(), l.imag()});
    if (r.verdict.stable) m["frequencies"] = r.verdict.frequencies;
    m["reason"] = r.verdict.reason;
    models[std::string(name(r.kind))] = m;
  }
  out["models"] = models;
  return out.dump(2) + "\n";
}

namespace {

std::string intervals_text(const std::vector<SpinInterval>& intervals) {
  if (intervals.empty()) return "none";
  std::string text;
  for (const auto& i : intervals) {
    if (!text.empty()) text += ", ";
    text += i.hi ? fmt::format("[{:.6g}, {:.6g}]", i.lo, *i.hi) : fmt::format("above {:.6g}", i.lo);
  }
  return text;
}

}  // namespace

std::string stability_text(const Body& body, double spin, const std::vector<ModelReport>& reports) {
  std::ostringstream out;
  out << fmt::format("Body: A = {:g}, B = {:g}, C = {:g} kg m^2; m g R = {:g} N m ({})\n", body.A,
                     body.B, body.C, body.mgR(),
                     body.length > 0 ? "centre of mass above O" :
                     body.length < 0 ? "hanging: centre of mass below O" : "centre of mass at O");
  out << fmt::format("Spin: w0 = {:g} rad/s ({:.0f} rpm)\n\n", spin, spin * 30.0 / M_PI);
  out << fmt::format("{:<13} {:<9} {:>16}  {:<28} {}\n", "model", "verdict", "critical rad/s",
                     "stable spins (rad/s)", "why");
  for (const auto& r : reports) {
    out << fmt::format("{:<13} {:<9} {:>16}  {:<28} {}\n", name(r.kind),
                       r.verdict.stable ? "stable" : "UNSTABLE",
                       r.critical ? fmt::format("{:.6g}", *r.critical) : "none",
                       intervals_text(r.intervals), r.verdict.reason);
  }
  out << "\n(first-order: the paper's model (4), (9); body-fixed: its model (5), which the paper "
         "itself calls erroneous; linearized: the exact linearisation, the one to trust.)\n";
  const auto& paper = reports[0];
  const auto& truth = reports[2];
  if (paper.verdict.stable != truth.verdict.stable) {
    out << fmt::format(
        "\nWARNING: the paper's model (4) says {} at this spin, but the exact linearisation says "
        "{}.\n  Model (4) is the linearisation only for A = B (erratum E3); trust `linearized`.\n",
        paper.verdict.stable ? "stable" : "unstable", truth.verdict.stable ? "stable" : "unstable");
  } else if (paper.critical != truth.critical &&
             !(paper.critical && truth.critical &&
               std::abs(*paper.critical - *truth.critical) <= 1e-9 * *truth.critical)) {
    out << fmt::format(
        "\nNote: the paper's condition (9) puts the critical spin at {}, the exact linearisation "
        "at {} (erratum E3).\n",
        paper.critical ? fmt::format("{:.6g} rad/s", *paper.critical) : "none",
        truth.critical ? fmt::format("{:.6g} rad/s", *truth.critical) : "none (no spin stabilises it)");
  }
  if (std::abs(body.A - body.B) <= 1e-12 * std::max(body.A, body.B) && body.mgR() > 0)
    out << "\nSymmetric top: the classical sleeping-top criterion C^2 w0^2 > 4 A m g R applies "
           "(strictly: at equality the motion grows, erratum E2).\n";
  return out.str();
}

Action add_stability_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "stability", "Linear stability of the first-order, body-fixed and linearized models at a spin");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"});
  return [inputs] {
    inputs->resolve();
    const auto reports = analyse(inputs->body(), inputs->state().spin);
    write_output(inputs->output(), inputs->format() == "json"
                                       ? stability_json(inputs->body(), inputs->state().spin, reports)
                                       : stability_text(inputs->body(), inputs->state().spin, reports));
  };
}

}  // namespace heavytop::cli

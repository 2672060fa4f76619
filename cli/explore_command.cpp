// heavytop explore: the explorer page (SPEC section 15), one self-contained HTML file with the
// core compiled to WebAssembly inside it, its inputs starting at the configuration given here
// (--config and every option of `heavytop stability`: the body, the motion, the damping with
// --driven, the table, the answer's --horizon, --max-tilt and --lifetime-horizon; the built-in
// toy top without them). The page is built by Emscripten (web/, the CMake target heavytop_web);
// this command copies it (report::explorer_page(), which every report's explore.html and
// Python's explore() come from too: window.HEAVYTOP_INITIAL, the body with its radii, the motion
// with its motor, the damping) with, when the configuration holds more than those (the table,
// the answer's options), the whole configuration as the page's start (window.HEAVYTOP_CONFIG; else
// it stays null and the page is byte for byte Python's explore()).
#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/report/report.hpp"
#include "heavytop/table.hpp"

namespace heavytop::cli {
namespace {

// The page's start: the configuration's sections as the page's window.heavytop takes them
// ({body, motion, damping, table}) and the answer's options ({horizon, max_tilt,
// lifetime_horizon, max_steps}: stability's flags), as JSON that a <script> holds.
std::string page_start(const Inputs& inputs, const AnswerOptions& o) {
  using nlohmann::json;
  const Body& b = inputs.body();
  const InitialState& s = inputs.state();
  const Table& t = inputs.table();
  json config;
  config["body"] = {{"A", b.A},         {"B", b.B},
                    {"C", b.C},         {"mass", b.mass},
                    {"gravity", b.gravity}, {"length", b.length},
                    {"tip_radius", b.tip_radius}, {"rim_radius", b.rim_radius}};
  // The air drags on the parts' own surfaces (io::table_of): with the air on, the page takes the
  // solid parts themselves (its "parts" mode), so its answer is stability's. Else the moments.
  const auto& parts = inputs.configuration().parts;
  const bool solids = !parts.empty() && std::none_of(parts.begin(), parts.end(), [](const auto& p) { return p.mesh; });
  if (t.air && solids) {
    json list = json::array();
    for (const auto& p : parts) {
      const SolidPart& q = p.solid;
      json part = {{"shape", name(q.shape)}, {"radius", q.radius}, {"z0", q.z0}};
      if (q.shape != PartShape::Sphere) part["height"] = q.height;
      if (q.shape == PartShape::Tube) part["inner_radius"] = q.inner_radius;
      if (q.shape == PartShape::Cone) part["apex"] = q.apex_up ? "up" : "down";
      if (q.density) part["density"] = *q.density;
      if (q.mass) part["mass"] = *q.mass;
      list.push_back(part);
    }
    config["body"] = {{"gravity", b.gravity}, {"tip_radius", b.tip_radius}, {"rim_radius", b.rim_radius},
                      {"part", list}};
  }
  config["motion"] = {{"spin", s.spin},           {"theta0", s.theta0},       {"phi0", s.phi0},
                      {"theta_rate0", s.theta_rate0}, {"phi_rate0", s.phi_rate0}, {"driven", b.damping.driven}};
  config["damping"] = {{"transverse", b.damping.transverse}, {"axial", b.damping.axial},
                       {"friction", b.damping.friction}};
  if (t.on_table()) {  // [table]: its other keys only where the contact takes them (io::table_of)
    json table = {{"contact", std::string(name(t.contact))}};
    if (t.contact == Contact::Sliding) {
      table["friction"] = t.friction;
      table["friction_law"] = std::string(name(t.friction_law));
      if (t.friction_law == FrictionLaw::Viscous) table["slip_speed"] = t.slip_speed;
      // A material by its name where it is one of the common ones, else by its numbers.
      auto material = [&](const std::optional<Material>& m, const std::string& prefix) {
        if (!m) return;
        for (const auto& named : common_materials())
          if (named.material.modulus == m->modulus && named.material.poisson == m->poisson) {
            table[prefix + "material"] = std::string(named.name);
            return;
          }
        table[prefix + "modulus"] = m->modulus;
        table[prefix + "poisson"] = m->poisson;
      };
      material(t.tip_material, "tip_");
      material(t.material, "");
      if (t.rolling_resistance > 0.0) table["rolling_resistance"] = t.rolling_resistance;
    }
    if (t.air) {
      table["air"] = true;
      table["air_density"] = t.air->density;
      table["air_viscosity"] = t.air->viscosity;
    }
    config["table"] = table;
  }
  json stability = {{"horizon", o.horizon}, {"max_tilt", o.max_tilt}};
  if (o.damped_horizon) stability["lifetime_horizon"] = *o.damped_horizon;
  if (o.integrator.max_steps != Tolerances{}.max_steps) stability["max_steps"] = o.integrator.max_steps;
  std::string text = json{{"config", config}, {"stability", stability}}.dump();
  // Inside a <script>: no "</" (a string of the file could hold "</script>").
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  return text;
}

// True if the page's start holds more than HEAVYTOP_INITIAL's (io::explorer_page: the body with
// its radii, the motion with its motor, the damping): a table or answer options of its own.
bool beyond_initial(const Inputs& inputs, const AnswerOptions& o) {
  return inputs.table().on_table() || o.horizon != AnswerOptions{}.horizon || o.max_tilt != AnswerOptions{}.max_tilt ||
         o.damped_horizon.has_value() || o.integrator.max_steps != Tolerances{}.max_steps;
}

}  // namespace

Action add_explore_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "explore", "Write the explorer page: one self-contained HTML file (the core in WebAssembly) that answers any "
                 "body and spin live in a browser, from file:// with no network");
  InputUses uses;
  uses.table = true;  // the page answers a top on a table as `stability` does (SPEC section 16)
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"html"}, uses);
  auto o = std::make_shared<AnswerOptions>();
  // stability's answer options, which the page's answer uses (as `heavytop stability` does).
  auto answer_flags = std::make_shared<AnswerFlags>(*cmd, *o);
  return [inputs, o, answer_flags] {
    inputs->resolve();
    answer_flags->apply();  // stability's checks, under stability's flags
    if (inputs->output().empty())
      throw InvalidInput("--output", "give the page's file, e.g. --output explore.html (or - for stdout)");
    auto page = report::explorer_page(inputs->body(), inputs->state());
    if (!page) throw InvalidInput("explore", io::kExplorerPageMissing);
    const std::string mark = "/*HEAVYTOP_CONFIG*/null";
    const auto at = page->find(mark);
    if (at == std::string::npos) throw Failure("explore: the explorer page has no place for its start (HEAVYTOP_CONFIG)");
    if (beyond_initial(*inputs, *o)) page->replace(at, mark.size(), page_start(*inputs, *o));
    write_output(inputs->output(), *page);  // "-": stdout (SPEC section 1)
  };
}

}  // namespace heavytop::cli

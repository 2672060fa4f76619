// The body on a table (SPEC section 16): heavytop.Table, checked by the command line's reader of
// [table] (io::table_of, so its messages are the CLI's), the run on the table
// (simulate_on_table) and the analysis on it (analyse_top_on_table), returned as the CLI's JSON
// (io::table_trajectory_json's "table" and "summary", io::table_stability_json) and words
// (io::table_answer_text): nothing here words a result again.
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/table.hpp"
#include "interrupt.hpp"

namespace heavytop::python {

using namespace pybind11::literals;

namespace {

constexpr const char* kTableDoc = R"doc(The table under the body (SPEC section 16, a configuration file's [table]). Immutable.

    Table(contact="pivot", *, friction=None, friction_law=None, slip_speed=None, tip_material=None,
          material=None, rolling_resistance=None, air=None, air_density=None, air_viscosity=None)

contact: "pivot" (O fixed: no table; sections 1-15) | "frictionless" | "rolling" | "sliding"
friction: mu (dimensionless, >= 0; default 0): "sliding" only                 [--table-friction]
friction_law: "viscous" (F = -mu N v / slip_speed, the default) | "coulomb" | "contensou"
    (Coulomb's law over the tip's Hertz patch, with its drilling torque): "sliding" only
slip_speed: m/s (> 0; default 1): the viscous law's reference speed           [--slip-speed]
tip_material, material: "contensou": the tip's and the table's materials, names of the common
    ones ("steel", "brass", "aluminium", "glass", "abs", "nylon", "wood", "oak", "marble")
    or (modulus in Pa, poisson) pairs                          [--tip-material, --table-material]
rolling_resistance: m (>= 0; default 0): "sliding" under "viscous" or "contensou"
air: True: the still air's torque against the spin (a body given by its moments is dragged as
    its equivalent disc; load() takes the parts' surfaces from the file)           [--air]
air_density: kg/m^3 (> 0; default 1.204), air_viscosity: Pa s (> 0; default 1.813e-5)

The body's shape where it touches is Body's tip_radius and rim_radius (m). Checked by the
command line's own reader of [table], a key given as given there (None: not given): bad values
raise InvalidInput with its message, e.g. "table.friction: must be a finite number >= 0",
"table.friction: applies to table.contact = \"sliding\" only (here \"rolling\")". Give it to
simulate(body, table=...) and stability(body, spin, table=...); load() reads it from [table].
)doc";

// A material as the file gives it: a name, or (modulus, poisson) under the two keys.
void set_material(io::Configuration& config, const py::object& value, const char* named, const char* modulus,
                  const char* poisson) {
  if (value.is_none()) return;
  if (py::isinstance<py::str>(value)) {
    config.settings[named] = value.cast<std::string>();
    return;
  }
  const auto pair = value.cast<std::pair<double, double>>();
  config.settings[modulus] = pair.first;
  config.settings[poisson] = pair.second;
}

Table make_table(const std::string& contact, std::optional<double> friction, std::optional<std::string> friction_law,
                 std::optional<double> slip_speed, const py::object& tip_material, const py::object& material,
                 std::optional<double> rolling_resistance, std::optional<bool> air, std::optional<double> air_density,
                 std::optional<double> air_viscosity) {
  io::Configuration config;  // [table] as a file gives it: the keys given, checked by the CLI's reader
  config.settings["table.contact"] = contact;
  if (friction) config.settings["table.friction"] = *friction;
  if (friction_law) config.settings["table.friction_law"] = *friction_law;
  if (slip_speed) config.settings["table.slip_speed"] = *slip_speed;
  set_material(config, tip_material, "table.tip_material", "table.tip_modulus", "table.tip_poisson");
  set_material(config, material, "table.material", "table.modulus", "table.poisson");
  if (rolling_resistance) config.settings["table.rolling_resistance"] = *rolling_resistance;
  if (air) config.settings["table.air"] = *air;
  if (air_density) config.settings["table.air_density"] = *air_density;
  if (air_viscosity) config.settings["table.air_viscosity"] = *air_viscosity;
  return io::table_of(config);
}

py::object material_state(const std::optional<Material>& m) {
  return m ? py::object(py::make_tuple(m->modulus, m->poisson)) : py::object(py::none());
}

py::tuple table_state(const Table& t) {
  py::list surfaces;
  for (const auto& a : t.air_surfaces)
    surfaces.append(py::make_tuple(static_cast<int>(a.kind), a.radius, a.inner_radius, a.length));
  return py::make_tuple(std::string(name(t.contact)), t.friction, std::string(name(t.friction_law)), t.slip_speed,
                        material_state(t.tip_material), material_state(t.material), t.rolling_resistance,
                        t.air ? py::object(py::make_tuple(t.air->density, t.air->viscosity)) : py::object(py::none()),
                        py::tuple(surfaces));
}

// The "table" object of `simulate --format json` (the contact, its law, the body's radii) and
// its "summary", from the io layer's own JSON of the run without its rows.
std::pair<py::object, py::object> run_objects(const Body& body, const Table& table, const InitialState& state,
                                              const TableSummary& summary) {
  TableRun header;
  header.summary = summary;
  const py::object json = from_json(io::table_trajectory_json(body, table, state, header));
  return {json["table"], json["summary"]};
}

/// (columns, summary, table) of `simulate --model nonlinear --format json` on `table`: the CSV's
/// columns as NumPy arrays, the JSON's "summary" and "table".
py::tuple simulate_on_table_columns(const Body& body, const Table& table, const InitialState& state, double t_end,
                                    std::size_t samples, const Tolerances& tolerances, Integrator integrator) {
  TableRun run = without_gil([&] {
    return simulate_on_table(body, table, state, SampleGrid{t_end, samples}, tolerances, poll_signals(), integrator);
  });
  auto [settings, summary] = run_objects(body, table, state, run.summary);
  Trajectory& tr = run.trajectory;
  const auto names = tr.column_names();
  py::dict columns;
  for (std::size_t c = 0; c < names.size(); ++c) columns[py::str(names[c])] = to_numpy(std::move(tr.column(c)));
  return py::make_tuple(columns, summary, settings);
}

}  // namespace

py::tuple simulate_table(const Body& body, const Table& table, const InitialState& state, const std::string& model,
                         const std::optional<std::string>& integrator, double t_end, std::size_t samples,
                         const Tolerances& tolerances) {
  // As `heavytop simulate` on a table (cli/simulate_command.cpp, run_on_table), the options
  // spelled as keyword arguments.
  if (model != "nonlinear")
    throw InvalidInput("table.contact", fmt::format("model=\"{}\" is the pivot's (SPEC section 16): on a table (contact "
                                                    "= \"{}\") use model=\"nonlinear\"",
                                                    model, name(table.contact)));
  // The name is resolve()'s, checked before.
  const Integrator chosen = integrator_from_name(integrator.value_or("auto")).value_or(Integrator::Auto);
  if (auto why = integrator_refusal(chosen, body, true, false)) throw InvalidInput("integrator", *why);
  return simulate_on_table_columns(body, table, state, t_end, samples, tolerances, chosen);
}

py::tuple stability_on_table(const Body& body, const Table& table, const InitialState& state,
                             const AnswerOptions& options) {
  std::string json, words;
  without_gil([&] {
    const TableAnalysis analysis = analyse_top_on_table(body, table, state, options);
    json = io::table_stability_json(body, table, analysis, analyse_stability(body, analysis.spin));
    words = io::table_answer_text(analysis.answer, table);
    return 0;
  });
  return py::make_tuple(from_json(json), words);
}

void bind_table(py::module_& m) {
  py::class_<Table>(m, "Table", kTableDoc)
      .def(py::init(&make_table), "contact"_a = "pivot", py::kw_only(), "friction"_a = py::none(),
           "friction_law"_a = py::none(), "slip_speed"_a = py::none(), "tip_material"_a = py::none(),
           "material"_a = py::none(), "rolling_resistance"_a = py::none(), "air"_a = py::none(),
           "air_density"_a = py::none(), "air_viscosity"_a = py::none(),
           "contact: \"pivot\" | \"frictionless\" | \"rolling\" | \"sliding\"\n"
           "friction: mu (>= 0), sliding only\n"
           "friction_law: \"viscous\" | \"coulomb\" | \"contensou\", sliding only\n"
           "slip_speed: m/s (> 0), the viscous law's reference speed\n"
           "tip_material, material: contensou: names or (modulus Pa, poisson)\n"
           "rolling_resistance: m (>= 0)\n"
           "air: True for the still air's torque; air_density kg/m^3, air_viscosity Pa s")
      .def_property_readonly("contact", [](const Table& t) { return std::string(name(t.contact)); },
                             "\"pivot\" | \"frictionless\" | \"rolling\" | \"sliding\"")
      .def_readonly("friction", &Table::friction, "mu (dimensionless): the sliding contact's friction coefficient")
      .def_property_readonly("friction_law", [](const Table& t) { return std::string(name(t.friction_law)); },
                             "\"viscous\" | \"coulomb\" (sliding)")
      .def_readonly("slip_speed", &Table::slip_speed, "m/s, the viscous law's reference speed")
      .def_readonly("rolling_resistance", &Table::rolling_resistance, "m, the rolling resistance's length")
      .def_property_readonly("air", [](const Table& t) { return t.air.has_value(); },
                             "True if the still air's torque acts")
      .def_property_readonly("has_losses", &Table::has_losses,
                             "True with the body's own losses (contensou, rolling resistance, air)")
      .def_property_readonly("on_table", &Table::on_table, "True for every contact but the pivot")
      .def("to_dict", [](const Table& t) {
             py::dict d("contact"_a = std::string(name(t.contact)));
             if (t.contact == Contact::Sliding) {
               d["friction"] = t.friction;
               d["friction_law"] = std::string(name(t.friction_law));
               d["slip_speed"] = t.slip_speed;
             }
             if (t.has_losses()) d["has_losses"] = true;
             return d;
           }, "The JSON's \"table\" object without the body's radii: {contact}, and for \"sliding\" friction,\n"
              "friction_law, slip_speed (m/s).")
      .def("__eq__", [](const Table& a, const Table& b) { return table_state(a).equal(table_state(b)); },
           py::is_operator())
      .def("__hash__", [](const Table& t) { return py::hash(table_state(t)); })
      .def("__repr__", [](const Table& t) {
             if (t.contact != Contact::Sliding)
               return fmt::format("heavytop.Table(\"{}\"{})", name(t.contact),
                                  t.on_table() && t.slip_speed != 1.0 ? fmt::format(", slip_speed={}", t.slip_speed)
                                                                      : std::string());
             std::string extra;  // the body's own losses, where set (a file's part surfaces are not shown)
             auto material = [](const Material& m) { return fmt::format("({}, {})", m.modulus, m.poisson); };
             if (t.tip_material) extra += ", tip_material=" + material(*t.tip_material);
             if (t.material) extra += ", material=" + material(*t.material);
             if (t.rolling_resistance > 0.0) extra += fmt::format(", rolling_resistance={}", t.rolling_resistance);
             if (t.air)
               extra += fmt::format(", air=True, air_density={}, air_viscosity={}", t.air->density, t.air->viscosity);
             return fmt::format("heavytop.Table(\"sliding\", friction={}, friction_law=\"{}\", slip_speed={}{})",
                                t.friction, name(t.friction_law), t.slip_speed, extra);
           })
      .def(py::pickle(&table_state, [](const py::tuple& s) {
        Table t;
        t.contact = contact_from_name(s[0].cast<std::string>()).value_or(Contact::Pivot);
        t.friction = s[1].cast<double>();
        t.friction_law = friction_law_from_name(s[2].cast<std::string>()).value_or(FrictionLaw::Viscous);
        t.slip_speed = s[3].cast<double>();
        auto material = [](const py::object& m) -> std::optional<Material> {
          if (m.is_none()) return std::nullopt;
          const auto pair = m.cast<std::pair<double, double>>();
          return Material{pair.first, pair.second};
        };
        t.tip_material = material(s[4]);
        t.material = material(s[5]);
        t.rolling_resistance = s[6].cast<double>();
        if (!s[7].is_none()) {
          const auto pair = s[7].cast<std::pair<double, double>>();
          t.air = Air{pair.first, pair.second};
        }
        for (const auto& a : s[8].cast<py::tuple>()) {
          const auto f = a.cast<std::tuple<int, double, double, double>>();
          t.air_surfaces.push_back({static_cast<AirSurface::Kind>(std::get<0>(f)), std::get<1>(f), std::get<2>(f),
                                    std::get<3>(f)});
        }
        validate(t);
        return t;
      }));
}

}  // namespace heavytop::python

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

    Table(contact="pivot", *, friction=None, friction_law=None, slip_speed=None)

contact: "pivot" (O fixed: no table; sections 1-15) | "frictionless" | "rolling" | "sliding"
friction: mu (dimensionless, >= 0; default 0): "sliding" only                 [--table-friction]
friction_law: "viscous" (F = -mu N v / slip_speed, the default) | "coulomb": "sliding" only
slip_speed: m/s (> 0; default 1): the viscous law's reference speed           [--slip-speed]

The body's shape where it touches is Body's tip_radius and rim_radius (m). Checked by the
command line's own reader of [table], a key given as given there (None: not given): bad values
raise InvalidInput with its message, e.g. "table.friction: must be a finite number >= 0",
"table.friction: applies to table.contact = \"sliding\" only (here \"rolling\")". Give it to
simulate(body, table=...) and stability(body, spin, table=...); load() reads it from [table].
)doc";

Table make_table(const std::string& contact, std::optional<double> friction, std::optional<std::string> friction_law,
                 std::optional<double> slip_speed) {
  io::Configuration config;  // [table] as a file gives it: the keys given, checked by the CLI's reader
  config.settings["table.contact"] = contact;
  if (friction) config.settings["table.friction"] = *friction;
  if (friction_law) config.settings["table.friction_law"] = *friction_law;
  if (slip_speed) config.settings["table.slip_speed"] = *slip_speed;
  return io::table_of(config);
}

py::tuple table_state(const Table& t) {
  return py::make_tuple(std::string(name(t.contact)), t.friction, std::string(name(t.friction_law)), t.slip_speed);
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
           "friction_law"_a = py::none(), "slip_speed"_a = py::none(),
           "contact: \"pivot\" | \"frictionless\" | \"rolling\" | \"sliding\"\n"
           "friction: mu (>= 0), sliding only\n"
           "friction_law: \"viscous\" | \"coulomb\", sliding only\n"
           "slip_speed: m/s (> 0), the viscous law's reference speed")
      .def_property_readonly("contact", [](const Table& t) { return std::string(name(t.contact)); },
                             "\"pivot\" | \"frictionless\" | \"rolling\" | \"sliding\"")
      .def_readonly("friction", &Table::friction, "mu (dimensionless): the sliding contact's friction coefficient")
      .def_property_readonly("friction_law", [](const Table& t) { return std::string(name(t.friction_law)); },
                             "\"viscous\" | \"coulomb\" (sliding)")
      .def_readonly("slip_speed", &Table::slip_speed, "m/s, the viscous law's reference speed")
      .def_property_readonly("on_table", &Table::on_table, "True for every contact but the pivot")
      .def("to_dict", [](const Table& t) {
             py::dict d("contact"_a = std::string(name(t.contact)));
             if (t.contact == Contact::Sliding) {
               d["friction"] = t.friction;
               d["friction_law"] = std::string(name(t.friction_law));
               d["slip_speed"] = t.slip_speed;
             }
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
             return fmt::format("heavytop.Table(\"sliding\", friction={}, friction_law=\"{}\", slip_speed={})",
                                t.friction, name(t.friction_law), t.slip_speed);
           })
      .def(py::pickle(&table_state, [](const py::tuple& s) {
        Table t;
        t.contact = contact_from_name(s[0].cast<std::string>()).value_or(Contact::Pivot);
        t.friction = s[1].cast<double>();
        t.friction_law = friction_law_from_name(s[2].cast<std::string>()).value_or(FrictionLaw::Viscous);
        t.slip_speed = s[3].cast<double>();
        validate(t);
        return t;
      }));
}

}  // namespace heavytop::python

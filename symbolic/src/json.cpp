// The derivations as JSON, shared by `heavytop derive --format json` and the Python module.
#include "heavytop/symbolic/json.hpp"

#include <nlohmann/json.hpp>

#include "heavytop/symbolic/print.hpp"

namespace heavytop::symbolic {
namespace {

using Json = nlohmann::ordered_json;
using GiNaC::ex;
using GiNaC::matrix;

std::string cas(const ex& e) { return to_string(tidy(e), Style::Cas); }

Json matrix_json(const matrix& a) {
  Json rows = Json::array();
  for (unsigned i = 0; i < a.rows(); ++i) {
    Json row = Json::array();
    for (unsigned j = 0; j < a.cols(); ++j) row.push_back(cas(a(i, j)));
    rows.push_back(row);
  }
  return rows;
}

std::string relation(const Inequality& in) { return in.strict ? ">" : ">="; }

// A string sympy's parse_expr reads (after ^ -> **): relations joined by &, or True/False.
std::string condition_cas(const StabilityCondition& c) {
  if (c.never) return "False";
  if (c.all_of.empty()) return "True";
  if (c.all_of.size() == 1)
    return cas(c.all_of[0].lhs) + " " + relation(c.all_of[0]) + " " + cas(c.all_of[0].rhs);
  std::string out;
  for (const auto& in : c.all_of)
    out += (out.empty() ? "(" : " & (") + cas(in.lhs) + " " + relation(in) + " " + cas(in.rhs) + ")";
  return out;
}

}  // namespace

std::string derivation_json(const Derivation& d) {
  Json out;
  out["M"] = matrix_json(d.M);
  out["G"] = matrix_json(d.G);
  out["K"] = matrix_json(d.K);
  out["characteristic_polynomial"] = cas(d.characteristic_polynomial);
  out["stability_condition"] = condition_cas(d.stability);
  return out.dump(2) + "\n";
}

std::string rotations_json(const Rotations& r) {
  const std::pair<const char*, const matrix*> named[] = {
      {"A1", &r.A1},     {"A2", &r.A2},     {"A3", &r.A3},
      {"A1A2", &r.A1A2}, {"A2A1", &r.A2A1}, {"commutator", &r.commutator}};
  Json out;
  for (const auto& [label, value] : named) {
    Json rows = Json::array();
    for (unsigned i = 0; i < value->rows(); ++i) {
      Json row = Json::array();
      for (unsigned j = 0; j < value->cols(); ++j)
        row.push_back(to_string(value->operator()(i, j), Style::Cas));
      rows.push_back(row);
    }
    out[label] = rows;
  }
  return out.dump(2) + "\n";
}

std::string check_json(const std::vector<CheckRow>& rows) {
  Json out;
  bool all_ok = true;
  out["rows"] = Json::array();
  for (const auto& row : rows) {
    const Derivation& d = row.derivation;
    Json r;
    r["method"] = std::string(name(d.method));
    r["sequence"] = std::string(name(d.sequence));
    r["order"] = d.order;
    r["M"] = matrix_json(d.M);
    r["G"] = matrix_json(d.G);
    r["K"] = matrix_json(d.K);
    r["model"] = row.model ? Json(std::string(name(*row.model))) : Json(nullptr);
    r["expected"] = row.expected ? Json(std::string(name(*row.expected))) : Json(nullptr);
    r["as_expected"] = row.as_expected();
    r["why"] = row.why;
    out["rows"].push_back(r);
    all_ok = all_ok && row.as_expected();
  }
  out["all_as_expected"] = all_ok;
  return out.dump(2) + "\n";
}

}  // namespace heavytop::symbolic

// heavytop derive: the paper's models derived symbolically (GiNaC), as text, LaTeX or JSON;
// built into the program heavytop-derive (derive_main.cpp), which `heavytop derive` runs.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"

#include "heavytop/symbolic/derive.hpp"
#include "heavytop/symbolic/json.hpp"
#include "heavytop/symbolic/print.hpp"
#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::cli {


namespace {

using GiNaC::ex;
using GiNaC::matrix;
using namespace heavytop::symbolic;

struct Options {
  std::string method = "euler-moving";
  std::string sequence = "phi-theta";
  int order = 1;
  bool rotations = false;
  bool check = false;
  std::string format = "text";
  std::string output;
  CLI::Option* method_option = nullptr;
  CLI::Option* sequence_option = nullptr;
  CLI::Option* order_option = nullptr;
};

// ---- expressions -------------------------------------------------------------------------

std::string tex(const ex& e) { return to_string(tidy(e), Style::Latex); }
// T, V and angular velocities read best expanded, term by term.
std::string text_expanded(const ex& e) { return to_string(e.expand(), Style::Text); }
std::string tex_expanded(const ex& e) { return to_string(e.expand(), Style::Latex); }

std::string matrix_text(const matrix& a, std::string (*show)(const ex&) = text) {
  std::string out = "[";
  for (unsigned i = 0; i < a.rows(); ++i) {
    out += i ? ", [" : "[";
    for (unsigned j = 0; j < a.cols(); ++j) out += (j ? ", " : "") + show(a(i, j));
    out += "]";
  }
  return out + "]";
}

std::string vector_text(const matrix& v, std::string (*show)(const ex&) = text_expanded) {
  std::string out = "(";
  for (unsigned i = 0; i < v.rows(); ++i) out += (i ? ", " : "") + show(v(i, 0));
  return out + ")";
}

std::string matrix_tex(const matrix& a, std::string (*show)(const ex&) = tex) {
  std::string out = "\\left(\\begin{array}{" + std::string(a.cols(), 'c') + "}";
  for (unsigned i = 0; i < a.rows(); ++i) {
    for (unsigned j = 0; j < a.cols(); ++j) out += (j ? " & " : " ") + show(a(i, j));
    out += i + 1 < a.rows() ? " \\\\" : " ";
  }
  return out + "\\end{array}\\right)";
}

// The equations as the paper prints them: inertia and gyroscopic terms = -K q.
std::vector<std::pair<ex, ex>> equations(const Derivation& d) {
  const Symbols& s = symbols();
  const ex q[2] = {s.phi, s.theta}, q_t[2] = {s.phi_t, s.theta_t},
           q_tt[2] = {s.phi_tt, s.theta_tt};
  std::vector<std::pair<ex, ex>> rows;
  for (unsigned i = 0; i < 2; ++i) {
    ex lhs = 0, rhs = 0;
    for (unsigned j = 0; j < 2; ++j) {
      lhs += d.M(i, j) * q_tt[j] + tidy(d.G(i, j)) * q_t[j];
      rhs -= tidy(d.K(i, j)) * q[j];
    }
    rows.emplace_back(lhs, rhs);
  }
  return rows;
}

// ---- stability condition -----------------------------------------------------------------

std::string relation(const Inequality& in) { return in.strict ? ">" : ">="; }

std::string condition_text(const StabilityCondition& c) {
  if (c.never) return "never (no parameter values make it stable)";
  if (c.all_of.empty()) return "always";
  std::string out;
  for (const auto& in : c.all_of)
    out += (out.empty() ? "" : "  and  ") + text(in.lhs) + " " + relation(in) + " " + text(in.rhs);
  return out;
}

std::string condition_tex(const StabilityCondition& c) {
  if (c.never) return "\\mbox{never stable}";
  if (c.all_of.empty()) return "\\mbox{always stable}";
  std::string out;
  for (const auto& in : c.all_of)
    out += (out.empty() ? "" : ", \\quad ") + tex(in.lhs) + (in.strict ? " > " : " \\geq ") +
           tex(in.rhs);
  return out;
}

// ---- one derivation ----------------------------------------------------------------------

std::string route_title(Method method) {
  switch (method) {
    case Method::EulerMoving:
      return "Euler's dynamic equations projected on the moving (Resal) axes (section 3)";
    case Method::EulerFixed:
      return "the angular-momentum theorem projected on the fixed axes (section 5)";
    case Method::EulerBody:
      return "Euler's equations on axes attached to the body, psi = omega0 t (section 3; the "
             "paper's erroneous route)";
    case Method::Lagrange:
      return "Lagrange's equations of the second kind (section 6)";
  }
  return "";
}

std::string sequence_title(Sequence sequence) {
  return sequence == Sequence::PhiTheta ? "phi then theta (A^(1) = A2 A1)"
                                        : "theta then phi (A^(2) = A1 A2)";
}

std::string model_note(const Derivation& d) {
  const auto model = identify(d);
  if (model) return fmt::format("This is the paper's {}.", name(*model));
  if (d.method == Method::Lagrange && d.order == 1)
    return "This is neither of the paper's models: with first-order kinematics T has no doubled "
           "products (no gyroscopic terms) and V no quadratic terms; Lagrange needs order 2 "
           "(section 6).";
  return "This is neither of the paper's models (4) or (5).";
}

std::string derivation_text(const Derivation& d) {
  std::ostringstream out;
  out << "heavytop derive: " << route_title(d.method) << "\n";
  out << "Rotations " << sequence_title(d.sequence) << "; kinematics to order " << d.order
      << " in the small quantities.\n\n";
  const bool fixed = d.method == Method::EulerFixed;
  out << "Angular velocity of the body, on the " << (fixed ? "fixed axes l, m, n" : "moving axes i, j, k")
      << (d.method == Method::EulerBody ? " (frame attached to the body: psi' = omega0)" : "") << ":\n";
  out << "  w = " << vector_text(d.omega) << "\n";
  if (d.method == Method::Lagrange) {
    out << "Kinetic and potential energy to second order:\n";
    out << "  T = " << text_expanded(d.T) << "\n";
    out << "  V = " << text_expanded(d.V) << "\n";
  }
  out << "\nThe psi equation, linearised: " << text_expanded(d.psi_equation) << " = 0";
  out << (d.psi_equation.is_zero() ? " (identically)\n"
                                   : ", so psi' is constant; with psi = 0 it drops out.\n");
  out << "\nEquations of motion, linear in the small quantities:\n";
  for (const auto& [lhs, rhs] : equations(d)) out << "  " << text(lhs) << " = " << text(rhs) << "\n";
  out << "\nAs M q'' + G q' + K q = 0 with q = (phi, theta):\n";
  out << "  M = " << matrix_text(d.M) << "\n";
  out << "  G = " << matrix_text(d.G) << "\n";
  out << "  K = " << matrix_text(d.K) << "\n";
  out << model_note(d) << "\n";
  if (identify(d) == PaperModel::Four)
    out << "Note: (4) is the exact linearisation of the top only for A = B (erratum E3); "
           "`heavytop stability` sets it beside the true one.\n";
  if (identify(d) == PaperModel::Five)
    out << "Note: the paper calls (5) erroneous: psi = omega0 t is not small, so the small-angle "
           "table does not apply to a frame attached to the body.\n";
  out << "\nCharacteristic polynomial det(M lambda^2 + G lambda + K)"
      << (identify(d) == PaperModel::Four ? " (A B times the paper's (8))" : "") << ":\n";
  out << "  " << text(d.characteristic_polynomial) << "\n";
  out << "\nStability (a top: A, B, C, m, g, R > 0):\n  " << condition_text(d.stability) << "\n";
  if (identify(d) == PaperModel::Four)
    out << "  = the paper's (9) with strict inequality: at equality the frequencies merge into a "
           "Jordan block and the motion grows (erratum E2).\n";
  out << "Derived from the polynomial:\n";
  for (const auto& step : d.stability.steps) out << "  - " << step << "\n";
  return out.str();
}

std::string derivation_latex(const Derivation& d) {
  std::ostringstream out;
  out << "% heavytop derive --method " << name(d.method) << " --sequence " << name(d.sequence)
      << " --order " << d.order << "\n% " << route_title(d.method) << ". " << model_note(d)
      << "\n";
  out << "\\begin{equation}\n\\left\\{\\begin{array}{l}\n";
  const auto rows = equations(d);
  for (size_t i = 0; i < rows.size(); ++i)
    out << tex(rows[i].first) << " = " << tex(rows[i].second) << (i + 1 < rows.size() ? " \\\\\n" : "\n");
  out << "\\end{array}\\right.\n\\end{equation}\n";
  out << "\\begin{equation}\nM = " << matrix_tex(d.M) << ", \\quad G = " << matrix_tex(d.G)
      << ", \\quad K = " << matrix_tex(d.K) << "\n\\end{equation}\n";
  out << "\\begin{equation}\n\\det\\left(M \\lambda^{2} + G \\lambda + K\\right) = "
      << tex(d.characteristic_polynomial) << " = 0\n\\end{equation}\n";
  out << "\\begin{equation}\n" << condition_tex(d.stability) << "\n\\end{equation}\n";
  return out.str();
}

// ---- --rotations -------------------------------------------------------------------------

struct NamedMatrix {
  const char* name;
  const matrix* value;
};

std::vector<NamedMatrix> named(const Rotations& r) {
  return {{"A1", &r.A1},     {"A2", &r.A2},     {"A3", &r.A3},
          {"A1A2", &r.A1A2}, {"A2A1", &r.A2A1}, {"commutator", &r.commutator}};
}

bool is_zero(const matrix& a) {
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j)
      if (!a(i, j).is_zero()) return false;
  return true;
}

std::string rotations_text(const Rotations& r) {
  std::ostringstream out;
  out << "heavytop derive --rotations: small rotations to order " << r.order
      << " (section 1; rows are i, j, k in terms of l, m, n)\n\n";
  for (const auto& [label, value] : named(r)) {
    out << label << ":\n";
    for (unsigned i = 0; i < value->rows(); ++i) {
      out << "  [";
      for (unsigned j = 0; j < value->cols(); ++j)
        out << (j ? ", " : "") << text_expanded(value->operator()(i, j));
      out << "]\n";
    }
  }
  out << "\n"
      << (is_zero(r.commutator)
              ? "The rotations commute to this order: first-order models do not depend on the "
                "order of the small rotations.\n"
              : "The rotations do not commute to this order (the paper's matrix (1)).\n");
  out << "\nAngular velocities (sections 2 and 4), psi the third small angle:\n";
  for (Sequence s : kSequences) {
    const AngularVelocities w = angular_velocities(s, r.order);
    out << "  " << sequence_title(s) << ":\n";
    out << "    axis frame, on i, j, k: w1 = " << vector_text(w.frame_axes) << "\n";
    out << "    axis frame, on l, m, n: w1 = " << vector_text(w.frame_fixed) << "\n";
    out << "    body, on i, j, k (2):   w = " << vector_text(w.body_axes) << "\n";
    out << "    body, on l, m, n (3):   w = " << vector_text(w.body_fixed) << "\n";
  }
  return out.str();
}

std::string rotations_latex(const Rotations& r) {
  std::ostringstream out;
  out << "% heavytop derive --rotations --order " << r.order << "\n";
  const auto list = named(r);
  const char* tex_names[] = {"A_1", "A_2", "A_3", "A_1 A_2", "A_2 A_1", "A_1 A_2 - A_2 A_1"};
  // Three lines that fit a page: the rotations, their products, the commutator.
  for (auto [first, last] : {std::pair<size_t, size_t>{0, 3}, {3, 5}, {5, 6}}) {
    out << "\\begin{equation}\n";
    for (size_t k = first; k < last; ++k)
      out << tex_names[k] << " = " << matrix_tex(*list[k].value) << (k + 1 < last ? ", \\quad\n" : "\n");
    out << "\\end{equation}\n";
  }
  for (Sequence s : kSequences) {
    const AngularVelocities w = angular_velocities(s, r.order);
    out << "% " << sequence_title(s) << ": the body's angular velocity on i, j, k (2) and on l, m, n (3)\n";
    out << "\\begin{equation}\n\\omega_{xyz} = " << matrix_tex(w.body_axes, tex_expanded)
        << ", \\quad \\omega_{\\xi\\eta\\zeta} = " << matrix_tex(w.body_fixed, tex_expanded) << "\n\\end{equation}\n";
  }
  return out.str();
}

// ---- --check -----------------------------------------------------------------------------

std::string result_name(const std::optional<PaperModel>& model) {
  return model ? std::string(name(*model)) : "neither";
}

std::string check_text(const std::vector<CheckRow>& rows) {
  std::ostringstream out;
  out << "heavytop derive --check: every route and rotation sequence, as M q'' + G q' + K q = 0, "
         "M = diag(A, B)\n\n";
  out << fmt::format("{:<13} {:<10} {:>5}  {:<18} {:<18} {:<12} {:<10} {:<10} {}\n", "method",
                     "sequence", "order", "G12", "G21", "K11 = K22", "result", "paper", "");
  for (const auto& row : rows) {
    const Derivation& d = row.derivation;
    const std::string k = GiNaC::normal(d.K(0, 0) - d.K(1, 1)).is_zero()
                              ? text(d.K(0, 0))
                              : text(d.K(0, 0)) + " / " + text(d.K(1, 1));
    out << fmt::format("{:<13} {:<10} {:>5}  {:<18} {:<18} {:<12} {:<10} {:<10} {}\n",
                       name(d.method), name(d.sequence), d.order, text(d.G(0, 1)),
                       text(d.G(1, 0)), k, result_name(row.model), result_name(row.expected),
                       row.as_expected() ? "agrees" : "DISAGREES");
  }
  // Which routes give the same model, grouped.
  std::vector<std::vector<const CheckRow*>> groups;
  for (const auto& row : rows) {
    bool placed = false;
    for (auto& group : groups)
      if (same_model(group.front()->derivation, row.derivation)) {
        group.push_back(&row);
        placed = true;
        break;
      }
    if (!placed) groups.push_back({&row});
  }
  out << "\nRoutes that agree with one another:\n";
  for (const auto& group : groups) {
    out << "  " << result_name(group.front()->model) << ":";
    for (const CheckRow* row : group)
      out << " " << name(row->derivation.method) << "/" << name(row->derivation.sequence) << "/"
          << row->derivation.order;
    out << "\n";
  }
  out << "\nSo: the first-order models do not depend on the sequence (section 4), the fixed axes "
         "give the moving axes' model (section 5), Lagrange with second-order T and V gives it "
         "for both sequences (section 6), and only the body-attached frame (euler-body) differs: "
         "model (5).\n";
  return out.str();
}

std::string check_latex(const std::vector<CheckRow>& rows) {
  std::ostringstream out;
  out << "% heavytop derive --check\n\\begin{tabular}{lllllll}\n"
         "method & sequence & order & $G_{12}$ & $G_{21}$ & $K_{11} = K_{22}$ & result \\\\\n\\hline\n";
  for (const auto& row : rows) {
    const Derivation& d = row.derivation;
    out << name(d.method) << " & " << name(d.sequence) << " & " << d.order << " & $"
        << tex(d.G(0, 1)) << "$ & $" << tex(d.G(1, 0)) << "$ & $" << tex(d.K(0, 0)) << "$ & "
        << result_name(row.model) << " \\\\\n";
  }
  out << "\\end{tabular}\n";
  return out.str();
}

}  // namespace

Action add_derive_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "derive", "Derive the paper's models symbolically: M q'' + G q' + K q = 0, its "
                "characteristic polynomial and stability condition");
  auto o = std::make_shared<Options>();
  o->method_option = cmd->add_option("--method", o->method,
                                     "euler-moving | euler-fixed | euler-body | lagrange")
                         ->capture_default_str();
  o->sequence_option =
      cmd->add_option("--sequence", o->sequence, "phi-theta | theta-phi: order of the rotations")
          ->capture_default_str();
  o->order_option =
      cmd->add_option("--order", o->order, "1 | 2: order of smallness kept in the kinematics")
          ->capture_default_str();
  cmd->add_flag("--rotations", o->rotations,
                "the small-rotation matrices, their products and angular velocities instead");
  cmd->add_flag("--check", o->check,
                "derive every route and sequence and show which agree (exit 1 if the paper's "
                "claims do not hold)");
  cmd->add_option("--format", o->format, "text | latex | json")->capture_default_str();
  cmd->add_option("--output", o->output, "file to write (default: stdout)");

  return [o] {
    if (o->format != "text" && o->format != "latex" && o->format != "json")
      throw InvalidInput("--format", "must be text, latex or json");
    if (o->order != 1 && o->order != 2) throw InvalidInput("--order", "must be 1 or 2");
    const auto method = method_from_name(o->method);
    if (!method)
      throw InvalidInput("--method", "must be euler-moving, euler-fixed, euler-body or lagrange");
    const auto sequence = sequence_from_name(o->sequence);
    if (!sequence) throw InvalidInput("--sequence", "must be phi-theta or theta-phi");
    if (o->rotations && o->check)
      throw InvalidInput("--check", "cannot be combined with --rotations");
    if ((o->rotations || o->check) && (o->method_option->count() || o->sequence_option->count()))
      throw InvalidInput(o->method_option->count() ? "--method" : "--sequence",
                         std::string("does not apply to ") + (o->rotations ? "--rotations" : "--check"));

    std::string content;
    if (o->rotations) {
      const Rotations r = rotations(o->order);
      content = o->format == "json"    ? rotations_json(r)
                : o->format == "latex" ? rotations_latex(r)
                                       : rotations_text(r);
    } else if (o->check) {
      // Both orders unless --order picks one.
      const auto rows = check(o->order_option->count() ? std::vector<int>{o->order}
                                                       : std::vector<int>{1, 2});
      bool all_ok = true;
      for (const auto& row : rows) all_ok = all_ok && row.as_expected();
      content = o->format == "json"    ? check_json(rows)
                : o->format == "latex" ? check_latex(rows)
                                       : check_text(rows);
      write_output(o->output, content);
      if (!all_ok) throw Failure("derive --check: a route does not give the model the paper states");
      return;
    } else {
      const Derivation d = derive(*method, *sequence, o->order);
      content = o->format == "json"    ? derivation_json(d)
                : o->format == "latex" ? derivation_latex(d)
                                       : derivation_text(d);
    }
    write_output(o->output, content);
  };
}

}  // namespace heavytop::cli

#include "heavytop/io/formats.hpp"

#include <cmath>
#include <sstream>

#include <fmt/compile.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "heavytop/units.hpp"

namespace heavytop::io {
namespace {

using Json = nlohmann::ordered_json;

Json optional_number(const std::optional<double>& x) { return x ? Json(*x) : Json(nullptr); }

/// The "body" object of every JSON output.
Json body_json(const Body& b) {
  Json out = {{"A", b.A}, {"B", b.B}, {"C", b.C}, {"mass", b.mass}, {"gravity", b.gravity}, {"length", b.length}};
  if (b.tip_radius != 0.0) out["tip_radius"] = b.tip_radius;  // SPEC 16's shape, when given
  if (b.rim_radius != 0.0) out["rim_radius"] = b.rim_radius;
  if (is_general(b)) {  // SPEC section 11's keys, only when the body has them (ordinary JSON unchanged)
    out["offset_x"] = b.general.offset_x;
    out["offset_y"] = b.general.offset_y;
    out["Ixy"] = b.general.Ixy;
    out["Ixz"] = b.general.Ixz;
    out["Iyz"] = b.general.Iyz;
  }
  return out;
}

/// The "damping" object (SPEC section 6), beside "body" when the body is not conservative.
void add_damping(Json& out, const Body& b) {
  if (b.damping.conservative()) return;
  out["damping"] = {{"transverse", b.damping.transverse}, {"axial", b.damping.axial},
                    {"friction", b.damping.friction}, {"driven", b.damping.driven}};
}

}  // namespace

namespace {

Json stability_object(const Body& body, double spin, const std::vector<ModelStability>& models, Json answer) {
  Json out;
  out["body"] = body_json(body);
  if (!is_realizable(body)) out["realizable"] = false;  // SPEC section 1, beside the body
  add_damping(out, body);
  out["spin"] = spin;
  out["answer"] = std::move(answer);  // SPEC 14: what a person asks first
  Json by_name = Json::object();
  for (const auto& r : models) {
    Json m;
    m["stable"] = r.verdict.stable;
    m["critical_spin"] = optional_number(r.critical);
    m["stable_spin_intervals"] = Json::array();
    for (const auto& i : r.intervals)
      m["stable_spin_intervals"].push_back({i.lo, optional_number(i.hi)});
    m["eigenvalues"] = Json::array();
    for (const auto& l : r.verdict.eigenvalues) m["eigenvalues"].push_back({l.real(), l.imag()});
    if (r.verdict.stable) m["frequencies"] = r.verdict.frequencies;
    m["growth_rate"] = r.verdict.growth_rate;
    m["reason"] = r.verdict.reason;
    by_name[std::string(name(r.kind))] = m;
  }
  out["models"] = by_name;
  return out;
}

}  // namespace


namespace {

/// SPEC section 7's "normal_form" object (null outside index 2 with a stable linearisation).
Json normal_form_json(const std::optional<NormalForm>& nf) {
  if (!nf) return nullptr;
  Json n;
  n["frequencies"] = {nf->w1, nf->w2};
  n["c20"] = nf->c20;
  n["c11"] = nf->c11;
  n["c02"] = nf->c02;
  n["D"] = nf->D;
  n["resonance"] = nf->resonance == 2 || nf->resonance == 3 ? Json(std::string(resonance_name(nf->resonance))) : Json(nullptr);
  n["a13"] = optional_number(nf->a13);
  return n;
}

Json intervals_json(const std::vector<SpinInterval>& intervals) {
  Json a = Json::array();
  for (const auto& i : intervals) a.push_back({i.lo, optional_number(i.hi)});
  return a;
}

}  // namespace

namespace {

Json answer_object(const Answer& a) {
  Json out;
  out["verdict"] = std::string(name(a.verdict));
  out["proven"] = a.proven;
  out["reason"] = answer_reason(a);
  out["max_tilt"] = optional_number(a.max_tilt);
  out["falls_at"] = optional_number(a.falls_at);
  out["horizon"] = a.horizon;
  out["min_spin"] = optional_number(a.min_spin);
  out["lifetime"] = optional_number(a.lifetime);
  return out;
}

}  // namespace

namespace {

Json quantity_json(const UncertainQuantity& q) {
  Json out;
  out["value"] = q.value;
  out["standard_uncertainty"] = q.standard_uncertainty;
  out["interval"] = Json::array({q.lo, q.hi});
  return out;
}

Json outcome_json(const std::optional<UncertainOutcome>& o) {
  if (!o) return nullptr;
  Json out = quantity_json(*o);
  out["fraction"] = o->fraction;
  return out;
}

Json uncertainty_object(const UncertaintyAnalysis& u) {
  Json out;
  out["method"] = std::string(name(u.method));
  out["draws"] = u.draws;
  out["coverage"] = u.coverage;
  out["p_stays_up"] = u.p_stays_up;
  out["p_stays_up_interval"] = Json::array({u.p_stays_up_lo, u.p_stays_up_hi});
  out["critical_spin"] = u.critical_spin ? quantity_json(*u.critical_spin) : Json(nullptr);
  out["falls_at"] = outcome_json(u.falls_at);
  out["max_tilt"] = outcome_json(u.max_tilt);
  Json sensitivity = Json::object();
  for (const auto& [key, value] : u.sensitivity)  // NaN (no critical spin) as null
    sensitivity[key] = std::isfinite(value) ? Json(value) : Json(nullptr);
  out["sensitivity"] = sensitivity;
  return out;
}

}  // namespace

std::string uncertainty_json(const UncertaintyAnalysis& uncertainty) {
  return uncertainty_object(uncertainty).dump(2) + "\n";
}

std::string stability_json(const Body& body, const TopAnalysis& analysis, const UncertaintyAnalysis* uncertainty) {
  const double spin = analysis.spin;
  const auto& models = analysis.models;
  const auto& lyapunov = analysis.lyapunov;
  const auto& wander = analysis.wander;
  const auto& answer = analysis.answer;
  Json out = stability_object(body, spin, models, answer_object(answer));
  Json l;
  l["verdict"] = std::string(name(lyapunov.verdict.verdict));
  l["certificate"] = std::string(name(lyapunov.verdict.certificate));
  l["energy_index"] = lyapunov.verdict.energy_index;
  l["stable_spin_intervals"] = intervals_json(lyapunov.intervals);
  l["superfast_spin"] = optional_number(lyapunov.superfast);
  l["normal_form"] = normal_form_json(lyapunov.verdict.normal_form);
  out["lyapunov"] = l;
  Json w;
  w["max_tilt"] = optional_number(wander.max_tilt);
  w["method"] = wander.closed_form ? "closed form" : "integrated";
  w["horizon"] = optional_number(wander.horizon);
  if (!wander.max_tilt) w["note"] = wander.note;
  out["wander"] = w;
  if (uncertainty) out["uncertainty"] = uncertainty_object(*uncertainty);
  return out.dump(2) + "\n";
}

namespace {

Json table_settings_json(const Body& body, const Table& table) {
  Json t;
  t["contact"] = std::string(name(table.contact));
  if (table.contact == Contact::Sliding) {
    t["friction"] = table.friction;
    t["friction_law"] = std::string(name(table.friction_law));
    t["slip_speed"] = table.slip_speed;
  }
  t["tip_radius"] = body.tip_radius;
  t["rim_radius"] = body.rim_radius;
  // The body's own losses (docs/contract.md), only where they act: earlier outputs stay as they were.
  auto material = [](const std::optional<Material>& m) -> Json {
    if (!m) return nullptr;
    return {{"modulus", m->modulus}, {"poisson", m->poisson}};
  };
  if (table.friction_law == FrictionLaw::Contensou) {
    t["tip_material"] = material(table.tip_material);
    t["material"] = material(table.material);
  }
  if (table.rolling_resistance > 0.0) t["rolling_resistance"] = table.rolling_resistance;
  if (table.air) t["air"] = {{"density", table.air->density}, {"viscosity", table.air->viscosity},
                             {"surfaces", table.air_surfaces.empty() ? "equivalent disc" : "parts"}};
  return t;
}

Json losses_json(const TableLosses& l) {
  return {{"sliding", l.sliding}, {"drilling", l.drilling}, {"rolling", l.rolling}, {"air", l.air}};
}

Json spin_down_json(const TableSpinDown& d) {
  return {{"critical_spin", optional_number(d.critical_spin)},
          {"time_to_critical", optional_number(d.time_to_critical)},
          {"patch_radius", d.patch_radius},
          {"drilling_torque", d.drilling_torque},
          {"air_torque", d.air_torque},
          {"losses", losses_json(d.losses)}};
}

Json spinning_state_json(const SpinningStateStability& s) {
  if (!s.exists) return nullptr;
  Json j;
  j["stable"] = s.stable;
  j["asymptotically"] = s.asymptotically;
  j["critical_spin"] = optional_number(s.critical_spin);
  j["stable_spin_intervals"] = Json::array();
  for (const auto& [lo, hi] : s.stable_spin_intervals) j["stable_spin_intervals"].push_back({lo, optional_number(hi)});
  j["eigenvalues"] = Json::array();
  for (const auto& l : s.eigenvalues) j["eigenvalues"].push_back({l.real(), l.imag()});
  j["growth_rate"] = s.growth_rate;
  return j;
}

}  // namespace

std::string table_trajectory_json(const Body& body, const Table& table, const InitialState& s, const TableRun& run) {
  Json out;
  out["model"] = "nonlinear";
  out["body"] = body_json(body);
  if (!is_realizable(body)) out["realizable"] = false;
  out["motion"] = {{"spin", s.spin}, {"theta0", s.theta0}, {"phi0", s.phi0},
                   {"theta_rate0", s.theta_rate0}, {"phi_rate0", s.phi_rate0}};
  out["table"] = table_settings_json(body, table);
  const Trajectory& tr = run.trajectory;
  const auto names = tr.column_names();
  out["columns"] = names;
  for (std::size_t c = 0; c < names.size(); ++c) out[names[c]] = tr.column(c);
  const TableSummary& m = run.summary;
  out["summary"] = {{"end", m.end == TableSummary::End::LeftTable ? "leaves the table" : "completed"},
                    {"end_time", m.end_time},
                    {"steps", m.steps},
                    {"rhs_evaluations", m.rhs_evaluations},
                    {"switches", m.switches},
                    {"integrator", name(m.integrator)},
                    {"max_relative_energy_drift", m.max_relative_energy_drift},
                    {"max_relative_jellett_drift", m.max_relative_jellett_drift},
                    {"max_relative_vertical_momentum_drift", m.max_relative_vertical_momentum_drift}};
  if (table.has_losses()) out["summary"]["losses"] = losses_json(m.losses);
  return out.dump() + "\n";
}

std::string table_stability_json(const Body& body, const Table& table, const TableAnalysis& analysis,
                                 const std::vector<ModelStability>& pivot_models) {
  const TableAnswer& a = analysis.answer;
  Json answer;
  answer["verdict"] = std::string(name(a.verdict));
  answer["proven"] = a.proven;
  answer["reason"] = table_answer_reason(a, table);
  answer["max_tilt"] = a.max_tilt;
  answer["falls_at"] = optional_number(a.falls_at);
  answer["horizon"] = a.horizon;
  answer["min_spin"] = optional_number(a.min_spin);
  answer["lifetime"] = nullptr;
  answer["table"] = {{"upright_at", optional_number(a.upright_at)},
                     {"turns_over_at", optional_number(a.turns_over_at)},
                     {"leaves_at", optional_number(a.leaves_at)},
                     {"track", a.track},
                     {"final_tilt", a.final_tilt},
                     {"final_spin", a.final_spin}};
  if (a.spin_down) answer["table"]["spin_down"] = spin_down_json(*a.spin_down);
  Json out = stability_object(body, analysis.spin, pivot_models, std::move(answer));
  Json t = table_settings_json(body, table);
  t["upright"] = spinning_state_json(analysis.stability.upright);
  t["inverted"] = spinning_state_json(analysis.stability.inverted);
  out["table"] = t;
  return out.dump(2) + "\n";
}

std::string table_stability_text(const Body& body, const Table& table, const TableAnalysis& analysis) {
  std::ostringstream out;
  out << table_answer_text(analysis.answer, table) << "\n\n";
  out << "The details\n-----------\n";
  out << fmt::format("Body: A = {:g}, B = {:g}, C = {:g} kg m^2 about O; m = {:g} kg, l = {:g} m (A_G = {:g}, "
                     "B_G = {:g} kg m^2 about G); tip radius {:g} m, rim radius {:g} m\n",
                     body.A, body.B, body.C, body.mass, body.length, central_moment_A(body), central_moment_B(body),
                     body.tip_radius, body.rim_radius);
  out << fmt::format("Spinning states at {:.6g} rad/s ({}), linearised in body axes:\n", analysis.spin,
                     name(table.contact));
  const auto state = [&](const char* label, const SpinningStateStability& s) {
    if (!s.exists) {
      out << fmt::format("  {}: none (a rim's axis cannot stand vertical)\n", label);
      return;
    }
    std::string intervals;
    for (const auto& [lo, hi] : s.stable_spin_intervals)
      intervals += fmt::format("{}{}", intervals.empty() ? "" : ", ",
                               hi ? fmt::format("[{:.6g}, {:.6g}]", lo, *hi)
                                  : lo == 0.0 ? std::string("every spin") : fmt::format("from {:.6g}", lo));
    out << fmt::format("  {}: {}{}; growth rate {:.4g} 1/s; stable for spins (rad/s): {}\n", label,
                       s.stable ? "stable" : "unstable", s.asymptotically ? ", asymptotically" : "", s.growth_rate,
                       intervals.empty() ? "none" : intervals);
  };
  state("upright (tilt 0)", analysis.stability.upright);
  state("inverted (tilt pi)", analysis.stability.inverted);
  return out.str();
}

std::string intervals_text(const std::vector<SpinInterval>& intervals) {
  if (intervals.empty()) return "none";
  std::string text;
  for (const auto& i : intervals) {
    if (!text.empty()) text += ", ";
    text += i.hi ? fmt::format("{}{:.6g}, {:.6g}{}", i.lo_included ? "[" : "(", i.lo, *i.hi, i.hi_included ? "]" : ")")
            : i.lo == 0.0 ? std::string(i.lo_included ? "every spin" : "every spin > 0")
            : i.lo_included ? fmt::format("from {:.6g}", i.lo)
                            : fmt::format("above {:.6g}", i.lo);
  }
  return text;
}

namespace {

/// The linear models' table and the notes on the paper's errors (the first half of `stability`).
std::string linear_stability_text(const Body& body, double spin, const std::vector<ModelStability>& models) {
  std::ostringstream out;
  out << fmt::format("Body: A = {:g}, B = {:g}, C = {:g} kg m^2; m g R = {:g} N m ({})\n", body.A,
                     body.B, body.C, body.mgR(),
                     body.length > 0 ? "centre of mass above O" :
                     body.length < 0 ? "hanging: centre of mass below O" : "centre of mass at O");
  const Damping& d = body.damping;
  if (!d.conservative())
    out << fmt::format("Damping: transverse d_t = {:g} N m s, axial d_a = {:g} N m s, friction tau0 = {:g} N m{}\n",
                       d.transverse, d.axial, d.friction, d.driven ? "; driven (a motor holds the spin)" : "");
  out << fmt::format("Spin: w0 = {:g} rad/s ({:.0f} rpm)\n\n", spin, spin * 30.0 / M_PI);
  out << fmt::format("{:<13} {:<9} {:>16}  {:<28} {}\n", "model", "verdict", "critical rad/s",
                     "stable spins (rad/s)", "why");
  for (const auto& r : models) {
    out << fmt::format("{:<13} {:<9} {:>16}  {:<28} {}\n", name(r.kind),
                       r.verdict.stable ? "stable" : "UNSTABLE",
                       r.critical ? fmt::format("{:.6g}", *r.critical) : "none",
                       intervals_text(r.intervals), r.verdict.reason);
  }
  // SPEC section 9: text gives spins in rpm too.
  std::string rpm;
  for (const auto& r : models)
    rpm += fmt::format("{}{} {}", rpm.empty() ? "" : ", ", name(r.kind),
                       r.critical ? fmt::format("{:.6g}", rpm_from_rad_per_s(*r.critical)) : "none");
  out << "critical spins in rpm: " << rpm << "\n";
  out << "\n(first-order: the paper's model (4), (9); body-fixed: its model (5), which the paper "
         "itself calls erroneous; linearized: the exact linearisation, the one to trust.)\n";
  const auto& paper = models[0];
  const auto& truth = models[2];
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
  if (d.transverse > 0.0) {
    if (truth.intervals.empty())
      out << fmt::format(
          "\nUnder the drag d_t = {:g} N m s no spin holds this body up (Kelvin-Tait-Chetaev: drag destroys "
          "stability that rests on gyroscopic forces alone).\n",
          d.transverse);
    if (truth.verdict.growth_rate > 0.0)
      out << fmt::format("At w0 = {:g} rad/s the growing mode e-folds in {:.4g} s (growth rate {:.4g} 1/s).\n", spin,
                         1.0 / truth.verdict.growth_rate, truth.verdict.growth_rate);
    else if (truth.verdict.growth_rate < 0.0)
      out << fmt::format("At w0 = {:g} rad/s every mode decays: the slowest e-folds in {:.4g} s.\n", spin,
                         -1.0 / truth.verdict.growth_rate);
  }
  if (is_symmetric(body) && body.mgR() > 0 && d.transverse == 0.0)
    out << "\nSymmetric top: the classical sleeping-top criterion C^2 w0^2 > 4 A m g R applies "
           "(strictly: at equality the motion grows, erratum E2).\n";
  return out.str();
}

}  // namespace

namespace {

/// The lines under the Lyapunov verdict at index 2 (SPEC section 7): the normal form, that a
/// KAM verdict holds for perturbations small enough, and how far the spin is from a resonance
/// or from D = 0.
std::string normal_form_text(const LyapunovVerdict& v, double spin, const std::vector<SpinInterval>& intervals) {
  if (!v.normal_form)
    return "  Not decided: w1 = w2 (the 1:1 resonance), where Arnold's theorem does not apply; "
           "internal damping (energy lost at constant momentum) destroys this rotation.\n";
  const NormalForm& nf = *v.normal_form;
  const ResonanceDistance near = resonance_distance(nf);
  std::string text = fmt::format(
      "  Normal form (order 4): w1 = {:.6g}, w2 = {:.6g} rad/s; c20 = {:.6g}, c11 = {:.6g}, c02 = {:.6g}; "
      "D = {:.6g} (|D| = {:.3g} of |c20| w2^2 + |c11| w1 w2 + |c02| w1^2; 0 would be undecided){}\n",
      nf.w1, nf.w2, nf.c20, nf.c11, nf.c02, nf.D, nf.D_scale > 0.0 ? std::abs(nf.D) / nf.D_scale : 0.0,
      nf.resonance == 2 || nf.resonance == 3
          ? fmt::format("; at the {} resonance{}", resonance_name(nf.resonance),
                        nf.a13 ? fmt::format(", a13 = {:.6g}", *nf.a13) : std::string(" (harmless: no cubic terms)"))
          : std::string());
  text += fmt::format("  Frequency ratio w1/w2 = {:.6g}, {:.3g} (relative) from the nearest resonance that matters ({})",
                      nf.w1 / nf.w2, near.distance, near.nearest);
  for (const auto& i : intervals)
    if (spin >= i.lo && (!i.hi || spin <= *i.hi)) {
      text += fmt::format("; the spins proven stable around this one: {} rad/s", intervals_text({i}));
      break;
    }
  text += ".\n";
  if (v.verdict == LyapunovVerdictKind::Stable)
    text += "  The KAM verdict holds for perturbations small enough (the theorem gives no size); internal "
            "damping (energy lost at constant momentum) destroys this rotation.\n";
  else if (v.verdict == LyapunovVerdictKind::Undecided)
    text += "  Not decided: the order-4 normal form is degenerate here; order 6 would decide.\n";
  return text;
}

}  // namespace

std::string stability_text(const Body& body, const TopAnalysis& analysis, const UncertaintyAnalysis* uncertainty) {
  const double spin = analysis.spin;
  const auto& models = analysis.models;
  const auto& lyapunov = analysis.lyapunov;
  const auto& wander = analysis.wander;
  const auto& answer = analysis.answer;
  std::ostringstream out;
  out << answer_text(answer) << (uncertainty ? " " + uncertainty_sentence(*uncertainty) : std::string()) << "\n\n";
  out << "The details\n-----------\n";
  out << linear_stability_text(body, spin, models);
  const LyapunovVerdict& v = lyapunov.verdict;
  out << fmt::format("\nThe real body (nonlinear, conservative{}), beyond the linearisation:\n",
                     body.damping.conservative() ? "" : ": the damping above ignored here; the answer above includes it");
  out << fmt::format("  linearly stable (the exact linearisation): {}\n",
                     models.back().verdict.stable ? "yes" : "no");
  out << fmt::format("  Lyapunov: {} ({}; certificate {})\n", name(v.verdict), v.reason, name(v.certificate));
  out << fmt::format("  energy index {} (s1 = {:.6g}, s2 = {:.6g} N m); proven stable for spins (rad/s): {}; "
                     "superfast {}\n",
                     v.energy_index, v.s1, v.s2, intervals_text(lyapunov.intervals),
                     lyapunov.superfast ? fmt::format("from {:.6g} rad/s ({:.6g} rpm)", *lyapunov.superfast,
                                                        rpm_from_rad_per_s(*lyapunov.superfast))
                                       : "at no spin");
  if (v.certificate == LyapunovCertificate::CriticalQuartic)
    out << "  At the boundary of (9) the linear models grow (a Jordan block, erratum E2), but the real "
           "symmetric top does not: started delta off vertical its tilt stays below about sqrt(2 delta).\n";
  if (v.energy_index == 2 && (v.normal_form || v.verdict == LyapunovVerdictKind::Undecided))
    out << normal_form_text(v, spin, lyapunov.intervals);
  if (wander.max_tilt)
    out << fmt::format("  Axis wander from the given state: largest tilt {:.6g} rad ({})\n", *wander.max_tilt,
                       wander.closed_form ? "closed form"
                                          : fmt::format("integrated over {:g} s", wander.horizon.value_or(0.0)));
  else
    out << fmt::format("  Axis wander from the given state: not computed ({})\n", wander.note);
  out << "\n" << kStabilityGlossary;
  return out.str();
}


std::string lifetime_json(const Lifetime& life) {
  Json out;
  out["spin_decay"] = {{"critical_spin", optional_number(life.critical_spin)},
                       {"time_to_critical", optional_number(life.time_to_critical)}};
  out["fall"] = {{"time", optional_number(life.fall_time)}, {"spin", optional_number(life.fall_spin)},
                 {"max_tilt", life.max_tilt}};
  out["horizon"] = life.horizon;
  return out.dump(2) + "\n";
}

std::string table_lifetime_json(const TableLifetime& life) {
  const TableAnswer& a = life.answer;
  Json out;
  out["spin_decay"] = {{"critical_spin", optional_number(life.spin_down.critical_spin)},
                       {"time_to_critical", optional_number(life.spin_down.time_to_critical)}};
  std::optional<double> fall_spin;
  if (a.falls_at) fall_spin = a.final_spin;  // the run ends at the fall
  out["fall"] = {{"time", optional_number(a.falls_at)}, {"spin", optional_number(fall_spin)},
                 {"max_tilt", a.fall_threshold}};
  out["horizon"] = a.horizon;
  out["table"] = {{"verdict", std::string(name(a.verdict))}, {"spin_down", spin_down_json(life.spin_down)}};
  return out.dump(2) + "\n";
}

std::string table_lifetime_text(const TableLifetime& life, const Table& table) {
  const TableAnswer& a = life.answer;
  std::string text = a.falls_at ? fmt::format("Falls after {:.4g} s (its tilt passes {:.3g} degrees).", *a.falls_at,
                                              a.fall_threshold * 180.0 / M_PI)
                                : table_answer_headline(a);
  text += table_spin_down_words(life.spin_down, table);
  text += "\n" + table_answer_reason(a, table) + "\n";
  return text;
}

namespace {
std::string spin_text(double w) { return fmt::format("{:.6g} rad/s ({:.5g} rpm)", w, w * 30.0 / M_PI); }
}  // namespace

std::string lifetime_text(const Body& body, const InitialState& initial, const Lifetime& life) {
  std::ostringstream out;
  const Damping& d = body.damping;
  // The answer first (SPEC 14): how long it stays up.
  out << (life.fall_time ? fmt::format("Falls after {:.4g} s (its tilt passes {:.3g} degrees).\n", *life.fall_time,
                                       life.max_tilt * 180.0 / M_PI)
                         : fmt::format("Stays up for the {:.4g} s computed (its tilt stays below {:.3g} degrees).\n",
                                       life.horizon, life.max_tilt * 180.0 / M_PI));
  // Exactly upright it never tilts, however slowly it spins (an unstable equilibrium below the
  // critical spin): say so, and when.
  if (!life.fall_time && at_rest_upright(initial) && life.time_to_critical && *life.time_to_critical < life.horizon)
    out << fmt::format("But only because it starts exactly upright: from t = {:.4g} s its spin is below the critical "
                       "spin and the slightest disturbance makes it fall.\n",
                       *life.time_to_critical);
  if (life.max_tilt != life.limit_given)
    out << fmt::format("It started beyond the {:.3g} degree limit of a fall, so a fall here is a tilt past {:.3g} "
                       "degrees, halfway from its start to upside down.\n",
                       life.limit_given * 180.0 / M_PI, life.max_tilt * 180.0 / M_PI);
  out << fmt::format("Spin {} with axial damping d_a = {:g} N m s, friction tau0 = {:g} N m, transverse "
                     "damping d_t = {:g} N m s{}.\n",
                     spin_text(initial.spin), d.axial, d.friction, d.transverse,
                     d.driven ? "; driven: a motor holds the spin" : "");
  if (!life.critical_spin)
    out << "Critical spin: none (no spin holds this body up, even without damping).\n";
  else if (*life.critical_spin == 0.0)
    out << "Critical spin: 0 (stable at every spin without damping).\n";
  else if (d.driven)
    out << fmt::format("The spin stays at {}: the motor holds it above the critical spin {}.\n", spin_text(initial.spin),
                       spin_text(*life.critical_spin));
  else if (!life.time_to_critical)
    out << fmt::format("The spin never reaches the critical spin {} (nothing slows it).\n",
                       spin_text(*life.critical_spin));
  else if (*life.time_to_critical == 0.0)
    out << fmt::format("The spin is already at or below the critical spin {}.\n", spin_text(*life.critical_spin));
  else
    out << fmt::format("The spin reaches the critical spin {} at t = {:.6g} s ({}).\n", spin_text(*life.critical_spin),
                       *life.time_to_critical,
                       life.law_exact ? "the closed-form spin law" : "the spin law, approximate for A != B");
  if (life.fall_time)
    out << fmt::format("The top falls (tilt past {:g} rad) at t = {:.6g} s, spinning at {}.\n", life.max_tilt,
                       *life.fall_time, spin_text(*life.fall_spin));
  else
    out << fmt::format("The top does not fall within {:g} s (largest tilt {:.4g} rad, threshold {:g} rad).\n",
                       life.horizon, life.largest_tilt, life.max_tilt);
  return out.str();
}

std::string number(double value) {
  if (std::isnan(value)) return "nan";
  return fmt::format("{}", value);
}

std::string trajectory_csv_header(const Trajectory& tr) {
  const auto names = tr.column_names();
  std::string head;
  for (std::size_t c = 0; c < names.size(); ++c) head += (c ? "," : "") + names[c];
  return head + "\n";
}

std::string trajectory_csv_rows(const Trajectory& tr, std::size_t begin, std::size_t end) {
  std::vector<const std::vector<double>*> columns;
  for (std::size_t c = 0; c < kTrajectoryColumns.size() + tr.extra.size(); ++c) columns.push_back(&tr.column(c));
  // Each number with a compiled "{}" (the same shortest round-trip text as fmt::format) written
  // through a plain char pointer straight into the string, sized once for the worst case: half
  // the instructions of formatting through a back_inserter into a buffer (callgrind), and these
  // 11 numbers a sample are most of a CSV's cost. kRoom chars hold any double and its separator
  // this way: at most 17 digits, a sign, a point and "e-308" or 4 leading zeros (24), a comma.
  constexpr std::size_t kRoom = 32;
  std::string text(end > begin ? (end - begin) * columns.size() * kRoom : 0, '\0');
  char* p = text.data();
  for (std::size_t i = begin; i < end; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) *p++ = ',';
      p = fmt::format_to(p, FMT_COMPILE("{}"), (*columns[c])[i] + 0.0);
    }
    *p++ = '\n';
  }
  text.resize(static_cast<std::size_t>(p - text.data()));
  return text;
}

std::string trajectory_csv(const Trajectory& tr) { return trajectory_csv_header(tr) + trajectory_csv_rows(tr, 0, tr.size()); }

std::string trajectory_json(Model model, const Body& body, const InitialState& s, const Trajectory& tr,
                            const NonlinearSummary* summary) {
  Json out;
  out["model"] = std::string(name(model));
  out["body"] = body_json(body);
  if (!is_realizable(body)) out["realizable"] = false;  // SPEC section 1, beside the body
  out["motion"] = {{"spin", s.spin}, {"theta0", s.theta0}, {"phi0", s.phi0},
                   {"theta_rate0", s.theta_rate0}, {"phi_rate0", s.phi_rate0}};
  const auto names = tr.column_names();
  out["columns"] = names;
  for (std::size_t c = 0; c < names.size(); ++c) out[names[c]] = tr.column(c);
  if (summary) {
    out["summary"] = {{"steps", summary->steps},
                      {"rejected_steps", summary->rejected_steps},
                      {"rhs_evaluations", summary->rhs_evaluations},
                      {"max_relative_energy_drift", summary->max_relative_energy_drift},
                      {"max_relative_vertical_momentum_drift", summary->max_relative_vertical_momentum_drift}};
  }
  return out.dump() + "\n";
}


std::string comparison_json(const Comparison& c) {
  Json out;
  out["nonlinear"] = {{"nutation_frequency", optional_number(c.nonlinear_frequencies.nutation)},
                      {"precession_rate", optional_number(c.nonlinear_frequencies.precession)},
                      {"steps", c.summary.steps},
                      {"max_relative_energy_drift", c.summary.max_relative_energy_drift}};
  Json models = Json::object();
  for (const auto& m : c.models) {
    if (m.diverged_at) {  // beyond any small-motion meaning: when, and the error until then
      models[m.model] = {{"diverged_at", *m.diverged_at},
                         {"max_angle_error", m.max_angle_error},
                         {"final_angle_error", nullptr},
                         {"nutation_frequency", nullptr},
                         {"precession_rate", nullptr},
                         {"nutation_relative_error", nullptr},
                         {"precession_relative_error", nullptr}};
      continue;
    }
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
                    "nutation_relative_error,precession_relative_error,diverged_at\n";
  auto cell = [](const std::optional<double>& x) { return x ? number(*x) : std::string(); };
  out += fmt::format("nonlinear,0,0,{},{},0,0,\n", cell(c.nonlinear_frequencies.nutation),
                     cell(c.nonlinear_frequencies.precession));
  for (const auto& m : c.models)
    out += m.diverged_at ? fmt::format("{},{},,,,,,{}\n", m.model, number(m.max_angle_error), number(*m.diverged_at))
                         : fmt::format("{},{},{},{},{},{},{},\n", m.model, number(m.max_angle_error), number(m.final_angle_error),
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
    if (m.diverged_at)
      out << fmt::format("{:<15} {:>12.3e}   diverges at t = {:.4g} s (its angles pass {:g} rad: no small motion "
                         "left to compare)\n", m.model, m.max_angle_error, *m.diverged_at, kDivergedAngle);
    else
    out << fmt::format("{:<15} {:>12.3e} {:>12.3e} {:>12} {:>10} {:>12} {:>10}\n", m.model, m.max_angle_error,
                       m.final_angle_error, freq(m.frequencies.nutation), rel(m.nutation_relative_error),
                       freq(m.frequencies.precession), rel(m.precession_relative_error));
  out << fmt::format("\nIntegrator: {} steps, energy drift {:.1e} (relative).\n", c.summary.steps,
                     c.summary.max_relative_energy_drift);
  return out.str();
}

std::string sweep_csv_header(const std::vector<SweepAxis>& axes, bool nonlinear, bool tolerance) {
  std::string h;
  for (const auto& a : axes) h += a.key + ",";
  for (std::size_t m = 0; m < kLinearModels.size(); ++m) h += fmt::format("{}{}", m ? "," : "", name(kLinearModels[m]));
  h += ",lyapunov,lyapunov_certificate";
  if (nonlinear) h += ",nonlinear";
  if (nonlinear && tolerance) h += ",nonlinear_tolerance";
  return h + "\n";
}

std::string sweep_csv_rows(const std::vector<SweepAxis>& axes, std::size_t begin, const std::vector<SweepVerdict>& verdicts,
                           bool tolerance) {
  fmt::memory_buffer out;
  for (std::size_t r = 0; r < verdicts.size(); ++r) {
    for (double value : grid_values(axes, begin + r)) fmt::format_to(fmt::appender(out), "{},", value);
    const auto& v = verdicts[r];
    fmt::format_to(fmt::appender(out), "{},{},{},{},{}", int(v.linear[0]), int(v.linear[1]), int(v.linear[2]),
                   int(v.lyapunov), name(v.lyapunov_certificate));
    if (v.nonlinear) fmt::format_to(fmt::appender(out), ",{}", int(*v.nonlinear));
    if (v.nonlinear && tolerance) fmt::format_to(fmt::appender(out), ",{}", v.nonlinear_tolerance.value_or(std::nan("")));
    out.push_back('\n');
  }
  return fmt::to_string(out);
}

void refuse_general_keys(const Body& body) {
  const GeneralInertia& g = body.general;
  for (const auto& [key, value] : {std::pair{"body.Ixy", g.Ixy}, std::pair{"body.Ixz", g.Ixz}, std::pair{"body.Iyz", g.Iyz},
                                   std::pair{"body.offset_x", g.offset_x}, std::pair{"body.offset_y", g.offset_y}})
    if (value != 0.0)
      throw InvalidInput(key, fmt::format("is {:g}: the general body (SPEC section 11: the centre of mass off the z axis, "
                                          "products of inertia) is integrated by `simulate --model nonlinear` only "
                                          "(`heavytop body` reports it)",
                                          value));
}

void refuse_general_in(const Body& body, const std::string& command) {
  if (const char* key = first_general_key(body))
    throw InvalidInput(key, fmt::format("is nonzero: the general body (SPEC section 11: the centre of mass off the z "
                                        "axis, products of inertia) is integrated by `simulate --model nonlinear` "
                                        "only, not by {}",
                                        command));
}

std::optional<std::string> explorer_page(std::string built_page, const Body& b, const InitialState& s) {
  const std::string mark = "/*HEAVYTOP_INITIAL*/null";
  const auto at = built_page.find(mark);
  if (at == std::string::npos) return std::nullopt;
  // The tip's and rim's radii and the motor only when given, so a page of a body without them
  // stays what it was (issue 46: a report's and Python's page dropped `driven`).
  std::string radii;
  if (b.tip_radius != 0.0) radii += fmt::format(", \"tip_radius\": {}", number(b.tip_radius));
  if (b.rim_radius != 0.0) radii += fmt::format(", \"rim_radius\": {}", number(b.rim_radius));
  built_page.replace(
      at, mark.size(),
      fmt::format("{{\"body\": {{\"A\": {}, \"B\": {}, \"C\": {}, \"mass\": {}, \"gravity\": {}, \"length\": {}{}}}, "
                  "\"motion\": {{\"spin\": {}, \"theta0\": {}, \"phi0\": {}, \"theta_rate0\": {}, \"phi_rate0\": {}{}}}, "
                  "\"damping\": {{\"transverse\": {}, \"axial\": {}, \"friction\": {}}}}}",
                  number(b.A), number(b.B), number(b.C), number(b.mass), number(b.gravity), number(b.length), radii,
                  number(s.spin), number(s.theta0), number(s.phi0), number(s.theta_rate0), number(s.phi_rate0),
                  b.damping.driven ? ", \"driven\": true" : "", number(b.damping.transverse), number(b.damping.axial),
                  number(b.damping.friction)));
  return built_page;
}

}  // namespace heavytop::io

#include "heavytop/io/body_formats.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "heavytop/io/body_parts.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/units.hpp"

namespace heavytop::io {
namespace {

using Json = nlohmann::ordered_json;

Json matrix_json(const Eigen::Matrix3d& m) {
  Json a = Json::array();
  for (int i = 0; i < 3; ++i) a.push_back({m(i, 0), m(i, 1), m(i, 2)});
  return a;
}

Json state_json(const InitialState& s) {
  return {{"spin", s.spin}, {"theta0", s.theta0}, {"phi0", s.phi0}, {"theta_rate0", s.theta_rate0},
          {"phi_rate0", s.phi_rate0}};
}

// A state as a [motion] section a configuration can hold (numbers that read back exactly).
std::string state_toml(const InitialState& s, const std::string& indent) {
  return fmt::format("{0}[motion]\n{0}spin = {1}\n{0}theta0 = {2}\n{0}phi0 = {3}\n{0}theta_rate0 = {4}\n"
                     "{0}phi_rate0 = {5}\n",
                     indent, number(s.spin), number(s.theta0), number(s.phi0), number(s.theta_rate0),
                     number(s.phi_rate0));
}

std::string spin_text(double w) { return fmt::format("{:.6g} rad/s ({:.6g} rpm)", w, rpm_from_rad_per_s(w)); }

}  // namespace

std::string body_json(const AssembledBody& body, double gravity) {
  const BodyAssembly& a = body.assembly;
  Json out;
  out["A"] = a.A;
  out["B"] = a.B;
  out["C"] = a.C;
  out["mass"] = a.total.mass;
  out["length"] = a.length;
  out["gravity"] = gravity;
  out["products"] = {{"xy", a.Ixy}, {"xz", a.Ixz}, {"yz", a.Iyz}};
  out["offset"] = {{"x", a.offset_x}, {"y", a.offset_y}};
  out["principal_axis_tilt"] = a.principal_tilt;
  out["general"] = a.general();
  if (!is_realizable(as_given(a))) out["realizable"] = false;  // SPEC section 1
  Json parts = Json::array();
  for (std::size_t i = 0; i < body.names.size() && i < body.parts.size(); ++i) {
    const MassProperties& p = body.parts[i];
    parts.push_back({{"name", body.names[i]},
                     {"mass", p.mass},
                     {"centre_of_mass", {p.centre.x(), p.centre.y(), p.centre.z()}},
                     {"inertia", matrix_json(p.inertia)}});
  }
  out["parts"] = parts;
  return out.dump(2) + "\n";
}

std::string body_text(const AssembledBody& body, double gravity, const std::optional<UprightSpin>& upright) {
  const BodyAssembly& a = body.assembly;
  std::ostringstream out;
  if (!body.names.empty()) {
    out << fmt::format("{} part{} (SI units; body axes x, y, z through O; moments about O):\n", body.names.size(),
                       body.names.size() == 1 ? "" : "s");
    out << fmt::format("  {:<34} {:>12} {:>14} {:>12} {:>12}\n", "part", "mass kg", "centre z m", "Ixx kg m^2",
                       "Izz kg m^2");
    for (std::size_t i = 0; i < body.names.size() && i < body.parts.size(); ++i) {
      const MassProperties& p = body.parts[i];
      out << fmt::format("  {:<34} {:>12.6g} {:>14.6g} {:>12.6g} {:>12.6g}\n", body.names[i], p.mass, p.centre.z(),
                         p.inertia(0, 0), p.inertia(2, 2));
    }
    out << "\n";
  }
  out << fmt::format("Body: A = {:.9g}, B = {:.9g}, C = {:.9g} kg m^2 about O; mass {:.9g} kg; R = {:.9g} m ({})\n",
                     a.A, a.B, a.C, a.total.mass, a.length,
                     a.length > 0 ? "centre of mass above O" : a.length < 0 ? "centre of mass below O" : "at O");
  if (upright)  // the number a toy maker designs for, in the rpm a motor or a stroboscope reads
    out << (!upright->critical ? std::string("Minimum spin to stand upright: none holds it upright (the linearized "
                                             "model, without damping)\n")
            : *upright->critical == 0.0
                ? fmt::format("Minimum spin to stand upright: none needed, upright is stable at any spin ({})\n",
                              a.length < 0 ? "the centre of mass hangs below O" : "the linearized model")
                : fmt::format("Minimum spin to stand upright (the critical spin of the linearized model, without "
                              "damping): {}\n",
                              spin_text(*upright->critical)));
  out << fmt::format("Products of inertia: Ixy = {:.3g}, Ixz = {:.3g}, Iyz = {:.3g} kg m^2; centre of mass off the "
                     "axis: x = {:.3g}, y = {:.3g} m\n",
                     a.Ixy, a.Ixz, a.Iyz, a.offset_x, a.offset_y);
  if (a.general()) {
    out << fmt::format("\nNOT a body of the models: {}{}. The principal axis nearest z is {:.3g} rad ({:.3g} deg) "
                       "from it.\nThe general body (SPEC section 11) is integrated by `simulate --model nonlinear` "
                       "only: every other model and command refuses it.\n",
                       a.offset_x != 0.0 || a.offset_y != 0.0
                           ? fmt::format("the centre of mass is {:.3g} m off the z axis",
                                         std::hypot(a.offset_x, a.offset_y))
                           : std::string(),
                       a.Ixy != 0.0 || a.Ixz != 0.0 || a.Iyz != 0.0
                           ? std::string(a.offset_x != 0.0 || a.offset_y != 0.0 ? "; " : "") +
                                 "z is not a principal axis through O"
                           : std::string(),
                       a.principal_tilt, a.principal_tilt * 180 / M_PI);
  } else {
    out << "z is a principal axis through O with the centre of mass on it (offsets and products below 1e-9 of the "
           "body's size count as 0):\nevery command accepts this body. As a [body] section:\n\n";
    out << fmt::format("  [body]\n  A = {}\n  B = {}\n  C = {}\n  mass = {}\n  gravity = {}\n  length = {}\n",
                       number(a.A), number(a.B), number(a.C), number(a.total.mass), number(gravity), number(a.length));
  }
  return out.str();
}

std::string precession_json(const Body& body, double tilt, double spin, const PrecessionAnalysis* steady,
                            const std::vector<PermanentRotation>& rotations) {
  Json out;
  out["body"] = {{"A", body.A}, {"B", body.B}, {"C", body.C}, {"mass", body.mass}, {"gravity", body.gravity},
                 {"length", body.length}};
  if (!is_realizable(body)) out["realizable"] = false;  // SPEC section 1, beside the body
  out["tilt"] = tilt;
  out["spin"] = spin;
  auto optional = [](const std::optional<double>& x) { return x ? Json(*x) : Json(nullptr); };
  if (steady) {
    auto one = [](const std::optional<SteadyPrecession>& p) {
      if (!p) return Json(nullptr);
      return Json{{"rate", p->rate}, {"period", p->period}, {"nutation_frequency", p->nutation_frequency},
                  {"state", state_json(p->state)}};
    };
    out["steady_precession"] = {{"slow", one(steady->slow)},
                                {"fast", one(steady->fast)},
                                {"min_spin", optional(steady->min_spin)},
                                {"slow_limit", steady->slow_limit},
                                {"fast_limit", optional(steady->fast_limit)}};
  } else {
    out["steady_precession"] = nullptr;
  }
  Json rot = Json::array();
  for (const auto& p : rotations) {
    Json ev = Json::array();
    for (const auto& l : p.eigenvalues) ev.push_back({l.real(), l.imag()});
    rot.push_back({{"plane", p.plane == 'x' ? "x-z" : "y-z"},
                   {"rate", p.rate},
                   {"period", p.period},
                   {"stable", p.stable},
                   {"eigenvalues", ev},
                   {"state", state_json(p.state)}});
  }
  out["permanent_rotations"] = rot;
  return out.dump(2) + "\n";
}

std::string precession_text(const Body& body, double tilt, double spin, const PrecessionAnalysis* steady,
                            const std::vector<PermanentRotation>& rotations) {
  std::ostringstream out;
  out << fmt::format("Body: A = {:g}, B = {:g}, C = {:g} kg m^2; m g R = {:g} N m. Tilt {:.6g} rad ({:.6g} deg) "
                     "from the upward vertical.\n",
                     body.A, body.B, body.C, body.mgR(), tilt, tilt * 180 / M_PI);
  if (steady) {
    out << fmt::format("\nSteady precession at spin w3 = w.k = {} (A cos(theta) W^2 - C w3 W + m g R = 0):\n",
                       spin_text(spin));
    if (steady->min_spin)
      out << fmt::format("  minimum spin for steady precession at this tilt: {}\n", spin_text(*steady->min_spin));
    else
      out << "  every spin has a steady precession at this tilt (m g R cos(theta) <= 0)\n";
    if (!steady->slow && !steady->fast) out << "  none at this spin: it is below the minimum.\n";
    for (const auto& [label, p] : {std::pair{"slow", &steady->slow}, std::pair{"fast", &steady->fast}}) {
      if (!*p) continue;
      const SteadyPrecession& s = **p;
      out << fmt::format("  {}: W = {} about the upward vertical, period {:.6g} s; small nutation about it at "
                         "{:.6g} rad/s (stable)\n",
                         label, spin_text(s.rate), s.period, s.nutation_frequency);
      out << state_toml(s.state, "      ");
    }
    out << fmt::format("  as the spin grows: slow -> m g R / (C w3) = {:.6g} rad/s{}\n", steady->slow_limit,
                       steady->fast_limit ? fmt::format(", fast -> C w3 / (A cos theta) = {:.6g} rad/s",
                                                        *steady->fast_limit)
                                          : std::string());
  } else {
    out << "\nA != B: no steady precession with a relative spin (the Lagrange top's); the permanent rotations:\n";
  }
  out << "\nPermanent rotations about the vertical at this tilt (cos(tilt) = m g R / ((C - K) W^2), K = A or B):\n";
  if (rotations.empty()) out << "  none: m g R / ((C - K) cos(tilt)) <= 0 for both planes.\n";
  for (const auto& p : rotations) {
    out << fmt::format("  vertical in the body's {} plane (K = {}): W = {}, period {:.6g} s, {}\n",
                       p.plane == 'x' ? "x-z" : "y-z", p.plane == 'x' ? "A" : "B", spin_text(p.rate), p.period,
                       p.stable ? "linearly stable (eigenvalues on the imaginary axis)" : "UNSTABLE (linearised)");
    out << state_toml(p.state, "      ");
  }
  return out.str();
}

}  // namespace heavytop::io

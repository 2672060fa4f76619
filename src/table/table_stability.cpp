// The linear stability of the body spinning about its vertical axis on the table (SPEC section
// 16): the body-frame equations of contact_dynamics.hpp linearised by the complex step (exact
// derivatives: the same lines evaluated at x + i h e_j, h = 1e-30), their eigenvalues, and the
// spins where the verdict changes, scanned and bisected.
#include "heavytop/table.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>

#include "table/contact_dynamics.hpp"

namespace heavytop {

namespace {

using detail::TableParameters;
using Cx = std::complex<double>;
using CV3 = detail::Vec3<Cx>;

// The reduced body-frame variables: gamma_1, gamma_2 (gamma_3 = +-sqrt(1 - ...): upright or
// inverted), omega (3), and, unless the body rolls, G's velocity v_1, v_2 in body axes (v_3 from
// the height constraint v . gamma = f' c'). Returns their rates.
Eigen::VectorXcd reduced_rates(const TableParameters& p, bool inverted, const Eigen::VectorXcd& x) {
  const Cx g3 = (inverted ? -1.0 : 1.0) * detail::sqrt_of(Cx(1.0) - x[0] * x[0] - x[1] * x[1]);
  const CV3 gamma(x[0], x[1], g3), omega(x[2], x[3], x[4]);
  const bool rolls = p.contact == Contact::Rolling;
  Eigen::VectorXcd rates(x.size());
  const CV3 gamma_dot = detail::cross(gamma, omega);
  rates[0] = gamma_dot[0];
  rates[1] = gamma_dot[1];
  if (rolls) {
    const auto m = detail::rolling_motion(p, gamma, omega);
    for (int i = 0; i < 3; ++i) rates[2 + i] = m.omega_dot[i];
    return rates;
  }
  const auto g = detail::contact_geometry(p, gamma);
  const Cx z_rate = g.f1 * gamma_dot[2];
  const CV3 v(x[5], x[6], (z_rate - x[5] * gamma[0] - x[6] * gamma[1]) / gamma[2]);
  const auto m = detail::sliding_motion(p, gamma, omega, v);
  for (int i = 0; i < 3; ++i) rates[2 + i] = m.omega_dot[i];
  const CV3 v_dot = m.accel - detail::cross(omega, v);  // body-axes rate of a fixed-frame vector
  rates[5] = v_dot[0];
  rates[6] = v_dot[1];
  return rates;
}

Eigen::MatrixXd jacobian(const TableParameters& p, bool inverted, double spin) {
  const int n = p.contact == Contact::Rolling ? 5 : 7;
  Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n);
  x[4] = spin;
  Eigen::MatrixXd J(n, n);
  constexpr double h = 1e-30;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXcd xj = x;
    xj[j] += Cx(0.0, h);
    J.col(j) = reduced_rates(p, inverted, xj).imag() / h;
  }
  return J;
}

std::vector<Cx> eigenvalues_of(const TableParameters& p, bool inverted, double spin) {
  const Eigen::MatrixXd J = jacobian(p, inverted, spin);
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(J, false);
  std::vector<Cx> values(solver.eigenvalues().data(), solver.eigenvalues().data() + J.rows());
  std::sort(values.begin(), values.end(), [](Cx a, Cx b) { return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag(); });
  return values;
}

// The scale of the eigenvalues below which a real part counts as zero: rounding in the
// eigensolver of a matrix of this size (1/s). Where friction makes a real part cross zero
// linearly in the spin, a scanned end moves by this over the crossing's slope (1e-11 of the
// largest eigenvalue: within 1e-7 relative of the closed forms, tests); a real part that
// vanishes faster than the spin grows (a sharp tip sliding: like w^-4) is lost below it at
// spins far above any top's, which is why the symmetric body's ends are the closed forms.
double zero_scale(const std::vector<Cx>& values) {
  double largest = 0.0;
  for (Cx v : values) largest = std::max(largest, std::abs(v));
  return 1e-11 * std::max(largest, 1e-300);
}

struct Verdict {
  bool stable = false, asymptotically = false;
  double growth_rate = 0.0;
};

Verdict verdict_of(const std::vector<Cx>& values) {
  const double zero = zero_scale(values);
  Verdict v{true, true, -HUGE_VAL};
  for (Cx e : values) {
    v.growth_rate = std::max(v.growth_rate, e.real());
    if (e.real() > zero) v.stable = false;
    if (std::abs(e) > zero && !(e.real() < -zero)) v.asymptotically = false;
  }
  v.asymptotically = v.asymptotically && v.stable;
  return v;
}

// rad/s, the spin scale of the body on its contact: gravity's frequency sqrt(m g d / I).
double spin_scale(const TableParameters& p) {
  const double d = std::max({std::abs(p.length), p.tip_radius, 1e-300});
  const double inertia = std::min({p.Ag, p.Bg, p.C});
  const double w = std::sqrt(p.mass * std::max(p.gravity, 1e-300) * d / inertia);
  return std::isfinite(w) && w > 0.0 ? w : 1.0;
}

// The spins (rad/s) where a symmetric body on a sphere changes stability, in closed form
// (docs/table.md; the tests check each against the numerical linearisation): nullopt for the
// bodies that have none (A != B), an empty list where no spin changes it. The inverted state
// is the upright one of the body turned over: l -> -l.
std::optional<std::vector<double>> closed_form_changes(const TableParameters& p, bool inverted) {
  // The body's own losses keep these: linearised, Contensou's law is the viscous one with
  // slip_speed eps w (the change is free of slip_speed), the air's torque acts on the spin alone
  // (decoupled from the tilt at first order), and the drilling torque and rolling resistance are
  // left out (parameters_for_stability).
  if (p.Ag != p.Bg || p.rim_radius > 0.0) return std::nullopt;
  const double l = inverted ? -p.length : p.length, r = p.tip_radius, a = r + l, m = p.mass, g = p.gravity;
  double w2 = -1.0;  // the square of the spin that changes it, if > 0
  switch (p.contact) {
    case Contact::Frictionless:  // C^2 w^2 = 4 A_G m g l
      w2 = 4.0 * p.Ag * m * g * l / (p.C * p.C);
      break;
    case Contact::Rolling: {  // Routh: w^2 (C + m r a)^2 = 4 (A_G + m a^2) m g l
      const double H = p.C + m * r * a;
      w2 = 4.0 * (p.Ag + m * a * a) * m * g * l / (H * H);
      break;
    }
    case Contact::Sliding:  // a root crosses at i w r / a, without slip: w^2 = m g l a^2 / (r (C a - A_G r))
      if (r > 0.0 && p.friction > 0.0) w2 = m * g * l * a * a / (r * (p.C * a - p.Ag * r));
      else if (p.friction == 0.0) w2 = 4.0 * p.Ag * m * g * l / (p.C * p.C);  // frictionless
      break;
    case Contact::Pivot: break;
  }
  std::vector<double> changes;
  if (std::isfinite(w2) && w2 > 0.0) changes.push_back(std::sqrt(w2));
  return changes;
}

// The spins w >= 0 where the state is stable, as [lo, hi or above] intervals. Each interval
// between the spins that change the verdict (closed form, or else a geometric scan from 1e-3
// to 1e4 times the spin scale with each change bisected) takes the verdict of the eigenvalues
// at a spin inside it.
std::vector<std::pair<double, std::optional<double>>> stable_spins(const TableParameters& p, bool inverted) {
  auto stable_at = [&](double w) { return verdict_of(eigenvalues_of(p, inverted, w)).stable; };
  std::vector<double> changes;
  if (auto closed = closed_form_changes(p, inverted)) {
    changes = *closed;
  } else {
    const double scale = spin_scale(p);
    constexpr int kPoints = 700;
    double previous_w = 0.0;
    bool previous = stable_at(0.0);
    for (int i = 0; i <= kPoints; ++i) {
      const double w = scale * std::pow(10.0, -3.0 + 7.0 * i / kPoints);
      const bool now = stable_at(w);
      if (now != previous) {
        double a = previous_w, b = w;
        for (int k = 0; k < 200 && b - a > 1e-14 * b; ++k) {
          const double mid = 0.5 * (a + b);
          (stable_at(mid) == previous ? a : b) = mid;
        }
        changes.push_back(0.5 * (a + b));
      }
      previous = now;
      previous_w = w;
    }
  }
  std::vector<std::pair<double, std::optional<double>>> intervals;
  const double first_probe = changes.empty() ? spin_scale(p) : 0.5 * changes.front();
  for (std::size_t i = 0; i <= changes.size(); ++i) {
    const double lo = i == 0 ? 0.0 : changes[i - 1];
    const std::optional<double> hi = i < changes.size() ? std::optional<double>(changes[i]) : std::nullopt;
    const double probe = i == 0 ? first_probe : hi ? std::sqrt(lo * *hi) : 2.0 * lo;
    if (!stable_at(probe)) continue;
    if (!intervals.empty() && intervals.back().second && *intervals.back().second == lo)
      intervals.back().second = hi;  // no change after all: one interval
    else
      intervals.push_back({lo, hi});
  }
  return intervals;
}

SpinningStateStability state_stability(const TableParameters& p, bool inverted, double spin) {
  SpinningStateStability s;
  if (p.rim_radius > 0.0) {
    s.exists = false;
    return s;
  }
  s.eigenvalues = eigenvalues_of(p, inverted, spin);
  const Verdict v = verdict_of(s.eigenvalues);
  s.stable = v.stable;
  s.asymptotically = v.asymptotically;
  s.growth_rate = v.growth_rate;
  s.stable_spin_intervals = stable_spins(p, inverted);
  if (!s.stable_spin_intervals.empty() && !s.stable_spin_intervals.back().second)
    s.critical_spin = s.stable_spin_intervals.back().first;
  return s;
}

TableParameters parameters_for_stability(const Body& body, const Table& table) {
  TableParameters p = TableParameters::of(body, table);
  // Under Coulomb friction the vertical spinning state sticks: it rolls.
  if (table.contact == Contact::Sliding && table.friction_law == FrictionLaw::Coulomb) p.contact = Contact::Rolling;
  // Rolling resistance is set-valued at rest (its regularisation's slope is not physics): the
  // spinning state is linearised without it. Nor with Contensou's drilling torque: it slows the
  // spin about the vertical, and with the spin held (the state is not an equilibrium then) its
  // tilt of the vertical torque would read as a growth at M / (C w), which is only the horizontal
  // angular momentum kept while the vertical one falls: the tilt grows as 1 / w over the whole
  // spin-down, not exponentially (docs/table.md). The patch's friction force and the air stay.
  p.rolling_resistance = 0.0;
  p.drilling = false;
  return p;
}

}  // namespace

std::vector<std::complex<double>> table_eigenvalues(const Body& body, const Table& table, double spin, bool inverted) {
  validate(table, body);
  return eigenvalues_of(parameters_for_stability(body, table), inverted, spin);
}

TableStability table_stability(const Body& body, const Table& table, double spin) {
  validate(table, body);
  if (!table.on_table()) throw InvalidInput("table.contact", "the table's stability needs a table, not \"pivot\"");
  if (!std::isfinite(spin)) throw InvalidInput("motion.spin", "must be finite");
  const TableParameters p = parameters_for_stability(body, table);
  TableStability out;
  out.contact = table.contact;
  out.upright = state_stability(p, false, spin);
  out.inverted = state_stability(p, true, spin);
  return out;
}

}  // namespace heavytop

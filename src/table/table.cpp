// The body on a table (SPEC section 16): the contact's names and checks, and its motion
// integrated by the one DOP853 stepper (integrators/dop853/stepper.hpp) with the normal force's
// zero located on the dense output.
#include "heavytop/table.hpp"

#include <array>
#include <cmath>
#include <complex>
#include <functional>
#include <stdexcept>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "heavytop/frames.hpp"
#include "heavytop/rigid_body.hpp"

#include "integrators/dop853/stepper.hpp"
#include "integrators/rosenbrock/stepper.hpp"
#include "integrators/monitor.hpp"
#include "table/contact_dynamics.hpp"

namespace heavytop {

namespace {

struct ContactName {
  Contact contact;
  std::string_view name;
};
constexpr ContactName kContacts[] = {{Contact::Pivot, "pivot"},
                                     {Contact::Frictionless, "frictionless"},
                                     {Contact::Rolling, "rolling"},
                                     {Contact::Sliding, "sliding"}};

}  // namespace

std::string_view name(Contact contact) {
  for (const auto& c : kContacts)
    if (c.contact == contact) return c.name;
  return "pivot";
}

std::optional<Contact> contact_from_name(std::string_view text) {
  for (const auto& c : kContacts)
    if (c.name == text) return c.contact;
  return std::nullopt;
}

std::string_view name(FrictionLaw law) {
  return law == FrictionLaw::Coulomb ? "coulomb" : law == FrictionLaw::Contensou ? "contensou" : "viscous";
}

std::optional<FrictionLaw> friction_law_from_name(std::string_view text) {
  for (FrictionLaw law : {FrictionLaw::Viscous, FrictionLaw::Coulomb, FrictionLaw::Contensou})
    if (text == name(law)) return law;
  return std::nullopt;
}

namespace {

void validate_material(const std::optional<Material>& material, const char* key) {
  if (!material)
    throw InvalidInput(key, fmt::format("is needed by friction_law = \"contensou\" (Hertz's contact patch): one of {}, "
                                        "or its modulus and poisson",
                                        material_names()));
  if (!(std::isfinite(material->modulus) && material->modulus > 0.0))
    throw InvalidInput(key, "its modulus must be a finite number > 0 (Pa)");
  if (!(std::isfinite(material->poisson) && material->poisson >= 0.0 && material->poisson < 0.5))
    throw InvalidInput(key, "its poisson ratio must be in [0, 0.5)");
}

}  // namespace

void validate(const Table& table) {
  if (!(std::isfinite(table.friction) && table.friction >= 0.0))
    throw InvalidInput("table.friction", "must be a finite number >= 0");
  if (!(std::isfinite(table.slip_speed) && table.slip_speed > 0.0))
    throw InvalidInput("table.slip_speed", "must be a finite number > 0 (m/s)");
  if (table.friction_law == FrictionLaw::Contensou) {
    validate_material(table.tip_material, "table.tip_material");
    validate_material(table.material, "table.material");
  }
  if (!(std::isfinite(table.rolling_resistance) && table.rolling_resistance >= 0.0))
    throw InvalidInput("table.rolling_resistance", "must be a finite number >= 0 (m)");
  if (table.rolling_resistance > 0.0 &&
      (table.contact != Contact::Sliding || table.friction_law == FrictionLaw::Coulomb))
    throw InvalidInput("table.rolling_resistance", "applies to table.contact = \"sliding\" under the viscous or "
                                                   "contensou law only");
  if (table.air) {
    if (!(std::isfinite(table.air->density) && table.air->density > 0.0))
      throw InvalidInput("table.air_density", "must be a finite number > 0 (kg/m^3)");
    if (!(std::isfinite(table.air->viscosity) && table.air->viscosity > 0.0))
      throw InvalidInput("table.air_viscosity", "must be a finite number > 0 (Pa s)");
  }
}

bool Table::IsValid(std::string* why) const {
  try {
    validate(*this);
    return true;
  } catch (const InvalidInput& e) {
    if (why) *why = fmt::format("{}: {}", e.key(), e.rule());
    return false;
  }
}

void validate(const Table& table, const Body& body) {
  validate(table);
  validate(body);
  if (!table.on_table()) return;
  if (const char* key = first_general_key(body))
    throw InvalidInput(key, "a body on a table must have its centre of mass on the axis and principal axes "
                            "(SPEC section 16; the general body of section 11 is for the pivot)");
  const Damping& d = body.damping;
  const char* damped = d.transverse != 0.0 ? "damping.transverse"
                       : d.axial != 0.0    ? "damping.axial"
                       : d.friction != 0.0 ? "damping.friction"
                       : d.driven          ? "motion.driven"
                                           : nullptr;
  if (damped)
    throw InvalidInput(damped, fmt::format("applies to the pivot only: on a table (table.contact = \"{}\") the losses "
                                           "are the contact's (table.friction)",
                                           name(table.contact)));
  if (table.contact == Contact::Sliding && table.friction_law == FrictionLaw::Contensou) {
    if (!(body.tip_radius > 0.0))
      throw InvalidInput("body.tip_radius", "must be > 0 for friction_law = \"contensou\": Hertz's patch is a round "
                                            "tip's (give the tip's radius of curvature)");
    if (body.rim_radius > 0.0)
      throw InvalidInput("body.rim_radius", "must be 0 for friction_law = \"contensou\" (a ring's patch is not modelled)");
  }
}

double stiff_table_ratio(double tolerance) { return 5e3 * std::pow(1e-8 / tolerance, 0.4); }

Integrator table_integrator(const Body& body, const Table& table, const InitialState& initial,
                            const Tolerances& tolerances) {
  if (table.contact != Contact::Sliding || table.friction_law == FrictionLaw::Coulomb || table.friction == 0.0)
    return Integrator::Dop853;
  const double reach = std::abs(body.length) + body.tip_radius + body.rim_radius;
  const double inertia = std::min({central_moment_A(body), central_moment_B(body), body.C});
  // Contensou's law acts as the viscous one with slip_speed eps |w_n| (the patch at N = m g).
  const double slip_speed =
      table.friction_law == FrictionLaw::Viscous
          ? table.slip_speed
          : std::max(detail::drilling_arm(detail::TableParameters::of(body, table), body.mass * body.gravity) *
                         std::abs(initial.spin),
                     detail::kContensouRegularisation);
  const double relaxation = table.friction * body.gravity / slip_speed * (1.0 + body.mass * reach * reach / inertia);
  const double own = std::max({std::abs(initial.spin), std::abs(initial.theta_rate0), std::abs(initial.phi_rate0),
                               std::sqrt(body.mass * body.gravity * reach / inertia)});
  const double tolerance = std::min(tolerances.rtol, tolerances.atol);
  return relaxation > stiff_table_ratio(tolerance) * own ? Integrator::Rosenbrock4 : Integrator::Dop853;
}

double central_moment_A(const Body& body) noexcept { return body.A - body.mass * body.length * body.length; }
double central_moment_B(const Body& body) noexcept { return body.B - body.mass * body.length * body.length; }

namespace {

using detail::ContactMotion;
using detail::TableParameters;
using V3 = Eigen::Vector3d;
constexpr std::size_t kStateSize = 11;  // q (4), omega in body axes (3), G's x, y (2), G's vx, vy (2)
template <class T>
using StateOf = std::array<T, kStateSize>;
using TableVector = StateOf<double>;
using Complex = std::complex<double>;

// The rotation body-to-fixed of q / |q|: from_vector()'s formula (rigid_body.cpp), in any scalar
// (the Jacobian's complex step); q = 0 gives the identity.
template <class T>
Eigen::Matrix<T, 3, 3> rotation_of(const StateOf<T>& y) {
  const T qw = y[0], qx = y[1], qy = y[2], qz = y[3];
  const T n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const T s = std::real(n2) > 0.0 ? T(2.0) / n2 : T(0.0);
  const T tx = s * qx, ty = s * qy, tz = s * qz;
  const T twx = tx * qw, twy = ty * qw, twz = tz * qw;
  const T txx = tx * qx, txy = ty * qx, txz = tz * qx, tyy = ty * qy, tyz = tz * qy, tzz = tz * qz;
  Eigen::Matrix<T, 3, 3> R;
  R << T(1.0) - (tyy + tzz), txy - twz, txz + twy,  //
      txy + twz, T(1.0) - (txx + tzz), tyz - twx,    //
      txz - twy, tyz + twx, T(1.0) - (txx + tyy);
  return R;
}

// One instant of the motion: what the right-hand side and the samples need.
template <class T>
struct InstantOf {
  Eigen::Matrix<T, 3, 3> R;  // body to fixed
  detail::Vec3<T> gamma, omega;  // body axes
  detail::Vec3<T> velocity;      // G's velocity, body axes
  ContactMotion<T> motion;
  detail::ContactGeometry<T> geometry;
};
using Instant = InstantOf<double>;

template <class T>
InstantOf<T> instant_of(const TableParameters& p, const StateOf<T>& y) {
  using Vec = detail::Vec3<T>;
  InstantOf<T> in;
  in.R = rotation_of(y);
  in.gamma = in.R.row(2).transpose();
  in.omega = Vec(y[4], y[5], y[6]);
  in.geometry = detail::contact_geometry(p, in.gamma);
  if (p.contact == Contact::Rolling) {
    in.velocity = detail::cross(in.omega, in.geometry.s);
    in.motion = detail::rolling_motion(p, in.gamma, in.omega);
  } else {
    const T z_rate = in.geometry.f1 * detail::cross(in.gamma, in.omega)[2];
    in.velocity = in.R.transpose() * Vec(y[9], y[10], z_rate);
    in.motion = detail::sliding_motion(p, in.gamma, in.omega, in.velocity);
  }
  return in;
}

struct TableSystem {
  TableParameters p;

  template <class T>
  void rates(const StateOf<T>& y, StateOf<T>& dydt) const {
    const InstantOf<T> in = instant_of(p, y);
    const T qw = y[0], qx = y[1], qy = y[2], qz = y[3], w1 = y[4], w2 = y[5], w3 = y[6];
    dydt[0] = 0.5 * (-qx * w1 - qy * w2 - qz * w3);
    dydt[1] = 0.5 * (qw * w1 + qy * w3 - qz * w2);
    dydt[2] = 0.5 * (qw * w2 + qz * w1 - qx * w3);
    dydt[3] = 0.5 * (qw * w3 + qx * w2 - qy * w1);
    for (int i = 0; i < 3; ++i) dydt[4 + i] = in.motion.omega_dot[i];
    const detail::Vec3<T> v = in.R * in.velocity, a = in.R * in.motion.accel;
    dydt[7] = v[0];
    dydt[8] = v[1];
    dydt[9] = a[0];
    dydt[10] = a[1];
  }

  void operator()(const TableVector& y, TableVector& dydt, double) const { rates(y, dydt); }

  // d(rates)/dy by the complex step, column by column: exact to rounding (no difference quotient).
  void jacobian(const TableVector& y, Eigen::Matrix<double, kStateSize, kStateSize>& J) const {
    constexpr double h = 1e-30;
    StateOf<Complex> z, dz;
    for (std::size_t j = 0; j < kStateSize; ++j) {
      for (std::size_t i = 0; i < kStateSize; ++i) z[i] = y[i];
      z[j] += Complex(0.0, h);
      rates(z, dz);
      for (std::size_t i = 0; i < kStateSize; ++i) J(i, j) = dz[i].imag() / h;
    }
  }
};

// m: P in the fixed frame (its height 0): G's horizontal position less G - P.
V3 contact_point(const TableVector& y, const Instant& in) { return V3(y[7], y[8], 0.0) - in.R * in.geometry.s; }

// The quantities a run watches (SPEC section 16's columns).
struct Watched {
  double energy, jellett, vertical_momentum;
};

Watched watched(const TableParameters& p, const Instant& in) {
  const V3 L = detail::inertia_times(p, in.omega);
  return {0.5 * p.mass * in.velocity.squaredNorm() + 0.5 * in.omega.dot(L) +
              p.mass * p.gravity * in.geometry.height_of_G(p),
          L.dot(in.geometry.s), L.dot(in.gamma)};
}

// W: the rate at which each loss takes energy at one instant (>= 0 each).
TableLosses power_of(const Instant& in) {
  const V3 friction = in.motion.force - in.motion.normal * in.gamma;
  return {-friction.dot(in.motion.slip), -in.motion.drilling.dot(in.omega), -in.motion.rolling.dot(in.omega),
          -in.motion.air.dot(in.omega)};
}

void add(TableLosses& sum, const TableLosses& more, double weight = 1.0) {
  sum.sliding += weight * more.sliding;
  sum.drilling += weight * more.drilling;
  sum.rolling += weight * more.rolling;
  sum.air += weight * more.air;
}

struct DriftScales {
  double energy, jellett, momentum;
};

struct TableHooks {
  TableParameters p;
  TableSummary* summary;
  Watched initial;
  DriftScales scales;
  std::size_t evaluations_before = 0;  // by the run's earlier segments (Coulomb's switches)

  void project(TableVector& y, TableVector& dydt) { detail::renormalise_quaternion(y, dydt); }
  void rejected() {}
  void accepted(double, const TableVector& y, std::size_t evaluations) {
    ++summary->steps;
    summary->rhs_evaluations = evaluations_before + evaluations;
    const Watched w = watched(p, instant_of(p, y));
    auto raise = [](double& drift, double value, double start, double scale) {
      drift = std::max(drift, std::abs(value - start) / scale);
    };
    raise(summary->max_relative_energy_drift, w.energy, initial.energy, scales.energy);
    raise(summary->max_relative_jellett_drift, w.jellett, initial.jellett, scales.jellett);
    raise(summary->max_relative_vertical_momentum_drift, w.vertical_momentum, initial.vertical_momentum,
          scales.momentum);
  }
  void evaluated(std::size_t evaluations) { summary->rhs_evaluations = evaluations_before + evaluations; }
};

using Dop853 = detail::Dop853Stepper<kStateSize, TableSystem, TableHooks>;
using Rosenbrock4 = detail::RosenbrockStepper<kStateSize, TableSystem, TableHooks>;

// Appends the sample of state y at t to the run's trajectory.
class TableSampler {
 public:
  TableSampler(Trajectory& out, bool losses) : out_(out), losses_(losses) {
    out_.extra.clear();
    for (auto c : kAxisDirectionColumns) out_.extra.emplace_back(std::string(c), std::vector<double>{});
    for (auto c : kTableColumns) out_.extra.emplace_back(std::string(c), std::vector<double>{});
    if (losses_)
      for (auto c : kLossColumns) out_.extra.emplace_back(std::string(c), std::vector<double>{});
  }

  // `p`: the equations of that moment (Coulomb's: rolling while the contact sticks); `losses`:
  // the energy each loss has taken by t.
  void add(double t, const TableVector& y, const TableParameters& p, const TableLosses& losses) {
    const Instant in = instant_of(p, y);
    const V3 k = in.R.col(2), k_rate = in.R * in.omega.cross(V3::UnitZ());
    const AxisAngles a = axis_angles(k, k_rate);
    out_.t.push_back(t);
    out_.theta.push_back(a.theta);
    out_.phi.push_back(a.phi);
    out_.theta_rate.push_back(a.theta_rate);
    out_.phi_rate.push_back(a.phi_rate);
    const V3 P = contact_point(y, in);
    const V3 slip = in.motion.slip - in.motion.slip.dot(in.gamma) * in.gamma;
    const Watched w = watched(p, in);
    const double values[] = {tilt_of_axis(k[0], k[1], k[2]),
                             azimuth_.of_axis(k[0], k[1]),
                             P[0],
                             P[1],
                             in.geometry.height_of_O(p),
                             in.motion.normal,
                             p.contact == Contact::Rolling ? 0.0 : slip.norm(),
                             in.omega[2],
                             w.energy,
                             w.jellett,
                             w.vertical_momentum};
    for (std::size_t i = 0; i < std::size(values); ++i) out_.extra[i].second.push_back(values[i]);
    if (losses_) {
      const double taken[] = {losses.sliding, losses.drilling, losses.rolling, losses.air};
      for (std::size_t i = 0; i < std::size(taken); ++i) out_.extra[std::size(values) + i].second.push_back(taken[i]);
    }
  }

 private:
  Trajectory& out_;
  bool losses_;
  ContinuousAzimuth azimuth_;
};

TableVector initial_vector(const TableParameters& p, const InitialState& initial) {
  const RigidBodyVector x = to_vector(initial_rigid_body_state(initial));
  TableVector y{};
  for (int i = 0; i < 7; ++i) y[i] = x[i];
  const Eigen::Matrix3d R = rotation_of(y);
  const V3 gamma = R.row(2).transpose(), omega(y[4], y[5], y[6]);
  const auto g = detail::contact_geometry(p, gamma);
  const V3 G = R * g.s;  // P at the table's origin
  // O at rest horizontally (frictionless, sliding), or rolling.
  const V3 v = R * (p.contact == Contact::Rolling ? omega.cross(g.s) : omega.cross(V3(0.0, 0.0, p.length)));
  y[7] = G[0];
  y[8] = G[1];
  y[9] = v[0];
  y[10] = v[1];
  return y;
}

[[noreturn]] void painleve(double t) {
  throw std::runtime_error(fmt::format("table: the normal force is undetermined at t = {:.9g} s (Painleve's paradox: "
                                       "friction too strong at this tilt); the run stops there", t));
}

}  // namespace

namespace detail {

// The time in [a, b] where g(state) changes sign (g(a), g(b) of opposite signs; an end where it
// is zero or the signs agree by rounding), on a dense output `state_at(t, y)`, by TOMS 748 to
// 1e-12 relative: every event of a run on the table.
template <class StateAt, class G>
double sign_change(StateAt&& state_at, double a, double b, G&& g) {
  TableVector y;
  auto at = [&](double t) {
    state_at(t, y);
    return g(y);
  };
  const double fa = at(a), fb = at(b);
  if (fa == 0.0) return a;
  if (fb == 0.0 || (fa > 0.0) == (fb > 0.0)) return fa * fb > 0.0 && std::abs(fa) < std::abs(fb) ? a : b;
  boost::uintmax_t iterations = 100;
  const auto r = boost::math::tools::toms748_solve(
      at, a, b, fa, fb, [](double x, double z) { return std::abs(z - x) <= 1e-12 * std::max(1.0, std::abs(x)); },
      iterations);
  return 0.5 * (r.first + r.second);
}

// One run on the table, step by step: `on_step(view)` sees each accepted step's interval
// [t0, t1] (t1 an event's time when one ends the step) with its dense output and the equations
// of the moment, and returns false to stop. The run ends at `horizon`, when the normal force
// reaches 0 (its zero located on the dense output) or when on_step stops it. Under Coulomb's
// law the run is a sequence of segments, each a fresh stepper from the state at a switch: the
// contact slips (F = -mu N v / |v|) until the slip vanishes, then sticks (the rolling equations)
// while the force that takes stays within mu N (Leine and Glocker's switches, located as events).
class TableIntegration {
 public:
  TableIntegration(const Body& body, const Table& table, const InitialState& initial, double horizon,
                   const Tolerances& tolerances, Integrator integrator)
      : p_(TableParameters::of(body, table)), horizon_(horizon), tolerances_(tolerances) {
    validate(table, body);
    if (!table.on_table()) throw InvalidInput("table.contact", "needs a table, not \"pivot\"");
    validate(initial);
    validate(tolerances);
    check_integrator(integrator, body, true, false);
    if (!(std::isfinite(horizon) && horizon >= 0.0)) throw InvalidInput("t_end", "must be a finite number >= 0");
    stick_ = p_;
    stick_.contact = Contact::Rolling;
    y0_ = initial_vector(p_, initial);
    const Instant in0 = instant_of(p_, y0_);
    if (p_.rim_radius > 0.0 && !(in0.geometry.S > 0.0))
      throw InvalidInput("motion.theta0", "a rim (body.rim_radius > 0) with its axis exactly vertical lies flat on "
                                          "the table: start it tilted");
    initial_ = watched(p_, in0);
    const double reach = std::abs(p_.length) + p_.tip_radius + p_.rim_radius;
    const double kinetic = initial_.energy - p_.mass * p_.gravity * in0.geometry.height_of_G(p_);
    const double L0 = detail::inertia_times(p_, in0.omega).norm();
    auto positive = [](double x) { return x > 0.0 ? x : 1.0; };
    scales_ = {positive(kinetic + p_.mass * p_.gravity * reach), positive(L0 * reach), positive(L0)};
    // The slip a slipping segment starts from when the contact stops sticking (m/s): far below
    // any tolerance on a velocity, enough to give the friction its direction.
    onset_slip_ = 1e-12 * std::sqrt(std::max(p_.gravity, 1.0) * std::max(reach, 1e-6));
    stop_slip_ = 1e3 * onset_slip_;
    stuck_ = false;
    if (coulomb()) {
      if (slip_of(in0).norm() == 0.0) {
        if (sticks(y0_)) {
          stuck_ = true;
        } else {
          start_slip(y0_);
          armed_ = false;
        }
      }
    }
    const Instant first = instant_of(parameters(), y0_);
    if (!(first.motion.denominator > 0.0)) painleve(0.0);
    normal0_ = first.motion.normal;
    integrator_ = integrator == Integrator::Auto ? table_integrator(body, table, initial, tolerances) : integrator;
  }

  Integrator integrator() const { return integrator_; }

  // The equations of the moment: the contact's, or rolling while Coulomb's contact sticks.
  const TableParameters& parameters() const { return stuck_ ? stick_ : p_; }
  const TableVector& initial_state() const { return y0_; }

  // One accepted step, whichever stepper took it.
  struct StepView {
    const std::function<void(double, TableVector&)>& dense;  // the segment's dense output, its own time
    const TableParameters& params;
    double offset, t0, t1;        // s: the segment's start, the step's ends
    const TableVector& start;     // the state at t0
    const TableVector& end;       // the state at the step's end (before an event cut it short)
    TableLosses before;           // J: what the losses took before t0 (Table::has_losses() only)
    void state_at(double t, TableVector& y) const { dense(t - offset, y); }
    // J: what the losses took by t in [t0, t1]: their powers integrated on the dense output.
    TableLosses losses_at(double t) const {
      TableLosses sum = before;
      if (params.has_losses()) add(sum, losses_over(t0, t));
      return sum;
    }
    // J: the losses' powers integrated over [a, b] by Gauss-Legendre's 5 points (order 10, on
    // the dense output of order 7: below the run's own tolerance).
    TableLosses losses_over(double a, double b) const {
      static constexpr double kNodes[] = {0.0, 0.5384693101056831, 0.9061798459386640};
      static constexpr double kWeights[] = {0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
      TableLosses sum;
      TableVector y;
      const double middle = 0.5 * (a + b), half = 0.5 * (b - a);
      for (int i = 0; i < 3; ++i)
        for (double sign : {-1.0, 1.0}) {
          if (i == 0 && sign > 0.0) continue;
          state_at(middle + sign * half * kNodes[i], y);
          add(sum, power_of(instant_of(params, y)), half * kWeights[i]);
        }
      return sum;
    }
  };

  template <class OnStep>
  void run(TableSummary& summary, OnStep&& on_step) {
    summary = TableSummary{};
    if (normal0_ < 0.0) {
      summary.end = TableSummary::End::LeftTable;
      return;
    }
    if (horizon_ == 0.0) return;
    double offset = 0.0;
    int stalled = 0;
    TableVector y_start = y0_;
    for (;;) {
      const bool switched = integrator_ == Integrator::Rosenbrock4 ? segment<Rosenbrock4>(summary, on_step, offset, stalled, y_start)
                                   : segment<Dop853>(summary, on_step, offset, stalled, y_start);
      if (!switched) return;
    }
  }

 private:
  // One segment of the run, a fresh stepper from y_start at offset: true if it ended at a
  // Coulomb switch (offset and y_start then the switch's), false if the run is over.
  template <class Stepper, class OnStep>
  bool segment(TableSummary& summary, OnStep& on_step, double& offset, int& stalled, TableVector& y_start) {
    const TableParameters q = parameters();
    Stepper stepper(TableSystem{q}, y_start, horizon_ - offset, tolerances_,
                    TableHooks{q, &summary, initial_, scales_, summary.rhs_evaluations});
    const std::function<void(double, TableVector&)> dense = [&stepper](double t, TableVector& y) {
      stepper.interpolate(t, y);
    };
    // Hands a step to on_step, then books its losses.
    auto deliver = [&](const StepView& view) {
      const bool go_on = on_step(view);
      if (q.has_losses()) add(summary.losses, view.losses_over(view.t0, view.t1));
      return go_on;
    };
    while (offset + stepper.time() < horizon_) {
      stepper.step();
      StepView view{dense, q, offset, offset + stepper.previous_time(), offset + stepper.time(),
                    stepper.previous_state(), stepper.state(), summary.losses};
      const Instant end = instant_of(q, stepper.state());
      if (!(end.motion.denominator > 0.0)) painleve(view.t1);
      // The events of this step, the earliest first: leaving the table, Coulomb's switch.
      std::optional<double> leave, change;
      if (end.motion.normal < 0.0)
        leave = locate(view, [&](const TableVector& y) { return instant_of(q, y).motion.normal; });
      if (coulomb()) change = switch_in(view);
      if (leave && (!change || *leave <= *change)) {
        summary.end = TableSummary::End::LeftTable;
        summary.end_time = *leave;
        view.t1 = *leave;
        deliver(view);
        return false;
      }
      if (change) {
        view.t1 = *change;
        summary.end_time = *change;
        if (!deliver(view)) return false;
        stepper.interpolate(*change - offset, y_start);
        // Stick if the force that takes is within the cone, else slip on from the switch.
        if (!stuck_ && sticks(y_start)) {
          stuck_ = true;
          set_rolling_velocity(y_start);
        } else {
          stuck_ = false;
          start_slip(y_start);
          armed_ = false;
        }
        ++summary.switches;
        // Switches that no longer advance the time (Zeno's chatter): stop, saying where.
        stalled = *change > offset ? 0 : stalled + 1;
        if (stalled > 100)
          throw std::runtime_error(fmt::format("table: the contact switches between sticking and slipping without "
                                               "end at t = {:.9g} s (Coulomb's law at a point)", *change));
        offset = *change;
        return true;
      }
      summary.end_time = view.t1;
      if (!deliver(view)) return false;
    }
    return false;
  }

  bool coulomb() const { return p_.contact == Contact::Sliding && p_.law == FrictionLaw::Coulomb; }

  static V3 slip_of(const Instant& in) {
    const V3& v = in.motion.slip;
    return v - v.dot(in.gamma) * in.gamma;
  }

  // The force the contact takes if it sticks at y (body axes), and the normal force.
  std::pair<V3, double> sticking_force(const TableVector& y) const {
    const Instant in = instant_of(stick_, y);
    const V3 F = in.motion.force - in.motion.normal * in.gamma;
    return {F, in.motion.normal};
  }
  bool sticks(const TableVector& y) const {
    const auto [F, N] = sticking_force(y);
    return F.norm() <= p_.friction * N;
  }
  // G's horizontal velocity as rolling demands.
  void set_rolling_velocity(TableVector& y) const {
    const Instant in = instant_of(stick_, y);
    const V3 v = in.R * in.velocity;
    y[9] = v[0];
    y[10] = v[1];
  }
  // From rolling, a slip of onset_slip_ against the force the contact could not take.
  void start_slip(TableVector& y) const {
    set_rolling_velocity(y);
    const auto [F, N] = sticking_force(y);
    const Instant in = instant_of(stick_, y);
    const V3 Ff = in.R * F;
    const double norm = std::hypot(Ff[0], Ff[1]);
    if (norm > 0.0) {
      y[9] -= onset_slip_ * Ff[0] / norm;
      y[10] -= onset_slip_ * Ff[1] / norm;
    }
  }

  // Coulomb's switch in this step: sticking, the force leaves the cone (mu N - |F| < 0);
  // slipping, the slip stops (its component along its direction at the step's start < 0).
  std::optional<double> switch_in(const StepView& view) {
    if (stuck_) {
      auto margin = [&](const TableVector& y) {
        const auto [F, N] = sticking_force(y);
        return p_.friction * N - F.norm();
      };
      if (margin(view.end) >= 0.0) return std::nullopt;
      return locate(view, margin);
    }
    const V3 before = slip_of(instant_of(p_, view.start));
    const double size = before.norm();
    // A slip that starts from a switch grows from onset_slip_ and turns into the direction the
    // body's inertia gives it: its stop is watched once it has grown past 10 stop_slip_.
    if (!armed_) {
      armed_ = slip_of(instant_of(p_, view.end)).norm() > 10.0 * stop_slip_;
      return std::nullopt;
    }
    if (!(size > 0.0)) return std::nullopt;
    // The slip stops where it passes through zero (its component along its direction at the
    // step's start, held, turns negative) or falls below stop_slip_ (a slip that spirals in:
    // its direction turns ever faster and the steps shrink with it).
    const V3 direction = rotation_of(view.start) * before / size;
    auto along = [&](const TableVector& y) {
      const Instant in = instant_of(p_, y);
      return (in.R * slip_of(in)).dot(direction);
    };
    auto above_stop = [&](const TableVector& y) { return slip_of(instant_of(p_, y)).norm() - stop_slip_; };
    std::optional<double> first;
    if (along(view.end) <= 0.0) first = locate(view, along);
    if (above_stop(view.end) < 0.0) {
      const double t = locate(view, above_stop);
      if (!first || t < *first) first = t;
    }
    return first;
  }

  // The first zero of g over the step (g >= 0 at its start, < 0 at its end).
  template <class G>
  static double locate(const StepView& view, G&& g) {
    return sign_change([&](double t, TableVector& y) { view.state_at(t, y); }, view.t0, view.t1, g);
  }

  TableParameters p_, stick_;
  double horizon_;
  Tolerances tolerances_;
  TableVector y0_;
  Watched initial_;
  DriftScales scales_;
  double normal0_ = 0.0;
  double onset_slip_ = 0.0, stop_slip_ = 0.0;  // m/s
  Integrator integrator_ = Integrator::Dop853;  // Dop853 or Rosenbrock4
  bool stuck_ = false;
  bool armed_ = true;  // slipping: the slip's stop is watched (see switch_in)
};

}  // namespace detail

TableRun simulate_on_table(const Body& body, const Table& table, const InitialState& initial, const SampleGrid& grid,
                           const Tolerances& tolerances, const Progress& progress, Integrator integrator) {
  detail::TableIntegration integration(body, table, initial, grid.t_end, tolerances, integrator);
  TableRun run;
  TableSampler sampler(run.trajectory, table.has_losses());
  run.trajectory.reserve(grid.count);
  sampler.add(0.0, integration.initial_state(), integration.parameters(), TableLosses{});
  std::size_t next = 1;
  TableVector y;
  integration.run(run.summary, [&](const detail::TableIntegration::StepView& step) {
    for (; next < grid.count && grid.time(next) <= step.t1; ++next) {
      step.state_at(grid.time(next), y);
      sampler.add(grid.time(next), y, step.params, step.losses_at(grid.time(next)));
      if (progress) progress(grid.time(next));
    }
    if (run.summary.end == TableSummary::End::LeftTable && run.trajectory.t.back() != step.t1) {
      step.state_at(step.t1, y);  // the last row at the event
      sampler.add(step.t1, y, step.params, step.losses_at(step.t1));
    }
    return true;
  });
  if (run.summary.end == TableSummary::End::Completed) run.summary.end_time = run.trajectory.t.back();
  run.summary.integrator = integration.integrator();
  return run;
}

namespace {

// The tilt of state y (rad): k = R(q) e3 from q itself.
double tilt_of(const TableVector& y) {
  const double qw = y[0], qx = y[1], qy = y[2], qz = y[3];
  return tilt_of_axis(2.0 * (qx * qz + qw * qy), 2.0 * (qy * qz - qw * qx), qw * qw - qx * qx - qy * qy + qz * qz);
}

// The answer's watch over one run: the tilt's crossings of its levels located on the dense output,
// the track of P.
class AnswerWatch {
 public:
  AnswerWatch(const TableParameters& p, TableAnswer& answer, double start_tilt) : p_(p), a_(answer), tilt_(start_tilt) {
    if (start_tilt < kSleepingTilt) below_since_ = 0.0;
  }

  // Returns false once the answer is decided (a fall).
  bool step(const detail::TableIntegration::StepView& view) {
    constexpr int kPoints = 4;  // per step: a step spans a fraction of the fastest turn
    TableVector y;
    for (int j = 1; j <= kPoints; ++j) {
      const double t = j == kPoints ? view.t1 : view.t0 + (view.t1 - view.t0) * j / kPoints;
      view.state_at(t, y);
      const double tilt = tilt_of(y);
      const Instant in = instant_of(view.params, y);
      const V3 P = contact_point(y, in);
      a_.track = std::max(a_.track, std::hypot(P[0], P[1]));
      const double before_max = a_.max_tilt;
      a_.max_tilt = std::max(a_.max_tilt, tilt);
      const double t_before = t_;
      const double before = tilt_;
      auto crossing = [&](double level) { return locate(view, t_before, t, level); };
      if (!a_.turns_over_at && before < kHalfPi && tilt >= kHalfPi) a_.turns_over_at = crossing(kHalfPi);
      if (before >= kSleepingTilt && tilt < kSleepingTilt) below_since_ = crossing(kSleepingTilt);
      if (before < kSleepingTilt && tilt >= kSleepingTilt) below_since_.reset();
      const bool can_fall = p_.length > 0.0 && a_.start_tilt < a_.fall_threshold;
      if (can_fall && !a_.falls_at && before < a_.fall_threshold && tilt >= a_.fall_threshold) {
        a_.falls_at = crossing(a_.fall_threshold);
        view.state_at(*a_.falls_at, y);
        a_.max_tilt = std::max(before_max, tilt_of(y));  // the run ends at the crossing, as the pivot's does
        finish(*a_.falls_at, y);
        return false;
      }
      t_ = t;
      tilt_ = tilt;
      finish(t, y);
    }
    return true;
  }

  std::optional<double> sleeping_since() const { return below_since_; }

 private:
  static constexpr double kHalfPi = 1.5707963267948966;

  void finish(double t, const TableVector& y) {
    a_.end_time = t;
    a_.final_tilt = tilt_of(y);
    a_.final_spin = y[6];
  }

  double locate(const detail::TableIntegration::StepView& view, double a, double b, double level) const {
    return detail::sign_change([&](double t, TableVector& y) { view.state_at(t, y); }, a, b,
                               [&](const TableVector& y) { return tilt_of(y) - level; });
  }

  const TableParameters& p_;
  TableAnswer& a_;
  double t_ = 0.0, tilt_;
  std::optional<double> below_since_;
};

}  // namespace

TableSpinDown table_spin_down(const Body& body, const Table& table, double spin) {
  validate(table, body);
  if (!(std::isfinite(spin) && spin > 0.0)) throw InvalidInput("motion.spin", "must be a finite number > 0 (rad/s)");
  const TableParameters p = TableParameters::of(body, table);
  TableSpinDown out;
  out.critical_spin = table_stability(body, table, spin).upright.critical_spin;
  const double load = body.mass * body.gravity;
  if (table.contact == Contact::Sliding && table.friction_law == FrictionLaw::Contensou) {
    out.patch_radius = hertz_contact_radius(load, body.tip_radius, p.contact_modulus);
    out.drilling_torque = table.friction * load * kHertzDrillingArm * out.patch_radius;
  }
  auto air = [&](double w) { return p.air ? air_torque(p.air_surfaces, p.air_properties, w) : 0.0; };
  out.air_torque = air(spin);
  if (!out.critical_spin) return out;
  const double low = *out.critical_spin;
  if (spin <= low) {
    out.time_to_critical = 0.0;
    return out;
  }
  if (!(out.drilling_torque + air(low) > 0.0)) return out;  // nothing slows it
  // dt = C dw / M(w); each loss takes M_i(w) w dt.
  using boost::math::quadrature::gauss_kronrod;
  auto integral = [&](auto&& f) { return gauss_kronrod<double, 31>::integrate(f, low, spin, 10, 1e-13); };
  const double C = body.C;
  out.time_to_critical = integral([&](double w) { return C / (out.drilling_torque + air(w)); });
  out.losses.drilling = integral([&](double w) { return C * w * out.drilling_torque / (out.drilling_torque + air(w)); });
  out.losses.air = integral([&](double w) { return C * w * air(w) / (out.drilling_torque + air(w)); });
  return out;
}

TableAnalysis analyse_top_on_table(const Body& body, const Table& table, const InitialState& initial,
                                   const AnswerOptions& options) {
  validate(options);
  TableAnalysis out;
  out.spin = initial.spin;
  out.stability = table_stability(body, table, initial.spin);
  TableAnswer& a = out.answer;
  a.spin = initial.spin;
  a.fall_threshold = body.touch_tilt.value_or(options.max_tilt);
  a.part_touches = body.touch_tilt.has_value();
  a.horizon = options.horizon;
  a.min_spin = out.stability.upright.critical_spin;
  detail::TableIntegration integration(body, table, initial, options.horizon, options.integrator, Integrator::Auto);
  a.start_tilt = a.max_tilt = a.final_tilt = tilt_of(integration.initial_state());
  a.final_spin = initial.spin;
  AnswerWatch watch(integration.parameters(), a, a.start_tilt);
  TableSummary summary;
  try {
    integration.run(summary, [&](const detail::TableIntegration::StepView& view) { return watch.step(view); });
  } catch (const RunFailure& failure) {  // the answer says how far it got, as the pivot's does
    a.stopped = failure.what();
    a.horizon = failure.reached();
  }
  if (summary.end == TableSummary::End::LeftTable) {
    a.leaves_at = summary.end_time;
    a.end_time = summary.end_time;
  }
  if (!a.falls_at && !a.leaves_at && a.stopped.empty()) a.upright_at = watch.sleeping_since();
  a.ends_upside_down = a.turns_over_at && std::abs(a.final_tilt - 3.141592653589793) < kUpsideDownWithin;
  if (a.upright_at) {
    const auto upright = table_stability(body, table, a.final_spin).upright;
    a.upright_attracts = upright.asymptotically;
  }
  if (table.has_losses() && initial.spin > 0.0) a.spin_down = table_spin_down(body, table, initial.spin);
  if (a.leaves_at) {
    a.verdict = AnswerVerdict::LeavesTable;
    a.proven = true;
  } else if (a.falls_at) {
    a.verdict = AnswerVerdict::Falls;
    a.proven = true;
  } else if (a.turns_over_at) {
    a.verdict = AnswerVerdict::TurnsOver;
    a.proven = true;
  } else if (a.upright_at) {
    a.verdict = AnswerVerdict::StaysUp;  // risen and asleep; the words say what is and is not proven
  } else {
    a.verdict = AnswerVerdict::StaysUpForHorizon;
  }
  return out;
}

}  // namespace heavytop

namespace heavytop {

TableLifetime table_lifetime(const Body& body, const Table& table, const InitialState& initial,
                             std::optional<double> horizon, const AnswerOptions& options) {
  if (horizon && !(std::isfinite(*horizon) && *horizon > 0.0))
    throw InvalidInput("horizon", "must be a finite number > 0 (s)");
  TableLifetime out;
  out.spin_down = table_spin_down(body, table, initial.spin);
  const auto& t = out.spin_down.time_to_critical;
  // The fall comes soon after the spin passes the critical spin; a run 10 times as long (the
  // pivot's rule) costs minutes on a table.
  out.horizon = horizon ? *horizon : t && *t > 0.0 ? std::max(1.5 * *t, 10.0) : options.horizon;
  AnswerOptions o = options;
  o.horizon = out.horizon;
  out.answer = analyse_top_on_table(body, table, initial, o).answer;
  return out;
}

}  // namespace heavytop

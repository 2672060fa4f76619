#pragma once
/// \file
/// The body on a table (SPEC section 16): instead of a pivot, the body stands on the horizontal
/// plane zeta = 0 (gravity along -zeta) with a sphere of radius Body::tip_radius centred at O
/// (or a ring of radius Body::rim_radius about the axis through O, thickened by tip_radius),
/// and touches it at the lowest point P. The height of O and the normal force follow exactly
/// from the attitude (no penalty springs); the contact law sets the horizontal force at P.
/// Physics, laws and sources: docs/table.md.

#include <complex>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/answer.hpp"
#include "heavytop/body.hpp"
#include "heavytop/contact_losses.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/progress.hpp"
#include "heavytop/simulate.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// What holds the body at O or P (SPEC section 16, `table.contact`).
enum class Contact {
  Pivot,         ///< "pivot": O fixed (sections 1-15); no table
  Frictionless,  ///< "frictionless": the normal force only
  Rolling,       ///< "rolling": P does not slip (nonholonomic); energy conserved
  Sliding,       ///< "sliding": a friction force at P by `FrictionLaw`
};

/// The friction law of Contact::Sliding (SPEC section 16, `table.friction_law`).
enum class FrictionLaw {
  Viscous,  ///< "viscous": F = -mu N v_P / slip_speed (Cohen 1977 with slip_speed 1 m/s)
  Coulomb,  ///< "coulomb": the set-valued law (stick while |F| <= mu N, slip against the slip)
  /// "contensou": Coulomb's law over Hertz's contact patch of the tip's sphere, the friction
  /// force and the drilling torque coupled (F = -mu N v / D, M = -mu N eps^2 w_n / D,
  /// D = |(v, eps w_n)|, eps = (3 pi / 16) a; Leine and Glocker 2003): the spinning patch slides
  /// easily, so the law acts as the viscous one with slip_speed eps |w_n| (docs/table.md)
  Contensou,
};

std::string_view name(Contact contact);
std::string_view name(FrictionLaw law);
/// The contact called `name` ("pivot", "frictionless", "rolling", "sliding"), or nullopt.
std::optional<Contact> contact_from_name(std::string_view name);
/// The law called `name` ("viscous", "coulomb", "contensou"), or nullopt.
std::optional<FrictionLaw> friction_law_from_name(std::string_view name);

/// The table under the body (SPEC section 16's `[table]`); the default is the pivot.
struct Table {
  Contact contact = Contact::Pivot;
  double friction = 0.0;                        ///< mu (dimensionless, >= 0): Sliding only
  FrictionLaw friction_law = FrictionLaw::Viscous;
  double slip_speed = 1.0;                      ///< m/s (> 0): the viscous law's reference speed
  /// The tip's and the table's materials (Hertz's patch): FrictionLaw::Contensou needs both.
  std::optional<Material> tip_material, material;
  /// m (>= 0): the rolling resistance's length delta (Sliding, not Coulomb): a torque
  /// -delta N w_r / |w_r| against the body's rolling, w_r its angular velocity along the table
  /// (regularised below 1e-3 rad/s); 0: none.
  double rolling_resistance = 0.0;
  /// Still air around the body (any contact but the pivot): its torque against the spin about
  /// the axis, from air_surfaces; nullopt: none.
  std::optional<Air> air;
  /// The surfaces the air drags on (air_surfaces() of the body's parts); empty: the body's
  /// equivalent_disc().
  std::vector<AirSurface> air_surfaces;

  /// True for every contact but the pivot.
  bool on_table() const noexcept { return contact != Contact::Pivot; }
  /// True if the contact dissipates by the body's own losses (Contensou's law, rolling
  /// resistance or the air), which the runs then account for (TableSummary::losses).
  bool has_losses() const noexcept {
    return friction_law == FrictionLaw::Contensou || rolling_resistance > 0.0 || air.has_value();
  }
  /// True if every setting is in range; else false with "key: rule" in `why` (keys
  /// "table.friction", "table.slip_speed").
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput for the first rule `table` breaks: "table.friction" finite and >= 0,
/// "table.slip_speed" finite and > 0; "table.tip_material" and "table.material" given (moduli
/// finite and > 0, Poisson's ratios in [0, 0.5)) for Contensou's law; "table.rolling_resistance"
/// finite and >= 0, and 0 but for sliding under the viscous or Contensou law;
/// "table.air_density", "table.air_viscosity" finite and > 0.
void validate(const Table& table);

/// validate(table) and validate(body), then, on a table,
/// for what the body cannot do there: a general body (SPEC section 11; key its first nonzero
/// term), a damped one (key "damping.*": the table's own losses are its contact's), Contensou's
/// law without a round tip (key "body.tip_radius": > 0, and no rim), and a
/// rim whose axis starts exactly vertical is checked by simulate_on_table (key "motion.theta0").
void validate(const Table& table, const Body& body);

/// J: the energy each of the contact's losses has taken, from the run's start (each >= 0).
struct TableLosses {
  double sliding = 0.0;   ///< the friction force's work against the slip at P
  double drilling = 0.0;  ///< Contensou's drilling torque's against the spin about the vertical
  double rolling = 0.0;   ///< the rolling resistance's
  double air = 0.0;       ///< the air's torque's against the spin about the axis
  double total() const noexcept { return sliding + drilling + rolling + air; }
};

/// What a run on the table did and how it ended.
struct TableSummary {
  enum class End {
    Completed,    ///< every sample computed
    LeftTable,    ///< the normal force reached 0 at `end_time`: the body leaves the table
  };
  End end = End::Completed;
  double end_time = 0.0;        ///< s, the last sample's time (the event's when it ended early)
  std::size_t steps = 0;        ///< accepted steps
  std::size_t rhs_evaluations = 0;
  std::size_t switches = 0;     ///< Coulomb's law: the contact's switches between sticking and slipping
  Integrator integrator = Integrator::Dop853;  ///< the one that ran: Dop853, or Rosenbrock4 (stiff)
  /// The largest |Q(t) - Q(0)| over the accepted steps, relative to the scales of docs/table.md:
  /// the energy (over T(0) + m g |l| + m g r) and Jellett's integral and the vertical angular
  /// momentum about G (over |L_G(0)| (|l| + r + rim) and |L_G(0)|; 0 where they are zero).
  double max_relative_energy_drift = 0.0;
  double max_relative_jellett_drift = 0.0;
  double max_relative_vertical_momentum_drift = 0.0;
  /// Where the energy went (Table::has_losses() only; else zero): each loss's power integrated
  /// over every accepted step (Gauss-Legendre, 5 points, on the dense output), to the end.
  TableLosses losses;
};

/// The columns a table trajectory has after SPEC's seven (t, theta, phi, theta_rate, phi_rate,
/// tilt, azimuth), in order (SPEC section 16): x, y (m: P on the table), height (m: O above the
/// table), normal_force (N), slip_speed (m/s), spin (rad/s: w . k), energy (J), jellett
/// (kg m^3/s: -L_G . (P - G)); then vertical_momentum (kg m^2/s: L_G . e_zeta).
inline constexpr std::string_view kTableColumns[] = {"x",    "y",      "height", "normal_force", "slip_speed",
                                                     "spin", "energy", "jellett", "vertical_momentum"};
/// The columns after kTableColumns of a table with losses (Table::has_losses()): J, the energy
/// each loss has taken since t = 0 (TableLosses).
inline constexpr std::string_view kLossColumns[] = {"loss_sliding", "loss_drilling", "loss_rolling", "loss_air"};

/// A run on the table.
struct TableRun {
  Trajectory trajectory;  ///< t, theta, phi, theta_rate, phi_rate, then extra: tilt, azimuth, kTableColumns
  TableSummary summary;
};

/// The motion of `body` on `table` (not the pivot) from `initial` (SPEC section 2's attitude and
/// angular velocity; P at the table's origin; O without horizontal velocity, or rolling), sampled
/// at `grid`, integrated by `integrator` (kIntegratorSupport's table column: Dop853, the stepper
/// of dop853.hpp; Rosenbrock4, Boost.Odeint's L-stable Rosenbrock 4 with an exact Jacobian, for
/// stiff viscous sliding; Auto: table_integrator()) at `tolerances` (which apply to the
/// quaternion, the angular velocity in rad/s and G's horizontal position and velocity in m and
/// m/s). Ends early, with a last sample at the event, when the normal force reaches 0 (located
/// to 1e-12 s on the dense output). Under Coulomb's law the contact's switches between slipping
/// and sticking are located the same way and each restarts the stepper (TableSummary::switches).
/// Throws InvalidInput for bad input (validate(table, body), the state, the tolerances, key
/// "integrator" for one that cannot integrate a table; N < 0 at t = 0 is not an error: it ends
/// the run at t = 0) and std::runtime_error (one line, with the time) for a numerical failure or
/// Painleve's paradox (the normal force undetermined).
TableRun simulate_on_table(const Body& body, const Table& table, const InitialState& initial, const SampleGrid& grid,
                           const Tolerances& tolerances = {}, const Progress& progress = {},
                           Integrator integrator = Integrator::Auto);

/// The integrator Integrator::Auto stands for on a table: Rosenbrock4 where the viscous law's
/// relaxation rate (mu g / slip_speed times the slip's inertia factor 1 + m |G - P|^2 / I_G, 1/s)
/// exceeds stiff_table_ratio(tolerance) times the motion's own fastest rate (the spin, the
/// tilt's rates, sqrt(m g |G - P| / I_G)), else Dop853. Measured on the tippe top
/// (docs/table.md): DOP853's steps are held to about 12 / rate there, Rosenbrock 4's by its
/// accuracy at order 4, each of its steps costing about 4 of DOP853's.
Integrator table_integrator(const Body& body, const Table& table, const InitialState& initial,
                            const Tolerances& tolerances);
/// The stiffness ratio (dimensionless) above which Rosenbrock4 is the faster at `tolerance`
/// (min(rtol, atol)): 5e3 at 1e-8, growing as tolerance^-0.4 (about 1.8e5 at 1e-12), where the two
/// took the same time on the tippe top (docs/table.md).
double stiff_table_ratio(double tolerance);

/// A body's central moments about its transverse axes through G (kg m^2): A - m l^2, B - m l^2.
double central_moment_A(const Body& body) noexcept;
double central_moment_B(const Body& body) noexcept;

/// The linear stability of the body spinning about its vertical axis on the table (SPEC section
/// 16's "upright" and "inverted").
struct SpinningStateStability {
  bool exists = true;         ///< false for a rim (a disc with a vertical axis lies flat)
  bool stable = false;        ///< every eigenvalue has real part <= 0 (to rounding), none repeated on the axis
  bool asymptotically = false;  ///< every eigenvalue but the spin family's zeros has real part < 0
  std::optional<double> critical_spin;  ///< rad/s: the slowest spin above which it is stable
  std::vector<std::pair<double, std::optional<double>>> stable_spin_intervals;  ///< rad/s, [lo, hi or above]
  std::vector<std::complex<double>> eigenvalues;  ///< 1/s, of the body-frame linearisation, sorted
  double growth_rate = 0.0;   ///< 1/s, the largest real part
};

struct TableStability {
  Contact contact = Contact::Pivot;
  SpinningStateStability upright;   ///< tilt 0
  SpinningStateStability inverted;  ///< tilt pi
};

/// The linear stability of the upright and inverted spinning states at `spin` (rad/s) on `table`
/// (not the pivot): the eigenvalues of the exact linearisation of the body-frame equations
/// (complex-step derivatives: exact to rounding), the intervals by scanning the spin and
/// bisecting each change. Under Coulomb friction the vertical state sticks: the rolling one.
TableStability table_stability(const Body& body, const Table& table, double spin);

/// The eigenvalues (1/s) of the linearisation at `spin` of the upright (`inverted` false) or
/// inverted state, as table_stability() computes them.
std::vector<std::complex<double>> table_eigenvalues(const Body& body, const Table& table, double spin, bool inverted);

/// How a top asleep upright on the table (tilt 0, its tip not slipping) spins down under its
/// own losses (Table::has_losses()): C w' = -(M_drilling + M_air(w)), M_drilling = mu m g
/// (3 pi / 16) a with Hertz's patch a at N = m g (Contensou's law, asleep: pure drilling), M_air
/// the air's torque on its surfaces; rolling resistance and sliding take nothing while it
/// sleeps. The time from `spin` to the critical spin is that law's quadrature (Gauss-Kronrod).
struct TableSpinDown {
  std::optional<double> critical_spin;     ///< rad/s, the upright state's on this table (table_stability)
  std::optional<double> time_to_critical;  ///< s, 0 if at or below it; nullopt if never (no loss, no critical spin)
  double patch_radius = 0.0;               ///< m, Hertz's a at N = m g (0 without Contensou's law)
  double drilling_torque = 0.0;            ///< N m, M_drilling (0 without Contensou's law)
  double air_torque = 0.0;                 ///< N m, M_air at `spin` (0 without air)
  TableLosses losses;                      ///< J, what each loss takes from `spin` to the critical spin
};

/// The spin-down of `body` asleep on `table` from `spin` (rad/s, > 0). Throws InvalidInput as
/// validate(table, body).
TableSpinDown table_spin_down(const Body& body, const Table& table, double spin);

/// The tilt (rad) below which a top on a table counts as upright and asleep (SPEC 16's
/// `upright_at`), and within which of pi a turned-over body counts as upside down.
inline constexpr double kSleepingTilt = 0.01;
inline constexpr double kUpsideDownWithin = 0.1;

/// The answer on a table (SPEC sections 14 and 16), from the computed motion: the numbers only
/// (io/ puts them into words).
struct TableAnswer {
  AnswerVerdict verdict = AnswerVerdict::StaysUpForHorizon;
  bool proven = false;          ///< a computed event (falls, turns over, leaves the table)
  double spin = 0.0;            ///< rad/s, w0
  double start_tilt = 0.0;      ///< rad
  double max_tilt = 0.0;        ///< rad, the largest tilt of the run
  double final_tilt = 0.0;      ///< rad, at the run's end
  double final_spin = 0.0;      ///< rad/s, w . k at the run's end
  /// rad, the tilt where another part reaches the table (Body::touch_tilt), else
  /// AnswerOptions::max_tilt (a fall needs length > 0)
  double fall_threshold = 1.0;
  bool part_touches = false;    ///< fall_threshold is where another part reaches the table
  std::optional<double> falls_at;       ///< s, the tilt passes fall_threshold from below
  std::optional<double> upright_at;     ///< s, from then on the tilt stays below kSleepingTilt
  std::optional<double> turns_over_at;  ///< s, the tilt passes pi/2
  std::optional<double> leaves_at;      ///< s, the normal force reaches 0
  bool ends_upside_down = false;        ///< turned over and ends within kUpsideDownWithin of pi
  double horizon = 0.0;         ///< s, the run's horizon (AnswerOptions::horizon)
  double end_time = 0.0;        ///< s, where the run ended (the horizon, a fall or leaving)
  double track = 0.0;           ///< m, the largest distance of P from where it started
  /// rad/s, the upright state's critical spin on this table (TableStability), nullopt if none.
  std::optional<double> min_spin;
  /// Why the run stopped before the horizon (its integrator's RunFailure: max_steps, a step too
  /// small), empty if it did not; horizon is then the time it reached, and the verdict, unless an
  /// event came first, StaysUpForHorizon with nothing claimed ("Not decided.").
  std::string stopped;
  /// The upright state is asymptotically stable at the run's final spin (with upright_at: the
  /// top has risen to a state that attracts its neighbourhood; Lyapunov's first method).
  bool upright_attracts = false;
  /// With the body's own losses (Table::has_losses()): how long it spins asleep (table_spin_down).
  std::optional<TableSpinDown> spin_down;
};

/// Everything `stability` says on a table, computed once.
struct TableAnalysis {
  double spin = 0.0;           ///< rad/s
  TableStability stability;    ///< table_stability(body, table, spin)
  TableAnswer answer;          ///< from the motion over options.horizon
};

/// The table's stability at the spin of `initial` and the answer from the motion followed
/// over options.horizon at options.integrator's tolerances, its events (leaving, falling past
/// options.max_tilt for a body with length > 0, turning over, rising to sleep) located on the
/// dense output to 1e-9 s. Throws InvalidInput for bad input, std::runtime_error for a failed run.
TableAnalysis analyse_top_on_table(const Body& body, const Table& table, const InitialState& initial,
                                   const AnswerOptions& options = {});

/// How long a top stays up on the table (SPEC section 8's `lifetime`, on a table): its spin-down
/// asleep (table_spin_down) and, from the given start, the computed motion's fall.
struct TableLifetime {
  TableSpinDown spin_down;
  /// s, the run's horizon: the options' or, by default, 1.5 times the time to the critical spin
  /// and at least 10 s (when that is null: AnswerOptions' default horizon)
  double horizon = 0.0;
  TableAnswer answer;  ///< the motion over the horizon (falls_at, final_spin, max_tilt, ...)
};

/// The lifetime of `body` on `table` from `initial` (spin > 0): table_spin_down() and
/// analyse_top_on_table()'s motion over `horizon` (nullopt: TableLifetime::horizon's default)
/// with `options`' limit, tolerances and step budget. Throws as those do.
TableLifetime table_lifetime(const Body& body, const Table& table, const InitialState& initial,
                             std::optional<double> horizon, const AnswerOptions& options = {});

}  // namespace heavytop

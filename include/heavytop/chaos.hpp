#pragma once
/// \file
/// How long the motion can be predicted (SPEC section 17, "Chaos"): the Lyapunov exponents of
/// the Euler-Poisson flow of the conservative body on its pivot, MEGNO, the prediction horizon
/// and the Poincare section psi = 0. docs/chaos.md says what is claimed and what is not.
///
/// The flow is that of the body-axes state (w, gamma): w the angular velocity (rad/s) and gamma
/// the upward vertical (dimensionless, |gamma| = 1), both in body axes,
///     I w' = (I w) x w + m g (gamma x r),     gamma' = gamma x w,
/// I the inertia tensor about O and r the centre of mass (0, 0, length) (SPEC sections 1-2; the
/// general body of section 11 adds the products of inertia and the centre's x and y). Its
/// variational equations delta' = J(w, gamma) delta use the exact 6x6 Jacobian J.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/progress.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// s, SPEC section 17's default horizon T.
inline constexpr double kDefaultChaosHorizon = 1000.0;
/// dimensionless, the relative precision delta of the start when none is given (SPEC 17).
inline constexpr double kDefaultChaosPrecision = 1e-15;
/// The most rows of ChaosResult::history (SPEC 17).
inline constexpr std::size_t kMaxChaosHistory = 1000;

/// Options of analyse_chaos() and poincare_section().
struct ChaosOptions {
  /// s, T: the run's length, finite and > 0.
  double horizon = kDefaultChaosHorizon;
  /// dimensionless, delta in (0, 1): the relative precision to which the start (w, gamma) is
  /// known; nullopt: kDefaultChaosPrecision (the `[uncertainty]` inputs may set it).
  std::optional<double> precision;
  /// s, > 0: how often the tangent vectors are re-orthonormalised (Benettin's renormalisation,
  /// at the first step start at or after each multiple of it; the exponents do not depend on it,
  /// the tangent equations being linear, only overflow does).
  double renormalisation_interval = 1.0;
  /// The DOP853 run's tolerances, on the state and the tangent vectors alike (keys "rtol",
  /// "atol", "max_steps").
  Tolerances tolerances;
  /// The first tangent vector (Benettin's), (delta w in rad/s, delta gamma dimensionless), any
  /// nonzero length; nullopt: a fixed generic direction. The other five complete it to an
  /// orthonormal frame.
  std::optional<std::array<double, 6>> initial_tangent;
  /// Also the Poincare section psi = 0 (ChaosResult::section), from the same run.
  bool section = false;

  /// True if every setting is in range; else false and a one-line "key: rule" in `why` (key
  /// "horizon", "precision", "renormalisation_interval", "initial_tangent" or the tolerances').
  bool IsValid(std::string* why) const;
};

/// Throws InvalidInput for the first setting out of range (ChaosOptions::IsValid's keys).
void validate(const ChaosOptions& options);

/// One crossing of the Poincare section: psi = 0 (mod 2 pi) with psi' > 0, psi = atan2(gamma_1,
/// gamma_2) the third ZXZ Euler angle, located as an event on the dense output (TOMS 748).
struct SectionCrossing {
  double t = 0.0;          ///< s
  double tilt = 0.0;       ///< rad, acos(gamma_3): the axis's angle from the upward vertical
  double tilt_rate = 0.0;  ///< rad/s, d tilt / dt
  std::array<double, 3> omega{};  ///< rad/s, w in body axes there (the integrated state)
  std::array<double, 3> gamma{};  ///< dimensionless, the upward vertical in body axes there
};

/// The Poincare section over [0, horizon] and how well the run kept the energy.
struct PoincareSection {
  std::vector<SectionCrossing> crossings;  ///< in time order
  /// dimensionless, max |E(t) - E(0)| / (kinetic energy + m g |r|) at the run's steps.
  double max_relative_energy_drift = 0.0;
};

/// What analyse_chaos() found (SPEC section 17's JSON, plus how the run went).
struct ChaosResult {
  /// 1/s, the largest exponent: Benettin's sum of the logarithms of the first tangent vector's
  /// growth over the run, divided by T.
  double lyapunov_exponent = 0.0;
  /// 1/s, its error as the run's history supports it: the larger of the batch means' standard
  /// error (ten equal blocks' exponents) and the RMS deviation of l(t) from l(T) over t >= T/2
  /// (docs/chaos.md).
  double lyapunov_error = 0.0;
  /// (s, 1/s): the running value l(t) at the first step end in each T/1000 (renormalised or
  /// not: the first vector's growth since its last renormalisation counts), at most
  /// kMaxChaosHistory rows, the last at T.
  std::vector<std::array<double, 2>> history;
  /// 1/s, all six exponents by QR (Shimada-Nagashima), in descending order.
  std::array<double, 6> spectrum{};
  /// dimensionless, MEGNO's mean <Y>(T) (Cincotta-Simo): -> 2 on a torus, ~ l T / 2 if chaotic.
  double megno = 0.0;
  /// s, ln(1e-2 / delta) / l when chaotic (0 when delta >= 1e-2); nullopt when not chaotic.
  std::optional<double> prediction_horizon;
  /// dimensionless, delta (the options' or kDefaultChaosPrecision).
  double precision = kDefaultChaosPrecision;
  /// l > 4 ln T / T + 3 lyapunov_error and megno > 4 (SPEC 17).
  bool chaotic = false;
  /// s, T.
  double horizon = 0.0;
  /// 1/s, 4 ln T / T: what a regular motion's exponent still shows at T.
  double regular_bound = 0.0;
  /// The Poincare section, when ChaosOptions::section.
  std::optional<PoincareSection> section;
  std::size_t steps = 0;            ///< accepted DOP853 steps
  std::size_t rhs_evaluations = 0;  ///< evaluations of the augmented system
  double max_relative_energy_drift = 0.0;  ///< as PoincareSection's, over this run
};

/// The exponents, MEGNO and the prediction horizon of the motion of `body` from `initial`
/// (SPEC section 2's start) over options.horizon, by DOP853 on the flow with its six tangent
/// vectors, the time and MEGNO's two integrals (45 equations). The body must be conservative
/// on a pivot: damping throws InvalidInput("damping.transverse" / "damping.axial" / "damping.friction"), a
/// motor InvalidInput("motion.driven"). Bad options or body throw InvalidInput; a run that
/// cannot go on throws std::runtime_error ("dop853: ...").
ChaosResult analyse_chaos(const Body& body, const InitialState& initial, const ChaosOptions& options = {},
                          const Progress& progress = {});

/// The Poincare section alone (the flow without tangent vectors), same rules and options (the
/// tangent-vector settings unused).
PoincareSection poincare_section(const Body& body, const InitialState& initial, const ChaosOptions& options = {},
                                 const Progress& progress = {});

/// dimensionless, the rate of the Euler-Poisson flow at x = (w rad/s, gamma): (w', gamma') in
/// (rad/s^2, 1/s), and its exact Jacobian d x' / d x (row-major). The equations analyse_chaos()
/// integrates, exposed for checks.
std::array<double, 6> euler_poisson_rate(const Body& body, const std::array<double, 6>& x);
std::array<double, 36> euler_poisson_jacobian(const Body& body, const std::array<double, 6>& x);

}  // namespace heavytop

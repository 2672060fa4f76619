#pragma once
/// \file
/// Beyond the linearisation (SPEC section 7): is the real body's upright permanent rotation
/// Lyapunov stable? The verdict with the certificate that proves it, the energy index of the
/// amended potential, the spins proven stable (exact, in closed form) and the superfast spin.
/// The body is conservative here (damping ignored). docs/lyapunov.md derives every
/// certificate. An asymmetric body of energy index 2 that is linearly stable is decided by
/// Arnold's theorem on the order-4 Birkhoff normal form (normal_form.hpp), Markeev's at 1:3.
///
/// Also the wander: the largest tilt the full nonlinear motion from a given state reaches.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/normal_form.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/state.hpp"

namespace heavytop {

/// The answer to "is the real body's upright rotation Lyapunov stable?".
enum class LyapunovVerdictKind { Stable, Unstable, Undecided };

/// The argument behind a verdict (SPEC section 7's names). The numeric values are stored in
/// map files (io/map_file.cpp): new ones go after None, and kLastLyapunovCertificate follows.
enum class LyapunovCertificate {
  EnergyCasimir,      ///< "energy-casimir": the amended potential is definite (index 0)
  Chetaev,            ///< "chetaev": A = B, Chetaev's function with the axial momentum
  CriticalQuartic,    ///< "critical-quartic": A = B at C^2 w0^2 = 4 A m g R, the quartic term
  OddIndex,           ///< "odd-index": index 1, a real positive eigenvalue
  LinearInstability,  ///< "linear-instability": a growth the full equations share
  None,               ///< "none": not decided (the verdict is then Undecided)
  Kam,                ///< "kam": index 2, Arnold's theorem (D != 0, no 1:1 or 1:3 resonance)
  KamMarkeev,         ///< "kam-markeev": index 2 at 1:3, Markeev's |D| > 3 sqrt(3) a13 min(w)^2
  Resonance,          ///< "resonance": index 2 at 1:3 with |D| < 3 sqrt(3) a13 min(w)^2, unstable
};
/// The largest value of LyapunovCertificate (for loops over every certificate).
inline constexpr LyapunovCertificate kLastLyapunovCertificate = LyapunovCertificate::Resonance;

std::string_view name(LyapunovVerdictKind verdict);      ///< "stable" | "unstable" | "undecided"
std::string_view name(LyapunovCertificate certificate);  ///< SPEC section 7's spelling
/// True for the certificates that prove stability (energy-casimir, chetaev, critical-quartic,
/// kam, kam-markeev): lyapunov_stability's verdict is Stable exactly with these.
bool proves_stability(LyapunovCertificate certificate);

/// The Lyapunov verdict at one spin.
struct LyapunovVerdict {
  LyapunovVerdictKind verdict = LyapunovVerdictKind::Undecided;
  LyapunovCertificate certificate = LyapunovCertificate::None;
  /// The number of negative stiffnesses among s1, s2 (0, 1 or 2); a zero one is not negative.
  int energy_index = 0;
  /// N m (= J/rad^2), s1 = (C - A) w0^2 - m g R, the amended potential's stiffness in the
  /// tilt about body x (C - A taken as 0 when |C - A| <= kSymmetryTolerance max(C, A)).
  double s1 = 0.0;
  /// N m, s2 = (C - B) w0^2 - m g R, the same about body y.
  double s2 = 0.0;
  /// Why, for a person: the proof's name, or what is missing.
  std::string reason;
  /// Index 2 with a stable linearisation (and w1 != w2): the normal form the verdict rests on
  /// (certificates kam, kam-markeev, resonance, or none at D = 0); nullopt in every other case.
  std::optional<NormalForm> normal_form;
};

/// The Lyapunov verdict for the upright permanent rotation of the conservative `body` at spin
/// w0 (rad/s, finite). A stiffness counts as zero when it is below 1e-12 of its terms
/// (|C - A| w0^2 + |m g R|). Cases (docs/lyapunov.md):
///  - m g R = 0 and w0 = 0 (the free body at rest): unstable, certificate linear-instability
///    (the linearisation's neutral drift is an exact motion: a slow rotation about a transverse
///    principal axis turns the axis through any angle);
///  - A = B (is_symmetric): energy-casimir at index 0 with both stiffnesses > 0, else chetaev
///    where C^2 w0^2 > 4 A m g R, critical-quartic at equality (m g R > 0, to 1e-12 relative),
///    below it unstable (linear-instability: complex eigenvalues);
///  - A != B: index 0 with s1, s2 > 0: energy-casimir; index 1 (s1 s2 < 0): unstable, odd-index; m g R = 0
///    (the free body) rotating about its axis of least moment: stable, energy-casimir (with
///    |L|^2), or with C = A or C = B: unstable, linear-instability (it tumbles); otherwise
///    (index 2, or a zero stiffness): unstable, linear-instability if the exact linearisation
///    has an eigenvalue of positive real part; a zero stiffness: undecided, certificate none
///    (degenerate, left to higher-order terms); else index 2 with a stable linearisation, on
///    the normal form (SPEC section 7): kam when D != 0 away from 1:1 and 1:3; at 1:3
///    kam-markeev or (unstable) resonance by Markeev's inequality; undecided (none) at D = 0
///    (to kDegeneracyTolerance), at 1:1, or at equality in Markeev's inequality.
/// Throws InvalidInput for a body validate() refuses or a non-finite spin.
LyapunovVerdict lyapunov_stability(const Body& body, double spin);

/// The spins w0 >= 0 (rad/s) at which lyapunov_stability proves the body stable, ascending and
/// disjoint; an end is included exactly when lyapunov_stability proves that spin itself stable.
/// Ends that are roots of s1, s2, C^2 w0^2 - 4 A m g R or of the linearisation's conditions are
/// in closed form; the KAM pieces (index 2) exclude the spins where D = 0, w1 = w2, or 1:3
/// with Markeev's inequality failing, located by sign changes on a geometric grid of
/// kKamScanPoints spins per piece (an unbounded piece scanned up to 1e4 times its start or the
/// body's natural spin sqrt(|m g R| / min(A, B, C)): at large spins gravity fades, w1/w2 and
/// D / D_scale tend to the free body's limits, reached to 4 digits within 1e2 of the start in
/// every body tried, so no exception is sought beyond) and refined by bisection to rounding.
/// Two such spins closer than the grid's step can be missed.
std::vector<SpinInterval> lyapunov_stable_spin_intervals(const Body& body);

/// Spins per KAM piece scanned by lyapunov_stable_spin_intervals for D = 0 and resonances.
inline constexpr int kKamScanPoints = 600;

/// A spin (rad/s) where the KAM verdict fails inside an index-2 linearly stable piece.
struct KamException {
  double spin = 0.0;
  std::string_view what;  ///< "D = 0", "1:1" or "1:3"
};
/// The KAM exceptions of `body` (ascending), as lyapunov_stable_spin_intervals finds them.
std::vector<KamException> kam_exceptions(const Body& body);
/// rad/s, the smallest spin above which the energy index stays 0 ("superfast": both
/// stiffnesses >= 0): sqrt(max(m g R / (C - A), m g R / (C - B), 0)) when C >= A and C >= B
/// (with m g R <= 0 if C equals one of them); nullopt when no spin makes the body superfast.
std::optional<double> superfast_spin(const Body& body);

/// The Lyapunov side of `heavytop stability`.
struct LyapunovStability {
  LyapunovVerdict verdict;                ///< at the spin asked
  std::vector<SpinInterval> intervals;    ///< rad/s, lyapunov_stable_spin_intervals()
  std::optional<double> superfast;        ///< rad/s, superfast_spin()
};
LyapunovStability analyse_lyapunov(const Body& body, double spin);

/// How far the axis wanders in the full nonlinear motion from a state.
struct Wander {
  /// rad, the largest tilt acos(k_zeta) of the motion; nullopt when it could not be computed
  /// (then `note` says why).
  std::optional<double> max_tilt;
  /// true: exact (A = B: acos of the Lagrange cubic's root u_min; or the upright permanent
  /// rotation, which never tilts); false: the largest tilt of an integration over `horizon`.
  bool closed_form = true;
  std::optional<double> horizon;  ///< s, the integration's horizon (nullopt when closed form)
  std::string note;               ///< why max_tilt is missing, else empty
};

/// The most steps axis_wander() lets one integration take (a few seconds of work).
inline constexpr std::size_t kWanderMaxSteps = 2'000'000;

/// The largest tilt of the motion of `body` from `initial` (SPEC section 2 mapping): closed
/// form for A = B (lagrange_top's u_min) and for the upright state without transverse rates
/// (the permanent rotation: 0); otherwise tilt_extremes over [0, horizon] (s, > 0) with
/// `options` (max_steps capped at kWanderMaxSteps). Never throws for a valid body and state:
/// a failure leaves max_tilt empty and says why in `note`. `progress` is given to that run; what
/// it throws passes through unless it is a std::exception.
Wander axis_wander(const Body& body, const InitialState& initial, double horizon,
                   const Tolerances& options = {}, const Progress& progress = {});

}  // namespace heavytop

// The chaos of SPEC section 17: Lyapunov exponents (Benettin et al. 1980; Shimada & Nagashima
// 1979), MEGNO (Cincotta & Simo 2000) and the Poincare section psi = 0, all from one DOP853 run
// of the Euler-Poisson flow in body axes with its tangent vectors (docs/chaos.md).
#include "heavytop/chaos.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>
#include <boost/math/tools/toms748_solve.hpp>

#include "heavytop/frames.hpp"
#include "heavytop/simulate.hpp"
#include "integrators/dop853/stepper.hpp"
#include "integrators/integration.hpp"

namespace heavytop {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Layout of the augmented state: x = (w, gamma), then the six tangent vectors column by column
// (in the scaled coordinates below), the time (the stepper calls the system with t = 0: MEGNO's
// integrand needs the real one), MEGNO's integral of s delta'.delta / |delta|^2 and the integral
// of Y(s) = 2/s times that.
constexpr std::size_t kBase = 6;
constexpr std::size_t kTangents = kBase * kBase;
constexpr std::size_t kTime = kBase + kTangents;
constexpr std::size_t kMegnoY = kTime + 1;
constexpr std::size_t kMegnoMean = kTime + 2;
constexpr std::size_t kAugmented = kTime + 3;

Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

// The Euler-Poisson flow of a body: I, its inverse and m g r (N m), the general body's tensor
// and centre of mass (SPEC section 11) included, as they cost nothing here.
struct Flow {
  Mat3 I, I_inv;
  Vec3 mgr;

  explicit Flow(const Body& body) {
    const GeneralInertia& g = body.general;
    I << body.A, -g.Ixy, -g.Ixz, -g.Ixy, body.B, -g.Iyz, -g.Ixz, -g.Iyz, body.C;
    I_inv = I.inverse();
    mgr = body.mass * body.gravity * Vec3(g.offset_x, g.offset_y, body.length);
  }

  // w' = I^-1 ((I w) x w + gamma x m g r), gamma' = gamma x w.
  template <class X, class D>
  void rate(const X& x, D& d) const {
    const Vec3 w(x[0], x[1], x[2]), gamma(x[3], x[4], x[5]);
    const Vec3 w_dot = I_inv * ((I * w).cross(w) + gamma.cross(mgr));
    const Vec3 gamma_dot = gamma.cross(w);
    for (int i = 0; i < 3; ++i) {
      d[i] = w_dot[i];
      d[3 + i] = gamma_dot[i];
    }
  }

  // The exact Jacobian: d((I w) x w) = [I w]x dw - [w]x I dw, d(gamma x m g r) = -[m g r]x dgamma,
  // d(gamma x w) = -[w]x dgamma + [gamma]x dw.
  Mat6 jacobian(const double* x) const {
    const Vec3 w(x[0], x[1], x[2]), gamma(x[3], x[4], x[5]);
    Mat6 J;
    J.topLeftCorner<3, 3>() = I_inv * (cross_matrix(I * w) - cross_matrix(w) * I);
    J.topRightCorner<3, 3>() = -I_inv * cross_matrix(mgr);
    J.bottomLeftCorner<3, 3>() = cross_matrix(gamma);
    J.bottomRightCorner<3, 3>() = -cross_matrix(w);
    return J;
  }

  double energy(const double* x) const {
    const Vec3 w(x[0], x[1], x[2]), gamma(x[3], x[4], x[5]);
    return 0.5 * w.dot(I * w) + gamma.dot(mgr);
  }
};

// The tangent vectors live in (delta w / Omega, delta gamma): both dimensionless, so that the
// norm, the step's error control and MEGNO weigh a rate and an angle alike. Omega (rad/s) is
// the start's |w| or the gravity frequency, the larger; the exponents do not depend on it.
double tangent_scale(const Body& body, const Vec3& w0) {
  const double gravity_rate = 1.0 / gravity_time(body);
  const double omega = std::max(w0.norm(), std::isfinite(gravity_rate) ? gravity_rate : 0.0);
  return omega > 0.0 ? omega : 1.0;
}

// J in the scaled coordinates: S J S^-1, S = diag(1/Omega, 1/Omega, 1/Omega, 1, 1, 1).
Mat6 scaled_jacobian(const Flow& flow, const double* x, double omega) {
  Mat6 J = flow.jacobian(x);
  J.topRightCorner<3, 3>() /= omega;
  J.bottomLeftCorner<3, 3>() *= omega;
  return J;
}

template <std::size_t N>
struct ChaosSystem {
  Flow flow;
  double omega;  // rad/s, the tangent vectors' scale

  void operator()(const std::array<double, N>& y, std::array<double, N>& dydt, double) const {
    flow.rate(y, dydt);
    if constexpr (N == kAugmented) tangent_rates(y, dydt);
  }

  void tangent_rates(const std::array<double, N>& y, std::array<double, N>& dydt) const {
    const Mat6 J = scaled_jacobian(flow, y.data(), omega);
    Eigen::Map<const Mat6> V(y.data() + kBase);
    Eigen::Map<Mat6> dV(dydt.data() + kBase);
    dV.noalias() = J * V;
    // MEGNO: delta'.delta / |delta|^2 = d ln|delta| / dt of the first vector (Benettin's),
    // which its renormalisation leaves alone.
    const double t = y[kTime];
    const auto delta = V.col(0);
    const double growth = delta.dot(dV.col(0)) / delta.squaredNorm();
    dydt[kTime] = 1.0;
    dydt[kMegnoY] = t * growth;
    dydt[kMegnoMean] = t > 0.0 ? 2.0 * y[kMegnoY] / t : 0.0;
  }
};

// What the renormalisations accumulate: the logarithms of R's diagonal (Shimada-Nagashima; the
// first is Benettin's), and the running largest exponent.
struct Accumulator {
  double interval = 1.0, horizon = 1.0;
  double next = 1.0;              // s, the next renormalisation
  double next_row = 0.0;          // s, the next history row: horizon row / kMaxChaosHistory
  std::size_t row = 1;
  std::array<double, 6> log_sum{};
  std::vector<std::array<double, 2>> history;

  // Re-orthonormalises the tangent frame V = Q R (Householder), R's diagonal made positive so
  // that the first column stays the first vector's direction, and adds log R_ii.
  void renormalise(Eigen::Map<Mat6> V) {
    const Eigen::HouseholderQR<Mat6> qr(V);
    Mat6 Q = qr.householderQ() * Mat6::Identity();
    const Mat6& R = qr.matrixQR();
    for (int i = 0; i < 6; ++i) {
      log_sum[i] += std::log(std::abs(R(i, i)));
      if (R(i, i) < 0.0) Q.col(i) = -Q.col(i);
    }
    V = Q;
  }

  // A history row at the end of a step (t, the frame V there): S(t) is the sum so far plus the
  // first vector's growth since its last renormalisation, so rows need not wait for one.
  void record(double t, const double* frame) {
    if (t <= 0.0 || t < next_row) return;
    const double S = log_sum[0] + std::log(Eigen::Map<const Mat6>(frame).col(0).norm());
    history.push_back({t, S / t});
    while (next_row <= t) next_row = horizon * static_cast<double>(++row) / static_cast<double>(kMaxChaosHistory);
  }
};

// At each step's start (the stepper's project hook): the frame is renormalised once t has
// passed the next multiple of the interval, or sooner if a vector has grown by 1e100 (the
// tangent equations being linear, when does not change the sums, only overflow).
struct ChaosHooks {
  Accumulator* acc;
  ChaosSystem<kAugmented> system;

  void project(std::array<double, kAugmented>& y, std::array<double, kAugmented>& dydt) {
    const double t = y[kTime];
    Eigen::Map<Mat6> V(y.data() + kBase);
    if (t < acc->next && V.colwise().norm().maxCoeff() < 1e100) return;
    acc->renormalise(V);
    // The frame changed: so does its rate (linear in it); MEGNO's rates do not.
    system.tangent_rates(y, dydt);
    while (acc->next <= t) acc->next += acc->interval;
  }
  void rejected() {}
  void accepted(double, const std::array<double, kAugmented>&, std::size_t) {}
  void evaluated(std::size_t) {}
};

// 1/s, the error of l(T) that the run's history supports, the larger of two estimates: the
// batch means' standard error (the run cut into kBlocks equal blocks, the exponent of each from
// the growth S = t l(t) across it, their standard deviation over sqrt(kBlocks): the scatter of
// the local exponents, large when the orbit sticks near regular islands for a while), and the
// RMS deviation of l(t) from l(T) over the second half (a running value still drifting, as a
// regular orbit's ln t / t does). Neither sees an orbit's stickiness longer than a block.
double exponent_error(const std::vector<std::array<double, 2>>& history, double T) {
  constexpr int kBlocks = 10;
  if (history.size() < 2 * kBlocks) return std::abs(history.empty() ? 0.0 : history.back()[1]);
  auto growth_at = [&](double t) {  // S at the last row at or before t
    double S = 0.0;
    for (const auto& [tr, l] : history) {
      if (tr > t * (1.0 + 1e-12)) break;
      S = tr * l;
    }
    return S;
  };
  std::array<double, kBlocks> local{};
  for (int k = 0; k < kBlocks; ++k) {
    const double a = T * k / kBlocks, b = T * (k + 1) / kBlocks;
    local[k] = (growth_at(b) - growth_at(a)) / (b - a);
  }
  const double mean = std::accumulate(local.begin(), local.end(), 0.0) / kBlocks;
  double var = 0.0;
  for (double l : local) var += (l - mean) * (l - mean);
  const double batch = std::sqrt(var / (kBlocks - 1) / kBlocks);
  const double lT = history.back()[1];
  double sum = 0.0;
  std::size_t n = 0;
  for (const auto& [t, l] : history)
    if (t >= 0.5 * T) {
      sum += (l - lT) * (l - lT);
      ++n;
    }
  const double drift = n > 1 ? std::sqrt(sum / static_cast<double>(n - 1)) : 0.0;
  return std::max(batch, drift);
}

detail::Violation first_violation(const ChaosOptions& o) {
  if (!(std::isfinite(o.horizon) && o.horizon > 0.0)) return std::pair{"horizon", "must be a finite number > 0"};
  if (o.precision && !(*o.precision > 0.0 && *o.precision < 1.0))
    return std::pair{"precision", "must be in (0, 1)"};
  if (!(std::isfinite(o.renormalisation_interval) && o.renormalisation_interval > 0.0))
    return std::pair{"renormalisation_interval", "must be a finite number > 0"};
  if (o.initial_tangent) {
    const auto& v = *o.initial_tangent;
    const bool finite = std::all_of(v.begin(), v.end(), [](double c) { return std::isfinite(c); });
    const double n2 = std::inner_product(v.begin(), v.end(), v.begin(), 0.0);
    if (!finite || !(n2 > 0.0) || !std::isfinite(n2))
      return std::pair{"initial_tangent", "must be finite and nonzero"};
  }
  return std::nullopt;
}

// The conservative body on its pivot only: the flow has no torques of SPEC section 6.
void check_inputs(const Body& body, const InitialState& initial, const ChaosOptions& options) {
  validate(body);
  validate(initial);
  validate(options);
  const Damping& d = body.damping;
  if (d.transverse != 0.0)
    throw InvalidInput("damping.transverse", "chaos takes the conservative body only (no damping)");
  if (d.axial != 0.0) throw InvalidInput("damping.axial", "chaos takes the conservative body only (no damping)");
  if (d.friction != 0.0)
    throw InvalidInput("damping.friction", "chaos takes the conservative body only (no friction)");
  if (d.driven) throw InvalidInput("motion.driven", "chaos takes the free body only (no motor)");
  validate_horizon(body, initial, options.horizon, "horizon");
}

std::array<double, kBase> start_of(const InitialState& initial) {
  const RigidBodyState s = initial_rigid_body_state(initial);
  const Vec3 gamma = s.attitude.row(2).transpose();  // R^T e_zeta
  return {s.omega.x(), s.omega.y(), s.omega.z(), gamma.x(), gamma.y(), gamma.z()};
}

// The start's tangent frame: the first vector (scaled), completed to an orthonormal frame.
Mat6 initial_frame(const ChaosOptions& options, double omega) {
  Eigen::Matrix<double, 6, 1> v;
  if (options.initial_tangent) {
    for (int i = 0; i < 6; ++i) v[i] = (*options.initial_tangent)[i];
    v.head<3>() /= omega;
  } else {
    // A generic direction: no component zero, none in a symmetry's plane.
    v << 0.37, -0.52, 0.61, 0.23, -0.41, 0.17;
  }
  v.normalize();
  // [v, e_j for the five j other than v's largest component] is invertible; its QR's Q
  // starts with +-v.
  int largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  Mat6 M;
  M.col(0) = v;
  for (int j = 0, c = 1; j < 6; ++j)
    if (j != largest) M.col(c++) = Mat6::Identity().col(j);
  const Eigen::HouseholderQR<Mat6> qr(M);
  Mat6 Q = qr.householderQ() * Mat6::Identity();
  for (int i = 0; i < 6; ++i)
    if (qr.matrixQR()(i, i) < 0.0) Q.col(i) = -Q.col(i);
  return Q;
}

// psi' of the state x (1/s): (gamma_1' gamma_2 - gamma_2' gamma_1) / (gamma_1^2 + gamma_2^2).
double psi_rate(const double* x) {
  const double g1 = x[3], g2 = x[4], g3 = x[5], w1 = x[0], w2 = x[1], w3 = x[2];
  const double h2 = g1 * g1 + g2 * g2;
  return w3 - g3 * (w1 * g1 + w2 * g2) / h2;
}

SectionCrossing crossing_of(double t, const double* x) {
  SectionCrossing c;
  c.t = t;
  const double g1 = x[3], g2 = x[4], g3 = x[5], w1 = x[0], w2 = x[1], w3 = x[2];
  c.omega = {w1, w2, w3};
  c.gamma = {g1, g2, g3};
  c.tilt = tilt_of_axis(g1, g2, g3);
  // tilt = atan2(h, gamma_3), h = |(gamma_1, gamma_2)|: tilt' = (h' gamma_3 - gamma_3' h) / (h^2 + gamma_3^2).
  const double d1 = g2 * w3 - g3 * w2, d2 = g3 * w1 - g1 * w3, d3 = g1 * w2 - g2 * w1;
  const double h = std::hypot(g1, g2);
  const double h_rate = h > 0.0 ? (g1 * d1 + g2 * d2) / h : 0.0;
  c.tilt_rate = (h_rate * g3 - d3 * h) / (h * h + g3 * g3);
  return c;
}

// The crossings of psi = 0 with psi' > 0 in the step (t0, t1] of `stepper`: gamma_1 rising
// through 0 while gamma_2 > 0. The step is cut into pieces over which psi turns by less than
// about a radian (its rate from the step's ends and middle), so no pair of crossings hides in
// one piece; each sign change is then solved on the dense output by TOMS 748.
template <class Stepper>
void scan_section(Stepper& stepper, std::vector<SectionCrossing>& out) {
  using State = typename Stepper::State;
  const double t0 = stepper.previous_time(), t1 = stepper.time();
  State y;
  auto at = [&](double t) -> const State& {
    stepper.interpolate(t, y);
    return y;
  };
  double rate = 0.0;
  for (double t : {t0, 0.5 * (t0 + t1), t1}) {
    const State& s = at(t);
    const double r = std::abs(psi_rate(s.data()));
    rate = std::max(rate, std::isfinite(r) ? r : 0.0);
  }
  const double pieces_d = std::clamp(std::ceil(rate * (t1 - t0) / 0.5), 1.0, 4096.0);
  const int pieces = static_cast<int>(pieces_d);
  double a = t0, ga = stepper.previous_state()[3];
  for (int p = 1; p <= pieces; ++p) {
    const double b = p == pieces ? t1 : t0 + (t1 - t0) * p / pieces;
    const double gb = at(b)[3];
    if (ga < 0.0 && gb >= 0.0) {
      double root = b;
      if (gb > 0.0) {
        boost::uintmax_t iterations = 100;
        const auto r = boost::math::tools::toms748_solve(
            [&](double t) { return at(t)[3]; }, a, b, ga, gb,
            [](double lo, double hi) { return std::abs(hi - lo) <= 1e-14 * std::max(1.0, std::abs(lo)); },
            iterations);
        root = 0.5 * (r.first + r.second);
      }
      const State& s = at(root);
      if (s[4] > 0.0) out.push_back(crossing_of(root, s.data()));
    }
    a = b;
    ga = gb;
  }
}

// One run over [0, horizon]: the flow (N = 6) or the flow with its tangent frame and MEGNO
// (N = kAugmented). Returns the stepper's counts; fills the section and the energy drift.
template <std::size_t N, class Hooks>
void run(const Flow& flow, double omega, const std::array<double, N>& y0, const ChaosOptions& options, Hooks hooks,
         PoincareSection* section, ChaosResult& counts, const Progress& progress, std::array<double, N>& end,
         Accumulator* acc = nullptr) {
  detail::Dop853Stepper<N, ChaosSystem<N>, Hooks> stepper(ChaosSystem<N>{flow, omega}, y0, options.horizon,
                                                           options.tolerances, std::move(hooks));
  const double e0 = flow.energy(y0.data());
  const Vec3 w0(y0[0], y0[1], y0[2]);
  const double energy_scale = 0.5 * w0.dot(flow.I * w0) + flow.mgr.norm();
  double drift = 0.0;
  std::size_t steps = 0;
  while (stepper.time() < options.horizon) {
    stepper.step();
    ++steps;
    const double e = flow.energy(stepper.state().data());
    if (energy_scale > 0.0) drift = std::max(drift, std::abs(e - e0) / energy_scale);
    if (section) scan_section(stepper, section->crossings);
    if constexpr (N == kAugmented) acc->record(stepper.time(), stepper.state().data() + kBase);
    if (progress && steps % 64 == 0) progress(stepper.time());
  }
  if (section) section->max_relative_energy_drift = drift;
  counts.steps = steps;
  counts.rhs_evaluations = stepper.evaluations();
  counts.max_relative_energy_drift = drift;
  end = stepper.state();
}

}  // namespace

bool ChaosOptions::IsValid(std::string* why) const {
  return detail::is_valid(first_violation(*this), why) && tolerances.IsValid(why);
}

void validate(const ChaosOptions& options) {
  detail::throw_if_invalid(first_violation(options));
  validate(options.tolerances);
}

std::array<double, 6> euler_poisson_rate(const Body& body, const std::array<double, 6>& x) {
  std::array<double, 6> d{};
  Flow(body).rate(x, d);
  return d;
}

std::array<double, 36> euler_poisson_jacobian(const Body& body, const std::array<double, 6>& x) {
  const Mat6 J = Flow(body).jacobian(x.data());
  std::array<double, 36> out{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out[6 * i + j] = J(i, j);
  return out;
}

ChaosResult analyse_chaos(const Body& body, const InitialState& initial, const ChaosOptions& options,
                          const Progress& progress) {
  check_inputs(body, initial, options);
  const Flow flow(body);
  const std::array<double, kBase> x0 = start_of(initial);
  const double omega = tangent_scale(body, Vec3(x0[0], x0[1], x0[2]));

  std::array<double, kAugmented> y0{};
  std::copy(x0.begin(), x0.end(), y0.begin());
  const Mat6 frame = initial_frame(options, omega);
  std::copy(frame.data(), frame.data() + kTangents, y0.begin() + kBase);

  const double T = options.horizon;
  Accumulator acc;
  acc.interval = options.renormalisation_interval;
  acc.horizon = T;
  acc.next = options.renormalisation_interval;
  acc.next_row = T / static_cast<double>(kMaxChaosHistory);

  ChaosResult result;
  result.horizon = T;
  PoincareSection section;
  std::array<double, kAugmented> end{};
  run<kAugmented>(flow, omega, y0, options, ChaosHooks{&acc, ChaosSystem<kAugmented>{flow, omega}},
                  options.section ? &section : nullptr, result, progress, end, &acc);
  // The growth since the last renormalisation. The last step ends at T exactly, so the last
  // row is at T (one per T/1000 at most: kMaxChaosHistory rows).
  acc.renormalise(Eigen::Map<Mat6>(end.data() + kBase));
  if (acc.history.empty() || acc.history.back()[0] != T) acc.history.push_back({T, 0.0});
  acc.history.back()[1] = acc.log_sum[0] / T;
  if (acc.history.size() > kMaxChaosHistory) acc.history.erase(acc.history.end() - 2);

  result.lyapunov_exponent = acc.log_sum[0] / T;
  result.history = std::move(acc.history);
  for (int i = 0; i < 6; ++i) result.spectrum[i] = acc.log_sum[i] / T;
  std::sort(result.spectrum.begin(), result.spectrum.end(), std::greater<>());
  result.megno = end[kMegnoMean] / T;

  result.lyapunov_error = exponent_error(result.history, T);

  result.precision = options.precision.value_or(kDefaultChaosPrecision);
  result.regular_bound = 4.0 * std::log(T) / T;
  result.chaotic = result.lyapunov_exponent > result.regular_bound + 3.0 * result.lyapunov_error && result.megno > 4.0;
  if (result.chaotic)
    result.prediction_horizon =
        result.precision >= 1e-2 ? 0.0 : std::log(1e-2 / result.precision) / result.lyapunov_exponent;
  if (options.section) result.section = std::move(section);
  return result;
}

PoincareSection poincare_section(const Body& body, const InitialState& initial, const ChaosOptions& options,
                                 const Progress& progress) {
  check_inputs(body, initial, options);
  const Flow flow(body);
  const std::array<double, kBase> x0 = start_of(initial);
  PoincareSection section;
  ChaosResult counts;
  std::array<double, kBase> end{};
  run<kBase>(flow, 1.0, x0, options, detail::NoDop853Hooks{}, &section, counts, progress, end);
  return section;
}

}  // namespace heavytop

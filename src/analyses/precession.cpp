#include "heavytop/precession.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/format.h>


namespace heavytop {
namespace {

void validate_tilt(double tilt) {
  if (!(std::isfinite(tilt) && tilt > 0.0 && tilt < std::numbers::pi))
    throw InvalidInput("tilt", "must be a finite angle in (0, pi) rad from the upward vertical");
}

// cos(tilt), 0 within the tilt's own rounding: cos of the double nearest pi/2 is 6e-17, one ulp
// of the tilt, not a tilt off the horizontal. There the axle is horizontal (the classroom
// gyroscope): the precession quadratic is linear (only the slow precession exists) and no
// permanent rotation is possible, where 1/cos would give absurd rates of 1e17 rad/s.
double cos_of_tilt(double tilt) {
  const double c = std::cos(tilt);
  return std::abs(c) <= std::nextafter(tilt, 4.0) - tilt ? 0.0 : c;
}

// SPEC section 2's state for the axis at `tilt` in the xi-zeta plane, precessing at `rate`
// about the upward vertical with w.k = spin: k' = rate zeta x k = (0, rate sin(tilt), 0), so
// theta' = 0 and phi' = -rate sin(tilt) (k_eta = -sin phi).
InitialState precessing_state(double tilt, double rate, double spin) {
  InitialState s;
  s.theta0 = tilt;
  s.spin = spin;
  s.phi_rate0 = -rate * std::sin(tilt);
  return s;
}

SteadyPrecession steady(const Body& b, double tilt, double spin, double rate) {
  SteadyPrecession p;
  p.rate = rate;
  p.period = 2 * std::numbers::pi / std::abs(rate);
  const double a = b.C * spin / b.A - 2 * rate * std::cos(tilt);
  p.nutation_frequency = std::hypot(a, rate * std::sin(tilt));
  p.state = precessing_state(tilt, rate, spin);
  return p;
}

}  // namespace

PrecessionAnalysis analyse_precession(const Body& body, double tilt, double spin) {
  validate(body);
  refuse_general(body, "precession");
  if (!is_symmetric(body))
    throw InvalidInput("body.B", "steady precession needs a symmetric body (A = B); for A != B see the "
                                 "permanent rotations");
  validate_tilt(tilt);
  if (!std::isfinite(spin)) throw InvalidInput("motion.spin", "must be a finite number");
  PrecessionAnalysis r;
  r.tilt = tilt;
  r.spin = spin;
  const double A = body.A, C = body.C, mgR = body.mgR(), c = cos_of_tilt(tilt);
  // A cos(theta) Omega^2 - C w3 Omega + m g R = 0: the gravitational moment m g R sin(theta)
  // turns the angular momentum's horizontal part (docs/steady-precession.md).
  const double qa = A * c, qb = -C * spin, qc = mgR;
  r.slow_limit = spin != 0.0 ? mgR / (C * spin) : 0.0;
  if (qa != 0.0) r.fast_limit = C * spin / qa;
  if (mgR * c > 0.0) r.min_spin = 2.0 * std::sqrt(A * mgR * c) / C;
  std::vector<double> roots;
  if (qa == 0.0) {  // theta = pi/2 to rounding: the quadratic is linear
    if (qb != 0.0) roots.push_back(-qc / qb);
  } else if (qb == 0.0) {
    if (qa * qc < 0.0) roots = {std::sqrt(-qc / qa), -std::sqrt(-qc / qa)};
  } else {
    // The discriminant as qb^2 (1 - 4 qa qc / qb^2): qb^2 overflows a double at large spins
    // (1e200 rad/s made it inf and both roots vanished), its ratio does not.
    const double ratio = (4.0 * qa / qb) * (qc / qb);
    if (ratio <= 1.0) {
      const double q = -0.5 * (qb + std::copysign(std::abs(qb) * std::sqrt(1.0 - ratio), qb));
      roots = {q / qa, qc / q};
    }
  }
  roots.erase(std::remove_if(roots.begin(), roots.end(), [](double x) { return !(std::isfinite(x) && x != 0.0); }),
              roots.end());
  std::sort(roots.begin(), roots.end(), [](double x, double y) { return std::abs(x) < std::abs(y); });
  if (!roots.empty()) r.slow = steady(body, tilt, spin, roots[0]);
  if (roots.size() > 1) r.fast = steady(body, tilt, spin, roots[1]);
  return r;
}

std::vector<PermanentRotation> permanent_rotations(const Body& body, double tilt) {
  validate(body);
  refuse_general(body, "precession");
  validate_tilt(tilt);
  std::vector<PermanentRotation> out;
  const double mgR = body.mgR(), c = cos_of_tilt(tilt), s = std::sin(tilt);
  for (const char plane : {'x', 'y'}) {
    const double K = plane == 'x' ? body.A : body.B;
    // The vertical gamma = (s_, 0, c) or (0, s, c) in body axes, w = Omega gamma; Euler's
    // equations balance (C - K) Omega^2 s c against m g R s (docs/steady-precession.md).
    const double omega2 = mgR / ((body.C - K) * c);
    if (!(std::isfinite(omega2) && omega2 > 0.0)) continue;
    PermanentRotation p;
    p.plane = plane;
    p.rate = std::sqrt(omega2);
    p.period = 2 * std::numbers::pi / p.rate;
    Eigen::Vector3d gamma;
    if (plane == 'x') {  // body axes = Q(0, tilt): x = (cos, 0, -sin), so gamma = (-sin, 0, cos)
      p.state = precessing_state(tilt, p.rate, p.rate * c);
      gamma << -s, 0.0, c;
    } else {  // Q(tilt, 0): y = (0, cos, sin), z = (0, -sin, cos), gamma = (0, sin, cos);
      // Omega zeta = theta_rate0 (0, 1, 0) + spin k0 gives spin = Omega / cos, theta' = Omega tan.
      p.state.phi0 = tilt;
      p.state.spin = p.rate / c;
      p.state.theta_rate0 = p.rate * s / c;
      gamma << 0.0, s, c;
    }
    // Euler-Poisson in body axes, I w' = I w x w + m g R gamma x e_z, gamma' = gamma x w,
    // linearised about w = Omega gamma.
    const Eigen::Vector3d I(body.A, body.B, body.C), w = p.rate * gamma, Iw = I.cwiseProduct(w);
    auto cross = [](const Eigen::Vector3d& v) {
      Eigen::Matrix3d m;
      m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
      return m;
    };
    const Eigen::Matrix3d Iinv = I.cwiseInverse().asDiagonal();
    Eigen::Matrix<double, 6, 6> J;
    J.topLeftCorner<3, 3>() = Iinv * (cross(Iw) - cross(w) * I.asDiagonal());
    J.topRightCorner<3, 3>() = -mgR * Iinv * cross(Eigen::Vector3d::UnitZ());
    J.bottomLeftCorner<3, 3>() = cross(gamma);
    J.bottomRightCorner<3, 3>() = -cross(w);
    const Eigen::EigenSolver<Eigen::Matrix<double, 6, 6>> eig(J, false);
    std::array<std::complex<double>, 6> ev;
    for (int i = 0; i < 6; ++i) ev[i] = eig.eigenvalues()(i);
    std::sort(ev.begin(), ev.end(), [](auto x, auto y) {
      return std::abs(x) != std::abs(y) ? std::abs(x) < std::abs(y) : x.imag() < y.imag();
    });
    p.eigenvalues = ev;
    const double scale = std::abs(ev[5]);
    p.stable = std::all_of(ev.begin() + 2, ev.end(), [&](auto l) { return std::abs(l.real()) <= 1e-8 * scale; });
    out.push_back(p);
  }
  return out;
}

}  // namespace heavytop

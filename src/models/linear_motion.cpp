#include "heavytop/linear_motion.hpp"

#include <cmath>

#include <unsupported/Eigen/MatrixFunctions>

#include "math/quadratic.hpp"

namespace heavytop {
namespace {

using Complex = std::complex<double>;

// Roots closer than this fraction of their size use the cancellation-free product forms.
constexpr double kNearDouble = 0.25;

template <class T>
T sinc(T z) {
  return std::abs(z) < 1e-4 ? T(1.0) - z * z / 6.0 : std::sin(z) / z;
}

/// c(mu_i), s(mu_i) and the divided differences c[mu1,mu2], s[mu1,mu2] at time t, where
/// alpha_i = sqrt(-mu_i), c = cos(alpha t), s = sin(alpha t) / alpha.
template <class T>
struct Interpolants {
  T c1, s1, c12, s12;
};

template <class T>
Interpolants<T> interpolants(T mu1, T mu2, T alpha1, T alpha2, double t) {
  Interpolants<T> r;
  r.c1 = std::cos(alpha1 * t);
  r.s1 = T(t) * sinc(alpha1 * t);
  const double size = std::max(std::abs(mu1), std::abs(mu2));
  if (size == 0.0) {  // J^4 = 0: exp(J t) is the polynomial I + J t + J^2 t^2/2 + J^3 t^3/6
    r.c12 = T(t * t / 2.0);
    r.s12 = T(t * t * t / 6.0);
  } else if (std::abs(mu1 - mu2) >= kNearDouble * size) {
    const T inv = T(1.0) / (mu1 - mu2);
    r.c12 = (r.c1 - std::cos(alpha2 * t)) * inv;
    r.s12 = (r.s1 - T(t) * sinc(alpha2 * t)) * inv;
  } else {
    // mu1 - mu2 = -(alpha1 - alpha2)(alpha1 + alpha2) = -4 sigma delta; sum-to-product
    // identities remove the cancellation, and delta -> 0 gives the double-root derivatives.
    const T sigma = (alpha1 + alpha2) / 2.0, delta = (alpha1 - alpha2) / 2.0;
    const T ss = std::sin(sigma * t), cs = std::cos(sigma * t);
    const T sd = T(t) * sinc(delta * t), cd = std::cos(delta * t);
    r.c12 = ss / sigma * sd / 2.0;
    r.s12 = (ss / sigma * cd - cs * sd) / (T(2.0) * alpha1 * alpha2);
  }
  return r;
}

std::pair<Complex, Complex> mu_roots(const LinearModel& model, double spin) {
  const CharacteristicPolynomial p = characteristic_polynomial(model, spin);
  return detail::quadratic_roots(p.a4, p.a2, p.a0, p.a2 * p.a2 - 4.0 * p.a4 * p.a0);
}

}  // namespace

LinearSolution closed_form_solution(const LinearModel& model, double spin, const LinearState& x0) {
  LinearSolution s;
  std::tie(s.mu1, s.mu2) = mu_roots(model, spin);
  const Eigen::Matrix4d j = state_matrix(model, spin);
  const double mu1 = s.mu1.real();  // (J^2 - mu1) is applied to real vectors: see evaluate()
  s.x0 = x0;
  s.jx0 = j * x0;
  // For complex mu1 the residual vectors are complex; store real and imaginary parts through
  // the identity (J^2 - mu1) = (J^2 - Re mu1) - i Im mu1 in evaluate().
  s.w2 = j * s.jx0 - mu1 * x0;
  s.w3 = j * s.w2;
  s.oscillatory = s.mu1.imag() == 0.0 && s.mu1.real() < 0.0 && s.mu2.real() < 0.0 &&
                  s.mu1.real() != s.mu2.real();
  if (s.oscillatory) {
    s.alpha1 = std::sqrt(-s.mu1.real());
    s.alpha2 = std::sqrt(-s.mu2.real());
  }
  return s;
}

LinearState evaluate(const LinearSolution& s, double t) {
  if (s.oscillatory) {
    const auto r = interpolants<double>(s.mu1.real(), s.mu2.real(), s.alpha1, s.alpha2, t);
    return r.c1 * s.x0 + r.s1 * s.jx0 + r.c12 * s.w2 + r.s12 * s.w3;
  }
  const Complex alpha1 = std::sqrt(-s.mu1);
  Complex alpha2 = std::sqrt(-s.mu2);
  if (std::abs(alpha1 - alpha2) > std::abs(alpha1 + alpha2)) alpha2 = -alpha2;  // same branch
  const auto r = interpolants<Complex>(s.mu1, s.mu2, alpha1, alpha2, t);
  // (J^2 - mu1) x0 = w2 - i Im(mu1) x0, and J of it = w3 - i Im(mu1) J x0.
  const Complex i_im(0.0, s.mu1.imag());
  Eigen::Vector4cd x = r.c1 * s.x0.cast<Complex>() + r.s1 * s.jx0.cast<Complex>() +
                       r.c12 * (s.w2.cast<Complex>() - i_im * s.x0.cast<Complex>()) +
                       r.s12 * (s.w3.cast<Complex>() - i_im * s.jx0.cast<Complex>());
  return x.real();
}

LinearState matrix_exponential_solution(const LinearModel& model, double spin,
                                        const LinearState& x0, double t) {
  const Eigen::Matrix4d jt = state_matrix(model, spin) * t;
  return jt.exp() * x0;
}

LinearState initial_linear_state(const LinearModel& model, const InitialState& s) {
  LinearState x;
  if (model.kind == LinearModelKind::Linearized) {
    x << s.phi0, s.theta0, s.phi_rate0 + s.spin * s.theta0, s.theta_rate0 - s.spin * s.phi0;
  } else {
    x << s.phi0, s.theta0, s.phi_rate0, s.theta_rate0;
  }
  return x;
}

Trajectory simulate_linear(const LinearModel& model, const InitialState& state,
                           const std::vector<double>& times, LinearMethod method) {
  const LinearState x0 = initial_linear_state(model, state);
  const LinearSolution solution = closed_form_solution(model, state.spin, x0);
  const bool body_frame = model.kind == LinearModelKind::Linearized;
  Trajectory out;
  const std::size_t n = times.size();
  for (auto* column : {&out.t, &out.theta, &out.phi, &out.theta_rate, &out.phi_rate}) column->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = times[i];
    const LinearState x = method == LinearMethod::Analytic
                              ? evaluate(solution, t)
                              : matrix_exponential_solution(model, state.spin, x0, t);
    double theta = x[1], phi = x[0], theta_rate = x[3], phi_rate = x[2];
    if (body_frame) {  // z = theta - i phi = exp(i w0 t) z_b;  z' = exp(i w0 t)(z_b' + i w0 z_b)
      const Complex turn = std::polar(1.0, state.spin * t);
      const Complex zb(theta, -phi), zb_rate(theta_rate, -phi_rate);
      const Complex z = turn * zb, z_rate = turn * (zb_rate + Complex(0.0, state.spin) * zb);
      theta = z.real(), phi = -z.imag(), theta_rate = z_rate.real(), phi_rate = -z_rate.imag();
    }
    out.t[i] = t;
    out.theta[i] = theta + 0.0;  // + 0.0: no negative zeros in reports
    out.phi[i] = phi + 0.0;
    out.theta_rate[i] = theta_rate + 0.0;
    out.phi_rate[i] = phi_rate + 0.0;
  }
  return out;
}

Eigen::Vector2d paper_section8_solution(const Body& body, const InitialState& s, double t) {
  // Notation (10), (11) of the paper; the formula printed after (14), verbatim.
  const double A = body.A, B = body.B, C = body.C, k = body.mgR(), w0 = s.spin;
  const double half_p = (C * C * w0 * w0 - (A + B) * k) / (2.0 * A * B);
  const double root = std::sqrt(half_p * half_p - k * k / (A * B));
  const double alpha1 = std::sqrt(half_p - root), alpha2 = std::sqrt(half_p + root);
  const double a1 = C * w0 / A, a2 = -k / A;
  const double b1 = a1 * alpha1 / (a2 - alpha1 * alpha1);
  const double theta = std::cos(alpha1 * t) + std::sin(alpha1 * t) +
                       (s.theta0 - 1.0) * std::cos(alpha2 * t) +
                       (s.theta_rate0 - alpha1) / alpha2 * std::sin(alpha2 * t);
  const double phi = b1 * (std::cos(alpha1 * t) + std::sin(alpha1 * t)) +
                     (s.phi0 - b1) * std::cos(alpha2 * t) +
                     (s.phi_rate0 - b1 * alpha1) / alpha2 * std::sin(alpha2 * t);
  return {theta, phi};
}

}  // namespace heavytop

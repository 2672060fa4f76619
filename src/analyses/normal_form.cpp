#include "heavytop/normal_form.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <Eigen/Eigenvalues>

namespace heavytop {
namespace {

/// The body's inertia and m g R, divided by a reference moment I0 (1 for the chart's own units).
/// The normal form is computed in these dimensionless units (issue 46): in kg m^2 the matrix
/// J S mixes entries ~ I w^2 and ~ 1/I, and its eigen-decomposition loses digits as I^2 (a body
/// scaled by 1e-16 had frequencies 4.83, 4.59 for the linearised 5.60, 3.86; at 1e20 none at
/// all). Dividing moments and torques by the same I0 leaves time alone: the frequencies are
/// unchanged, p, the actions and H are divided by I0, and the c's, D and a13 multiplied by it.
struct Moments {
  double A = 0.0, B = 0.0, C = 0.0, k = 0.0;  // kg m^2 / I0 and J / I0 (k = m g R / I0)
};

Moments physical(const Body& body) { return {body.A, body.B, body.C, body.mgR()}; }

/// I0: the power of two nearest below the largest moment (exact to divide by, so that a body
/// whose largest moment is in [1, 2) kg m^2 keeps the bits it had in the chart's own units, and
/// bodies that differ by a power of two in mass give the same bits).
double reference_moment(const Body& body) { return std::ldexp(1.0, std::ilogb(std::max({body.A, body.B, body.C}))); }

Moments dimensionless(const Body& body, double I0) { return {body.A / I0, body.B / I0, body.C / I0, body.mgR() / I0}; }

Eigen::Matrix4d quadratic_form(const Moments& b, double L) {
  // H2 = l1^2/(2A) + l2^2/(2B) - (L/C)(q1 p2 - q2 p1) - (m g R/2)|q|^2, l1 = p2 + L q1/2,
  // l2 = -p1 + L q2/2 (docs/lyapunov.md, "The chart").
  const double A = b.A, B = b.B, C = b.C, k = b.k;
  Eigen::Matrix4d S = Eigen::Matrix4d::Zero();
  S(0, 0) = L * L / (4.0 * A) - k;
  S(1, 1) = L * L / (4.0 * B) - k;
  S(2, 2) = 1.0 / B;
  S(3, 3) = 1.0 / A;
  S(0, 3) = S(3, 0) = L / (2.0 * A) - L / C;   // q1 p2
  S(1, 2) = S(2, 1) = -L / (2.0 * B) + L / C;  // q2 p1
  return S;
}

double quartic(const Moments& b, double L, const Eigen::Vector4d& z) {
  // The cubic parts of Pi1, Pi2 (gamma3 = 1 - rho/2 + .., 1/(1 + gamma3) = (1 + rho/4)/2 + ..)
  // against their linear parts, the square of Pi3's quadratic part, and gravity's
  // -m g R rho^2 / 8 (docs/lyapunov.md).
  const double q1 = z[0], q2 = z[1], p1 = z[2], p2 = z[3];
  const double rho = q1 * q1 + q2 * q2, m = q1 * p2 - q2 * p1;
  const double l1 = p2 + 0.5 * L * q1, l2 = -p1 + 0.5 * L * q2;
  const double c1 = rho * (-0.5 * p2 + 0.125 * L * q1), c2 = rho * (0.5 * p1 + 0.125 * L * q2);
  return l1 * c1 / b.A + l2 * c2 / b.B + m * m / (2.0 * b.C) - b.k * rho * rho / 8.0;
}

/// The canonical structure of z = (q1, q2, p1, p2): z' = J grad H.
Eigen::Matrix4d canonical_J() {
  Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
  J(0, 2) = J(1, 3) = 1.0;
  J(2, 0) = J(3, 1) = -1.0;
  return J;
}

/// The points of the torus r = (r1, r2) in the chart: z = T (sqrt(2 r1) cos a1, sqrt(2 r2) cos a2,
/// sqrt(2 r1) sin a1, sqrt(2 r2) sin a2).
Eigen::Vector4d torus_point(const Eigen::Matrix4d& T, double r1, double r2, double a1, double a2) {
  const double s1 = std::sqrt(2.0 * r1), s2 = std::sqrt(2.0 * r2);
  return T * Eigen::Vector4d(s1 * std::cos(a1), s2 * std::cos(a2), s1 * std::sin(a1), s2 * std::sin(a2));
}

// H4 on a torus is a trigonometric polynomial of degree <= 4 in each angle, so the N-point
// trapezoidal rule with N = 8 > 4 gives its mean and its harmonic (1, 3) exactly (no alias of
// degree <= 4 folds onto them): "exact torus averages", up to rounding.
constexpr int kTorusPoints = 8;

/// The Fourier coefficient of H4 on the torus r at the harmonic exp(i (k1 a1 + k2 a2)); k = 0:
/// the mean.
std::complex<double> torus_harmonic(const Moments& body, double L, const Eigen::Matrix4d& T, double r1, double r2,
                                    int k1, int k2) {
  std::complex<double> sum = 0.0;
  for (int i = 0; i < kTorusPoints; ++i)
    for (int j = 0; j < kTorusPoints; ++j) {
      const double a1 = 2.0 * std::numbers::pi * i / kTorusPoints, a2 = 2.0 * std::numbers::pi * j / kTorusPoints;
      sum += quartic(body, L, torus_point(T, r1, r2, a1, a2)) * std::polar(1.0, -(k1 * a1 + k2 * a2));
    }
  return sum / double(kTorusPoints * kTorusPoints);
}

bool near_ratio(double a, double b, double k) {  // a = k b, to kResonanceTolerance
  return std::abs(a - k * b) <= kResonanceTolerance * (a + b);
}

}  // namespace

Eigen::Matrix4d reduced_quadratic_form(const Body& body, double L) { return quadratic_form(physical(body), L); }

double reduced_quartic(const Body& body, double L, const Eigen::Vector4d& z) { return quartic(physical(body), L, z); }

void chart_to_euler_poisson(double L, const Eigen::Vector4d& z, Eigen::Vector3d& Pi, Eigen::Vector3d& gamma) {
  const double q1 = z[0], q2 = z[1], p1 = z[2], p2 = z[3];
  const double g3 = std::sqrt(1.0 - (q1 * q1 + q2 * q2));
  Pi = {g3 * p2 + L * q1 / (1.0 + g3), -g3 * p1 + L * q2 / (1.0 + g3), L - (q1 * p2 - q2 * p1)};
  gamma = {q1, q2, g3};
}

double reduced_hamiltonian(const Body& body, double L, const Eigen::Vector4d& z) {
  Eigen::Vector3d Pi, gamma;
  chart_to_euler_poisson(L, z, Pi, gamma);
  return 0.5 * (Pi[0] * Pi[0] / body.A + Pi[1] * Pi[1] / body.B + Pi[2] * Pi[2] / body.C) + body.mgR() * gamma[2];
}

std::optional<NormalForm> birkhoff_normal_form(const Body& body, double spin) {
  validate(body);
  refuse_general(body, "the normal form");
  if (!std::isfinite(spin)) throw InvalidInput("motion.spin", "must be a finite number");
  // Everything below in the dimensionless units of Moments (moments and torques / I0, time
  // unchanged): p / I0, r / I0, H / I0. Every test in it is relative, as it must be there.
  const double I0 = reference_moment(body);
  const Moments m = dimensionless(body, I0);
  const double L = m.C * spin;
  NormalForm nf;
  const Eigen::Matrix4d S = quadratic_form(m, L), J = canonical_J();
  const Eigen::EigenSolver<Eigen::Matrix4d> eig(J * S);
  if (eig.info() != Eigen::Success) return std::nullopt;
  double size = 0.0;
  for (int i = 0; i < 4; ++i) size = std::max(size, std::abs(eig.eigenvalues()[i]));
  if (!(size > 0.0)) return std::nullopt;

  // For each eigenvalue i w (w > 0), v = a + i b: the sign of a^T J b is the Krein signature;
  // scaled to a^T J b = +-1 it gives the canonical pair (x, y) of that mode (docs/lyapunov.md).
  Eigen::Matrix4d T = Eigen::Matrix4d::Zero();
  int found[2] = {0, 0};  // modes of signature +, -
  for (int i = 0; i < 4; ++i) {
    const std::complex<double> l = eig.eigenvalues()[i];
    if (std::abs(l.real()) > 1e-9 * size) return std::nullopt;  // not linearly stable (or a collision)
    if (l.imag() <= 0.0) continue;
    if (l.imag() <= 1e-12 * size) return std::nullopt;           // a zero frequency: degenerate
    const Eigen::Vector4cd v = eig.eigenvectors().col(i);
    const Eigen::Vector4d a = v.real(), b = v.imag();
    const double kappa = a.dot(J * b);
    const int mode = kappa > 0.0 ? 0 : 1;
    if (kappa == 0.0 || found[mode]++ > 0) return std::nullopt;  // H2 definite, or a double pair
    const double scale = 1.0 / std::sqrt(std::abs(kappa));
    T.col(mode) = a * scale;
    T.col(mode + 2) = (mode == 0 ? b : Eigen::Vector4d(-b)) * scale;
    (mode == 0 ? nf.w1 : nf.w2) = l.imag();
  }
  if (found[0] != 1 || found[1] != 1) return std::nullopt;
  if (near_ratio(nf.w1, nf.w2, 1.0)) return std::nullopt;  // 1:1: the modes are not separated

  // <H4> on the torus (r1, r2) is c20 r1^2 + c11 r1 r2 + c02 r2^2.
  double c20 = torus_harmonic(m, L, T, 1.0, 0.0, 0, 0).real();
  double c02 = torus_harmonic(m, L, T, 0.0, 1.0, 0, 0).real();
  double c11 = torus_harmonic(m, L, T, 1.0, 1.0, 0, 0).real() - c20 - c02;

  // Mode 1 turns as a1' = -w1, mode 2 as a2' = +w2 (H2 = w1 r1 - w2 r2), so the harmonic
  // (k1, k2) is slow when k1 w1 = k2 w2: (1, 3) at w1 = 3 w2, (3, 1) at w2 = 3 w1.
  if (near_ratio(nf.w1, nf.w2, 3.0)) {
    nf.resonance = 3;
    nf.a13 = 2.0 * std::abs(torus_harmonic(m, L, T, 1.0, 1.0, 1, 3)) / I0;
  } else if (near_ratio(nf.w2, nf.w1, 3.0)) {
    nf.resonance = 3;
    nf.a13 = 2.0 * std::abs(torus_harmonic(m, L, T, 1.0, 1.0, 3, 1)) / I0;
  } else if (near_ratio(nf.w1, nf.w2, 2.0) || near_ratio(nf.w2, nf.w1, 2.0)) {
    nf.resonance = 2;
  }

  // Back to the chart's units: H4 = I0 <H4>'(r / I0) gives c = c' / I0 (a13 above too);
  // z = diag(1, 1, I0, I0) z' and zeta = sqrt(I0) zeta' give T = diag(1, 1, I0, I0) T' / sqrt(I0),
  // still symplectic. I0 a power of two: the c's and D are exact quotients.
  nf.L = body.C * spin;
  nf.c20 = c20 / I0;
  nf.c11 = c11 / I0;
  nf.c02 = c02 / I0;
  nf.D = nf.c20 * nf.w2 * nf.w2 + nf.c11 * nf.w1 * nf.w2 + nf.c02 * nf.w1 * nf.w1;
  nf.D_scale = std::abs(nf.c20) * nf.w2 * nf.w2 + std::abs(nf.c11) * nf.w1 * nf.w2 + std::abs(nf.c02) * nf.w1 * nf.w1;
  const double root = std::sqrt(I0);
  nf.T.topRows<2>() = T.topRows<2>() / root;
  nf.T.bottomRows<2>() = T.bottomRows<2>() * root;
  return nf;
}

std::string_view resonance_name(int resonance) {
  switch (resonance) {
    case 1: return "1:1";
    case 2: return "1:2";
    case 3: return "1:3";
    default: return "";
  }
}

ResonanceDistance resonance_distance(const NormalForm& nf) {
  const double sum = nf.w1 + nf.w2;
  const double d11 = std::abs(nf.w1 - nf.w2) / sum;
  const double d13 = std::min(std::abs(nf.w1 - 3.0 * nf.w2), std::abs(nf.w2 - 3.0 * nf.w1)) / sum;
  return d11 <= d13 ? ResonanceDistance{d11, "1:1"} : ResonanceDistance{d13, "1:3"};
}

}  // namespace heavytop

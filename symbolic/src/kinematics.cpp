#include "heavytop/symbolic/kinematics.hpp"

#include <stdexcept>

#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::symbolic {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

// Active right-handed rotations about the coordinate axes.
matrix rot_x(const ex& a) { return {{1, 0, 0}, {0, cos(a), -sin(a)}, {0, sin(a), cos(a)}}; }
matrix rot_y(const ex& a) { return {{cos(a), 0, sin(a)}, {0, 1, 0}, {-sin(a), 0, cos(a)}}; }
matrix rot_z(const ex& a) { return {{cos(a), -sin(a), 0}, {sin(a), cos(a), 0}, {0, 0, 1}}; }


void check_order(int order) {
  if (order != 1 && order != 2) throw std::invalid_argument("order must be 1 or 2");
}

}  // namespace

std::string_view name(Sequence sequence) {
  return sequence == Sequence::PhiTheta ? "phi-theta" : "theta-phi";
}

std::optional<Sequence> sequence_from_name(std::string_view text) {
  for (Sequence s : kSequences)
    if (name(s) == text) return s;
  return std::nullopt;
}

ex truncate(const ex& e, int order) {
  const Symbols& s = symbols();
  GiNaC::exmap scale;
  for (const ex& x : s.small()) scale[x] = s.eps * x;
  const ex scaled = e.subs(scale);
  ex kept = 0;
  if (!scaled.info(GiNaC::info_flags::polynomial)) {
    // Trigonometric (or rational) in eps: a genuine series expansion.
    kept = GiNaC::series_to_poly(scaled.series(s.eps == 0, order + 1));
  } else {
    // Polynomial: dropping high powers of eps is all a series would do, and much faster.
    const ex expanded = scaled.expand();
    for (int k = 0; k <= order; ++k) kept += expanded.coeff(s.eps, k) * pow(s.eps, k);
  }
  return kept.subs(s.eps == 1).expand();
}

matrix truncate(const matrix& a, int order) {
  matrix out(a.rows(), a.cols());
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) out(i, j) = truncate(a(i, j), order);
  return out;
}

std::vector<Coordinate> coordinates() {
  const Symbols& s = symbols();
  return {{s.phi, s.phi_t, s.phi_tt}, {s.theta, s.theta_t, s.theta_tt}, {s.psi, s.psi_t, s.psi_tt}};
}

ex time_derivative(const ex& e, const std::vector<Coordinate>& coords) {
  ex d = 0;
  for (const Coordinate& c : coords) {
    d += e.diff(c.q) * c.rate;
    if (GiNaC::is_a<GiNaC::symbol>(c.rate))
      d += e.diff(GiNaC::ex_to<GiNaC::symbol>(c.rate)) * c.acceleration;
  }
  return d;
}

matrix time_derivative(const matrix& a, const std::vector<Coordinate>& coords) {
  matrix out(a.rows(), a.cols());
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) out(i, j) = time_derivative(a(i, j), coords);
  return out;
}

Rotations rotations(int order) {
  check_order(order);
  const Symbols& s = symbols();
  Rotations r;
  r.order = order;
  // The paper's transition matrices are the transposes of the active rotations.
  r.A1 = truncate(transpose(rot_x(s.phi)), order);
  r.A2 = truncate(transpose(rot_y(s.theta)), order);
  r.A3 = truncate(transpose(rot_z(s.psi)), order);
  r.A1A2 = truncate(r.A1.mul(r.A2), order);
  r.A2A1 = truncate(r.A2.mul(r.A1), order);
  r.commutator = truncate(r.A1A2.sub(r.A2A1), order);
  return r;
}

matrix frame_rotation(Sequence sequence) {
  const Symbols& s = symbols();
  // phi-theta: A = A3 A2 A1, so R = A^T = R_x(phi) R_y(theta) R_z(psi): theta is about the
  // eta axis as turned by phi (the paper's intermediate axis Om). theta-phi: A = A3 A1 A2.
  const matrix tilt = sequence == Sequence::PhiTheta ? rot_x(s.phi).mul(rot_y(s.theta))
                                                     : rot_y(s.theta).mul(rot_x(s.phi));
  return tilt.mul(rot_z(s.psi));
}

matrix vee(const matrix& skew) { return {{skew(2, 1)}, {skew(0, 2)}, {skew(1, 0)}}; }

matrix cross(const matrix& a, const matrix& b) {
  return {{a(1, 0) * b(2, 0) - a(2, 0) * b(1, 0)},
          {a(2, 0) * b(0, 0) - a(0, 0) * b(2, 0)},
          {a(0, 0) * b(1, 0) - a(1, 0) * b(0, 0)}};
}

AngularVelocities angular_velocities(Sequence sequence, int order) {
  check_order(order);
  const Symbols& s = symbols();
  const auto coords = coordinates();
  // Truncating R first and then the products gives the same terms up to `order` as truncating
  // the exact R^T R' (d/dt never lowers the order), and keeps everything polynomial.
  const matrix R = truncate(frame_rotation(sequence), order);
  const matrix R_t = time_derivative(R, coords);
  AngularVelocities w;
  w.sequence = sequence;
  w.order = order;
  w.frame_axes = truncate(vee(transpose(R).mul(R_t)), order);
  w.frame_fixed = truncate(vee(R_t.mul(transpose(R))), order);
  const matrix spin = {{0}, {0}, {s.omega0}};  // omega0 k, on i, j, k
  w.body_axes = w.frame_axes.add(spin);
  w.body_fixed = truncate(w.frame_fixed.add(R.mul(spin)), order);
  return w;
}

}  // namespace heavytop::symbolic

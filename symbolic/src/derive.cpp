#include "heavytop/symbolic/derive.hpp"

#include "algebra.hpp"

#include <stdexcept>

#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::symbolic {
namespace {

using detail::ex_to_matrix;
using detail::is_zero_matrix;

using GiNaC::ex;
using GiNaC::matrix;

matrix column(const ex& x, const ex& y, const ex& z) { return {{x}, {y}, {z}}; }

matrix map_entries(const matrix& a, ex (*f)(const ex&)) {
  matrix out(a.rows(), a.cols());
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) out(i, j) = f(a(i, j));
  return out;
}

ex normal_of(const ex& e) { return GiNaC::normal(e); }

bool equal_matrices(const matrix& a, const matrix& b) { return is_zero_matrix(a.sub(b)); }

// The three scalar equations of a route (rows phi, theta, psi; each "= 0"), exact in the
// truncated kinematics, not yet linearised.
struct RouteEquations {
  std::vector<ex> rows;
  matrix omega;  // body angular velocity on the axes the route projects on
  ex T = 0, V = 0;
};

RouteEquations route_equations(Method method, Sequence sequence, int order) {
  const Symbols& s = symbols();
  const auto coords = coordinates();
  const matrix inertia = {{s.A, 0, 0}, {0, s.B, 0}, {0, 0, s.C}};
  const matrix e3 = column(0, 0, 1);

  // Kinematics of the axis frame at the requested order, every angle and rate small. Truncating
  // R first and then the products loses nothing up to `order`, as d/dt never lowers the order.
  const matrix R = truncate(frame_rotation(sequence), order);
  const matrix R_t = time_derivative(R, coords);
  matrix frame_omega = truncate(vee(R.transpose().mul(R_t)), order);  // w1 on i, j, k
  matrix up = truncate(R.transpose().mul(e3), order);                 // the vertical n on i, j, k
  matrix omega = frame_omega.add(e3.mul_scalar(s.omega0));           // the body's w
  if (method == Method::EulerBody) {
    // The frame attached to the body: psi' = omega0 and w1 = w, while the small-angle results
    // are kept (psi = 0 in the table). This is the step the paper calls an error.
    const GiNaC::exmap spin = {{s.psi, 0}, {s.psi_t, s.omega0}, {s.psi_tt, 0}};
    frame_omega = ex_to_matrix(frame_omega.subs(spin));
    up = ex_to_matrix(up.subs(spin));
    omega = frame_omega;
  }

  RouteEquations out;
  switch (method) {
    case Method::EulerMoving:
    case Method::EulerBody: {
      // dK/dt = (relative derivative) + w1 x K = r_c x P, all on the moving axes.
      const matrix K = inertia.mul(omega);
      const matrix moment = cross(e3.mul_scalar(s.R), up.mul_scalar(-s.m * s.g));
      const matrix lhs = time_derivative(K, coords).add(cross(frame_omega, K));
      const matrix eq = lhs.sub(moment);
      out.rows = {eq(0, 0), eq(1, 0), eq(2, 0)};
      out.omega = omega;
      break;
    }
    case Method::EulerFixed: {
      // K on l, m, n is differentiated directly: no transport term.
      const matrix K = truncate(R.mul(inertia.mul(omega)), order);
      const matrix r_c = R.mul(e3).mul_scalar(s.R);
      const matrix moment = cross(r_c, column(0, 0, -s.m * s.g));
      const matrix eq = time_derivative(K, coords).sub(moment);
      out.rows = {eq(0, 0), eq(1, 0), eq(2, 0)};
      out.omega = truncate(R.mul(omega), order);
      break;
    }
    case Method::Lagrange: {
      // T and V to second order: linear equations need every quadratic term of L.
      const ex T = truncate((omega.transpose().mul(inertia).mul(omega))(0, 0) / 2, 2);
      const ex V = truncate(s.m * s.g * s.R * R(2, 2), 2);
      const ex L = T - V;
      for (const Coordinate& c : coords) {
        const auto& rate = GiNaC::ex_to<GiNaC::symbol>(c.rate);
        out.rows.push_back(time_derivative(L.diff(rate), coords) - L.diff(c.q));
      }
      out.omega = omega;
      out.T = T;
      out.V = V;
      break;
    }
  }
  return out;
}

}  // namespace

std::string_view name(Method method) {
  switch (method) {
    case Method::EulerMoving: return "euler-moving";
    case Method::EulerFixed: return "euler-fixed";
    case Method::EulerBody: return "euler-body";
    case Method::Lagrange: return "lagrange";
  }
  return "?";
}

std::optional<Method> method_from_name(std::string_view text) {
  for (Method m : kMethods)
    if (name(m) == text) return m;
  return std::nullopt;
}

ex characteristic_polynomial(const matrix& M, const matrix& G, const matrix& K) {
  const ex lambda = symbols().lambda;
  const matrix pencil = M.mul_scalar(pow(lambda, 2)).add(G.mul_scalar(lambda)).add(K);
  return GiNaC::normal(pencil.determinant()).expand();
}

Derivation derive(Method method, Sequence sequence, int order) {
  if (order != 1 && order != 2) throw std::invalid_argument("order must be 1 or 2");
  const Symbols& s = symbols();
  RouteEquations route = route_equations(method, sequence, order);

  Derivation d;
  d.method = method;
  d.sequence = sequence;
  d.order = order;
  d.omega = route.omega;
  d.T = route.T;
  d.V = route.V;

  // Linearise: keep first-order terms; the upright spin must be a solution (no constant).
  std::vector<ex> rows;
  for (const ex& row : route.rows) {
    const ex linear = truncate(row, 1);
    if (!GiNaC::normal(linear.subs(GiNaC::exmap{{s.phi, 0}, {s.theta, 0}, {s.psi, 0}, {s.phi_t, 0},
                                                  {s.theta_t, 0}, {s.psi_t, 0}, {s.phi_tt, 0},
                                                  {s.theta_tt, 0}, {s.psi_tt, 0}}))
             .is_zero())
      throw std::logic_error("derive: the upright spin does not satisfy the equations");
    rows.push_back(linear);
  }
  d.psi_equation = rows[2];

  // The paper sets psi = 0 (its equation is C psi'' = 0) and keeps q = (phi, theta).
  const GiNaC::exmap no_psi = {{s.psi, 0}, {s.psi_t, 0}, {s.psi_tt, 0}};
  const ex q[2] = {s.phi, s.theta}, q_t[2] = {s.phi_t, s.theta_t},
           q_tt[2] = {s.phi_tt, s.theta_tt};
  matrix M(2, 2), G(2, 2), K(2, 2);
  for (unsigned i = 0; i < 2; ++i) {
    const ex row = rows[i].subs(no_psi).expand();
    ex rebuilt = 0;
    for (unsigned j = 0; j < 2; ++j) {
      M(i, j) = row.coeff(q_tt[j], 1);
      G(i, j) = row.coeff(q_t[j], 1);
      K(i, j) = row.coeff(q[j], 1);
      rebuilt += M(i, j) * q_tt[j] + G(i, j) * q_t[j] + K(i, j) * q[j];
    }
    if (!(row - rebuilt).expand().is_zero())
      throw std::logic_error("derive: the equations are not of the form M q'' + G q' + K q = 0");
  }
  // Scale the rows (a combination of the equations, same solutions) so that M = diag(A, B).
  if (GiNaC::normal(M.determinant()).is_zero())
    throw std::logic_error("derive: M is singular, no second-order system in phi, theta");
  const matrix scale = matrix{{s.A, 0}, {0, s.B}}.mul(M.inverse());
  d.M = map_entries(scale.mul(M), normal_of);
  d.G = map_entries(scale.mul(G), normal_of);
  d.K = map_entries(scale.mul(K), normal_of);
  d.characteristic_polynomial = characteristic_polynomial(d.M, d.G, d.K);
  d.stability = stability_condition(d.M, d.G, d.K);
  return d;
}

PaperMatrices paper_model(PaperModel model) {
  const Symbols& s = symbols();
  const ex k = s.m * s.g * s.R;
  PaperMatrices p;
  p.M = {{s.A, 0}, {0, s.B}};
  p.K = {{-k, 0}, {0, -k}};
  if (model == PaperModel::Four)
    p.G = {{0, s.C * s.omega0}, {-s.C * s.omega0, 0}};
  else
    p.G = {{0, (s.C - s.B) * s.omega0}, {-(s.C - s.A) * s.omega0, 0}};
  return p;
}

std::string_view name(PaperModel model) {
  return model == PaperModel::Four ? "model (4)" : "model (5)";
}

std::optional<PaperModel> identify(const Derivation& d) {
  for (PaperModel model : {PaperModel::Four, PaperModel::Five}) {
    const PaperMatrices p = paper_model(model);
    if (equal_matrices(d.M, p.M) && equal_matrices(d.G, p.G) && equal_matrices(d.K, p.K))
      return model;
  }
  return std::nullopt;
}

bool same_model(const Derivation& a, const Derivation& b) {
  return equal_matrices(a.M, b.M) && equal_matrices(a.G, b.G) && equal_matrices(a.K, b.K);
}

ex paper_polynomial_8() {
  const Symbols& s = symbols();
  const ex k = s.m * s.g * s.R;
  return pow(s.lambda, 4) +
         (pow(s.C, 2) * pow(s.omega0, 2) - (s.A + s.B) * k) / (s.A * s.B) * pow(s.lambda, 2) +
         pow(k, 2) / (s.A * s.B);
}

ex paper_bound_9() {
  const Symbols& s = symbols();
  return pow(sqrt(s.A) + sqrt(s.B), 2) * s.m * s.g * s.R / pow(s.C, 2);
}

std::vector<CheckRow> check(const std::vector<int>& orders) {
  std::vector<CheckRow> rows;
  for (int order : orders)
    for (Method method : kMethods)
      for (Sequence sequence : kSequences) {
        CheckRow row;
        row.derivation = derive(method, sequence, order);
        row.model = identify(row.derivation);
        switch (method) {
          case Method::EulerMoving:
            row.expected = PaperModel::Four;
            row.why = "section 3: Euler on the moving axes gives (4); section 4: either sequence";
            break;
          case Method::EulerFixed:
            row.expected = PaperModel::Four;
            row.why = "section 5: the fixed axes give (6), identical to (4)";
            break;
          case Method::EulerBody:
            row.expected = PaperModel::Five;
            row.why = "section 3: a frame attached to the body (psi = omega0 t) gives (5)";
            break;
          case Method::Lagrange:
            if (order >= 2) {
              row.expected = PaperModel::Four;
              row.why = "section 6: second-order T and V give (4) for either sequence";
            } else {
              row.expected = std::nullopt;
              row.why = "section 6: first-order kinematics lose the doubled products in T "
                        "(gyroscopic terms) and the quadratic V";
            }
            break;
        }
        rows.push_back(std::move(row));
      }
  return rows;
}

}  // namespace heavytop::symbolic

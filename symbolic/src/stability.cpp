// The stability condition of M q'' + G q' + K q = 0 read off its characteristic polynomial,
// which for these models is biquadratic: a4 mu^2 + a2 mu + a0 with mu = lambda^2.
#include <stdexcept>

#include "heavytop/symbolic/derive.hpp"

#include "algebra.hpp"
#include "heavytop/symbolic/print.hpp"
#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::symbolic {
namespace {

using detail::ex_to_matrix;
using detail::is_zero_matrix;

using GiNaC::ex;
using GiNaC::matrix;

bool has_symbol(const ex& e) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return true;
  for (size_t i = 0; i < e.nops(); ++i)
    if (has_symbol(e.op(i))) return true;
  return false;
}

// The sign of `e` for every positive value of the symbols, as far as its structure shows it
// (+1, -1, or 0 for unknown): constants such as 3 - 2 sqrt(2) are evaluated, products and
// sums of known signs combined.
int sign(const ex& e) {
  if (e.info(GiNaC::info_flags::positive)) return 1;
  if (e.info(GiNaC::info_flags::negative)) return -1;
  if (!has_symbol(e)) {
    const ex v = GiNaC::evalf(e);
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real()) return 0;
    const double x = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    return x > 1e-12 ? 1 : x < -1e-12 ? -1 : 0;
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    int product = 1;
    for (size_t i = 0; i < e.nops(); ++i) product *= sign(e.op(i));
    return product;
  }
  if (GiNaC::is_a<GiNaC::add>(e)) {
    const int first = sign(e.op(0));
    for (size_t i = 1; i < e.nops(); ++i)
      if (sign(e.op(i)) != first) return 0;
    return first;
  }
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1))) {
    const int base = sign(e.op(0));
    const GiNaC::numeric x = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
    if (base == 1) return 1;
    if (base == -1 && x.is_integer()) return x.is_even() ? 1 : -1;
  }
  return 0;
}

bool positive(const ex& e) {
  return sign(e) == 1 || sign(GiNaC::collect_common_factors(e.expand())) == 1 ||
         sign(factor_radicals(e)) == 1;
}

// Requirement "value > floor" for a value that may hold omega0^2 linearly: solved for omega0^2
// when it does, as the paper solves (9).
void require_above(StabilityCondition& out, const ex& value, const ex& floor) {
  const Symbols& s = symbols();
  const ex v = value.expand();
  const bool linear_in_spin_squared = v.info(GiNaC::info_flags::polynomial) &&
                                      v.degree(s.omega0) <= 2 &&
                                      v.coeff(s.omega0, 1).is_zero();
  const ex c1 = linear_in_spin_squared ? v.coeff(s.omega0, 2) : ex(0);
  if (!linear_in_spin_squared || c1.is_zero()) {
    if (positive((floor - v).expand())) {
      out.never = true;
      out.steps.push_back("it fails for every spin: " + text(v) + " <= " + text(floor));
    } else if (!positive((v - floor).expand())) {
      out.all_of.push_back({v, floor, true});
    }
    return;
  }
  const ex c0 = v.coeff(s.omega0, 0);
  const ex room = floor - c0;  // omega0^2 c1 > room
  const ex bound = factor_radicals(room / c1);
  const ex spin2 = pow(s.omega0, 2);
  if (positive(c1)) {
    out.all_of.push_back({spin2, bound, true});
    out.steps.push_back("solved for omega0^2 (its coefficient " + text(c1) + " is positive)");
  } else if (positive(room)) {
    // c1 <= 0 would make the left side at most c0 < floor: c1 > 0 is needed.
    out.all_of.push_back({factor_radicals(c1), 0, true});
    out.all_of.push_back({spin2, bound, true});
    out.steps.push_back("the coefficient of omega0^2, " + text(c1) +
                        ", must be positive (otherwise no spin is enough); then solved for "
                        "omega0^2");
  } else {
    out.all_of.push_back({v, floor, true});
  }
}

}  // namespace

StabilityCondition stability_condition(const matrix& M, const matrix& G, const matrix& K) {
  const Symbols& s = symbols();
  const ex p = characteristic_polynomial(M, G, K);
  if (!p.coeff(s.lambda, 1).is_zero() || !p.coeff(s.lambda, 3).is_zero())
    throw std::domain_error("stability_condition: the polynomial has odd powers of lambda");
  const ex a4 = GiNaC::normal(p.coeff(s.lambda, 4));
  const ex a2 = GiNaC::normal(p.coeff(s.lambda, 2));
  const ex a0 = GiNaC::normal(p.coeff(s.lambda, 0));
  if (!positive(a4))
    throw std::domain_error("stability_condition: lambda^4 coefficient not known positive");

  StabilityCondition out;
  out.steps.push_back("det(M lambda^2 + G lambda + K) = a4 lambda^4 + a2 lambda^2 + a0 with a4 = " +
                      text(a4) + ", a2 = " + text(a2) + ", a0 = " + text(a0));
  out.steps.push_back("stable when both roots mu = lambda^2 of a4 mu^2 + a2 mu + a0 are real and "
                      "negative (lambda = +-i alpha) and no root is defective");

  if (a0.is_zero()) {
    // lambda = 0 is a root; its eigenvectors are the q with K q = 0.
    if (a2.is_zero()) {
      out.never = true;
      out.steps.push_back("a2 = a0 = 0: lambda = 0 is a fourfold root with at most two "
                          "eigenvectors, a Jordan block: q grows like t");
    } else if (!is_zero_matrix(K)) {
      out.never = true;
      out.steps.push_back("a0 = 0 with K != 0: lambda = 0 is a double root with one eigenvector, "
                          "a Jordan block");
    } else {
      out.steps.push_back("a0 = 0 with K = 0: lambda = 0 is a semisimple double root; the other "
                          "pair needs a2 > 0");
      require_above(out, a2, 0);
    }
    return out;
  }

  if (positive(-a0)) {
    out.never = true;
    out.steps.push_back("a0 < 0: the roots mu have opposite signs, so one lambda is real > 0");
    return out;
  }
  if (!positive(a0)) out.all_of.push_back({a0, 0, true});

  const ex D = GiNaC::normal((pow(a2, 2) - 4 * a4 * a0).expand());
  if (D.is_zero()) {
    // A double pair lambda0^2 = mu0 = -a2/(2 a4) at every parameter value: semisimple only if
    // the whole matrix M mu0 + G lambda0 + K vanishes, i.e. G = 0 and K = -mu0 M.
    const ex mu0 = -a2 / (2 * a4);
    if (is_zero_matrix(G) && is_zero_matrix(ex_to_matrix(K.add(M.mul_scalar(mu0))))) {
      out.steps.push_back("D = 0 identically, with G = 0 and K = -mu0 M: a semisimple double "
                          "pair, stable when mu0 < 0, i.e. a2 > 0");
      require_above(out, a2, 0);
    } else {
      out.never = true;
      out.steps.push_back("D = 0 identically: a double pair with one eigenvector (Jordan block)");
    }
    return out;
  }

  // At D = a2^2 - 4 a4 a0 = 0 the two pairs merge into a double pair +-lambda0 != 0, and
  // M lambda0^2 + G lambda0 + K keeps G lambda0 != 0 off the diagonal: rank 1, one eigenvector,
  // a Jordan block. So the discriminant must be positive, not merely >= 0 (erratum E2).
  const bool gyroscopic = !is_zero_matrix(G);
  out.steps.push_back(
      "needed: a2 > 0 (the roots mu sum to -a2/a4 < 0) and D = a2^2 - 4 a4 a0 > 0 (mu real and "
      "distinct)");
  if (gyroscopic)
    out.steps.push_back("strictly: at D = 0 the double pair has one eigenvector since G != 0 "
                        "(a Jordan block, secular growth; erratum E2), though the paper writes >=");
  else
    out.steps.push_back("G = 0: whether D = 0 is defective is not examined; it is excluded");

  if (positive(a0)) {
    // a2 > 0 and a2^2 > 4 a4 a0 together say a2 > 2 sqrt(a4 a0), as a4 a0 > 0.
    const ex floor = (2 * sqrt((a4 * a0).expand())).expand();
    out.steps.push_back("a4 a0 > 0, so both together read a2 > 2 sqrt(a4 a0) = " + text(floor));
    require_above(out, a2, floor);
  } else {
    require_above(out, a2, 0);
    out.all_of.push_back({(pow(a2, 2) - 4 * a4 * a0).expand(), 0, true});
  }
  return out;
}

}  // namespace heavytop::symbolic

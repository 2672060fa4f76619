#include "heavytop/symbolic/print.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::symbolic {
namespace {

using GiNaC::ex;
using GiNaC::ex_to;
using GiNaC::is_a;
using GiNaC::numeric;

// The paper's order of parameters; symbols not listed sort after them, by name.
int parameter_rank(const std::string& name) {
  static const std::map<std::string, int> rank = {
      {"A", 0}, {"B", 1}, {"C", 2}, {"m", 3}, {"g", 4}, {"R", 5}, {"omega0", 6}, {"lambda", 7}};
  auto it = rank.find(name);
  return it == rank.end() ? 50 : it->second;
}

// Variables: accelerations, then rates, then angles, as the paper writes its equations.
int variable_rank(const std::string& name) {
  static const std::map<std::string, int> rank = {
      {"phi''", 0}, {"theta''", 1}, {"psi''", 2}, {"phi'", 3}, {"theta'", 4},
      {"psi'", 5},  {"phi", 6},     {"theta", 7}, {"psi", 8}};
  auto it = rank.find(name);
  return it == rank.end() ? -1 : it->second;
}

void collect_symbols(const ex& e, std::vector<std::string>& names) {
  if (is_a<GiNaC::symbol>(e)) {
    names.push_back(ex_to<GiNaC::symbol>(e).get_name());
    return;
  }
  for (size_t i = 0; i < e.nops(); ++i) collect_symbols(e.op(i), names);
}

// Sort key of a factor of a product: sums first (as in "(C - A) (C - B) omega0"), ordered by
// the parameters they hold, then symbols and their powers in rank order, then anything else.
std::tuple<int, int, std::vector<int>> factor_key(const ex& f) {
  ex base = is_a<GiNaC::power>(f) ? f.op(0) : f;
  if (is_a<GiNaC::add>(base)) {
    std::vector<std::string> names;
    collect_symbols(base, names);
    std::vector<int> ranks;
    for (const auto& n : names) ranks.push_back(parameter_rank(n));
    std::sort(ranks.begin(), ranks.end());
    return {0, 0, ranks};
  }
  if (is_a<GiNaC::symbol>(base)) {
    const std::string n = ex_to<GiNaC::symbol>(base).get_name();
    const int v = variable_rank(n);
    return {1, v >= 0 ? 100 + v : parameter_rank(n), {}};
  }
  return {2, 0, {}};
}

// e = coefficient * rest, with the numeric coefficient of a product split off.
std::pair<numeric, ex> split_coefficient(const ex& e) {
  if (is_a<numeric>(e)) return {ex_to<numeric>(e), 1};
  if (is_a<GiNaC::mul>(e)) {
    numeric c = 1;
    ex rest = 1;
    for (size_t i = 0; i < e.nops(); ++i) {
      if (is_a<numeric>(e.op(i)))
        c *= ex_to<numeric>(e.op(i));
      else
        rest *= e.op(i);
    }
    return {c, rest};
  }
  return {1, e};
}


bool printed_negative(const ex& term);

// Sort key of a term of a sum: falling powers of lambda, positive terms first, then by the
// first variable the term holds, then by its parameters.
std::tuple<int, int, int, std::vector<int>> term_key(const ex& term) {
  const Symbols& s = symbols();
  const int lambda_degree = term.has(s.lambda) ? term.degree(s.lambda) : 0;
  std::vector<std::string> names;
  collect_symbols(split_coefficient(term).second, names);
  int first_variable = 99;
  std::vector<int> parameters;
  for (const auto& n : names) {
    const int v = variable_rank(n);
    if (v >= 0)
      first_variable = std::min(first_variable, v);
    else
      parameters.push_back(parameter_rank(n));
  }
  std::sort(parameters.begin(), parameters.end());
  return {-lambda_degree, printed_negative(term) ? 1 : 0, first_variable, parameters};
}

// The rank of the symbol a sum is "about": its highest-ranked parameter (C in C - B).
int leading_rank(const ex& sum) {
  std::vector<std::string> names;
  collect_symbols(sum, names);
  int best = -1;
  for (const auto& n : names) best = std::max(best, parameter_rank(n));
  return best;
}

bool leads_negative(const ex& sum);

// The sign a term is printed with: its coefficient's, turned once for every sum factor that
// is printed turned round (odd powers only).
bool printed_negative(const ex& term) {
  const auto [c, rest] = split_coefficient(term);
  bool negative = c.is_negative();
  std::vector<ex> factors;
  if (is_a<GiNaC::mul>(rest))
    for (size_t i = 0; i < rest.nops(); ++i) factors.push_back(rest.op(i));
  else
    factors.push_back(rest);
  for (const ex& f : factors) {
    const ex base = is_a<GiNaC::power>(f) ? f.op(0) : f;
    const ex exponent = is_a<GiNaC::power>(f) ? f.op(1) : ex(1);
    if (is_a<GiNaC::add>(base) && is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_odd() &&
        leads_negative(base))
      negative = !negative;
  }
  return negative;
}

// True if the term of `sum` holding its leading symbol prints negative: B - C, not C - B.
bool leads_negative(const ex& sum) {
  const int lead = leading_rank(sum);
  for (size_t i = 0; i < sum.nops(); ++i) {
    std::vector<std::string> names;
    collect_symbols(sum.op(i), names);
    for (const auto& n : names)
      if (parameter_rank(n) == lead) return printed_negative(sum.op(i));
  }
  return false;
}

class Printer {
 public:
  explicit Printer(Style style) : style_(style) {}

  // Context: 0 at the top or as a term of a sum, 1 as a factor, 2 as the base of a power.
  std::string print(const ex& e, int context = 0) const {
    if (is_a<GiNaC::symbol>(e)) return symbol_name(ex_to<GiNaC::symbol>(e));
    if (is_a<GiNaC::add>(e)) return wrap(sum(e), context > 0);
    if (is_a<numeric>(e) || is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e)) {
      const auto [negative, magnitude] = signed_term(e);
      // A factor needs parentheses when signed or a fraction; a power's base when compound.
      const bool fraction = !latex() && magnitude.find('/') != std::string::npos;
      const bool compound = is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e) || fraction;
      return wrap((negative ? "-" : "") + magnitude, (negative && context > 0) ||
                                                         (fraction && context == 1) ||
                                                         (compound && context > 1));
    }
    if (is_a<GiNaC::function>(e)) return function(e);
    if (is_a<GiNaC::relational>(e)) return print(e.op(0)) + " = " + print(e.op(1));
    std::ostringstream out;  // anything else: GiNaC's own form
    out << e;
    return out.str();
  }

 private:
  Style style_;

  bool latex() const { return style_ == Style::Latex; }

  std::string wrap(const std::string& s, bool parens) const {
    if (!parens) return s;
    return latex() ? "\\left(" + s + "\\right)" : "(" + s + ")";
  }

  std::string symbol_name(const GiNaC::symbol& x) const {
    return latex() ? x.get_TeX_name() : x.get_name();
  }

  std::string plus() const { return style_ == Style::Cas ? "+" : " + "; }
  std::string minus() const { return style_ == Style::Cas ? "-" : " - "; }
  std::string times() const { return style_ == Style::Cas ? "*" : " "; }

  std::string sum(const ex& e) const {
    std::vector<ex> terms;
    for (size_t i = 0; i < e.nops(); ++i) terms.push_back(e.op(i));
    std::stable_sort(terms.begin(), terms.end(),
                     [](const ex& a, const ex& b) { return term_key(a) < term_key(b); });
    std::string out;
    for (size_t i = 0; i < terms.size(); ++i) {
      const auto [negative, magnitude] = signed_term(terms[i]);
      if (i == 0)
        out += negative ? "-" : "";
      else
        out += negative ? minus() : plus();
      out += magnitude;
    }
    return out;
  }

  // A term as its sign and the printed magnitude (numbers, products and powers).
  std::pair<bool, std::string> signed_term(const ex& e) const {
    if (is_a<numeric>(e)) {
      const numeric n = ex_to<numeric>(e);
      if (n.is_rational()) return product(e);
      std::ostringstream out;
      out << abs(n);
      return {n.is_negative(), out.str()};
    }
    if (is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e)) return product(e);
    return {false, print(e, 0)};
  }

  struct Factor {
    ex base;
    numeric exponent;
  };

  // c * numerator / denominator with factors in the paper's order; sums whose leading symbol
  // has a minus sign are turned round ((B - C) -> -(C - B)).
  std::pair<bool, std::string> product(const ex& e) const {
    auto [c, rest] = split_coefficient(e);
    std::vector<ex> ops;
    if (is_a<GiNaC::mul>(rest))
      for (size_t i = 0; i < rest.nops(); ++i) ops.push_back(rest.op(i));
    else if (rest != 1)
      ops.push_back(rest);
    std::vector<Factor> num, den;
    for (const ex& f : ops) {
      ex base = f;
      ex exponent = 1;
      if (is_a<GiNaC::power>(f)) {
        base = f.op(0);
        exponent = f.op(1);
      }
      if (!is_a<numeric>(exponent)) {  // symbolic exponent: print as is
        num.push_back({f, 1});
        continue;
      }
      numeric x = ex_to<numeric>(exponent);
      if (is_a<GiNaC::add>(base) && x.is_integer() && leads_negative(base)) {
        base = -base;  // numeric * sum distributes without expanding the terms
        if (x.is_odd()) c = -c;
      }
      if (x.is_negative())
        den.push_back({base, -x});
      else
        num.push_back({base, x});
    }
    auto by_key = [](const Factor& a, const Factor& b) {
      return factor_key(a.base) < factor_key(b.base);
    };
    std::stable_sort(num.begin(), num.end(), by_key);
    std::stable_sort(den.begin(), den.end(), by_key);
    const numeric magnitude = abs(c);
    const numeric p = magnitude.numer(), q = magnitude.denom();

    auto join = [&](const std::vector<Factor>& list, const numeric& lead) {
      std::string out;
      if (lead != 1 || list.empty()) {
        std::ostringstream n;
        n << lead;
        out = n.str();
      }
      for (const Factor& f : list) {
        if (!out.empty()) out += times();
        out += factor(f);
      }
      return out;
    };
    const std::string top = join(num, p);
    std::string out;
    if (den.empty() && q == 1) {
      out = top;
    } else if (latex()) {
      out = "\\frac{" + top + "}{" + join(den, q) + "}";
    } else {
      const bool single = (den.size() == 1 && q == 1) || (den.empty());
      const std::string bottom = join(den, q);
      out = top + "/" + (single ? bottom : "(" + bottom + ")");
    }
    return {c.is_negative(), out};
  }

  std::string factor(const Factor& f) const {
    if (f.exponent == 1) return print(f.base, 1);
    if (f.exponent == numeric(1, 2))
      return latex() ? "\\sqrt{" + print(f.base) + "}" : "sqrt(" + print(f.base) + ")";
    const std::string b = print(f.base, 2);
    std::ostringstream x;
    x << f.exponent;
    if (latex()) return "{" + b + "}^{" + x.str() + "}";
    return b + "^" + (f.exponent.is_integer() ? x.str() : "(" + x.str() + ")");
  }

  std::string function(const ex& e) const {
    const std::string n = ex_to<GiNaC::function>(e).get_name();
    std::string args;
    for (size_t i = 0; i < e.nops(); ++i) args += (i ? ", " : "") + print(e.op(i));
    if (latex()) return "\\" + n + "\\left(" + args + "\\right)";
    return n + "(" + args + ")";
  }
};

// Symbols that occur under a fractional power in `e`.
void radical_symbols(const ex& e, GiNaC::exset& found, bool under_root) {
  if (is_a<GiNaC::symbol>(e)) {
    if (under_root) found.insert(e);
    return;
  }
  if (is_a<GiNaC::power>(e) && is_a<numeric>(e.op(1)) && !ex_to<numeric>(e.op(1)).is_integer()) {
    radical_symbols(e.op(0), found, true);
    return;
  }
  for (size_t i = 0; i < e.nops(); ++i) radical_symbols(e.op(i), found, under_root);
}

ex factor_polynomial(const ex& e) {
  const ex nd = GiNaC::normal(e).numer_denom();
  return GiNaC::factor(nd.op(0)) / GiNaC::factor(nd.op(1));
}

}  // namespace

std::string to_string(const ex& e, Style style) { return Printer(style).print(e); }

ex factor_radicals(const ex& e) {
  GiNaC::exset under;
  radical_symbols(e, under, false);
  if (under.empty()) return factor_polynomial(e);
  // Only positive symbols may be written as squares: sqrt(x^2) = x needs x > 0.
  GiNaC::exmap to_square, back;
  int k = 0;
  for (const ex& x : under) {
    if (!x.info(GiNaC::info_flags::positive)) return e;
    GiNaC::possymbol root("r" + std::to_string(k++));
    to_square[x] = pow(root, 2);
    back[root] = sqrt(x);
  }
  // expand() applies sqrt(r^2 s^2) = r s for positive r, s; then it is a rational function.
  const ex rational = e.subs(to_square).expand();
  return factor_polynomial(rational).subs(back);
}

ex tidy(const ex& e) {
  const Symbols& s = symbols();
  auto tidy_coefficient = [&](const ex& c) {
    const ex expanded = c.expand();
    if (!expanded.has(s.omega0) || !expanded.info(GiNaC::info_flags::polynomial))
      return factor_radicals(expanded);
    ex out = 0;
    for (int k = expanded.ldegree(s.omega0); k <= expanded.degree(s.omega0); ++k)
      out += factor_radicals(expanded.coeff(s.omega0, k)) * pow(s.omega0, k);
    return out;
  };
  const ex expanded = e.expand();
  if (!expanded.has(s.lambda) || !expanded.info(GiNaC::info_flags::polynomial))
    return tidy_coefficient(expanded);
  ex out = 0;
  for (int k = expanded.ldegree(s.lambda); k <= expanded.degree(s.lambda); ++k)
    out += tidy_coefficient(expanded.coeff(s.lambda, k)) * pow(s.lambda, k);
  return out;
}

std::string text(const GiNaC::ex& e) { return to_string(tidy(e), Style::Text); }

}  // namespace heavytop::symbolic

#pragma once
// Private to heavytop_symbolic: the matrix helpers every route and the stability analysis use.

#include <ginac/ginac.h>

namespace heavytop::symbolic::detail {

/// `e` as a matrix (it must be one: the result of a matrix product or subs()).
inline GiNaC::matrix ex_to_matrix(const GiNaC::ex& e) { return GiNaC::ex_to<GiNaC::matrix>(e); }

/// True if every entry of `a` simplifies to zero (GiNaC::normal).
inline bool is_zero_matrix(const GiNaC::matrix& a) {
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j)
      if (!GiNaC::normal(a(i, j)).is_zero()) return false;
  return true;
}

}  // namespace heavytop::symbolic::detail

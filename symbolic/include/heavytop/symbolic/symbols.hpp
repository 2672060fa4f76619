#pragma once
/// \file
/// The symbols every derivation shares. GiNaC compares symbols by identity, not by name, so
/// there is exactly one instance of each, reached through symbols().

#include <ginac/ginac.h>

namespace heavytop::symbolic {

/// The parameters (positive, so that sqrt(A^2) = A), the small quantities and the
/// bookkeeping parameter. Names are those of SPEC section 5; TeX names follow the paper.
struct Symbols {
  GiNaC::possymbol A{"A"};                   ///< moment of inertia about x
  GiNaC::possymbol B{"B"};                   ///< moment of inertia about y
  GiNaC::possymbol C{"C"};                   ///< moment of inertia about the spin axis z
  GiNaC::possymbol m{"m"};                   ///< mass
  GiNaC::possymbol g{"g"};                   ///< gravity
  GiNaC::possymbol R{"R"};                   ///< distance O to the centre of mass (a top: R > 0)
  GiNaC::possymbol omega0{"omega0", "\\omega_0"};  ///< spin about the body axis
  GiNaC::symbol lambda{"lambda", "\\lambda"};      ///< exponent of e^(lambda t)

  GiNaC::realsymbol phi{"phi", "\\varphi"};        ///< small angle about the fixed xi axis
  GiNaC::realsymbol theta{"theta", "\\theta"};     ///< small angle about the (intermediate) eta axis
  GiNaC::realsymbol psi{"psi", "\\psi"};           ///< small angle about the axis z
  GiNaC::realsymbol phi_t{"phi'", "\\dot{\\varphi}"};      ///< d phi / dt
  GiNaC::realsymbol theta_t{"theta'", "\\dot{\\theta}"};   ///< d theta / dt
  GiNaC::realsymbol psi_t{"psi'", "\\dot{\\psi}"};         ///< d psi / dt
  GiNaC::realsymbol phi_tt{"phi''", "\\ddot{\\varphi}"};   ///< d^2 phi / dt^2
  GiNaC::realsymbol theta_tt{"theta''", "\\ddot{\\theta}"};///< d^2 theta / dt^2
  GiNaC::realsymbol psi_tt{"psi''", "\\ddot{\\psi}"};      ///< d^2 psi / dt^2

  GiNaC::realsymbol eps{"eps", "\\varepsilon"};    ///< order of smallness (bookkeeping only)

  /// Every small quantity: the angles, their rates and accelerations.
  GiNaC::lst small() const {
    return {phi, theta, psi, phi_t, theta_t, psi_t, phi_tt, theta_tt, psi_tt};
  }
};

/// The one instance of the shared symbols.
const Symbols& symbols();

}  // namespace heavytop::symbolic

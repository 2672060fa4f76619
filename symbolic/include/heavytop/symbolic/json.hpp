#pragma once
/// \file
/// The derivations as JSON (SPEC section 5, `heavytop derive --format json`): one rendering
/// shared by the command line and the Python module, so both print the same bytes. Every
/// expression is a string a computer-algebra system reads (Style::Cas: `^` for powers).

#include <string>
#include <vector>

#include "heavytop/symbolic/derive.hpp"
#include "heavytop/symbolic/kinematics.hpp"

namespace heavytop::symbolic {

/// {"M": [[..],[..]], "G": .., "K": .., "characteristic_polynomial": "..",
///  "stability_condition": ".."} for M q'' + G q' + K q = 0, q = (phi, theta). The condition
/// is relations joined by `&`, or True / False. Two-space indented, ends with a newline.
std::string derivation_json(const Derivation& derivation);

/// {"A1": .., "A2": .., "A3": .., "A1A2": .., "A2A1": .., "commutator": ..}: 3x3 arrays of
/// strings in phi, theta, psi. Two-space indented, ends with a newline.
std::string rotations_json(const Rotations& rotations);

/// {"rows": [{"method", "sequence", "order", "M", "G", "K", "model", "expected",
/// "as_expected", "why"}, ...], "all_as_expected": bool}: the --check table.
std::string check_json(const std::vector<CheckRow>& rows);

}  // namespace heavytop::symbolic

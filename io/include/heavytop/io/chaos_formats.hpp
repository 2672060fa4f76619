#pragma once
/// \file
/// The forms of the chaos command's results (SPEC section 17): JSON for scripts, a sentence
/// for people, the Poincare section as CSV.

#include <string>

#include "heavytop/chaos.hpp"

namespace heavytop::io {

/// `heavytop chaos --format json`: {"lyapunov_exponent" (1/s), "lyapunov_error" (1/s),
/// "history": [[t (s), l (1/s)], ...], "spectrum": [6 values, 1/s, descending], "megno",
/// "prediction_horizon" (s, or null), "precision", "chaotic"}, SPEC 17's keys and nothing else.
std::string chaos_json(const ChaosResult& result);

/// The text form: one sentence, "Chaotic: ..." with the prediction horizon, or "Not chaotic
/// over T s: ..." with what the exponent and MEGNO were measured against.
std::string chaos_text(const ChaosResult& result);

/// `heavytop chaos --section --format csv`: the header t,tilt,tilt_rate (s, rad, rad/s), one
/// row per crossing of psi = 0 with psi' > 0.
std::string section_csv(const PoincareSection& section);

/// The section as text: how many crossings, then the same rows.
std::string section_text(const PoincareSection& section, double horizon);

/// The section as JSON: {"columns": ["t", "tilt", "tilt_rate"], "rows": [[...], ...],
/// "max_relative_energy_drift"}.
std::string section_json(const PoincareSection& section);

}  // namespace heavytop::io

#pragma once
/// \file
/// A measured spin decay from a CSV file, for fit_spin_decay() (heavytop fit-decay --data).
///
///     # comment lines start with '#' (anywhere); blank lines are skipped
///     t,spin            <- the header, required: t (s) and spin (rad/s) or spin_rpm (rpm)
///     0,200.1
///     2.5,191.7
///
/// Comma separated, one point a line, the columns in either order. Every bad line is refused
/// with InvalidInput("data", "line N: <rule>") (N from 1, counting every line of the file).

#include <cstddef>
#include <string>
#include <string_view>

#include "heavytop/fit_decay.hpp"

namespace heavytop::io {

/// The largest decay file read_decay_csv() reads (bytes), about a million points.
inline constexpr std::size_t kMaxDecayDataBytes = 32u << 20;

/// Parses `text`, a decay CSV's content, into times (s) and spins (rad/s; rpm converted).
/// Refused (InvalidInput, key "data", the rule beginning "line N: " where a line is at fault):
/// no header or a header without t or without exactly one of spin and spin_rpm, an unknown or
/// repeated column, a row with another number of fields than the header, a field that is not
/// a number, a number that is not finite, t < 0 or below the previous t, spin < 0, fewer than
/// `min_points` points.
DecayData parse_decay_csv(std::string_view text, std::size_t min_points);

/// Reads `path` (at most kMaxDecayDataBytes; errors about the file itself name `path_key`,
/// e.g. "--data") and parses it as parse_decay_csv() does.
DecayData read_decay_csv(const std::string& path, const std::string& path_key, std::size_t min_points);

}  // namespace heavytop::io

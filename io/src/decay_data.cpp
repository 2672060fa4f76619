#include "heavytop/io/decay_data.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "heavytop/io/config.hpp"

namespace heavytop::io {
namespace {

constexpr double kRadPerSecondPerRpm = 2.0 * std::numbers::pi / 60.0;

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

// A field shown in a message: printable, and cut short.
std::string shown(std::string_view field) {
  return printable(field.size() > 40 ? std::string(field.substr(0, 40)) + "..." : std::string(field));
}

[[noreturn]] void refuse(std::size_t line, const std::string& rule) {
  throw InvalidInput("data", fmt::format("line {}: {}", line, rule));
}

double number_at(std::string_view field, std::size_t line, std::string_view column) {
  if (field.starts_with('+')) field.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (field.empty() || error != std::errc() || end != field.data() + field.size())
    refuse(line, fmt::format("{} '{}' is not a number", column, shown(field)));
  if (!std::isfinite(value)) refuse(line, fmt::format("{} must be a finite number", column));
  return value;
}

}  // namespace

DecayData parse_decay_csv(std::string_view text, std::size_t min_points) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a spreadsheet's UTF-8 byte order mark
  DecayData data;
  std::optional<std::size_t> t_column, spin_column;
  bool rpm = false;
  std::size_t columns = 0, line = 0;
  for (std::size_t start = 0; start <= text.size(); ++line) {
    const std::size_t newline = text.find('\n', start);
    const std::string_view raw =
        text.substr(start, newline == std::string_view::npos ? std::string_view::npos : newline - start);
    start = newline == std::string_view::npos ? text.size() + 1 : newline + 1;
    const std::string_view content = trim(raw);
    if (content.empty() || content.starts_with('#')) continue;
    const auto fields = split(content);
    if (columns == 0) {  // the header
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string_view name = fields[i];
        std::optional<std::size_t>* slot = name == "t" ? &t_column : (name == "spin" || name == "spin_rpm") ? &spin_column : nullptr;
        if (!slot)
          refuse(line + 1, fmt::format("unknown column '{}' (the header names t and spin (rad/s) or spin_rpm (rpm))",
                                       shown(name)));
        if (*slot) refuse(line + 1, name == "t" ? "the column t is given twice" : "give one of spin and spin_rpm, once");
        *slot = i;
        rpm = rpm || name == "spin_rpm";
      }
      if (!t_column || !spin_column)
        refuse(line + 1, "the header must name the columns t and spin (rad/s) or spin_rpm (rpm), e.g. 't,spin'");
      columns = fields.size();
      continue;
    }
    if (fields.size() != columns)
      refuse(line + 1, fmt::format("{} fields, the header has {}", fields.size(), columns));
    const double t = number_at(fields[*t_column], line + 1, "t");
    const double spin = number_at(fields[*spin_column], line + 1, rpm ? "spin_rpm" : "spin");
    if (t < 0.0) refuse(line + 1, "t must be >= 0 (s from the start)");
    if (!data.t.empty() && t < data.t.back())
      refuse(line + 1, fmt::format("t = {} is before the previous line's {} (t must not decrease)", t, data.t.back()));
    if (spin < 0.0) refuse(line + 1, "the spin must be >= 0 (its magnitude)");
    data.t.push_back(t);
    data.spin.push_back(rpm ? spin * kRadPerSecondPerRpm : spin);
  }
  if (columns == 0) throw InvalidInput("data", "no header line (t,spin or t,spin_rpm) and no data");
  if (data.t.size() < min_points)
    throw InvalidInput("data", fmt::format("{} points; at least {} are needed", data.t.size(), min_points));
  return data;
}

DecayData read_decay_csv(const std::string& path, const std::string& path_key, std::size_t min_points) {
  return parse_decay_csv(read_text_file(path, path_key, kMaxDecayDataBytes, "a spin-decay CSV file"), min_points);
}

}  // namespace heavytop::io

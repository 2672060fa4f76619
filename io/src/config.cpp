#include "heavytop/io/config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <new>

#include <fmt/format.h>
#include <toml++/toml.h>

namespace heavytop::io {
namespace {

struct Field {
  const char* key;
  double Body::*body = nullptr;
  double InitialState::*state = nullptr;
  double Damping::*damping = nullptr;  // of Body::damping
};

constexpr Field kFields[] = {
    {"body.A", &Body::A},
    {"body.B", &Body::B},
    {"body.C", &Body::C},
    {"body.mass", &Body::mass},
    {"body.gravity", &Body::gravity},
    {"body.length", &Body::length},
    {"motion.spin", nullptr, &InitialState::spin},
    {"motion.theta0", nullptr, &InitialState::theta0},
    {"motion.phi0", nullptr, &InitialState::phi0},
    {"motion.theta_rate0", nullptr, &InitialState::theta_rate0},
    {"motion.phi_rate0", nullptr, &InitialState::phi_rate0},
    {"damping.transverse", nullptr, nullptr, &Damping::transverse},
    {"damping.axial", nullptr, nullptr, &Damping::axial},
    {"damping.friction", nullptr, nullptr, &Damping::friction},
};

std::vector<std::string> keys_starting(std::string_view prefix) {
  std::vector<std::string> keys;
  for (const Field& f : kFields)
    if (std::string_view(f.key).starts_with(prefix)) keys.emplace_back(f.key);
  return keys;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else out += fmt::format("\\x{:02x}", u);
  }
  return out;
}

namespace {

double number_of(const toml::node& node, const std::string& key) {
  if (auto v = node.value_exact<double>()) return *v;
  if (auto v = node.value_exact<int64_t>()) return static_cast<double>(*v);
  throw InvalidInput(key, "must be a number");
}

}  // namespace

const std::vector<std::string>& body_keys() {
  static const auto keys = keys_starting("body.");
  return keys;
}
const std::vector<std::string>& motion_keys() {
  static const auto keys = keys_starting("motion.");
  return keys;
}
const std::vector<std::string>& required_body_keys() {
  static const std::vector<std::string> keys = {"body.A", "body.B", "body.C", "body.mass", "body.length"};
  return keys;
}

double* config_field(Body& body, InitialState& state, std::string_view key) {
  for (const Field& f : kFields)
    if (key == f.key) return f.body ? &(body.*f.body) : f.state ? &(state.*f.state) : &(body.damping.*f.damping);
  return nullptr;
}

const std::map<std::string, std::vector<std::string>>& command_sections() {
  static const std::map<std::string, std::vector<std::string>> sections = {
      {"simulate", {"model", "t_end", "samples", "method", "rtol", "atol", "integrator", "step", "order"}},
  };
  return sections;
}

std::optional<double> Configuration::number(const std::string& key) const {
  auto it = settings.find(key);
  if (it == settings.end()) return std::nullopt;
  if (auto* d = std::get_if<double>(&it->second)) return *d;
  if (auto* i = std::get_if<std::int64_t>(&it->second)) return static_cast<double>(*i);
  throw InvalidInput(key, "must be a number");
}

std::optional<std::int64_t> Configuration::integer(const std::string& key) const {
  auto it = settings.find(key);
  if (it == settings.end()) return std::nullopt;
  if (auto* i = std::get_if<std::int64_t>(&it->second)) return *i;
  if (auto* d = std::get_if<double>(&it->second); d && std::isfinite(*d) && *d == std::trunc(*d) &&
                                                  std::abs(*d) < 9e15)
    return static_cast<std::int64_t>(*d);
  throw InvalidInput(key, "must be a whole number");
}

std::optional<std::string> Configuration::string(const std::string& key) const {
  auto it = settings.find(key);
  if (it == settings.end()) return std::nullopt;
  if (auto* s = std::get_if<std::string>(&it->second)) return *s;
  throw InvalidInput(key, "must be a string");
}

Configuration parse_configuration(std::string_view text, const std::string& source, const std::string& path_key) {
  toml::table table;
  try {
    table = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw InvalidInput(path_key, fmt::format("{}:{}:{}: malformed TOML: {}", printable(source), where.line,
                                             where.column, printable(e.description())));
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // toml++ documents only parse_error; anything else is still bad input
    throw InvalidInput(path_key, fmt::format("{}: malformed TOML: {}", printable(source), printable(e.what())));
  }
  Configuration config;
  config.path = source;
  const auto& sections = command_sections();
  for (const auto& [section_key, node] : table) {
    const std::string section(section_key.str());
    const bool known = section == "body" || section == "motion" || section == "damping" || sections.count(section);
    if (!known)
      throw InvalidInput(section.empty() ? "\"\"" : printable(section), "unknown section in " + printable(source));
    const auto* sub = node.as_table();
    if (!sub) throw InvalidInput(section, "must be a [section] table");
    config.has_body = config.has_body || section == "body";
    for (const auto& [name_key, value] : *sub) {
      const std::string key = section + "." + std::string(name_key.str());
      if (double* field = config_field(config.body, config.motion, key)) {
        *field = number_of(value, key);
        config.given.insert(key);
        continue;
      }
      const auto it = sections.find(section);
      if (it == sections.end() || std::find(it->second.begin(), it->second.end(), name_key.str()) == it->second.end())
        throw InvalidInput(printable(key), "unknown key in " + printable(source));
      if (auto s = value.value_exact<std::string>()) config.settings[key] = *s;
      else if (auto i = value.value_exact<std::int64_t>()) config.settings[key] = *i;
      else if (auto d = value.value_exact<double>()) config.settings[key] = *d;
      else if (auto b = value.value_exact<bool>()) config.settings[key] = *b;
      else throw InvalidInput(key, "must be a number or a string");
    }
  }
  return config;
}

std::string read_text_file(const std::string& path, const std::string& path_key, std::size_t max_bytes,
                           std::string_view what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string shown = printable(path);
  if (!fs::exists(path, ec)) throw InvalidInput(path_key, fmt::format("cannot read '{}': no such file", shown));
  if (fs::is_directory(path, ec)) throw InvalidInput(path_key, fmt::format("cannot read '{}': it is a folder", shown));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(path_key, fmt::format("cannot read '{}'", shown));
  // One byte more than the limit tells a file at the limit from a larger one (or an endless
  // device); a pipe is read as far as that too. In blocks, so that a small file under a large
  // limit costs only its size.
  std::string text;
  constexpr std::size_t kBlock = 1 << 16;
  while (text.size() <= max_bytes && in) {
    const std::size_t before = text.size(), want = std::min(kBlock, max_bytes + 1 - before);
    text.resize(before + want);
    in.read(text.data() + before, static_cast<std::streamsize>(want));
    text.resize(before + static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InvalidInput(path_key, fmt::format("cannot read '{}'", shown));
  if (text.size() > max_bytes)
    throw InvalidInput(path_key, fmt::format("'{}' is larger than {} bytes: not {}", shown, max_bytes, what));
  return text;
}

Configuration read_configuration(const std::string& path, const std::string& path_key) {
  return parse_configuration(read_text_file(path, path_key, kMaxConfigurationBytes, "a configuration file"), path,
                             path_key);
}

}  // namespace heavytop::io

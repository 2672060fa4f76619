#include "common.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include <fmt/format.h>
#include <toml++/toml.h>

namespace heavytop::cli {
namespace {

struct KeySpec {
  const char* key;      // as in the configuration file, "section.name"
  const char* option;   // CLI11 option names
  const char* help;
};

constexpr KeySpec kKeys[] = {
    {"body.A", "--A", "kg m^2, moment of inertia about body x through O (> 0)"},
    {"body.B", "--B", "kg m^2, moment of inertia about body y through O (> 0)"},
    {"body.C", "--C", "kg m^2, moment of inertia about the spin axis z through O (> 0)"},
    {"body.mass", "--mass", "kg, mass m (> 0)"},
    {"body.gravity", "--gravity", "m/s^2, gravity g (>= 0, default 9.81)"},
    {"body.length", "--length", "m, R: signed distance O to centre of mass along z (< 0 hanging)"},
    {"motion.spin", "--spin", "rad/s, spin w0 about the body axis"},
    {"motion.theta0", "--theta0", "rad, initial theta (tilt towards xi)"},
    {"motion.phi0", "--phi0", "rad, initial phi (tilt about xi)"},
    {"motion.theta_rate0", "--theta_rate0,--theta-rate0", "rad/s, initial theta'"},
    {"motion.phi_rate0", "--phi_rate0,--phi-rate0", "rad/s, initial phi'"},
};

double* field(Body& b, InitialState& s, const std::string& key) {
  static const std::map<std::string, double Body::*> body_fields = {
      {"body.A", &Body::A},         {"body.B", &Body::B},       {"body.C", &Body::C},
      {"body.mass", &Body::mass},   {"body.gravity", &Body::gravity},
      {"body.length", &Body::length}};
  static const std::map<std::string, double InitialState::*> state_fields = {
      {"motion.spin", &InitialState::spin},
      {"motion.theta0", &InitialState::theta0},
      {"motion.phi0", &InitialState::phi0},
      {"motion.theta_rate0", &InitialState::theta_rate0},
      {"motion.phi_rate0", &InitialState::phi_rate0}};
  if (auto it = body_fields.find(key); it != body_fields.end()) return &(b.*(it->second));
  if (auto it = state_fields.find(key); it != state_fields.end()) return &(s.*(it->second));
  return nullptr;
}

std::optional<double> as_number(const toml::node& node, const std::string& key) {
  if (auto v = node.value_exact<double>()) return *v;
  if (auto v = node.value_exact<int64_t>()) return static_cast<double>(*v);
  throw InvalidInput(key, "must be a number");
}

}  // namespace

Inputs::Inputs(CLI::App& command, std::vector<std::string> formats) : format_(formats.front()) {
  command.add_option("--config", config_path_, "TOML configuration file (SPEC section 4); without it the built-in toy top")
      ->type_name("FILE");
  for (const KeySpec& spec : kKeys) {
    Override& o = overrides_[spec.key];
    o.option = command.add_option(spec.option, o.value, spec.help)
                   ->type_name("NUM")
                   ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    o.option->group(std::string(spec.key).starts_with("body.") ? "Body" : "Motion");
  }
  command.add_option("--format", format_, "output format")
      ->check(CLI::IsMember(formats))
      ->default_str(formats.front());
  command.add_option("--output", output_, "write to FILE instead of stdout")->type_name("FILE");
}

void Inputs::allow_section(const std::string& section, std::vector<std::string> keys) {
  sections_[section] = std::move(keys);
}

void Inputs::resolve() {
  Body body = example_toy_top();
  InitialState state = example_motion();
  if (!config_path_.empty()) {
    toml::table table;
    try {
      table = toml::parse_file(config_path_);
    } catch (const toml::parse_error& e) {
      const auto& where = e.source().begin;
      if (!std::filesystem::exists(config_path_))
        throw InvalidInput("--config", fmt::format("cannot read '{}': no such file", config_path_));
      throw InvalidInput("--config", fmt::format("{}:{}:{}: malformed TOML: {}", config_path_,
                                                 where.line, where.column, e.description()));
    }
    body = Body{};
    body.gravity = 9.81;
    state = InitialState{};
    bool seen_body = false;
    for (const auto& [section_key, node] : table) {
      const std::string section(section_key.str());
      const auto* sub = node.as_table();
      const bool known = section == "body" || section == "motion" || sections_.count(section);
      if (!known) throw InvalidInput(section, "unknown section in " + config_path_);
      if (!sub) throw InvalidInput(section, "must be a [section] table");
      seen_body = seen_body || section == "body";
      for (const auto& [name_key, value] : *sub) {
        const std::string key = section + "." + std::string(name_key.str());
        if (double* f = field(body, state, key)) {
          *f = *as_number(value, key);
        } else if (auto it = sections_.find(section); it != sections_.end() &&
                   std::find(it->second.begin(), it->second.end(), name_key.str()) != it->second.end()) {
          if (auto s = value.value_exact<std::string>()) section_strings_[key] = *s;
          else section_numbers_[key] = *as_number(value, key);
        } else {
          throw InvalidInput(key, "unknown key in " + config_path_);
        }
      }
      if (section == "body") {
        for (const char* required : {"A", "B", "C", "mass", "length"})
          if (!sub->contains(required))
            throw InvalidInput(std::string("body.") + required,
                               "is required in [body] (or give --" + std::string(required) + ")");
      }
    }
    if (!seen_body) {
      // A configuration with no [body]: every body key must come from the options.
      for (const char* required : {"A", "B", "C", "mass", "length"})
        if (!overrides_.at(std::string("body.") + required).option->count())
          throw InvalidInput(std::string("body.") + required,
                             "is required in [body] (or give --" + std::string(required) + ")");
    }
  }
  for (auto& [key, o] : overrides_)
    if (o.option->count()) *field(body, state, key) = o.value;
  validate(body);
  validate(state);
  body_ = body;
  state_ = state;
}

std::optional<double> Inputs::section_number(const std::string& section, const std::string& key) const {
  auto it = section_numbers_.find(section + "." + key);
  if (it == section_numbers_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> Inputs::section_string(const std::string& section,
                                                  const std::string& key) const {
  auto it = section_strings_.find(section + "." + key);
  if (it == section_strings_.end()) return std::nullopt;
  return it->second;
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& fill) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string pattern = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = mkstemp(pattern.data());
  if (fd < 0) throw Failure(fmt::format("--output: cannot create a file in '{}'", dir.string()));
  ::close(fd);
  try {
    fill(pattern);
    fs::rename(pattern, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(pattern, ignored);
    throw;
  }
}

void write_output(const std::string& path, const std::string& content) {
  if (path.empty() || path == "-") {
    std::cout << content << std::flush;
    return;
  }
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << content;
    out.close();
    if (!out) throw Failure(fmt::format("--output: cannot write '{}'", path));
  });
}

namespace {
double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

ProgressBar::ProgressBar(std::string label, double total)
    : label_(std::move(label)), total_(total), terminal_(isatty(STDERR_FILENO) && total > 0), start_(seconds_now()) {}

void ProgressBar::update(double done) {
  if (!terminal_) return;
  const double now = seconds_now();
  if (now - start_ < 1.0 || now - last_draw_ < 0.1) return;
  last_draw_ = now;
  shown_ = true;
  const double fraction = std::clamp(done / total_, 0.0, 1.0);
  const int width = 40, filled = static_cast<int>(width * fraction);
  std::cerr << fmt::format("\r{} [{:<{}}] {:3.0f}%", label_, std::string(filled, '#'), width, 100.0 * fraction)
            << std::flush;
}

ProgressBar::~ProgressBar() {
  if (shown_) std::cerr << "\n";
}


}  // namespace heavytop::cli

#include "common.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <unistd.h>

#include <fmt/format.h>

namespace heavytop::cli {
namespace {

struct KeyHelp {
  const char* key;      // as in the configuration file, "section.name"
  const char* option;   // CLI11 option names
  const char* help;
};

constexpr KeyHelp kKeys[] = {
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

}  // namespace

std::string flag_of(const std::string& field) {
  static const std::map<std::string, std::string> flags = {
      {"rtol", "--rtol"}, {"atol", "--atol"},       {"max_steps", "--max-steps"}, {"step", "--step"},
      {"order", "--order"}, {"horizon", "--horizon"}, {"max_tilt", "--max-tilt"},  {"vary", "--vary"},
      {"t_end", "--t-end"}, {"times", "--t-end"},
  };
  auto it = flags.find(field);
  return it == flags.end() ? field : it->second;
}

Inputs::Inputs(CLI::App& command, std::vector<std::string> formats) : format_(formats.front()) {
  command.add_option("--config", config_path_, "TOML configuration file (SPEC section 4); without it the built-in toy top")
      ->type_name("FILE");
  for (const KeyHelp& spec : kKeys) {
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

void Inputs::resolve() {
  Body body = example_toy_top();
  InitialState state = example_motion();
  if (!config_path_.empty()) {
    config_ = io::read_configuration(config_path_, "--config");
    body = config_.body;
    state = config_.motion;
    // Every required body key from the file or the command line.
    for (const std::string& key : io::required_body_keys())
      if (!config_.given.count(key) && !overrides_.at(key).option->count())
        throw InvalidInput(key, fmt::format("is required in [body] (or give --{})",
                                            key.substr(key.find('.') + 1)));
  }
  for (auto& [key, o] : overrides_)
    if (o.option->count()) *io::config_field(body, state, key) = o.value;
  validate(body);
  validate(state);
  body_ = body;
  state_ = state;
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

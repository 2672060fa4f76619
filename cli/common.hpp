#pragma once
// What every heavytop command shares: the body and motion options, the configuration file,
// output to a file by a temporary name and a rename, and the error conventions of SPEC section 1.

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "heavytop/body.hpp"
#include "heavytop/state.hpp"

namespace heavytop::cli {

/// Internal or numerical failure (exit 1); bad input is heavytop::InvalidInput (exit 2).
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The body and motion as given on the command line and in --config, merged.
class Inputs {
 public:
  /// Adds --config, one option per SPEC key, --format (choices, first is default), --output.
  Inputs(CLI::App& command, std::vector<std::string> formats);

  /// A further section the configuration file may hold for this command, e.g. "simulate",
  /// with its keys. Values reach the command through section_value().
  void allow_section(const std::string& section, std::vector<std::string> keys);

  /// Loads --config (if any), applies the options over it and validates. Throws InvalidInput.
  /// Without --config the base is the built-in example (a toy top), so options alone work.
  void resolve();

  const Body& body() const { return body_; }
  const InitialState& state() const { return state_; }
  const std::string& format() const { return format_; }
  const std::string& output() const { return output_; }
  /// A value of an allowed further section of the configuration file, if given there.
  std::optional<double> section_number(const std::string& section, const std::string& key) const;
  std::optional<std::string> section_string(const std::string& section, const std::string& key) const;

 private:
  struct Override {
    CLI::Option* option = nullptr;
    double value = 0.0;
  };
  std::string config_path_;
  std::string format_;
  std::string output_;
  std::map<std::string, Override> overrides_;  // "body.A", "motion.spin", ...
  std::map<std::string, std::vector<std::string>> sections_;
  std::map<std::string, double> section_numbers_;
  std::map<std::string, std::string> section_strings_;
  Body body_;
  InitialState state_;
};

/// Writes `content` to `path` ("" or "-": stdout) through a temporary file in the same
/// folder and a rename, so a failure never leaves a partial file.
void write_output(const std::string& path, const std::string& content);

/// Writes a file through a temporary name and a rename; `fill` writes the content to the
/// temporary path. Used for outputs produced by other programs (figures).
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& fill);

/// A progress bar on stderr, shown only when stderr is a terminal and the work has taken
/// more than a second; redrawn at most ten times a second.
class ProgressBar {
 public:
  ProgressBar(std::string label, double total);
  void update(double done);
  ~ProgressBar();

 private:
  std::string label_;
  double total_;
  bool terminal_;
  bool shown_ = false;
  double start_;
  double last_draw_ = 0.0;
};


}  // namespace heavytop::cli

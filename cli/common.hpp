#pragma once
// What every heavytop command shares: the body and motion options over --config, the output
// path, the progress bar, and the mapping of the library's field names to this command
// line's flags. Commands translate flags to the library's options, call it, and hand the
// result to heavytop_io; nothing here computes or formats a result.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "heavytop/answer.hpp"
#include "heavytop/body.hpp"
#include "heavytop/io/body_parts.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/state.hpp"

namespace heavytop::cli {

using io::Failure;

/// The command line's spelling of a library field ("rtol" -> "--rtol", "max_tilt" ->
/// "--max-tilt"); configuration keys ("body.A", "simulate.t_end") are kept as they are.
std::string flag_of(const std::string& field);

/// Writes `content` to --output ("" or "-": stdout), as io::write_output with key "--output".
inline void write_output(const std::string& path, const std::string& content) { io::write_output(path, content, "--output"); }

/// Runs `body` and turns what it throws into SPEC section 1's exit status and one line on
/// stderr: 2 for bad input (a parse error, InvalidInput with the field spelled as a flag), 1
/// for a failure (numerical, out of memory, a file), CLI11's for --help.
int run_reporting_errors(CLI::App& app, const std::function<int()>& body);

/// `heavytop derive ...`: runs the program heavytop-derive beside this one with the same
/// arguments (replacing this process when `replace_process`, else as a child whose exit
/// status it returns). Only that program links the computer algebra.
int run_derive(int argc, char** argv, bool replace_process);

/// The number of ranks of the MPI job this process was started in by mpirun or srun (from
/// the launchers' environment variables), or 0 if it was not started by an MPI launcher.
std::size_t mpi_launch_size();

/// `heavytop sweep ...` started by an MPI launcher: runs the program heavytop-mpi beside this
/// one with the same arguments (as run_derive does), which shares the grid among the ranks.
/// Returns -1 if there is no heavytop-mpi and the job has one rank (the serial sweep is then
/// the same), 2 (after saying why) if there is none and the job has more.
int run_sweep_under_mpi(int argc, char** argv, bool replace_process);

/// A CLI11 check for a count option such as --max-steps: a whole number >= 1 that fits a
/// 64-bit signed integer (CLI11 alone wraps "-1" and 2^64 into an unsigned count).
CLI::Validator positive_count();

/// `--NAME-deg` beside a command's `--NAME` in rad: the same angle typed in degrees (SPEC
/// section 9's units people use; rad_from_degrees(), the one conversion). apply() refuses the
/// two together (exit 2, naming both) and writes the degrees given, in rad, to the field; a
/// later message about that field (a rule it breaks) names this option and its degrees.
/// Not copyable: CLI11 holds the address of its value.
class DegreesOption {
 public:
  /// `rad` is the command's option in rad; `field` the name a library message gives its value
  /// ("max_tilt", "tilt", "motion.theta0"); `names` CLI11's ("--max-tilt-deg").
  DegreesOption(CLI::App& command, CLI::Option* rad, std::string field, const std::string& names,
                const std::string& help);
  DegreesOption(const DegreesOption&) = delete;
  DegreesOption& operator=(const DegreesOption&) = delete;
  bool given() const { return option_->count() > 0; }
  CLI::Option* option() const { return option_; }
  /// If given: refuses `rad` given too, else sets `target` to the degrees in rad.
  void apply(double& target) const;

 private:
  CLI::Option* rad_ = nullptr;
  CLI::Option* option_ = nullptr;
  std::string field_;
  double degrees_ = 0.0;
};

/// stability's answer options, one set of flags for `stability` and `explore` (whose page answers
/// as stability does): --horizon, --lifetime-horizon, --max-tilt, --max-tilt-deg, --max-steps
/// into `options` (which must outlive the command).
class AnswerFlags {
 public:
  AnswerFlags(CLI::App& command, AnswerOptions& options);
  /// After parsing: the degrees and the lifetime's horizon into the options, then validate(options).
  void apply() const;

 private:
  AnswerOptions& options_;
  std::optional<double> lifetime_horizon_;
  std::unique_ptr<DegreesOption> max_tilt_deg_;
};

/// Which of the configuration's sections a command uses: the body always; the motion (--spin,
/// --theta0, ...) and the damping (--transverse-damping, ..., --driven) unless cleared. An
/// option of a section the command does not use is refused by Inputs::resolve() (exit 2,
/// naming it), never silently ignored, and is not listed in --help.
struct InputUses {
  bool motion = true;
  bool damping = true;
  /// The table (SPEC section 16): --contact, --table-friction, --friction-law, --slip-speed,
  /// --tip-radius, --rim-radius over [table]. A command without it refuses a contact other than
  /// "pivot" (key table.contact), whatever the file says.
  bool table = false;
};

/// The body and motion as given on the command line and in --config, merged.
class Inputs {
 public:
  /// Adds --config, one option per SPEC key, --format (choices, first is default), --output.
  Inputs(CLI::App& command, std::vector<std::string> formats, InputUses uses = InputUses{});

  /// Loads --config (if any), applies the options over it and validates. Throws InvalidInput.
  /// Without --config the base is the built-in example (a toy top), so options alone work.
  /// A body made of parts (SPEC section 10) is assembled (meshes read); a general body (the
  /// centre of mass off z, products of inertia; SPEC section 11) is refused naming the part or
  /// the key unless `allow_general` (`heavytop body`, which reports it, and `simulate`, which
  /// integrates it in nonlinear and calls refuse_general() for every other model); then
  /// body().general holds its products and offset.
  void resolve(bool allow_general = false);

  /// After resolve(true): throws InvalidInput naming the part (its offset, its products) or the
  /// key of SPEC section 11 if the body is general, `what` (e.g. "simulate --model first-order")
  /// taking the ordinary body only.
  void refuse_general(const std::string& what) const;

  const Body& body() const { return body_; }
  const InitialState& state() const { return state_; }
  /// The table under the body (the pivot unless [table] or --contact says otherwise).
  const Table& table() const { return table_; }
  const std::string& format() const { return format_; }
  const std::string& output() const { return output_; }
  /// --config as given ("" without one: the built-in example is the base).
  const std::string& config_path() const { return config_path_; }
  /// After resolve(): true when the body is the built-in example's (no --config, no body key).
  bool builtin_example() const { return builtin_example_; }
  /// The configuration file's further sections (empty without --config).
  const io::Configuration& configuration() const { return config_; }
  /// The body as mass properties: its parts (or its moments) summed, with the general body's
  /// products and offset (after resolve()).
  const io::AssembledBody& assembly() const { return assembly_; }

 private:
  struct Override {
    CLI::Option* option = nullptr;
    double value = 0.0;
  };
  Table resolve_table(Body& body) const;
  CLI::App* command_ = nullptr;                 // its options' values are checked in resolve()
  std::string config_path_;
  std::string command_name_;
  bool builtin_example_ = false;
  InputUses uses_;
  std::string format_;
  std::string output_;
  std::map<std::string, Override> overrides_;  // "body.A", "motion.spin", ...
  CLI::Option* driven_ = nullptr;              // --driven (motion.driven, a boolean)
  bool driven_value_ = false;
  Override spin_rpm_;                           // --spin-rpm (SPEC section 9)
  std::map<std::string, DegreesOption> degrees_;  // "motion.theta0" -> --theta0-deg, "motion.phi0" -> --phi0-deg
  struct TableOptions {                         // InputUses::table
    CLI::Option* contact = nullptr;
    std::string contact_value;
    CLI::Option* friction_law = nullptr;
    std::string friction_law_value;
    CLI::Option *tip_material = nullptr, *material = nullptr, *air = nullptr;
    std::string tip_material_value, material_value;
    Override friction, slip_speed, tip_radius, rim_radius, rolling_resistance;
  };
  TableOptions table_options_;
  Table table_;
  io::AssembledBody assembly_;
  io::Configuration config_;
  Body body_;
  InitialState state_;
};

/// A command's own option that a configuration section may also set ("simulate.t_end"):
/// the command line wins, then the file, then the default already in `value`.
template <class T>
void apply_setting(const io::Configuration& config, const std::string& key, const CLI::Option* option, T& value) {
  if (option->count()) return;
  if constexpr (std::is_same_v<T, std::string>) {
    if (auto v = config.string(key)) value = *v;
  } else if constexpr (std::is_integral_v<T>) {
    if (auto v = config.integer(key)) value = static_cast<T>(*v);
  } else {
    if (auto v = config.number(key)) value = *v;
  }
}

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

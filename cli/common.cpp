#include "common.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <tuple>
#include <spawn.h>
#include <sys/wait.h>
#include <chrono>
#include <iostream>
#include <unistd.h>

#include <fmt/format.h>

#include "heavytop/io/formats.hpp"
#include "heavytop/units.hpp"

extern char** environ;

namespace heavytop::cli {
namespace fs = std::filesystem;
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
    {"damping.transverse", "--transverse-damping", "N m s, d_t: drag torque -d_t w_perp on the axis's motion (>= 0)"},
    {"damping.axial", "--axial-damping", "N m s, d_a: drag torque -d_a (w.k) k on the spin (>= 0)"},
    {"damping.friction", "--friction", "N m, tau0: dry friction torque -tau0 sign(w.k) k at the tip (>= 0)"},
};

const char* group_of(std::string_view key) {
  return key.starts_with("body.") ? "Body" : key.starts_with("damping.") ? "Damping" : "Motion";
}

}  // namespace

std::string flag_of(const std::string& field) {
  static const std::map<std::string, std::string> flags = {
      {"rtol", "--rtol"}, {"atol", "--atol"},       {"max_steps", "--max-steps"}, {"step", "--step"},
      {"order", "--order"}, {"horizon", "--horizon"}, {"lifetime_horizon", "--lifetime-horizon"}, {"max_tilt", "--max-tilt"},  {"vary", "--vary"},
      {"t_end", "--t-end"}, {"times", "--t-end"}, {"tilt", "--tilt"}, {"model", "--model"},
      {"method", "--method"}, {"integrator", "--integrator"}, {"slice", "--slice"}, {"map", "--map"},
  };
  auto it = flags.find(field);
  return it == flags.end() ? field : it->second;
}

CLI::Validator positive_count() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        long long n = 0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
        if (ec != std::errc() || end != value.data() + value.size() || n < 1)
          return "must be a whole number from 1 to " + std::to_string(std::numeric_limits<long long>::max());
        return "";
      },
      "INT >= 1");
}

namespace {

/// The angles given in degrees in this run, by the field their value went to: a message about
/// the field names the option typed (--max-tilt-deg) and the degrees, not the rad option.
struct DegreesGiven {
  std::string option;
  double degrees;
};
std::map<std::string, DegreesGiven>& degrees_given() {
  static std::map<std::string, DegreesGiven> given;
  return given;
}

}  // namespace

DegreesOption::DegreesOption(CLI::App& command, CLI::Option* rad, std::string field, const std::string& names,
                             const std::string& help)
    : rad_(rad), field_(std::move(field)) {
  option_ = command.add_option(names, degrees_, help)
                ->type_name("NUM")
                ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                ->group(rad->get_group());
}

AnswerFlags::AnswerFlags(CLI::App& command, AnswerOptions& options) : options_(options) {
  command
      .add_option("--horizon", options.horizon,
                  "s, how long the nonlinear body is followed when the Lyapunov verdict does not prove it "
                  "stable (the answer's fall, the wander for A != B); a damped body is followed over the "
                  "lifetime's horizon (--lifetime-horizon)")
      ->default_str("100");
  command.add_option("--lifetime-horizon", lifetime_horizon_,
                     "s, a damped body's run (default: lifetime's, 10 times the time to the critical spin)");
  auto* max_tilt = command
                       .add_option("--max-tilt", options.max_tilt,
                                   "rad, the tilt from the upward vertical past which the top has fallen")
                       ->default_str("1");
  max_tilt_deg_ = std::make_unique<DegreesOption>(command, max_tilt, "max_tilt", "--max-tilt-deg",
                                                  "degrees, the same (instead of --max-tilt)");
  command
      .add_option("--max-steps", options.integrator.max_steps,
                  "nonlinear: the most integration steps of the answer's run (the wander's at most 2000000); a run "
                  "that needs more answers the time it reached")
      ->check(positive_count())
      ->default_str(fmt::format("{}", options.integrator.max_steps));
}

void AnswerFlags::apply() const {
  max_tilt_deg_->apply(options_.max_tilt);
  options_.damped_horizon = lifetime_horizon_;
  validate(options_);  // before the body's analyses: a bad option costs nothing
}

void DegreesOption::apply(double& target) const {
  if (!given()) return;
  if (rad_->count())
    throw InvalidInput(option_->get_name(), fmt::format("give {} or {}, not both", rad_->get_name(), option_->get_name()));
  target = rad_from_degrees(degrees_);
  degrees_given()[field_] = {option_->get_name(), degrees_};
}

/// The realizability warning of the body resolve() made (SPEC section 1), empty for a real
/// body: printed by run_reporting_errors() when the command succeeds, so that bad input is
/// still refused in one line.
static std::string& realizability_warning() {
  static std::string warning;
  return warning;
}

/// io::implausible_size_warning() of the body resolve() made (a unit slip, mm typed as m),
/// printed as the realizability warning is.
static std::string& size_warning() {
  static std::string warning;
  return warning;
}

/// Throws InvalidInput naming the first option of `command` given an empty value (CLI11 makes
/// `--length ""` a 0 and `--config ""` no file at all).
static void refuse_empty_values(const CLI::App& command) {
  for (const CLI::Option* option : command.get_options()) {
    if (option->get_type_size() == 0) continue;  // a flag
    for (const std::string& value : option->results())
      if (value.empty()) throw InvalidInput(option->get_name(), "must not be empty");
  }
}

Inputs::Inputs(CLI::App& command, std::vector<std::string> formats, InputUses uses)
    : command_(&command), command_name_(command.get_name()), uses_(uses), format_(formats.front()) {
  command.add_option("--config", config_path_,
                     "TOML configuration file (docs/contract.md, section 4); without it the built-in toy top, "
                     "whose keys the options below override one by one")
      ->type_name("FILE");
  const auto used = [&](std::string_view group) {
    return group == "Motion" ? uses_.motion : group == "Damping" ? uses_.damping : true;
  };
  // Defaults as the help shows them: the toy top's without --config; the motion's are 0 once
  // the body is described (resolve()).
  Body example = example_toy_top();
  InitialState motion = example_motion();
  for (const KeyHelp& spec : kKeys) {
    Override& o = overrides_[spec.key];
    const double example_value = *io::config_field(example, motion, spec.key);
    const std::string group = group_of(spec.key);
    o.option = command.add_option(spec.option, o.value, spec.help)
                   ->type_name("NUM")
                   ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                   ->default_str(group == "Body" ? fmt::format("{:g} (toy top)", example_value)
                                 : group == "Motion" ? fmt::format("0; toy top alone: {:g}", example_value)
                                                     : std::string("0"));
    o.option->group(used(group) ? group : "");  // "": hidden, refused by resolve()
  }
  driven_ = command.add_option("--driven", driven_value_,
                               "true: a motor holds the spin w.k at its value at t = 0 (a gyroscope)")
                ->type_name("BOOL")
                ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                ->default_str("false")
                ->group(used("Damping") ? "Damping" : "");
  spin_rpm_.option = command.add_option("--spin-rpm,--spin_rpm", spin_rpm_.value, "rpm, spin w0 (instead of --spin)")
                         ->type_name("NUM")
                         ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                         ->default_str(fmt::format("0; toy top alone: {:.6g}", rpm_from_rad_per_s(motion.spin)))
                         ->group(used("Motion") ? "Motion" : "");
  // The initial angles in degrees too (SPEC section 9), beside --theta0 and --phi0.
  for (const auto& [key, names, help] :
       {std::tuple{"motion.theta0", "--theta0-deg,--theta0_deg", "degrees, initial theta (instead of --theta0)"},
        std::tuple{"motion.phi0", "--phi0-deg,--phi0_deg", "degrees, initial phi (instead of --phi0)"}}) {
    const DegreesOption& d = degrees_.try_emplace(key, command, overrides_.at(key).option, key, names, help).first->second;
    d.option()->default_str(
        fmt::format("0; toy top alone: {:.6g}", degrees_from_rad(*io::config_field(example, motion, key))));
  }
  if (uses_.table) {
    TableOptions& t = table_options_;
    const auto number = [&](Override& o, const char* name, const char* help, const char* group) {
      o.option = command.add_option(name, o.value, help)
                     ->type_name("NUM")
                     ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                     ->group(group);
    };
    number(t.tip_radius, "--tip-radius", "m, radius of the tip's sphere about O (>= 0; 0: a sharp point)", "Body");
    number(t.rim_radius, "--rim-radius", "m, or of the rim, a ring about the axis through O (>= 0; a coin)", "Body");
    const auto named = [&](std::string& value, const char* name, const char* help, const char* shown) {
      return command.add_option(name, value, help)
          ->type_name("NAME")
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
          ->default_str(shown)
          ->group("Table");
    };
    t.contact = named(t.contact_value, "--contact",
                      "pivot (O fixed), or the body on a table: frictionless, rolling or sliding", "pivot");
    number(t.friction, "--table-friction", "mu, the table's friction coefficient (sliding; >= 0)", "Table");
    t.friction_law = named(t.friction_law_value, "--friction-law",
                           "sliding: viscous (F = -mu N v / slip_speed), coulomb, or contensou (Coulomb over the "
                           "tip's Hertz patch, with its drilling torque)", "viscous");
    number(t.slip_speed, "--slip-speed", "m/s, the viscous law's reference speed (> 0, default 1)", "Table");
    const std::string materials = material_names();
    t.tip_material = named(t.tip_material_value, "--tip-material",
                           ("contensou: the tip's material, " + materials).c_str(), "");
    t.material = named(t.material_value, "--table-material", ("contensou: the table's material, " + materials).c_str(), "");
    number(t.rolling_resistance, "--rolling-resistance", "m, sliding: the rolling resistance's length (>= 0, default 0)",
           "Table");
    t.air = command.add_flag("--air")
                ->description("on a table: the still air's torque against the spin (20 C, 1 atm)")
                ->group("Table");
  }
  command.add_option("--format", format_, "output format")
      ->check(CLI::IsMember(formats))
      ->default_str(formats.front());
  command.add_option("--output", output_, "write to FILE instead of stdout")->type_name("FILE");
}

namespace {

/// The body keys a person gives to describe a body (gravity alone changes the planet, not the top).
constexpr const char* kDescribingKeys[] = {"body.A", "body.B", "body.C", "body.mass", "body.length"};

}  // namespace

void Inputs::resolve(bool allow_general) {
  // An option of a section this command does not use is refused, never ignored.
  const auto refuse_unused = [&](const CLI::Option* option, const char* section) {
    if (option->count())
      throw InvalidInput("--" + option->get_single_name(),
                         fmt::format("`heavytop {}` does not use the {} (it takes the body only)",
                                                         command_name_, section));
  };
  for (const KeyHelp& spec : kKeys) {
    const std::string_view group = group_of(spec.key);
    if ((group == "Motion" && !uses_.motion) || (group == "Damping" && !uses_.damping))
      refuse_unused(overrides_.at(spec.key).option, group == "Motion" ? "motion" : "damping");
  }
  if (!uses_.motion) refuse_unused(spin_rpm_.option, "motion");
  if (!uses_.motion)
    for (const auto& [key, d] : degrees_) refuse_unused(d.option(), "motion");
  if (!uses_.damping) refuse_unused(driven_, "damping");
  refuse_empty_values(*command_);
  Body body = example_toy_top();
  // One rule for the motion, the same in Python: its keys default to 0 (SPEC section 4) as soon
  // as the body is described (a --config, or any of --A --B --C --mass --length); only the
  // built-in example as a whole brings its own motion.
  bool described = !config_path_.empty();
  std::vector<std::string> from_example;  // body keys taken from the built-in toy top
  for (const char* key : kDescribingKeys) {
    if (overrides_.at(key).option->count()) described = true;
    else from_example.push_back(key);
  }
  InitialState state = described ? InitialState{} : example_motion();
  builtin_example_ = !described;
  if (config_path_.empty() && from_example.size() == std::size(kDescribingKeys)) from_example.clear();
  if (!config_path_.empty()) {
    from_example.clear();
    config_ = io::read_configuration(config_path_, "--config");
    body = config_.body;
    state = config_.motion;
    // Every required body key from the file or the command line (the parts give them all).
    if (config_.parts.empty())
      for (const std::string& key : io::required_body_keys())
        if (!config_.given.count(key) && !overrides_.at(key).option->count())
          throw InvalidInput(key, fmt::format("is required in [body] (or give --{}), unless [[body.part]] describe the body",
                                              key.substr(key.find('.') + 1)));
  }
  if (spin_rpm_.option->count()) {
    if (overrides_.at("motion.spin").option->count())
      throw InvalidInput("--spin-rpm", "give --spin or --spin-rpm, not both");
    state.spin = rad_per_s_from_rpm(spin_rpm_.value);
  }
  for (auto& [key, o] : overrides_) {
    if (!o.option->count()) continue;
    if (!config_.parts.empty() && key.starts_with("body.") && key != "body.gravity")
      throw InvalidInput(o.option->get_name(), "the body is made of parts in --config: A, B, C, mass and length "
                                               "come from them");
    *io::config_field(body, state, key) = o.value;
  }
  for (const auto& [key, d] : degrees_) d.apply(*io::config_field(body, state, key));
  if (driven_->count()) body.damping.driven = driven_value_;
  Table table = resolve_table(body);
  const Damping damping = body.damping;  // the parts below make the body's mass properties only
  const double tip_radius = body.tip_radius, rim_radius = body.rim_radius;  // the shape, not the mass
  if (!config_.parts.empty()) {
    assembly_ = io::assemble_parts(config_.parts);
    if (!allow_general) {
      const double gravity = body.gravity;
      body = body_of(assembly_.assembly, gravity, assembly_.names);
    } else {  // `body` reports it, `simulate --model nonlinear` integrates it: the tensor as it is
      body = io::as_given(assembly_.assembly, body);
    }
  } else {
    try {
      validate(body);
    } catch (const InvalidInput& e) {  // a partial body on the command line: say what it was combined with
      if (from_example.empty()) throw;
      std::string keys;
      for (const std::string& key : from_example)
        keys += fmt::format("{}{} = {:g}", keys.empty() ? "" : ", ", key.substr(5), *io::config_field(body, state, key));
      throw InvalidInput(e.key(), fmt::format("{} ({} came from the built-in toy top: give them too, or use --config)",
                                              e.rule(), keys));
    }
    assembly_ = io::assemble_moments(body, config_.general);
    const auto given = [&](const char* key) {
      const auto it = config_.general.find(key);
      return it == config_.general.end() ? 0.0 : it->second;
    };
    body.general = {given("body.Ixy"), given("body.Ixz"), given("body.Iyz"), given("body.offset_x"),
                    given("body.offset_y")};
    if (!allow_general) io::refuse_general_keys(body);
  }
  body.damping = damping;
  body.tip_radius = tip_radius;
  body.rim_radius = rim_radius;
  if (table.on_table()) body.touch_tilt = io::touch_tilt(config_.parts, body);
  validate(body);
  validate(state);
  if (table.on_table()) validate(table, body);
  if (!is_realizable(body))  // SPEC section 1: said once when the command has done its work
    realizability_warning() = (body.general.is_zero()
                      ? fmt::format("heavytop: warning: this body cannot exist as given: A + B - C = {:.6g} kg m^2 is "
                                    "less than 2 m R^2 = {} kg m^2 (its central moments break the triangle "
                                    "inequality); going on\n",
                                    body.A + body.B - body.C,
                                    std::isfinite(2.0 * body.mass * body.length * body.length)
                                        ? fmt::format("{:.6g}", 2.0 * body.mass * body.length * body.length)
                                        : std::string("beyond a double"))
                      : std::string("heavytop: warning: this body cannot exist as given: its principal moments of "
                                    "inertia about the centre of mass break the triangle inequality; going on\n"));
  size_warning() = io::implausible_size_warning(body);  // said with the realizability warning
  body_ = body;
  state_ = state;
  table_ = table;
}

Table Inputs::resolve_table(Body& body) const {
  // [table] from the file, then the command line's table options over it, checked as one.
  io::Configuration merged = config_;
  const TableOptions& t = table_options_;
  if (uses_.table) {
    if (t.contact->count()) merged.settings["table.contact"] = t.contact_value;
    if (t.friction_law->count()) merged.settings["table.friction_law"] = t.friction_law_value;
    if (t.friction.option->count()) merged.settings["table.friction"] = t.friction.value;
    if (t.slip_speed.option->count()) merged.settings["table.slip_speed"] = t.slip_speed.value;
    if (t.tip_material->count()) merged.settings["table.tip_material"] = t.tip_material_value;
    if (t.material->count()) merged.settings["table.material"] = t.material_value;
    if (t.rolling_resistance.option->count()) merged.settings["table.rolling_resistance"] = t.rolling_resistance.value;
    if (t.air->count()) merged.settings["table.air"] = true;
    if (t.tip_radius.option->count()) body.tip_radius = t.tip_radius.value;
    if (t.rim_radius.option->count()) body.rim_radius = t.rim_radius.value;
  }
  const Table table = io::table_of(merged);
  if (table.on_table() && !uses_.table)
    throw InvalidInput("table.contact", fmt::format("`heavytop {}` is for a body on a pivot; on a table (contact = "
                                                    "\"{}\") use `heavytop simulate` or `heavytop stability`",
                                                    command_name_, name(table.contact)));
  return table;
}

void Inputs::refuse_general(const std::string& what) const {
  if (!is_general(body_)) return;
  // A body of parts: body_of() names the part and says by how much it is general.
  if (!config_.parts.empty()) body_of(assembly_.assembly, body_.gravity, assembly_.names);
  io::refuse_general_in(body_, what);
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

int run_reporting_errors(CLI::App& app, const std::function<int()>& body) {
  try {
    const int status = body();
    std::cerr << realizability_warning() << size_warning();
    return status;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {  // `heavytop --version`: "heavytop VERSION" on stdout, exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // every message one line, whatever text the person gave
    std::cerr << fmt::format("heavytop: error: {}\n", printable(e.what()));
    return 2;
  } catch (const InvalidInput& e) {
    if (const auto it = degrees_given().find(e.key()); it != degrees_given().end()) {  // typed in degrees
      const DegreesGiven& d = it->second;
      std::cerr << fmt::format("heavytop: error: {}: {} (here {:g} degrees, {:.6g} rad)\n", d.option, e.rule(), d.degrees,
                               rad_from_degrees(d.degrees));
      return 2;
    }
    std::cerr << fmt::format("heavytop: error: {}: {}\n", flag_of(e.key()), e.rule());
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "heavytop: error: out of memory (fewer --samples, or --format csv, which streams)\n";
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {  // its what() is the library's wording
    std::cerr << fmt::format("heavytop: error: cannot use '{}': {}\n", printable(e.path1().string()), e.code().message());
    return 1;
  } catch (const std::exception& e) {
    std::cerr << fmt::format("heavytop: error: {}\n", printable(e.what()));
    return 1;
  }
}

namespace {

/// The path of the program `name` in this one's folder.
std::string program_beside(const char* argv0, const char* name) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ((ec ? fs::path(argv0) : self).parent_path() / name).string();
}

int run_beside(const char* program_name, const char* missing, int argc, char** argv, bool replace_process) {
  const std::string program = program_beside(argv[0], program_name);
  const std::string_view command = argc > 1 ? argv[1] : "";
  if (::access(program.c_str(), X_OK) != 0) {
    std::cerr << fmt::format("heavytop: error: {}: the program {} is not beside heavytop ({})\n", command,
                             program_name, missing);
    return 1;
  }
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  if (replace_process) {
    ::execv(program.c_str(), args.data());  // returns only on failure
  } else {
    pid_t pid = 0;
    if (::posix_spawn(&pid, program.c_str(), nullptr, nullptr, args.data(), environ) == 0) {
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    }
  }
  std::cerr << fmt::format("heavytop: error: {}: cannot run '{}': {}\n", command, program, std::strerror(errno));
  return 1;
}

}  // namespace

int run_derive(int argc, char** argv, bool replace_process) {
  return run_beside("heavytop-derive", "built without HEAVYTOP_BUILD_SYMBOLIC?", argc, argv, replace_process);
}

std::size_t mpi_launch_size() {
  // OpenMPI's mpirun, then the PMI variables of Slurm's srun and of MPICH's launchers.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE", "SLURM_NTASKS_MPI"})
    if (const char* value = std::getenv(name)) return std::max<std::size_t>(1, std::strtoull(value, nullptr, 10));
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

int run_sweep_under_mpi(int argc, char** argv, bool replace_process) {
  const bool built = ::access(program_beside(argv[0], "heavytop-mpi").c_str(), X_OK) == 0;
  if (!built && mpi_launch_size() > 1) {
    std::cerr << fmt::format("heavytop: error: sweep: started as one of {} MPI ranks, but this heavytop was built "
                             "without MPI (Debian's libopenmpi-dev): run it without mpirun, or rebuild\n",
                             mpi_launch_size());
    return 2;
  }
  if (!built) return -1;  // one rank: the serial sweep is the same
  return run_beside("heavytop-mpi", "built without MPI", argc, argv, replace_process);
}

}  // namespace heavytop::cli

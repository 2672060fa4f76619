#pragma once
/// \file
/// The configuration file (TOML, SPEC section 4): [body], [motion], and the sections that
/// commands add for their own settings (every command accepts every one of them, so one file
/// serves all).

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/mass_properties.hpp"
#include "heavytop/state.hpp"
#include "heavytop/table.hpp"
#include "heavytop/uncertainty.hpp"

namespace heavytop::io {

/// The keys of [body] and [motion], as "section.name" (SPEC sections 1, 2, 4), in SPEC order.
const std::vector<std::string>& body_keys();
const std::vector<std::string>& motion_keys();
/// The numeric keys of [damping] (SPEC section 6): "damping.transverse", "damping.axial",
/// "damping.friction"; they are Body::damping's fields.
const std::vector<std::string>& damping_keys();
/// SPEC section 6's boolean key: a motor holds the spin (Body::damping.driven).
inline constexpr std::string_view kDrivenKey = "motion.driven";
/// The [body] keys a configuration must give (all but gravity).
const std::vector<std::string>& required_body_keys();

/// The field of `body` or `state` a "body.*" / "motion.*" / "damping.*" key names (SI
/// units); nullptr for any other key (and for the boolean motion.driven).
double* config_field(Body& body, InitialState& state, std::string_view key);

/// The further sections a configuration may hold, with their keys: {"simulate": {"model", ...}}.
const std::map<std::string, std::vector<std::string>>& command_sections();

/// SPEC section 11's keys of [body]: the general body's offsets and products of inertia
/// ("body.offset_x", "body.offset_y", "body.Ixy", "body.Ixz", "body.Iyz"; m, kg m^2).
const std::vector<std::string>& general_body_keys();

/// One [[body.part]] of SPEC section 10 as the file gives it (the core checks its values when
/// the parts are assembled: io/body_parts.hpp).
struct PartSpec {
  std::string label;       ///< its shape, or for a mesh its file as written: "cone", "top.stl"
  bool mesh = false;       ///< shape = "mesh"
  SolidPart solid;         ///< the solid's shape and sizes; density or mass for a mesh too
  std::string file;        ///< mesh: the path, a relative one resolved against the configuration's folder
  double scale = 1.0;      ///< m per unit of the part's lengths (units "m": 1, "mm": 1e-3): a mesh's
                           ///< coordinates; a solid's sizes are already in m (parse_configuration())
  /// "body.part[i]" followed by the label in parentheses, as messages name the part.
  std::string name(std::size_t index) const;
};

/// A value of a further section, as TOML typed it.
using SettingValue = std::variant<std::int64_t, double, bool, std::string>;

/// A configuration file, read and checked against SPEC section 4.
struct Configuration {
  std::string path;                 ///< where it was read from
  Body body;                        ///< the keys given; the others as Body{} (gravity 9.81)
  InitialState motion;              ///< the keys given; the others 0
  std::set<std::string> given;      ///< the body and motion keys the file gives ("body.A", ...)
  bool has_body = false;            ///< the file has a [body] section
  std::vector<PartSpec> parts;      ///< [[body.part]] (SPEC section 10), in order; then body.A... are not given
  std::map<std::string, double> general;  ///< SPEC section 11's keys given ("body.Ixy" -> kg m^2)
  std::map<std::string, SettingValue> settings;  ///< further sections' values, "simulate.t_end"

  /// A further section's number (an integer is read as a double); nullopt if absent.
  /// Throws InvalidInput(key, "must be a number") for any other type.
  std::optional<double> number(const std::string& key) const;
  /// A further section's whole number; a float with a fraction or another type is refused.
  std::optional<std::int64_t> integer(const std::string& key) const;
  /// A further section's string; another type is refused.
  std::optional<std::string> string(const std::string& key) const;
};

/// Parses `text`, a configuration's content; `source` names it in messages (a path). Throws
/// InvalidInput naming `path_key` (e.g. "--config") when it is not TOML, and the offending
/// "section.key" for an unknown section or key or a value of the wrong type; nothing else for
/// any bytes (fuzz/fuzz_config.cpp). Does not check the body's rules (validate() does, once
/// the command line's values are applied). `motion.spin_rpm` is stored as motion.spin in rad/s
/// (given as "motion.spin" too), `motion.theta0_deg` and `motion.phi0_deg` as motion.theta0 and
/// motion.phi0 in rad; giving both of a pair is refused. A solid part's `units = "mm"` is
/// applied here (its radius, inner_radius, height and z0 stored in m); its density stays in
/// kg/m^3 and its mass in kg. No mesh file is read here.
Configuration parse_configuration(std::string_view text, const std::string& source, const std::string& path_key);

/// The largest configuration file read_configuration() reads (bytes): more is refused, so a
/// device such as /dev/zero given as a file is bad input, not an endless read.
inline constexpr std::size_t kMaxConfigurationBytes = 1 << 20;

/// The [table] section (SPEC section 16): the pivot when absent. Throws InvalidInput naming the
/// key for an unknown contact or law, a value out of range (Table::IsValid), the other keys
/// with contact = "pivot", and friction or friction_law with a contact other than "sliding".
Table table_of(const Configuration& config);

/// Text from the user as it goes into a one-line message (body.hpp's, for io's callers).
using heavytop::printable;

/// The content of the file `path`, at most `max_bytes` (more is refused, so a device such as
/// /dev/zero is bad input, not an endless read). Throws InvalidInput naming `path_key` when it
/// does not exist, is a folder, cannot be read or is too large ("not <what>").
std::string read_text_file(const std::string& path, const std::string& path_key, std::size_t max_bytes,
                           std::string_view what);

/// Reads `path` (at most kMaxConfigurationBytes) and parses it as parse_configuration() does.
/// Throws InvalidInput naming `path_key` also when the file cannot be read or is too large.
Configuration read_configuration(const std::string& path, const std::string& path_key);

/// Applies one key of [uncertainty] (SPEC section 17; `name` without the section, "A") to
/// `options`: a body or motion key's standard uncertainty as a number >= 0 in SI units, or as a
/// string, a number or a percentage ("2%": relative); `spin_rpm` an absolute one in rpm (stored
/// as spin's, rad/s); `distribution` "gaussian" | "uniform"; `draws` and `seed` whole numbers
/// >= 0 (a string holding one too: `--uncertain draws=1000`). Throws InvalidInput naming
/// "uncertainty.<name>" for anything else.
void set_uncertainty(UncertaintyOptions& options, const std::string& name, const SettingValue& value);

/// The [uncertainty] section (SPEC section 17): no uncertain input when absent. Throws
/// InvalidInput as set_uncertainty() does, and for spin and spin_rpm both given.
UncertaintyOptions uncertainty_of(const Configuration& config);

}  // namespace heavytop::io

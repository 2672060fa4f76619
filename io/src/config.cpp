#include "heavytop/io/config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "heavytop/units.hpp"

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
    {"body.tip_radius", &Body::tip_radius},
    {"body.rim_radius", &Body::rim_radius},
    {"motion.spin", nullptr, &InitialState::spin},
    {"motion.theta0", nullptr, &InitialState::theta0},
    {"motion.phi0", nullptr, &InitialState::phi0},
    {"motion.theta_rate0", nullptr, &InitialState::theta_rate0},
    {"motion.phi_rate0", nullptr, &InitialState::phi_rate0},
    {"damping.transverse", nullptr, nullptr, &Damping::transverse},
    {"damping.axial", nullptr, nullptr, &Damping::axial},
    {"damping.friction", nullptr, nullptr, &Damping::friction},
};

// [motion] keys in the units people use (SPEC section 9), each beside its SI key: read into
// the SI key's field, one of the two at most.
struct UnitAlias {
  const char* key;     // "motion.spin_rpm"
  const char* si_key;  // "motion.spin"
  double (*to_si)(double);
};
constexpr UnitAlias kUnitAliases[] = {
    {"motion.spin_rpm", "motion.spin", [](double rpm) { return rad_per_s_from_rpm(rpm); }},
    {"motion.theta0_deg", "motion.theta0", [](double degrees) { return rad_from_degrees(degrees); }},
    {"motion.phi0_deg", "motion.phi0", [](double degrees) { return rad_from_degrees(degrees); }},
};

const UnitAlias* unit_alias(std::string_view key) {
  for (const UnitAlias& alias : kUnitAliases)
    if (key == alias.key) return &alias;
  return nullptr;
}

std::vector<std::string> keys_starting(std::string_view prefix) {
  std::vector<std::string> keys;
  for (const Field& f : kFields)
    if (std::string_view(f.key).starts_with(prefix)) keys.emplace_back(f.key);
  return keys;
}

}  // namespace

namespace {

double number_of(const toml::node& node, const std::string& key) {
  if (auto v = node.value_exact<double>()) return *v;
  if (auto v = node.value_exact<int64_t>()) return static_cast<double>(*v);
  throw InvalidInput(key, "must be a number");
}

// The keys of a [[body.part]], and the shapes each applies to (SPEC section 10).
struct PartKey {
  const char* name;
  const char* shapes;  // the shapes it applies to, as they are named, or "" for every shape
};
constexpr PartKey kPartKeys[] = {
    {"shape", ""},           {"radius", "cylinder tube cone sphere"}, {"inner_radius", "tube"},
    {"height", "cylinder tube cone"}, {"z0", "cylinder tube cone sphere"}, {"apex", "cone"},
    {"density", ""},         {"mass", ""},          {"file", "mesh"},  {"units", ""},
};

std::string string_of(const toml::node& node, const std::string& key) {
  if (auto v = node.value_exact<std::string>()) return *v;
  throw InvalidInput(key, "must be a string");
}

PartSpec parse_part(const toml::table& table, std::size_t index, const std::string& source) {
  const std::string base = fmt::format("body.part[{}]", index);
  const auto* shape_node = table.get("shape");
  if (!shape_node) throw InvalidInput(base + ".shape", "is required: cylinder, tube, cone, sphere or mesh");
  PartSpec part;
  const std::string shape = string_of(*shape_node, base + ".shape");
  part.mesh = shape == "mesh";
  if (!part.mesh) {
    const auto solid = part_shape_from_name(shape);
    if (!solid)
      throw InvalidInput(base + ".shape", fmt::format("unknown shape '{}': must be cylinder, tube, cone, sphere or mesh",
                                                      printable(shape)));
    part.solid.shape = *solid;
  }
  part.label = printable(shape);
  for (const auto& [name_key, value] : table) {
    const std::string name(name_key.str());
    const std::string key = base + "." + printable(name);
    const PartKey* known = nullptr;
    for (const PartKey& k : kPartKeys)
      if (name == k.name) known = &k;
    if (!known) throw InvalidInput(key, "unknown key in " + printable(source));
    const std::string_view shapes(known->shapes);
    bool applies = shapes.empty();
    for (std::size_t at = 0; !applies && at < shapes.size();) {
      const std::size_t end = std::min(shapes.find(' ', at), shapes.size());
      applies = shapes.substr(at, end - at) == shape;
      at = end + 1;
    }
    if (!applies) throw InvalidInput(key, fmt::format("does not apply to shape '{}' (only to: {})", part.label, shapes));
    if (name == "shape") continue;
    if (name == "apex") {
      const std::string apex = string_of(value, key);
      if (apex != "down" && apex != "up") throw InvalidInput(key, "must be \"down\" or \"up\"");
      part.solid.apex_up = apex == "up";
    } else if (name == "file") {
      part.file = string_of(value, key);
      if (part.file.empty()) throw InvalidInput(key, "must name a mesh file (STL, OBJ or PLY)");
    } else if (name == "units") {
      const std::string units = string_of(value, key);
      if (units != "m" && units != "mm") throw InvalidInput(key, "must be \"m\" or \"mm\"");
      part.scale = units == "mm" ? 1e-3 : 1.0;
    } else {
      const double x = number_of(value, key);
      if (name == "radius") part.solid.radius = x;
      else if (name == "inner_radius") part.solid.inner_radius = x;
      else if (name == "height") part.solid.height = x;
      else if (name == "z0") part.solid.z0 = x;
      else if (name == "density") part.solid.density = x;
      else if (name == "mass") part.solid.mass = x;
    }
  }
  if (!part.mesh) {  // the lengths in m from here on (density stays kg/m^3: units names the lengths only)
    for (double* length : {&part.solid.radius, &part.solid.inner_radius, &part.solid.height, &part.solid.z0})
      *length *= part.scale;
  }
  if (part.mesh) {
    if (part.file.empty()) throw InvalidInput(base + ".file", "is required for shape 'mesh' (STL, OBJ or PLY)");
    part.label = printable(part.file);
    // Relative to the configuration's folder, so a configuration and its mesh move together.
    const std::filesystem::path file(part.file);
    if (file.is_relative()) part.file = (std::filesystem::path(source).parent_path() / file).string();
  }
  return part;
}

}  // namespace

std::string PartSpec::name(std::size_t index) const { return fmt::format("body.part[{}] ({})", index, label); }

const std::vector<std::string>& general_body_keys() {
  static const std::vector<std::string> keys = {"body.offset_x", "body.offset_y", "body.Ixy", "body.Ixz", "body.Iyz"};
  return keys;
}

const std::vector<std::string>& body_keys() {
  static const auto keys = keys_starting("body.");
  return keys;
}
const std::vector<std::string>& motion_keys() {
  static const auto keys = keys_starting("motion.");
  return keys;
}
const std::vector<std::string>& damping_keys() {
  static const auto keys = keys_starting("damping.");
  return keys;
}
const std::vector<std::string>& required_body_keys() {
  static const std::vector<std::string> keys = {"body.A", "body.B", "body.C", "body.mass", "body.length"};
  return keys;
}

double* config_field(Body& body, InitialState& state, std::string_view key) {
  for (const Field& f : kFields)
    if (key == f.key)
      return f.body ? &(body.*f.body) : f.state ? &(state.*f.state) : &(body.damping.*f.damping);
  return nullptr;
}

const std::map<std::string, std::vector<std::string>>& command_sections() {
  static const std::map<std::string, std::vector<std::string>> sections = {
      {"simulate", {"model", "t_end", "samples", "method", "rtol", "atol", "integrator", "step", "order"}},
      {"table", {"contact", "friction", "friction_law", "slip_speed", "tip_material", "tip_modulus", "tip_poisson",
                 "material", "modulus", "poisson", "rolling_resistance", "air", "air_density", "air_viscosity"}},
      // SPEC section 17: a standard uncertainty per body or motion key, and the draws' settings.
      {"uncertainty", {"A", "B", "C", "mass", "gravity", "length", "spin", "spin_rpm", "theta0", "phi0",
                       "theta_rate0", "phi_rate0", "distribution", "draws", "seed"}},
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
      if (key == "body.part") {  // [[body.part]]: an array of tables (SPEC section 10)
        const auto* parts = value.as_array();
        if (!parts || !parts->is_array_of_tables())
          throw InvalidInput(key, "must be an array of tables: [[body.part]]");
        for (const auto& part : *parts) config.parts.push_back(parse_part(*part.as_table(), config.parts.size(), source));
        continue;
      }
      if (const UnitAlias* alias = unit_alias(key)) {  // SPEC section 9: stored in SI (rad/s, rad)
        *config_field(config.body, config.motion, alias->si_key) = alias->to_si(number_of(value, key));
        config.given.insert(alias->key);
        continue;
      }
      const auto& general = general_body_keys();
      if (std::find(general.begin(), general.end(), key) != general.end()) {
        config.general[key] = number_of(value, key);
        continue;
      }
      if (double* field = config_field(config.body, config.motion, key)) {
        *field = number_of(value, key);
        config.given.insert(key);
        continue;
      }
      if (key == kDrivenKey) {
        const auto driven = value.value_exact<bool>();
        if (!driven) throw InvalidInput(key, "must be true or false");
        config.body.damping.driven = *driven;
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
  for (const UnitAlias& alias : kUnitAliases) {
    if (!config.given.count(alias.key)) continue;
    const std::string_view si_name = std::string_view(alias.si_key).substr(7), name = std::string_view(alias.key).substr(7);
    if (config.given.count(alias.si_key))
      throw InvalidInput(alias.key, fmt::format("give {} or {}, not both", si_name, name));
    config.given.erase(alias.key);
    config.given.insert(alias.si_key);
  }
  if (!config.parts.empty()) {
    for (const std::string& key : required_body_keys())
      if (config.given.count(key))
        throw InvalidInput(key, "cannot be given with [[body.part]]: the parts make the body (give one or the other)");
    if (!config.general.empty())
      throw InvalidInput(config.general.begin()->first,
                         "cannot be given with [[body.part]]: the parts make the body (give one or the other)");
  }
  return config;
}

namespace {

// A material of the contact: by name from the common ones ("steel"), or by its modulus (Pa)
// and Poisson's ratio; nullopt when none of the three keys is given.
std::optional<Material> material_of(const Configuration& config, const std::string& named, const std::string& modulus,
                                    const std::string& poisson) {
  const auto name = config.string(named);
  const auto E = config.number(modulus);
  const auto nu = config.number(poisson);
  if (name && (E || nu))
    throw InvalidInput(E ? modulus : poisson, fmt::format("give {} or {} and {}, not both", named, modulus, poisson));
  if (name) {
    const auto known = material_from_name(*name);
    if (!known)
      throw InvalidInput(named, fmt::format("unknown material \"{}\": must be one of {} (or give {} and {})",
                                            printable(*name), material_names(), modulus, poisson));
    return known;
  }
  if (!E && !nu) return std::nullopt;
  if (!E || !nu) throw InvalidInput(E ? poisson : modulus, fmt::format("is needed with {}", E ? modulus : poisson));
  return Material{*E, *nu};
}

}  // namespace

Table table_of(const Configuration& config) {
  Table table;
  if (const auto contact = config.string("table.contact")) {
    const auto known = contact_from_name(*contact);
    if (!known)
      throw InvalidInput("table.contact", fmt::format("unknown contact \"{}\": must be \"pivot\", \"frictionless\", "
                                                      "\"rolling\" or \"sliding\"", printable(*contact)));
    table.contact = *known;
  }
  if (!table.on_table())
    for (const auto& [key, value] : config.settings)
      if (key.rfind("table.", 0) == 0 && key != "table.contact")
        throw InvalidInput(key, "applies to a body on a table only: set table.contact to \"frictionless\", "
                                "\"rolling\" or \"sliding\" (the pivot holds O fixed)");
  if (table.contact != Contact::Sliding)
    for (const char* key : {"table.friction", "table.friction_law", "table.rolling_resistance", "table.tip_material",
                            "table.tip_modulus", "table.tip_poisson", "table.material", "table.modulus",
                            "table.poisson"})
      if (table.on_table() && config.settings.count(key))
        throw InvalidInput(key, fmt::format("applies to table.contact = \"sliding\" only (here \"{}\")",
                                            name(table.contact)));
  if (const auto mu = config.number("table.friction")) table.friction = *mu;
  if (const auto law = config.string("table.friction_law")) {
    const auto known = friction_law_from_name(*law);
    if (!known)
      throw InvalidInput("table.friction_law", fmt::format("unknown law \"{}\": must be \"viscous\", \"coulomb\" or "
                                                           "\"contensou\"",
                                                           printable(*law)));
    table.friction_law = *known;
  }
  if (const auto v = config.number("table.slip_speed")) table.slip_speed = *v;
  table.tip_material = material_of(config, "table.tip_material", "table.tip_modulus", "table.tip_poisson");
  table.material = material_of(config, "table.material", "table.modulus", "table.poisson");
  if (table.friction_law != FrictionLaw::Contensou)
    for (const char* key : {"table.tip_material", "table.tip_modulus", "table.tip_poisson", "table.material",
                            "table.modulus", "table.poisson"})
      if (config.settings.count(key))
        throw InvalidInput(key, "applies to friction_law = \"contensou\" only (Hertz's contact patch)");
  if (const auto delta = config.number("table.rolling_resistance")) table.rolling_resistance = *delta;
  const auto density = config.number("table.air_density");
  const auto viscosity = config.number("table.air_viscosity");
  bool air = false;
  if (config.settings.count("table.air")) {
    const auto* flag = std::get_if<bool>(&config.settings.at("table.air"));
    if (!flag) throw InvalidInput("table.air", "must be true or false");
    air = *flag;
  }
  if ((density || viscosity) && !air)
    throw InvalidInput(density ? "table.air_density" : "table.air_viscosity", "needs table.air = true");
  if (air) {
    table.air = Air{};
    if (density) table.air->density = *density;
    if (viscosity) table.air->viscosity = *viscosity;
    // The parts' own surfaces; a body given by its moments, or with a mesh among its parts,
    // is dragged as its equivalent disc (the core's default for no surfaces).
    const bool solids = !config.parts.empty() &&
                        std::none_of(config.parts.begin(), config.parts.end(), [](const PartSpec& p) { return p.mesh; });
    if (solids) {
      std::vector<SolidPart> parts;
      for (const auto& p : config.parts) parts.push_back(p.solid);
      table.air_surfaces = air_surfaces(parts);
    }
  }
  validate(table);
  return table;
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

// ---- [uncertainty] (SPEC section 17) ------------------------------------------------------------

namespace {

/// The whole of `text` as a finite number, or nullopt.
std::optional<double> whole_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.empty()) return std::nullopt;
  const std::string copy(text);
  char* end = nullptr;
  const double x = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

std::int64_t whole_count(const std::string& key, const SettingValue& value, const char* rule) {
  if (const auto* i = std::get_if<std::int64_t>(&value)) {
    if (*i < 0) throw InvalidInput(key, rule);
    return *i;
  }
  std::optional<double> x;
  if (const auto* d = std::get_if<double>(&value)) x = *d;
  if (const auto* s = std::get_if<std::string>(&value)) x = whole_number(*s);
  if (!x || *x < 0.0 || *x != std::trunc(*x) || *x > 9e15) throw InvalidInput(key, rule);
  return static_cast<std::int64_t>(*x);
}

}  // namespace

void set_uncertainty(UncertaintyOptions& options, const std::string& name, const SettingValue& value) {
  const std::string key = "uncertainty." + name;
  if (name == "distribution") {
    const auto* s = std::get_if<std::string>(&value);
    const auto d = s ? uncertainty_distribution_from_name(*s) : std::nullopt;
    if (!d) throw InvalidInput(key, "must be \"gaussian\" or \"uniform\"");
    options.distribution = *d;
    return;
  }
  if (name == "draws") {
    options.draws = whole_count(key, value, "must be a whole number >= 0 (0: adaptive, JCGM 101 7.9)");
    return;
  }
  if (name == "seed") {
    options.seed = static_cast<std::uint64_t>(whole_count(key, value, "must be a whole number >= 0"));
    return;
  }
  const bool rpm = name == "spin_rpm";
  const std::string field = rpm ? "spin" : name;
  const auto& keys = uncertain_keys();
  if (std::find(keys.begin(), keys.end(), field) == keys.end())
    throw InvalidInput(printable(key), "unknown key (a body or motion key, distribution, draws or seed)");
  InputUncertainty in;
  std::optional<double> x;
  if (const auto* d = std::get_if<double>(&value)) x = *d;
  else if (const auto* i = std::get_if<std::int64_t>(&value)) x = static_cast<double>(*i);
  else if (const auto* s = std::get_if<std::string>(&value)) {
    std::string_view text = *s;
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    if (!text.empty() && text.back() == '%') {  // relative: "2%" is 0.02 of the nominal value
      text.remove_suffix(1);
      in.relative = true;
      x = whole_number(text);
      if (x) *x /= 100.0;
    } else {
      x = whole_number(text);
    }
  }
  const char* rule = "must be a standard uncertainty >= 0: a number in the key's unit, or a percentage such as \"2%\"";
  if (!x || !(*x >= 0.0)) throw InvalidInput(printable(key), rule);
  in.value = rpm && !in.relative ? rad_per_s_from_rpm(*x) : *x;
  options.inputs[field] = in;
}

UncertaintyOptions uncertainty_of(const Configuration& config) {
  UncertaintyOptions options;
  const std::string prefix = "uncertainty.";
  for (const auto& [key, value] : config.settings)
    if (key.compare(0, prefix.size(), prefix) == 0) set_uncertainty(options, key.substr(prefix.size()), value);
  if (config.settings.count("uncertainty.spin") && config.settings.count("uncertainty.spin_rpm"))
    throw InvalidInput("uncertainty.spin_rpm", "give spin or spin_rpm, not both");
  return options;
}

}  // namespace heavytop::io

// libFuzzer target: the configuration parser (heavytop_io) on arbitrary bytes, then what the
// command line does with a configuration it has read (cli/common.cpp, Inputs::resolve, and
// the commands' typed settings): the required keys, validate() of the body and the motion,
// the stability analysis a valid body allows (cheap), and every known setting of every
// further section through each typed getter.
//
// Allowed: heavytop::InvalidInput, with a one-line message (SPEC section 1). A finding is
// anything else: another exception escaping (libFuzzer reports it as a deadly signal after
// std::terminate), a crash, undefined behaviour or an address error (the sanitizers), a
// leak, or a message spread over several lines (abort() below).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "heavytop/body.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/state.hpp"

namespace {

using heavytop::InvalidInput;

// The CLI prints "heavytop: error: KEY: RULE" on one line.
void check_one_line(const InvalidInput& e) {
  const std::string message = e.key() + ": " + e.rule();
  if (e.key().empty() || message.find_first_of("\n\r") != std::string::npos) {
    std::fprintf(stderr, "fuzz_config: a message that is not one line naming a key: '%s'\n", message.c_str());
    std::abort();
  }
}

// Runs f; InvalidInput is the one way it may refuse. Returns whether f completed.
template <class F>
bool accepted(F&& f) {
  try {
    f();
    return true;
  } catch (const InvalidInput& e) {
    check_one_line(e);
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace io = heavytop::io;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::Configuration config;
  if (!accepted([&] { config = io::parse_configuration(text, "fuzz.toml", "--config"); })) return 0;

  // As Inputs::resolve: the required body keys (the command line may give them instead).
  for (const std::string& key : io::required_body_keys()) (void)config.given.count(key);
  for (const auto& keys : {io::body_keys(), io::motion_keys()})
    for (const std::string& key : keys)
      if (io::config_field(config.body, config.motion, key) == nullptr) std::abort();  // a key without a field

  const bool body_ok = accepted([&] { heavytop::validate(config.body); });
  const bool motion_ok = accepted([&] { heavytop::validate(config.motion); });
  if (body_ok && motion_ok)  // what `heavytop stability --config` computes
    accepted([&] { (void)heavytop::analyse_stability(config.body, config.motion.spin); });

  // Every command reads its section's settings with the getter of the type it wants.
  for (const auto& [section, keys] : io::command_sections())
    for (const std::string& name : keys) {
      const std::string key = section + "." + name;
      accepted([&] { (void)config.number(key); });
      accepted([&] { (void)config.integer(key); });
      accepted([&] { (void)config.string(key); });
    }
  return 0;
}

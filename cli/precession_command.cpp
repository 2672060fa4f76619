// heavytop precession --tilt THETA: the steady motions at a tilt (steady precessions of a
// symmetric top, tilted permanent rotations) and the initial states that start on them.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/body_formats.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/precession.hpp"

namespace heavytop::cli {

Action add_precession_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "precession", "Steady motions at a tilt: a symmetric top's slow and fast steady precessions at its spin, the "
                    "minimum spin, the permanent rotations about the vertical, each with its initial state");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"});
  auto tilt = std::make_shared<double>(0.0);
  auto* tilt_option = cmd->add_option("--tilt", *tilt, "rad, the axis's angle from the upward vertical, in (0, pi)");
  auto tilt_deg = std::make_shared<DegreesOption>(*cmd, tilt_option, "tilt", "--tilt-deg",
                                                  "degrees, the same angle (instead of --tilt), in (0, 180)");
  return [inputs, tilt, tilt_option, tilt_deg] {
    // One of the two is required; a message naming only --tilt misled a person who typed --tilt-deg.
    if (!tilt_option->count() && !tilt_deg->given())
      throw InvalidInput("--tilt", "is required: the axis's angle from the upward vertical in rad, or --tilt-deg in "
                                   "degrees");
    tilt_deg->apply(*tilt);
    inputs->resolve();
    const Body& body = inputs->body();
    const double spin = inputs->state().spin;
    if (!body.damping.conservative())
      std::cerr << "heavytop: warning: " << io::kPrecessionIgnoresDamping << "\n";
    std::optional<PrecessionAnalysis> steady;
    if (is_symmetric(body)) steady = analyse_precession(body, *tilt, spin);
    const auto rotations = permanent_rotations(body, *tilt);
    const PrecessionAnalysis* p = steady ? &*steady : nullptr;
    write_output(inputs->output(), inputs->format() == "json" ? io::precession_json(body, *tilt, spin, p, rotations)
                                                              : io::precession_text(body, *tilt, spin, p, rotations));
  };
}

}  // namespace heavytop::cli

// heavytop fit-decay: a stopwatch's spin decay in, the [damping] section out. The axial damping
// d_a and the dry friction tau0 (and the spin at t = 0) are fitted by fit_spin_decay() (core);
// the CSV is read and the result written by heavytop_io.
#include <cmath>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/fit_decay.hpp"
#include "heavytop/io/decay_data.hpp"
#include "heavytop/io/formats.hpp"

namespace heavytop::cli {

Action add_fit_decay_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "fit-decay", "Fit the axial damping and the dry friction ([damping] axial, friction) to a measured spin "
                   "decay (CSV: t and spin or spin_rpm), through the law C w' = -d_a w - tau0 sign(w) with C from "
                   "the body");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"},
                                         InputUses{.motion = false, .damping = false});
  auto data = std::make_shared<std::string>();
  auto spin0 = std::make_shared<double>(0.0);
  cmd->add_option("--data", *data, "CSV file: a header naming t (s) and spin (rad/s) or spin_rpm (rpm), one point a "
                                   "line, '#' comment lines")
      ->type_name("FILE")
      ->required();
  auto* spin0_option =
      cmd->add_option("--known-spin0", *spin0, "rad/s: the spin at t = 0 is known and not fitted (default: fitted)")
          ->type_name("NUM");
  return [inputs, data, spin0, spin0_option] {
    inputs->resolve();
    FitDecayOptions options;
    if (spin0_option->count()) {
      if (!(std::isfinite(*spin0) && *spin0 > 0.0)) throw InvalidInput("--known-spin0", "must be a finite number > 0");
      options.fit_spin0 = false;
      options.spin0 = *spin0;
    }
    const DecayData points = io::read_decay_csv(*data, "--data", options.fit_spin0 ? 4 : 3);
    const DecayFit fit = fit_spin_decay(inputs->body(), points, options);
    write_output(inputs->output(), inputs->format() == "json" ? io::fit_decay_json(fit)
                                                              : io::fit_decay_text(fit, inputs->body().damping));
    if (!fit.summary.converged) throw Failure("fit-decay: the fit did not converge: " + fit.summary.termination);
  };
}

}  // namespace heavytop::cli

// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues;
// then the real body's Lyapunov verdict (SPEC section 7) and how far its axis wanders; first of
// all, the answer (SPEC section 14).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/table.hpp"
#include "heavytop/uncertainty.hpp"

namespace heavytop::cli {

Action add_stability_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "stability", "Linear stability of the first-order, body-fixed and linearized models at a spin, "
                   "and the real body's Lyapunov verdict");
  InputUses uses;
  uses.table = true;
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"text", "json"}, uses);
  auto options = std::make_shared<AnswerOptions>();
  auto answer_flags = std::make_shared<AnswerFlags>(*cmd, *options);
  auto brief = std::make_shared<bool>(false);
  cmd->add_flag("--brief", *brief, "text: the answer only (the text's first paragraph, for a class), no details");
  auto uncertain = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--uncertain", *uncertain,
                  "KEY=VALUE, repeatable: a body or motion key's standard uncertainty (SI, or \"2%\" relative), or "
                  "distribution, draws, seed; over the file's [uncertainty] key by key (SPEC 17)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return [inputs, options, answer_flags, brief, uncertain] {
    inputs->resolve();
    // The JSON holds the answer as "answer" beside the details; a trimmed JSON would break its keys.
    if (*brief && inputs->format() != "text")
      throw InvalidInput("--brief", "gives the answer in words, with --format text only (the JSON's \"answer\" is "
                                    "the same answer)");
    answer_flags->apply();
    const Body& body = inputs->body();
    // SPEC 17: the file's [uncertainty], then --uncertain key by key over it.
    UncertaintyOptions uncertainty = io::uncertainty_of(inputs->configuration());
    for (const std::string& item : *uncertain) {
      const auto eq = item.find('=');
      if (eq == std::string::npos || eq == 0)
        throw InvalidInput("--uncertain", "must be KEY=VALUE (e.g. A=2% or C=1e-7), not '" + printable(item) + "'");
      io::set_uncertainty(uncertainty, item.substr(0, eq), item.substr(eq + 1));
    }
    if (uncertainty.any()) validate(uncertainty, body, inputs->state());
    if (const Table& table = inputs->table(); table.on_table()) {  // SPEC section 16
      if (uncertainty.any())
        throw InvalidInput("uncertainty", "is propagated to the answer on a pivot only, not on a table (SPEC 16)");
      const TableAnalysis analysis = analyse_top_on_table(body, table, inputs->state(), *options);
      write_output(inputs->output(),
                   inputs->format() == "json"
                       ? io::table_stability_json(body, table, analysis, analyse_stability(body, analysis.spin))
                   : *brief ? io::table_answer_text(analysis.answer, table) + "\n"  // as the text opens
                            : io::table_stability_text(body, table, analysis));
      return;
    }
    const TopAnalysis analysis = [&] {
      ProgressBar bar("stability", answer_run_length(body, inputs->state(), *options));
      return analyse_top(body, inputs->state(), *options, [&bar](double t) { bar.update(t); });
    }();
    std::optional<UncertaintyAnalysis> how_sure;
    if (uncertainty.any()) how_sure = analyse_uncertainty(body, inputs->state(), uncertainty, *options);
    const UncertaintyAnalysis* u = how_sure ? &*how_sure : nullptr;
    write_output(inputs->output(),
                 inputs->format() == "json" ? io::stability_json(body, analysis, u)
                 : *brief ? io::answer_text(analysis.answer) + (u ? " " + io::uncertainty_sentence(*u) : "") + "\n"
                          : io::stability_text(body, analysis, u));
  };
}

}  // namespace heavytop::cli

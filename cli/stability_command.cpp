// heavytop stability: each linear model's verdict at the spin, its stable spins, its eigenvalues;
// then the real body's Lyapunov verdict (SPEC section 7) and how far its axis wanders; first of
// all, the answer (SPEC section 14).
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/table.hpp"

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
  return [inputs, options, answer_flags, brief] {
    inputs->resolve();
    // The JSON holds the answer as "answer" beside the details; a trimmed JSON would break its keys.
    if (*brief && inputs->format() != "text")
      throw InvalidInput("--brief", "gives the answer in words, with --format text only (the JSON's \"answer\" is "
                                    "the same answer)");
    answer_flags->apply();
    const Body& body = inputs->body();
    if (const Table& table = inputs->table(); table.on_table()) {  // SPEC section 16
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
    write_output(inputs->output(), inputs->format() == "json" ? io::stability_json(body, analysis)
                                   : *brief                     ? io::answer_text(analysis.answer) + "\n"
                                                                : io::stability_text(body, analysis));
  };
}

}  // namespace heavytop::cli

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "heavytop/io/formats.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/report/report.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop::report {
using io::write_output;
namespace fs = std::filesystem;

namespace {

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string all_trajectories_csv(const Comparison& c) {
  std::string out = "t,theta_nonlinear,phi_nonlinear";
  for (const auto& m : c.models) out += fmt::format(",theta_{0},phi_{0}", m.model);
  out += "\n";
  for (std::size_t i = 0; i < c.nonlinear.size(); ++i) {
    out += fmt::format("{},{},{}", c.nonlinear.t[i], c.nonlinear.theta[i], c.nonlinear.phi[i]);
    for (const auto& m : c.models) out += fmt::format(",{},{}", m.trajectory.theta[i], m.trajectory.phi[i]);
    out += "\n";
  }
  return out;
}

std::string errata_html(const Body& body, const InitialState& state, const std::vector<ModelStability>& reports) {
  std::string items;
  const bool symmetric = is_symmetric(body);
  items += "<li><b>E1, section 8.</b> The paper's printed general solution does not satisfy its own model (4) "
           "(eight constants for a fourth-order system, then four of them set to 1). heavytop's closed form "
           "solves (4) for every input, with the t&nbsp;cos, t&nbsp;sin terms at a double root.</li>";
  const double boundary = paper_condition_9_spin(body);
  if (body.mgR() <= 0.0) {
    items += "<li><b>E2</b> does not apply: with the centre of mass at or below O, (9) asks for no spin, "
             "so there is no boundary spin to misjudge.</li>";
  } else items += fmt::format(
      "<li><b>E2, condition (9).</b> The boundary w0 = {:.6g} rad/s is not stable: the two frequencies merge "
      "into a Jordan block and the amplitude grows linearly. Stability needs strict inequality.{}</li>",
      boundary,
      std::abs(std::abs(state.spin) - boundary) <= 1e-3 * boundary ? " <b>This spin is at the boundary.</b>" : "");
  if (!symmetric) {
    const auto& paper = reports[0];
    const auto& truth = reports[2];
    auto crit = [](const std::optional<double>& c) {
      return c ? fmt::format("{:.6g} rad/s ({:.6g} rpm)", *c, *c * 30.0 / M_PI) : std::string("none");
    };
    items += fmt::format(
        "<li><b>E3, this body is asymmetric (A &ne; B).</b> Model (4) is the linearisation only for A = B. "
        "(9) puts the critical spin at {}; the exact linearisation at {}.{}</li>",
        crit(paper.critical), crit(truth.critical),
        paper.verdict.stable != truth.verdict.stable
            ? fmt::format(" <b>At this spin (4) says {} and the truth is {}.</b>",
                          paper.verdict.stable ? "stable" : "unstable", truth.verdict.stable ? "stable" : "unstable")
            : std::string());
  } else {
    items += "<li><b>E3</b> does not apply: for a symmetric body (A = B) the paper's (4) is the exact "
             "linearisation and (9) is the classical sleeping-top criterion C&sup2;w0&sup2; &gt; 4 A m g R.</li>";
  }
  if (body.length != 0.0 && is_planar(body))
    items += "<li><b>E0.</b> A + B = C means all the mass lies in the plane z = 0, so the centre of mass "
             "cannot be off O: this body is an idealisation.</li>";
  return "<ul>" + items + "</ul>";
}

std::string table_html(const std::vector<ModelStability>& reports) {
  std::string rows;
  for (const auto& r : reports) {
    rows += fmt::format("<tr><td>{}</td><td class='{}'>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", name(r.kind),
                        r.verdict.stable ? "ok" : "bad", r.verdict.stable ? "stable" : "unstable",
                        r.critical ? fmt::format("{:.6g}", *r.critical) : "none",
                        io::intervals_text(r.intervals), html_escape(r.verdict.reason));
  }
  return "<table><tr><th>model</th><th>verdict</th><th>critical spin (rad/s)</th><th>stable spins (rad/s)</th>"
         "<th>why</th></tr>\n" + rows + "</table>";
}

std::string comparison_html(const Comparison& c) {
  auto f = [](const std::optional<double>& x) { return x ? fmt::format("{:.6g}", *x) : std::string("&ndash;"); };
  auto e = [](const std::optional<double>& x) { return x ? fmt::format("{:.2e}", *x) : std::string("&ndash;"); };
  std::string rows = fmt::format("<tr><td>nonlinear (truth)</td><td></td><td></td><td>{}</td><td></td><td>{}</td><td></td></tr>\n",
                                 f(c.nonlinear_frequencies.nutation), f(c.nonlinear_frequencies.precession));
  for (const auto& m : c.models)
    if (m.diverged_at)
      rows += fmt::format("<tr><td>{}</td><td>{:.3e}</td><td colspan='5'>diverges at t = {:.4g} s (its angles pass "
                          "{:g} rad: no small motion left to compare)</td></tr>\n",
                          m.model, m.max_angle_error, *m.diverged_at, kDivergedAngle);
    else
    rows += fmt::format("<tr><td>{}</td><td>{:.3e}</td><td>{:.3e}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                        m.model, m.max_angle_error, m.final_angle_error, f(m.frequencies.nutation),
                        e(m.nutation_relative_error), f(m.frequencies.precession), e(m.precession_relative_error));
  return "<table><tr><th>model</th><th>max angle error (rad)</th><th>final error (rad)</th><th>nutation (rad/s)</th>"
         "<th>rel. error</th><th>precession (rad/s)</th><th>rel. error</th></tr>\n" + rows + "</table>";
}

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 1100px; margin: 2em auto; color: #222; line-height: 1.45; }
h1 { font-size: 1.8em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 2em; }
table { border-collapse: collapse; margin: 1em 0; } td, th { border: 1px solid #ccc; padding: .3em .7em; text-align: left; }
th { background: #f2f2f2; } td.ok { color: #1a7f1a; font-weight: bold; } td.bad { color: #c62828; font-weight: bold; }
figure { margin: 1.5em 0; } figure img { width: 100%; border: 1px solid #ddd; } figcaption { color: #555; font-size: .95em; }
.note { background: #fff8e1; border-left: 4px solid #f9a825; padding: .5em 1em; }
)";

}  // namespace

namespace {

/// A private folder in the system's temporary directory, removed with everything in it.
class Staging {
 public:
  Staging() {
    std::string pattern = (fs::temp_directory_path() / "heavytop-report-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw io::Failure("cannot create a temporary folder for the report's figures");
    path_ = pattern;
  }
  ~Staging() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

void write_report(const std::string& dir, const Body& body, const InitialState& state, std::optional<double> t_end) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InvalidInput("--output", fmt::format("cannot create the folder '{}'", dir));
  // One report into a folder at a time; everything is made first, in a staging folder, and
  // only then put in place, so a failure leaves the folder as it was.
  const io::OutputLock lock((fs::path(dir) / "report").string(), "--output", dir);
  const Staging staging;

  const auto reports = analyse_stability(body, state.spin);
  const LyapunovStability lyapunov = analyse_lyapunov(body, state.spin);
  const double horizon = t_end.value_or(natural_horizon(body, state.spin));
  const Comparison c = compare_models(body, state, sample_times(horizon, 4001));
  const Wander wander = axis_wander(body, state, horizon);

  std::vector<Figure> figures = plot_motion(staging.path(), c);
  figures.push_back(plot_stability_diagram(staging.path(), body, state));
  figures.push_back(plot_wander(staging.path(), body, reports[2].critical));
  // The stability map: B/A over the values a real body allows, spin up to well past the truth's threshold.
  const auto [lo, hi] = realizable_ratio_range(body);
  double top = std::max(2.0 * std::abs(state.spin), 1e-9);
  for (const auto& r : reports)
    if (r.kind != LinearModelKind::BodyFixed && r.critical) top = std::max(top, 2.0 * *r.critical);
  const std::vector<SweepAxis> axes{{"B/A", lo, hi, 200}, {"spin", 0.0, top, 200}};
  const auto verdicts = sweep_verdicts(body, state, axes, SweepOptions{}, 0, grid_size(axes));
  figures.push_back(plot_sweep_map(staging.path(), axes, verdicts));

  std::vector<std::pair<std::string, std::string>> data = {
      {"stability.json", io::stability_json(body, state.spin, reports, lyapunov, wander)},
      {"comparison.json", io::comparison_json(c)},
      {"comparison.csv", io::comparison_csv(c)},
      {"trajectories.csv", all_trajectories_csv(c)},
      {"stability-map.csv", io::sweep_csv_header(axes, false) + io::sweep_csv_rows(axes, 0, verdicts)},
  };

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>heavytop report</title><style>"
       << kStyle << "</style></head><body>\n<h1>heavytop: the heavy top, its models and the truth</h1>\n";
  html << fmt::format(
      "<p>Body: A = {:g}, B = {:g}, C = {:g} kg&nbsp;m&sup2;, m = {:g} kg, g = {:g} m/s&sup2;, R = {:g} m "
      "(m g R = {:g} N&nbsp;m, {}). Spin w0 = {:g} rad/s ({:.0f} rpm); start theta0 = {:g}, phi0 = {:g} rad, "
      "rates {:g}, {:g} rad/s.</p>\n",
      body.A, body.B, body.C, body.mass, body.gravity, body.length, body.mgR(),
      body.length > 0 ? "centre of mass above the pivot" : body.length < 0 ? "hanging" : "centre of mass at the pivot",
      state.spin, state.spin * 30.0 / std::numbers::pi, state.theta0, state.phi0, state.theta_rate0, state.phi_rate0);
  html << "<h2>Is it stable?</h2>\n<p><i>first-order</i> is the paper's model (4) and its condition (9); "
          "<i>body-fixed</i> its model (5), which the paper itself calls erroneous; <i>linearized</i> the exact "
          "linearisation about the upright spin, the one to trust.</p>\n"
       << table_html(reports);
  if (reports[0].verdict.stable != reports[2].verdict.stable)
    html << "<p class='note'>The paper's model (4) and the exact linearisation disagree at this spin (erratum E3).</p>\n";
  // The second question: the real body, beyond the linearisation (docs/lyapunov.md).
  const LyapunovVerdict& v = lyapunov.verdict;
  html << fmt::format(
      "<p><b>The real body</b> (nonlinear, conservative) at this spin: Lyapunov <b>{}</b> ({}; certificate "
      "<code>{}</code>). Energy index {}; proven stable for spins (rad/s): {}; superfast {}.{}{}</p>\n",
      name(v.verdict), html_escape(v.reason), name(v.certificate), v.energy_index,
      io::intervals_text(lyapunov.intervals),
      lyapunov.superfast ? fmt::format("from {:.6g} rad/s", *lyapunov.superfast) : std::string("at no spin"),
      v.certificate == LyapunovCertificate::CriticalQuartic
          ? " At the boundary of (9) the linear models grow (a Jordan block), but the real symmetric top does not: "
            "started &delta; off vertical its tilt stays below about &radic;(2&delta;) (erratum E2)."
          : "",
      wander.max_tilt ? fmt::format(" From the given start the axis tilts at most {:.4g} rad ({}).", *wander.max_tilt,
                                    wander.closed_form ? "closed form" : "integrated")
                      : std::string());
  html << "<h2>How does it move?</h2>\n<p>Every model from the same start over " << fmt::format("{:.4g}", horizon)
       << " s, against the full nonlinear body (" << c.summary.steps << " integrator steps, relative energy drift "
       << fmt::format("{:.1e}", c.summary.max_relative_energy_drift) << ").</p>\n"
       << comparison_html(c);
  for (const Figure& f : figures)
    html << fmt::format("<figure><img src='{0}.svg' alt='{1}'><figcaption>{1} (<a href='{0}.png'>PNG</a>, "
                        "<a href='{0}.svg'>SVG</a>)</figcaption></figure>\n",
                        f.name, html_escape(f.caption));
  html << "<h2>Where the paper is wrong, for this body</h2>\n" << errata_html(body, state, reports);
  html << "<h2>Data</h2>\n<ul><li><a href='stability.json'>stability.json</a>: as <code>heavytop stability --format json</code></li>"
          "<li><a href='comparison.json'>comparison.json</a>, <a href='comparison.csv'>comparison.csv</a>: as "
          "<code>heavytop compare</code></li><li><a href='trajectories.csv'>trajectories.csv</a>: theta, phi of every "
          "model (rad) against t (s)</li><li><a href='stability-map.csv'>stability-map.csv</a>: the map's verdicts</li></ul>\n"
          "<p><small>Made by heavytop. Units SI; angles as in SPEC.md section 2.</small></p>\n</body></html>\n";
  data.emplace_back("report.html", html.str());

  // Everything is made: put it in place, each file by a temporary name and a rename.
  for (const Figure& f : figures)
    for (const char* extension : {".png", ".svg"}) {
      const std::string from = (fs::path(staging.path()) / (f.name + extension)).string();
      io::write_atomically((fs::path(dir) / (f.name + extension)).string(), [&](const std::string& to) {
        fs::copy_file(from, to, fs::copy_options::overwrite_existing);
      });
    }
  for (const auto& [name, content] : data) write_output((fs::path(dir) / name).string(), content);
}

}  // namespace heavytop::report

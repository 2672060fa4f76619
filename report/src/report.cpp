#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/mesh_file.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/report/animation.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/report/report.hpp"
#include "heavytop/answer.hpp"
#include "heavytop/compare.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/table.hpp"
#include "web_assets.hpp"

namespace heavytop::report {
using io::write_output;
namespace fs = std::filesystem;

namespace {

/// Text for the page, in an element or in a quoted attribute (a caption is an alt='...': "the
/// paper's" ended it).
std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '\'') out += "&#39;";
    else if (c == '"') out += "&quot;";
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

/// Six significant digits: enough for a screen, a third of the bytes of a double's 17.
double display(double x) { return std::stod(fmt::format("{:.6g}", x)); }

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve(4 * ((bytes.size() + 2) / 3));
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

/// Whether the page carries a mesh part's file (its own triangles, parsed by three.js's loader
/// for STL, OBJ or PLY), else why not (its format "stl", "obj" or "ply" in `format`).
bool mesh_carried(const DrawnPart& part, std::string& format, std::string& why) {
  std::string extension = fs::path(part.mesh_file).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return std::tolower(ch); });
  std::error_code ec;
  const auto bytes = fs::file_size(part.mesh_file, ec);
  if (extension != ".stl" && extension != ".obj" && extension != ".ply") {
    why = fmt::format("a {} file, which the page cannot read", extension.empty() ? "mesh" : extension);
    return false;
  }
  if (!ec && bytes > kMaxDrawnMeshBytes) {
    why = fmt::format("{:.0f} MB, more than the page carries", double(bytes) / 1e6);
    return false;
  }
  format = extension.substr(1);
  return true;
}

/// The parts as the page draws them (report/web/src/main.js buildBody()): a solid's shape and
/// sizes (m); a mesh's file bytes (base64) with its format (by the file's extension) and scale,
/// or for a file too large to carry (or of a format the page's loaders do not read) its bounding
/// box from the triangles heavytop read.
nlohmann::json parts_json(const std::vector<DrawnPart>& parts) {
  using nlohmann::json;
  json out = json::array();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const DrawnPart& part = parts[i];
    if (part.solid) {
      const SolidPart& s = *part.solid;
      json p = {{"shape", name(s.shape)}, {"label", part.label}, {"radius", s.radius}, {"z0", s.z0}};
      if (s.shape != PartShape::Sphere) p["height"] = s.height;
      if (s.shape == PartShape::Tube) p["inner_radius"] = s.inner_radius;
      if (s.shape == PartShape::Cone) p["apex"] = s.apex_up ? "up" : "down";
      out.push_back(p);
      continue;
    }
    const std::string key = fmt::format("body.part[{}] ({})", i, part.label);
    json p = {{"shape", "mesh"}, {"label", part.label}, {"scale", part.scale}};
    std::string format, why;
    if (mesh_carried(part, format, why)) {
      p["format"] = format;
      p["data"] = base64(io::read_text_file(part.mesh_file, key, kMaxDrawnMeshBytes, "a mesh file"));
    } else {
      const TriangleMesh mesh = io::read_mesh(part.mesh_file, part.scale, key);
      Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
      for (const auto& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      p["format"] = "box";
      p["box"] = {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}};
      p["why"] = why;
    }
    out.push_back(p);
  }
  return out;
}

/// The samples the page shows of a run of n, and a series' values at them: a value that is not
/// finite, or past the end of a model's trajectory (one that stopped on a numerical failure), is
/// null: the page leaves a gap, never a made-up number.
struct Shown {
  std::vector<std::size_t> index;
  explicit Shown(std::size_t n) : index(display_samples(n)) {}
  static nlohmann::json value(const std::vector<double>& v, std::size_t i) {
    return i < v.size() && std::isfinite(v[i]) ? nlohmann::json(display(v[i])) : nlohmann::json(nullptr);
  }
  nlohmann::json pick(const std::vector<double>& v) const {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i : index) a.push_back(value(v, i));
    return a;
  }
};

/// What the 3D view draws (report/web/src/main.js buildView()): the body, as its parts or its
/// equivalent ellipsoid, moving as `nonlinear` (theta, phi and the spin angle psi), and the
/// playback speed.
nlohmann::json view_json(const Body& body, const Trajectory& nonlinear, const std::vector<DrawnPart>& parts) {
  using nlohmann::json;
  const std::size_t n = nonlinear.size();
  const Shown shown(n);
  const std::vector<double> psi = spin_angles(body, nonlinear);
  double spin_rate = 0.0;  // rad/s, the fastest spin of the samples (for the page's aliasing note)
  for (std::size_t i = 1; i < n; ++i)
    if (nonlinear.t[i] > nonlinear.t[i - 1])
      spin_rate = std::max(spin_rate, std::abs(psi[i] - psi[i - 1]) / (nonlinear.t[i] - nonlinear.t[i - 1]));
  // Playback: the fastest of these speeds at which the spin turns at most 30 degrees a frame
  // (60 frames a second) and the motion lasts at least 8 s; else the slowest.
  const std::vector<double> speeds{1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0};
  const double horizon = n ? nonlinear.t.back() : 0.0;
  double speed = speeds.front();
  for (double s : speeds)
    if (s * spin_rate / 60.0 <= std::numbers::pi / 6.0 && horizon / s >= 8.0) speed = s;
  const EquivalentEllipsoid shape = equivalent_ellipsoid(body);
  return {
      {"body", {{"A", body.A}, {"B", body.B}, {"C", body.C}, {"mass", body.mass}, {"gravity", body.gravity}, {"length", body.length}}},
      {"t", shown.pick(nonlinear.t)},
      {"display", {{"samples", shown.index.size()}, {"computed_samples", n}}},
      {"nonlinear", {{"theta", shown.pick(nonlinear.theta)}, {"phi", shown.pick(nonlinear.phi)}, {"psi", shown.pick(psi)}}},
      {"models", json::array()},
      {"shape", {{"semi_axes", shape.semi_axes}, {"centre", shape.centre}, {"note", shape.note}}},
      {"parts", parts_json(parts)},
      {"playback", {{"speed", speed}, {"speeds", speeds}, {"spin_rate", spin_rate}}},
  };
}

/// The report's numbers for its page script (report/web/src/main.js), as a classic script that
/// assigns window.HEAVYTOP_REPORT (pages opened from file:// may not fetch() a JSON file): the
/// 3D view's (view_json()), every model's motion, the map and the diagram.
std::string page_data_js(const Body& body, const InitialState& state, const Comparison& c,
                         const std::vector<SweepAxis>& map_axes, const std::vector<SweepVerdict>& map,
                         const DiagramGrid& diagram, const std::vector<DrawnPart>& parts, bool explorer) {
  using nlohmann::json;
  const Shown shown(c.nonlinear.size());
  const double horizon = c.nonlinear.size() ? c.nonlinear.t.back() : 0.0;
  json models = json::array();
  for (const auto& m : c.models) {
    json errors = json::array();
    for (std::size_t i : shown.index)
      errors.push_back(i < m.trajectory.size() ? Shown::value({angle_error(m.trajectory, c.nonlinear, i)}, 0) : json(nullptr));
    models.push_back({{"name", m.model}, {"theta", shown.pick(m.trajectory.theta)}, {"phi", shown.pick(m.trajectory.phi)},
                      {"error", errors}, {"diverged_at", m.diverged_at ? json(*m.diverged_at) : json(nullptr)}});
  }
  const AngleUnit unit = angle_unit(c);
  auto axis = [](const SweepAxis& a) {
    const std::string label = a.key == "spin" ? "spin w0 (rad/s)" : a.key;
    return json{{"key", a.key}, {"start", a.start}, {"stop", a.stop}, {"count", a.count}, {"label", label}};
  };
  std::string verdicts, certificates;
  for (const SweepVerdict& v : map) {
    verdicts += "0123456789abcdef"[int(v.linear[0]) | int(v.linear[1]) << 1 | int(v.linear[2]) << 2 | int(v.lyapunov) << 3];
    certificates += char('0' + int(v.lyapunov_certificate));
  }
  json certificate_names = json::array();
  for (int k = 0; k <= int(kLastLyapunovCertificate); ++k) certificate_names.push_back(name(LyapunovCertificate(k)));
  json points = json::array();
  for (std::size_t i = 0; i < diagram.verdicts.size(); ++i) {
    const auto p = grid_values(diagram.axes, i);
    points.push_back({display(p[0]), display(p[1]), diagram.verdicts[i].nonlinear.value_or(false) ? 1 : 0});
  }
  const auto [up_word, down_word] = diagram_words(body);
  json data = view_json(body, c.nonlinear, parts);
  data.update({
      {"spin", state.spin},
      {"models", models},
      {"angle_scale", unit.scale},
      {"angle_unit", unit.name},
      {"map", {{"x", axis(map_axes[0])}, {"y", axis(map_axes[1])}, {"verdicts", verdicts}, {"certificates", certificates}}},
      {"certificates", certificate_names},
      {"diagram", {{"points", points}, {"start_tilt", diagram.start_tilt}, {"max_tilt", diagram.max_tilt},
                   {"horizon", diagram.horizon}, {"up_word", up_word}, {"down_word", down_word}}},
      {"body_point", {body.B / body.A, std::abs(state.spin)}},
      // The explorer beside the report (explore.html): a map point's motion opens there.
      {"explorer", explorer},
      {"start", {{"theta0", state.theta0}, {"phi0", state.phi0}, {"theta_rate0", state.theta_rate0}, {"phi_rate0", state.phi_rate0}}},
      {"cli_body", fmt::format("--A {:g} --C {:g} --mass {:g} --gravity {:g} --length {:g}", body.A, body.C, body.mass,
                               body.gravity, body.length)},
      {"cli_start", fmt::format("--theta0 {:g} --phi0 {:g} --theta-rate0 {:g} --phi-rate0 {:g} --t-end {:g} --samples 2001",
                                state.theta0, state.phi0, state.theta_rate0, state.phi_rate0, horizon)},
  });
  return "// Written by heavytop report: the numbers behind report.html's interactive view.\nwindow.HEAVYTOP_REPORT = " +
         data.dump() + ";\n";
}

/// The 3D view (drawn by heavytop-report.js), first on the page: what a lecture projects. In a
/// build without the page script, a note instead; the static figures follow in both cases.
std::string view_html(const Comparison& c, const EquivalentEllipsoid& shape, const std::vector<DrawnPart>& parts) {
  if (const char* why = detail::web_assets_missing())
    return fmt::format("<p class='note' id='no-interactive'>No interactive view in this report: {}. The static "
                       "figures below show the same motion.</p>\n", html_escape(why));
  std::string drawn;
  if (parts.empty()) {
    drawn = "The body is drawn as the uniform ellipsoid with its mass and moments (centre of mass at R on the spin axis)" +
            (shape.note.empty() ? std::string() : fmt::format(" (not to scale: {})", html_escape(shape.note))) +
            ", on a spindle through O (the spindle and the point are drawn only to show the axis).";
  } else {
    std::string names;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      std::string what;
      if (const auto& solid = parts[i].solid) {
        what = fmt::format("a {}", name(solid->shape));
        if (solid->shape == PartShape::Cone) what += solid->apex_up ? " (point up)" : " (point down)";
      } else {
        std::string format, why;
        what = mesh_carried(parts[i], format, why)
                   ? fmt::format("the mesh <code>{}</code> (its own triangles)", html_escape(parts[i].label))
                   : fmt::format("the mesh <code>{}</code> (drawn as its bounding box: {})", html_escape(parts[i].label),
                                 html_escape(why));
      }
      names += fmt::format("{}{}", i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ", what);
    }
    drawn = fmt::format("The body is drawn as it is made, to scale and where the configuration puts {}: {}.",
                        parts.size() == 1 ? "it" : "each part", names);
  }
  std::string boxes;
  for (const auto& m : c.models)
    boxes += fmt::format("<label><input type='checkbox' id='overlay-{0}'> {0}{1}</label> ", m.model,
                         m.diverged_at ? fmt::format(" (diverges at {:.3g} s)", *m.diverged_at) : "");
  return fmt::format(R"(<section id='interactive'>
<h2>Watch it move</h2>
<p>The full nonlinear motion. {0} The red sector and ball on its rim turn with the body at its true spin angle; black: the
fixed point O, the vertical (dashed) and the path of the axis's tip; the floor (grid) is below the body's lowest point. Drag
to turn the view, scroll to zoom. Inset (bottom right): straight down on the tip, xi to the right, eta up,
<span id='inset-scale'></span> from centre to edge.</p>
<div id='scene'></div>
<div class='controls'><button id='play'>Pause</button>
<label>speed <input type='range' id='speed' min='0' max='1' step='1'> <span id='speed-value'></span></label>
<label>time <input type='range' id='scrub' min='0' max='10000' value='0' step='1'></label> <span id='time'></span></div>
<p class='controls'><label class='exaggerate'><input type='checkbox' id='exaggerate'> <b>exaggerate tilt x10</b>
(not to scale: the axis drawn 10 times as far from the vertical, at most upside down, so a small wobble shows)</label></p>
<p class='controls'>Overlay each approximate model's axis (its tip's path in its colour) beside the nonlinear one: {1}</p>
<p class='note' id='spin-note' hidden></p>
<p><small>Display data: {2} of the {3} computed samples (six digits); <a href='trajectories.csv'>trajectories.csv</a>
has them all.</small></p>
</section>
)",
                     drawn, boxes,
                     display_samples(c.nonlinear.size()).size(), c.nonlinear.size());
}

/// The interactive plots and the stability explorer (nothing without the page script).
std::string plots_html(const Body& body) {
  if (detail::web_assets_missing()) return "";
  return fmt::format(R"(<section id='interactive-plots'>
<h2>Interactive plots</h2>
<p>Drag to zoom (double-click to reset), hover for values, click a legend entry to hide or show its curve; click a
time to show that moment in the 3D view above.</p>
<div id='plots'></div>
<h2>Stability explorer</h2>
<p>The stability map's grid (colours as in the map below: green both (4) and the exact linearisation stable, red only (4),
blue only the exact one, grey neither) with the diagram's nonlinear runs (white circles: {0}; black crosses: {1}) and this
body (black +). Click a point for its verdicts.</p>
<canvas id='explorer' width='1000' height='560'></canvas>
<div id='explorer-info'><p>Click the map.</p></div>
</section>
)",
                     diagram_words(body).first, diagram_words(body).second);
}

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 1100px; margin: 2em auto; color: #222; line-height: 1.45; }
h1 { font-size: 1.8em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 2em; }
table { border-collapse: collapse; margin: 1em 0; } td, th { border: 1px solid #ccc; padding: .3em .7em; text-align: left; }
th { background: #f2f2f2; } td.ok { color: #1a7f1a; font-weight: bold; } td.bad { color: #c62828; font-weight: bold; }
figure { margin: 1.5em 0; } figure img { width: 100%; border: 1px solid #ddd; } figcaption { color: #555; font-size: .95em; }
.note { background: #fff8e1; border-left: 4px solid #f9a825; padding: .5em 1em; }
#scene { width: 100%; } #scene canvas { display: block; border: 1px solid #ddd; }
#explorer-frame { width: 100%; height: 1500px; border: 1px solid #ccc; }
.controls { display: flex; flex-wrap: wrap; gap: .6em 1.4em; align-items: center; margin: .6em 0; }
label.exaggerate { background: #fff3e0; border: 1px solid #f0b070; padding: .2em .6em; border-radius: 4px; }
.controls button { font-size: 1em; padding: .25em 1.2em; } #scrub { width: 22em; }
.plot { margin: 1em 0; } #explorer { width: 100%; max-width: 1000px; border: 1px solid #ddd; cursor: crosshair; }
b.ok { color: #1a7f1a; } b.bad { color: #c62828; }
p.answer { font-size: 1.25em; padding: .6em 1em; border-left: 6px solid #888; background: #f6f6f6; }
p.answer.up { border-color: #1a7f1a; } p.answer.falls { border-color: #c62828; } p.answer.unproven { border-color: #f9a825; }
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

// Everything is made: the figures from the staging folder and the data, each file into `dir`
// by a temporary name and a rename (the data's last file, report.html, appears last).
void put_in_place(const std::string& dir, const Staging& staging, const std::vector<Figure>& figures,
                  const std::vector<std::pair<std::string, std::string>>& data) {
  for (const Figure& f : figures)
    for (const char* extension : {".png", ".svg"}) {
      const std::string from = (fs::path(staging.path()) / (f.name + extension)).string();
      io::write_atomically((fs::path(dir) / (f.name + extension)).string(), [&](const std::string& to) {
        fs::copy_file(from, to, fs::copy_options::overwrite_existing);
      });
    }
  for (const auto& [name, content] : data) write_output((fs::path(dir) / name).string(), content);
}

}  // namespace

std::vector<std::pair<std::string, StabilityMap>> ReportMap::heat_maps() const {
  if (map.axes.size() < 2) throw InvalidInput("map", "a map of one key has no heat map (give a map of two or three keys)");
  if (map.axes.size() == 2) {
    if (!held.empty() || !values.empty())
      throw InvalidInput("slice", "a map of two keys is drawn whole (slices are for three-key maps)");
    return {{"", map}};
  }
  const std::string key = held.empty() ? map.axes.back().key : held;
  const auto axis = std::find_if(map.axes.begin(), map.axes.end(), [&](const MapAxis& a) { return a.key == key; });
  if (axis == map.axes.end())
    throw InvalidInput("slice", fmt::format("'{}' is not a varied key of the map", io::printable(key)));
  std::vector<double> at = values;
  if (at.empty()) at = {axis->values.front(), axis->values[axis->values.size() / 2], axis->values.back()};
  std::vector<std::pair<std::string, StabilityMap>> out;
  for (double v : at) {
    if (!std::isfinite(v)) throw InvalidInput("slice", fmt::format("the value of '{}' must be finite", key));
    out.emplace_back(fmt::format("at {} = {:.6g}", key, axis->values[nearest_index(axis->values, v)]), slice(map, key, v));
  }
  return out;
}

namespace {

/// s, the motion the report shows: up to the fall and a fifth more when the body falls (the
/// answer's run), else natural_horizon() (several nutation and precession periods).
double report_horizon(const Body& body, const InitialState& state, const Answer& answer) {
  if (answer.falls_at && *answer.falls_at > 0.0) return 1.2 * *answer.falls_at;
  return natural_horizon(body, state.spin);
}

/// "a symmetric top", "a damped asymmetric top", "a hanging symmetric body", ...
std::string body_words(const Body& body) {
  const std::string shape = is_symmetric(body) ? "symmetric" : "asymmetric";
  const std::string damped = body.damping.conservative() ? "" : body.damping.driven ? "driven, damped " : "damped ";
  const std::string kind = body.length > 0 ? "top" : body.length < 0 ? "hanging body" : "body balanced at its centre of mass";
  const std::string words = damped + shape + " " + kind;
  return (std::string("aeiou").find(words[0]) != std::string::npos ? "an " : "a ") + words;
}

}  // namespace

void write_report(const std::string& dir, const Body& body, const InitialState& state, std::optional<double> t_end,
                  const std::optional<ReportMap>& map, const std::string& source, const std::vector<DrawnPart>& parts,
                  const Progress& progress) {
  // A map's heat maps first: bad slices are refused before the folder is made.
  const auto heat_maps = map ? map->heat_maps() : std::vector<std::pair<std::string, StabilityMap>>{};
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InvalidInput("--output", fmt::format("cannot create the folder '{}'", dir));
  // One report into a folder at a time; everything is made first, in a staging folder, and
  // only then put in place, so a failure leaves the folder as it was.
  const io::OutputLock lock((fs::path(dir) / "report").string(), "--output", dir);
  const Staging staging;

  // The answer first (SPEC 14), as `stability` gives it; the motion shown covers what it says.
  const TopAnalysis analysis = analyse_top(body, state, {}, progress);
  const auto& [analysed_spin, reports, lyapunov, wander, answer, answer_life] = analysis;
  const double horizon = t_end.value_or(report_horizon(body, state, answer));
  const Comparison c = compare_models(body, state, sample_times(horizon, 4001), {}, progress);

  std::vector<Figure> figures = plot_motion(staging.path(), c);
  DiagramGrid diagram;
  figures.push_back(plot_stability_diagram(staging.path(), body, state, &diagram, progress));
  figures.push_back(plot_wander(staging.path(), body, reports[2].critical, progress));
  // The stability map: B/A over the values a real body allows, spin up to well past the truth's threshold.
  const auto [lo, hi] = realizable_ratio_range(body);
  double top = std::max(2.0 * std::abs(state.spin), 1e-9);
  for (const auto& r : reports)
    if (r.kind != LinearModelKind::BodyFixed && r.critical) top = std::max(top, 2.0 * *r.critical);
  // 160 x 160: the map reads as finely as at 200 x 200, and its CSV (every point computed,
  // 1.4 MB) keeps the folder of the built-in example under 5 MB.
  const std::vector<SweepAxis> axes{{"B/A", lo, hi, 160}, {"spin", 0.0, top, 160}};
  const auto verdicts = sweep_verdicts(body, state, axes, SweepOptions{}, 0, grid_size(axes));
  figures.push_back(plot_sweep_map(staging.path(), stability_map(axes, false, verdicts)));
  // A map file of the reader's: its heat maps (a three-key map's slices).
  std::vector<Figure> map_figures;
  for (const auto& [where, two] : heat_maps)
    map_figures.push_back(plot_sweep_map(staging.path(), two, fmt::format("map-{}", map_figures.size() + 1), where));
  // With damping: how long it stays up (SPEC section 8).
  std::optional<Lifetime> life;
  std::optional<Figure> life_figure;
  if (!body.damping.conservative()) {
    // The answer's run (default options on both sides: the same run); again only if it stopped,
    // to fail as before.
    life = answer_life ? *answer_life : lifetime(body, state, {}, progress);
    life_figure = plot_lifetime(staging.path(), body, state, *life, progress);
    figures.push_back(*life_figure);
  }

  std::vector<std::pair<std::string, std::string>> data = {
      {"stability.json", io::stability_json(body, analysis)},
      {"comparison.json", io::comparison_json(c)},
      {"comparison.csv", io::comparison_csv(c)},
      {"trajectories.csv", all_trajectories_csv(c)},
      {"stability-map.csv", io::sweep_csv_header(axes, false) + io::sweep_csv_rows(axes, 0, verdicts)},
  };
  if (life) data.emplace_back("lifetime.json", io::lifetime_json(*life));
  const auto assets = detail::web_assets();
  // The explorer (SPEC section 15) beside the report, so that it answers other spins and bodies
  // than its own: the page, starting at this body and motion, with the report's 3D view script.
  const std::optional<std::string> explorer = explorer_page(body, state, !assets.empty());
  if (explorer) data.emplace_back("explore.html", *explorer);
  if (!assets.empty()) data.emplace_back("report-data.js", page_data_js(body, state, c, axes, verdicts, diagram, parts, explorer.has_value()));

  std::ostringstream html;
  const std::string title = fmt::format("{}: {}", source.empty() ? "The built-in example, a wooden toy top" : source,
                                        body_words(body));
  html << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>heavytop: " << html_escape(title)
       << "</title><style>" << kStyle << "</style>\n";
  // Classic scripts beside the page (file:// allows no module imports and no fetch()).
  if (!assets.empty()) html << "<script src='report-data.js'></script>\n<script src='heavytop-report.js' defer></script>\n";
  html << "</head><body>\n<h1>" << html_escape(title) << "</h1>\n";
  // The answer: what a person asks first.
  // The numbers behind the words, to full precision, for scripts and the browser test.
  const auto exact = [](const std::optional<double>& x) { return x ? fmt::format("{:.17g}", *x) : std::string("null"); };
  html << fmt::format("<section id='answer' data-verdict='{}' data-proven='{}' data-falls-at='{}' data-lifetime='{}' "
                      "data-max-tilt='{}' data-min-spin='{}'>\n<h2>Does it stay up?</h2>\n"
                      "<p class='answer {}'><b>{}</b> {}</p>\n",
                      name(answer.verdict), answer.proven, exact(answer.falls_at), exact(answer.lifetime),
                      exact(answer.max_tilt), exact(answer.min_spin),
                      answer.verdict == AnswerVerdict::Falls ? "falls" : answer.proven ? "up" : "unproven",
                      html_escape(io::answer_headline(answer)),
                      html_escape(io::answer_reason(answer) + " " + io::answer_advice(answer)));
  html << fmt::format(
      "<p>Body: A = {:g}, B = {:g}, C = {:g} kg&nbsp;m&sup2;, m = {:g} kg, g = {:g} m/s&sup2;, R = {:g} m "
      "(m g R = {:g} N&nbsp;m, {}). Spin {:g} rad/s ({:.0f} rpm); started {:.3g} degrees ({:.3g} rad) off vertical "
      "(the paper's theta0 = {:g}, phi0 = {:g} rad, rates {:g}, {:g} rad/s).</p>\n",
      body.A, body.B, body.C, body.mass, body.gravity, body.length, body.mgR(),
      body.length > 0 ? "centre of mass above the pivot" : body.length < 0 ? "hanging" : "centre of mass at the pivot",
      state.spin, state.spin * 30.0 / std::numbers::pi, answer.start_tilt * 180.0 / std::numbers::pi,
      answer.start_tilt, state.theta0, state.phi0, state.theta_rate0, state.phi_rate0);
  if (life && life_figure)
    html << "<h3>How long does it stay up?</h3>\n<p>" << html_escape(io::lifetime_text(body, state, *life))
         << "</p>\n"
         << fmt::format("<figure><img src='{0}.svg' alt='{1}'><figcaption>{1} (<a href='{0}.png'>PNG</a>, "
                        "<a href='{0}.svg'>SVG</a>; <a href='lifetime.json'>lifetime.json</a>: as <code>heavytop "
                        "lifetime --format json</code>)</figcaption></figure>\n",
                        life_figure->name, html_escape(life_figure->caption));
  html << "</section>\n";
  html << view_html(c, equivalent_ellipsoid(body), parts);
  html << "<h2>The models: is it stable?</h2>\n<p><i>first-order</i> is the paper's model (4) and its condition (9); "
          "<i>body-fixed</i> its model (5), which the paper itself calls erroneous; <i>linearized</i> the exact "
          "linearisation about the upright spin, the one to trust. A model's <i>critical spin</i> is the slowest spin "
          "at which it is stable.</p>\n"
       << table_html(reports);
  if (reports[0].verdict.stable != reports[2].verdict.stable)
    html << "<p class='note'>The paper's model (4) and the exact linearisation disagree at this spin (erratum E3).</p>\n";
  // The second question: the real body, beyond the linearisation (docs/lyapunov.md).
  const LyapunovVerdict& v = lyapunov.verdict;
  html << fmt::format(
      "<p><b>The real body</b> (nonlinear, conservative{}) at this spin: Lyapunov <b>{}</b> ({}; certificate "
      "<code>{}</code>). Energy index {} (the number of negative stiffnesses: 0 is stable by energy alone); proven "
      "stable for spins (rad/s): {}; superfast {}.{}{}</p>\n",
      body.damping.conservative() ? "" : ", the damping left out of this verdict",
      name(v.verdict), html_escape(v.reason), name(v.certificate), v.energy_index,
      io::intervals_text(lyapunov.intervals),
      lyapunov.superfast ? fmt::format("from {:.6g} rad/s", *lyapunov.superfast) : std::string("at no spin"),
      v.certificate == LyapunovCertificate::CriticalQuartic
          ? std::string(" At the boundary of (9) the linear models grow (a Jordan block: a double frequency whose motion "
                        "grows like t), but the real symmetric top does not: started &delta; off vertical its tilt stays "
                        "below about &radic;(2&delta;) (erratum E2).")
      : v.normal_form
          ? fmt::format(" Birkhoff normal form (order 4): w1 = {:.6g}, w2 = {:.6g} rad/s, c20 = {:.6g}, c11 = {:.6g}, "
                        "c02 = {:.6g}, D = {:.6g}{}; a KAM verdict holds for perturbations small enough (no size given).",
                        v.normal_form->w1, v.normal_form->w2, v.normal_form->c20, v.normal_form->c11, v.normal_form->c02,
                        v.normal_form->D,
                        v.normal_form->a13 ? fmt::format(", at 1:3 with a13 = {:.6g}", *v.normal_form->a13) : std::string())
          : std::string(),
      wander.max_tilt ? fmt::format(" From the given start the axis tilts at most {:.4g} rad ({:.3g} degrees; {}).",
                                    *wander.max_tilt, *wander.max_tilt * 180.0 / std::numbers::pi,
                                    wander.closed_form ? "closed form"
                                                       : fmt::format("integrated over {:g} s", wander.horizon.value_or(0.0)))
                      : std::string());
  html << "<h2>How does it move?</h2>\n<p>Every model from the same start over " << fmt::format("{:.4g}", horizon)
       << " s" << (answer.falls_at && !t_end ? " (up to the fall and a little after)" : "")
       << (body.damping.conservative() ? "" : ", with the damping")
       << ", against the full nonlinear body (" << c.summary.steps << " integrator steps, relative energy drift "
       << fmt::format("{:.1e}", c.summary.max_relative_energy_drift) << ").</p>\n"
       << comparison_html(c);
  html << plots_html(body);
  if (map) {
    std::string keys;
    for (const auto& a : map->map.axes) keys += fmt::format("{}{} ({} values)", keys.empty() ? "" : ", ", a.key, a.values.size());
    html << "<h2>The map " << html_escape(map->file) << "</h2>\n<p>" << map->map.verdicts.size() << " points over "
         << html_escape(keys) << (map->map.nonlinear ? ", with the nonlinear verdict" : "")
         << (map->map.axes.size() == 3 ? "; heat maps at values of one key (the nearest grid values)." : ".") << "</p>\n";
    for (const Figure& f : map_figures)
      html << fmt::format("<figure><img src='{0}.svg' alt='{1}'><figcaption>{1} (<a href='{0}.png'>PNG</a>, "
                          "<a href='{0}.svg'>SVG</a>)</figcaption></figure>\n",
                          f.name, html_escape(f.caption));
  }
  if (explorer)
    html << "<section id='explorer-embed'>\n<h2>Other spins and bodies</h2>\n<p>The explorer answers them live, from this "
            "report's body and motion: change the spin (rad/s or rpm), the tilt, the damping, the body or its parts, or drop "
            "an STL, OBJ or PLY file; the answer, every model's verdict, the Lyapunov verdict, the motion in 3D and a "
            "stability map over two keys of your choice are computed in the page by heavytop's own core in WebAssembly "
            "(nothing installed, nothing sent). <a href='explore.html'>Open the explorer</a> (explore.html, in this folder) "
            "or <button type='button' id='explorer-open'>open it here</button>.</p>\n"
            "<iframe id='explorer-frame' title='heavytop explorer' hidden></iframe>\n"
            "<script>document.getElementById('explorer-open').addEventListener('click', function () {\n"
            "  var f = document.getElementById('explorer-frame'); if (!f.src) f.src = 'explore.html'; f.hidden = false;\n"
            "  this.disabled = true; f.scrollIntoView();\n});</script>\n</section>\n";
  html << "<h2>Figures (for print)</h2>\n";
  for (const Figure& f : figures)
    html << fmt::format("<figure><img src='{0}.svg' alt='{1}'><figcaption>{1} (<a href='{0}.png'>PNG</a>, "
                        "<a href='{0}.svg'>SVG</a>)</figcaption></figure>\n",
                        f.name, html_escape(f.caption));
  html << "<h2>Where the paper is wrong, for this body</h2>\n" << errata_html(body, state, reports);
  html << "<h2>Data</h2>\n<ul><li><a href='stability.json'>stability.json</a>: as <code>heavytop stability --format json</code></li>"
          "<li><a href='comparison.json'>comparison.json</a>, <a href='comparison.csv'>comparison.csv</a>: as "
          "<code>heavytop compare</code></li><li><a href='trajectories.csv'>trajectories.csv</a>: theta, phi of every "
          "model (rad) against t (s)</li><li><a href='stability-map.csv'>stability-map.csv</a>: the map's verdicts</li>"
       << (explorer ? "<li><a href='explore.html'>explore.html</a>: the explorer, starting at this body and motion (as "
                      "<code>heavytop explore</code> writes it)</li>" : "")
       << (assets.empty() ? "" : "<li><a href='report-data.js'>report-data.js</a>: what the interactive view draws "
                                 "(decimated for display, six digits), with the spin angle psi of the nonlinear body</li>")
       << "</ul>\n"
          "<p><small>Made by heavytop. Units SI (angles in rad unless degrees are named); the angles, keys and files are "
          "those of heavytop's contract (docs/contract.md in its repository).</small></p>\n</body></html>\n";
  for (const auto& asset : assets)
    data.emplace_back(asset.name, std::string(reinterpret_cast<const char*>(asset.data), asset.size));
  data.emplace_back("report.html", html.str());  // last: the page appears when all it needs is there

  // Everything is made: put it in place, each file by a temporary name and a rename.
  figures.insert(figures.end(), map_figures.begin(), map_figures.end());
  put_in_place(dir, staging, figures, data);
}


namespace {

/// s, the longest motion a table's report shows without an event (the first part of the
/// answer's horizon: a rolling coin's wobble over the answer's 100 s fills a figure solid).
constexpr double kTableShownHorizon = 10.0;

/// s, the motion a table's report shows: twice the answer's event (the turn-over, the rise to
/// sleep, leaving the table; a fall and a fifth more), so that what follows it shows; else the
/// answer's horizon, at most kTableShownHorizon.
double table_report_horizon(const TableAnswer& a) {
  if (a.falls_at && *a.falls_at > 0.0) return 1.2 * *a.falls_at;
  for (const auto& event : {a.turns_over_at, a.upright_at, a.leaves_at})
    if (event && *event > 0.0) return 2.0 * *event;
  return std::min(a.horizon, kTableShownHorizon);
}

/// The column `name` of a table run.
const std::vector<double>& run_column(const Trajectory& tr, std::string_view name) {
  for (const auto& [key, column] : tr.extra)
    if (key == name && column.size() == tr.size()) return column;
  throw InvalidInput("trajectory", fmt::format("a table run needs its '{}' column", name));
}

/// What the 3D view draws on a table: view_json()'s (the attitude from theta, phi and the spin
/// angle psi, psi' = w3 + theta' sin(phi) with w3 the run's `spin` column) and `table`: O's
/// position at the samples shown (m; O = P + r e_zeta - rho u, u = (cos(tilt) k - e_zeta) /
/// sin(tilt) the rim's direction down to P), P's track, the tip's and rim's radii.
nlohmann::json table_view_json(const Body& body, const Table& table, const Trajectory& run,
                               const std::vector<DrawnPart>& parts) {
  Trajectory attitude = run;  // with the axial momentum C w3 that spin_angles() integrates
  const std::vector<double>& spin = run_column(run, "spin");
  std::vector<double> axial(spin.size());
  for (std::size_t i = 0; i < spin.size(); ++i) axial[i] = body.C * spin[i];
  attitude.extra.emplace_back("axial_momentum", std::move(axial));
  nlohmann::json data = view_json(body, attitude, parts);
  const std::vector<double>& x = run_column(run, "x");
  const std::vector<double>& y = run_column(run, "y");
  const std::vector<double>& height = run_column(run, "height");
  std::vector<double> ox(run.size()), oy(run.size());
  for (std::size_t i = 0; i < run.size(); ++i) {
    const Eigen::Vector3d k = axis_frame(run.phi[i], run.theta[i]).col(2);
    const double s = std::hypot(k.x(), k.y());
    const double across = s > 1e-12 ? body.rim_radius * k.z() / s : 0.0;  // rho cos(tilt) / sin(tilt)
    ox[i] = x[i] - across * k.x();
    oy[i] = y[i] - across * k.y();
  }
  const Shown shown(run.size());
  const auto every = [](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i = 0; i < v.size(); ++i) a.push_back(Shown::value(v, i));
    return a;
  };
  data["table"] = {{"contact", name(table.contact)},
                   {"tip_radius", body.tip_radius},
                   {"rim_radius", body.rim_radius},
                   {"origin", {{"x", shown.pick(ox)}, {"y", shown.pick(oy)}, {"z", shown.pick(height)}}},
                   // P at every computed sample: its small loops at the nutation's frequency alias at the
                   // display's samples.
                   {"track", {{"t", every(run.t)}, {"x", every(x)}, {"y", every(y)}}}};
  return data;
}

/// The 3D view on a table (heavytop-report.js's buildView() with D.table), or the note without it.
std::string table_view_html(const Trajectory& run) {
  if (const char* why = detail::web_assets_missing())
    return fmt::format("<p class='note' id='no-interactive'>No interactive view in this report: {}. The static "
                       "figures below show the same motion.</p>\n", html_escape(why));
  return fmt::format(R"(<section id='interactive'>
<h2>Watch it move</h2>
<p>The full nonlinear motion on the table, as heavytop computed it. The body is drawn as its contact shape (the tip's
sphere, or the rim) or its parts; the red sector turns with the body at its true spin angle. The table is the grid at
height 0; the black line on it is the track of the contact point P so far. Drag to turn the view, scroll to zoom.<span
id='inset-scale' hidden></span></p>
<div id='scene'></div>
<div class='controls'><button id='play'>Pause</button>
<label>speed <input type='range' id='speed' min='0' max='1' step='1'> <span id='speed-value'></span></label>
<label>time <input type='range' id='scrub' min='0' max='10000' value='0' step='1'></label> <span id='time'></span>
<label><input type='checkbox' id='follow' checked> follow the body (untick: the whole track)</label></div>
<p class='note' id='spin-note' hidden></p>
<p><small>Display data: {0} of the {1} computed samples (six digits); <a href='trajectories.csv'>trajectories.csv</a>
has them all.</small></p>
</section>
)",
                     display_samples(run.size()).size(), run.size());
}

}  // namespace

void write_table_report(const std::string& dir, const Body& body, const Table& table, const InitialState& state,
                        std::optional<double> t_end, const std::string& source, const std::vector<DrawnPart>& parts) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InvalidInput("--output", fmt::format("cannot create the folder '{}'", dir));
  const io::OutputLock lock((fs::path(dir) / "report").string(), "--output", dir);
  const Staging staging;

  // The answer first (SPEC 14 and 16), as `stability` gives it; then one run over the motion shown.
  const TableAnalysis analysis = analyse_top_on_table(body, table, state);
  const TableAnswer& answer = analysis.answer;
  const double horizon = t_end.value_or(table_report_horizon(answer));
  const TableRun run = simulate_on_table(body, table, state, SampleGrid{horizon, 4001});
  const Trajectory& tr = run.trajectory;
  const std::vector<Figure> figures = plot_table_motion(staging.path(), run, answer);

  std::vector<std::pair<std::string, std::string>> data = {
      {"stability.json", io::table_stability_json(body, table, analysis, analyse_stability(body, analysis.spin))},
      {"trajectories.csv", io::trajectory_csv(tr)},
  };
  const auto assets = detail::web_assets();
  if (!assets.empty())
    data.emplace_back("report-data.js", "// Written by heavytop report: the numbers behind report.html's interactive "
                                        "view.\nwindow.HEAVYTOP_REPORT = " +
                                            table_view_json(body, table, tr, parts).dump() + ";\n");

  std::ostringstream html;
  const std::string title = fmt::format(
      "{}: {} {} on a table", source.empty() ? "The built-in example" : source,
      is_symmetric(body) ? "a symmetric" : "an asymmetric",
      body.rim_radius > 0.0 ? fmt::format("body on its rim ({:g} m)", body.rim_radius)
      : body.tip_radius > 0.0 ? fmt::format("body on a round tip ({:g} m)", body.tip_radius)
                              : std::string("body on a sharp point"));
  html << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>heavytop: " << html_escape(title)
       << "</title><style>" << kStyle << "</style>\n";
  if (!assets.empty()) html << "<script src='report-data.js'></script>\n<script src='heavytop-report.js' defer></script>\n";
  html << "<style>pre.details { background: #f6f6f6; padding: .8em 1em; white-space: pre-wrap; font-size: .9em; }</style>\n";
  html << "</head><body>\n<h1>" << html_escape(title) << "</h1>\n";
  const auto exact = [](const std::optional<double>& x) { return x ? fmt::format("{:.17g}", *x) : std::string("null"); };
  // The answer's words as `stability` prints them: the headline, then the rest of its text.
  const std::string headline = io::table_answer_headline(answer);
  std::string words = io::table_answer_text(answer, table);
  if (words.rfind(headline, 0) == 0) words.erase(0, headline.size());
  const bool bad = answer.verdict == AnswerVerdict::Falls || answer.verdict == AnswerVerdict::LeavesTable;
  const bool known = answer.proven || answer.verdict == AnswerVerdict::StaysUp;  // an event, or the rise to sleep
  html << fmt::format("<section id='answer' data-verdict='{}' data-proven='{}' data-turns-over-at='{}' "
                      "data-upright-at='{}' data-falls-at='{}' data-leaves-at='{}' data-track='{:.17g}'>\n"
                      "<h2>What does it do on the table?</h2>\n<p class='answer {}'><b>{}</b>{}</p>\n",
                      name(answer.verdict), answer.proven, exact(answer.turns_over_at), exact(answer.upright_at),
                      exact(answer.falls_at), exact(answer.leaves_at), answer.track,
                      bad ? "falls" : known ? "up" : "unproven", html_escape(headline), html_escape(words));
  // The details `stability` gives after the answer: the body and the spinning states.
  std::string details = io::table_stability_text(body, table, analysis);
  if (const auto at = details.find("The details\n"); at != std::string::npos) details.erase(0, at);
  html << "<pre class='details'>" << html_escape(details) << "</pre>\n</section>\n";
  html << table_view_html(tr);
  html << fmt::format("<h2>How does it move?</h2>\n<p>One run of the body on the table over {:.4g} s{} ({} integrator "
                      "steps{}{}{}).</p>\n",
                      tr.size() ? tr.t.back() : 0.0,
                      t_end ? std::string()
                      : answer.turns_over_at || answer.upright_at || answer.falls_at || answer.leaves_at
                          ? std::string(" (past the answer's event, to show what follows)")
                      : answer.horizon > kTableShownHorizon
                          ? fmt::format(" (the first {:g} s of the answer's {:.4g} s; <code>--t-end</code> shows more)",
                                        kTableShownHorizon, answer.horizon)
                          : std::string(" (the answer's horizon)"),
                      run.summary.steps,
                      // Friction takes energy: its drift is the loss, not an error.
                      table.contact == Contact::Sliding
                          ? std::string()
                          : fmt::format(", relative energy drift {:.1e}", run.summary.max_relative_energy_drift),
                      run.summary.switches ? fmt::format(", {} switches between sticking and slipping", run.summary.switches)
                                           : std::string(),
                      run.summary.end == TableSummary::End::LeftTable
                          ? fmt::format("; it leaves the table at t = {:.6g} s, where the run ends", run.summary.end_time)
                          : std::string());
  for (const Figure& f : figures)
    html << fmt::format("<figure id='figure-{0}'><img src='{0}.svg' alt='{1}'><figcaption>{1} (<a href='{0}.png'>PNG</a>, "
                        "<a href='{0}.svg'>SVG</a>)</figcaption></figure>\n",
                        f.name, html_escape(f.caption));
  std::string columns;
  for (const auto& c : tr.column_names()) columns += (columns.empty() ? "" : ", ") + c;
  html << "<h2>Data</h2>\n<ul><li><a href='stability.json'>stability.json</a>: as <code>heavytop stability --format "
          "json</code> on this table</li><li><a href='trajectories.csv'>trajectories.csv</a>: the run, as <code>heavytop "
          "simulate</code> on this table (columns "
       << html_escape(columns) << "; SI units)</li>"
       << (assets.empty() ? "" : "<li><a href='report-data.js'>report-data.js</a>: what the interactive view draws "
                                 "(decimated for display, six digits), with the spin angle psi and O's position</li>")
       << "</ul>\n<p><small>Made by heavytop. Units SI (angles in rad unless degrees are named); the table is SPEC "
          "section 16 (docs/table.md and docs/contract.md in its repository).</small></p>\n</body></html>\n";
  for (const auto& asset : assets)
    data.emplace_back(asset.name, std::string(reinterpret_cast<const char*>(asset.data), asset.size));
  data.emplace_back("report.html", html.str());

  put_in_place(dir, staging, figures, data);
}

namespace {

// Where the explorer page may be: $HEAVYTOP_EXPLORER_PAGE when set (and nowhere else), else beside
// the program (the build tree: build/heavytop and build/web/), where this library's build made it
// (for the Python module, so that its reports are the command's), where it is installed.
std::optional<fs::path> find_explorer_page() {
  std::vector<fs::path> candidates;
  std::error_code ec;
  if (const char* given = std::getenv("HEAVYTOP_EXPLORER_PAGE"))  // only there (a test: "" or a missing file)
    return given[0] && fs::is_regular_file(given, ec) ? std::optional<fs::path>(given) : std::nullopt;
  if (const fs::path self = fs::read_symlink("/proc/self/exe", ec); !ec)
    candidates = {self.parent_path() / "web" / "heavytop-explore.html",
                  self.parent_path().parent_path() / "share" / "heavytop" / "heavytop-explore.html"};
#if defined(HEAVYTOP_EXPLORER_PAGE)
  candidates.emplace_back(HEAVYTOP_EXPLORER_PAGE);
#endif
#if defined(HEAVYTOP_EXPLORER_INSTALLED)
  candidates.emplace_back(HEAVYTOP_EXPLORER_INSTALLED);
#endif
  for (const fs::path& candidate : candidates)
    if (fs::is_regular_file(candidate, ec)) return candidate;
  return std::nullopt;
}

}  // namespace

std::optional<std::string> explorer_page(const Body& body, const InitialState& state, bool shared_view) {
  const auto page = find_explorer_page();
  if (!page) return std::nullopt;
  std::ifstream in(*page, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::optional<std::string> started = io::explorer_page(text.str(), body, state);
  if (!in || !started) throw io::Failure(fmt::format("explore: '{}' is not the explorer page", page->string()));
  std::string html = std::move(*started);
  if (shared_view) {  // web/assemble.cjs puts the view's script between these marks, in a <script> of its own
    const std::string begin = "<script>/*HEAVYTOP_VIEW_BEGIN*/", end = "/*HEAVYTOP_VIEW_END*/</script>";
    const auto from = html.find(begin), to = html.find(end);
    if (from != std::string::npos && to != std::string::npos && to > from)
      html.replace(from, to + end.size() - from, "<script src='heavytop-report.js'></script>");
  }
  return html;
}

std::string view_data(const Body& body, const Trajectory& nonlinear, const std::vector<DrawnPart>& parts) {
  return view_json(body, nonlinear, parts).dump();
}

}  // namespace heavytop::report

#include "heavytop/report/figures.hpp"

#include "heavytop/simulate.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fmt/format.h>

#include "heavytop/frames.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/lyapunov.hpp"
#include "heavytop/stability.hpp"

extern char** environ;

namespace heavytop::report {
using io::Failure;

namespace {

namespace fs = std::filesystem;

struct Style {
  const char* color;
  const char* dash;
  double width;
};

// The models wide, the truth a thin black line drawn last, on top: where a model agrees with
// the truth both stay visible (a coloured band with a black centre line).
const std::map<std::string, Style> kStyles = {
    {"nonlinear", {"#000000", "solid", 1.2}},   {"first-order", {"#1f77b4", "solid", 4.0}},
    {"body-fixed", {"#ff7f0e", "'-'", 3.0}},    {"linearized", {"#2ca02c", "'.'", 4.0}},
    {"lagrange-exact", {"#9467bd", "'_'", 2.5}}};

std::string line_style(const std::string& model) {
  const Style& s = kStyles.at(model);
  return fmt::format("lc rgb {} dt {} lw {}", gnuplot_string(s.color), s.dash, s.width);
}

/// The folder a figure is drawn in (data, script, log and the PNG and SVG it makes). gnuplot
/// runs inside it and every path in a script is a plain relative name, so no path a user
/// chose (a folder name with a quote, say) is ever pasted into a script.
class Scratch {
 public:
  explicit Scratch(std::string dir) : dir_(std::move(dir)) {}
  std::string file(const std::string& name) const { return name; }        // as the script names it
  std::string path(const std::string& name) const { return (fs::path(dir_) / name).string(); }  // for us
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

/// One line from gnuplot's log: its non-empty lines joined (gnuplot puts the message after a
/// blank line and the offending command).
std::string log_line(const std::string& log) {
  std::ifstream in(log);
  std::string text, line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t^");
    if (first == std::string::npos) continue;
    text += (text.empty() ? "" : " / ") + line.substr(first);
  }
  return text.size() > 300 ? text.substr(0, 300) + "..." : text.empty() ? "no message" : text;
}

void run_gnuplot(const Scratch& scratch, const std::string& script, const std::string& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, scratch.dir().c_str());
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::string program = "gnuplot";
  char* argv[] = {program.data(), const_cast<char*>(script.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Failure("gnuplot not found: install Debian's gnuplot-nox (scripts/install-deps.sh)");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Failure(fmt::format("gnuplot failed on the figure '{}': {}", script, log_line(scratch.path(log))));
}

/// Renders `body` (gnuplot commands) to NAME.png and NAME.svg in the scratch folder.
Figure render(const std::string& name, const std::string& caption, const std::string& body, const Scratch& scratch,
              int width = 1400, int height = 900) {
  const std::string body_file = name + ".body.gp";
  std::ofstream(scratch.path(body_file)) << body;
  const std::string script = name + ".gp";
  std::ofstream(scratch.path(script)) << fmt::format(
      "set terminal pngcairo size {w},{h} enhanced font 'DejaVu Sans,18' linewidth 1.5\n"
      "set output {png}\nload {body}\nunset output\n"
      "set terminal svg size {w},{h} enhanced font 'DejaVu Sans,18' linewidth 1.5 background rgb 'white'\n"
      "set output {svg}\nload {body}\nunset output\n",
      fmt::arg("w", width), fmt::arg("h", height), fmt::arg("png", gnuplot_string(name + ".png")),
      fmt::arg("svg", gnuplot_string(name + ".svg")), fmt::arg("body", gnuplot_string(body_file)));
  run_gnuplot(scratch, script, name + ".log");
  return {name, caption};
}

/// rad, a range that shows the true motion with a margin (diverging models leave the plot).
double angle_range(const Comparison& c) {
  double r = 0.0;
  for (std::size_t i = 0; i < c.nonlinear.size(); ++i)
    r = std::max({r, std::abs(c.nonlinear.theta[i]), std::abs(c.nonlinear.phi[i])});
  return r > 0.0 ? 1.4 * r : 1e-3;
}

/// One model's data for the figures.
struct SeriesFile {
  std::string model;
  std::string path;                 ///< as the scripts name it
  std::optional<double> leaves_at;  ///< s, when it first leaves the charts' angle range
};

/// Writes the models' trajectories as t, theta, phi, error (rad), then k_xi, k_eta (the tip of
/// the unit axis seen from above), one file each, the nonlinear body last (drawn last, on top).
/// A model that leaves the angle range +-r is written up to its last sample inside it: drawn
/// further, gnuplot's clipped line to the far-away value would look like a vertical wall.
std::vector<SeriesFile> write_trajectories(const Comparison& c, double r, const Scratch& scratch) {
  std::vector<SeriesFile> files;
  auto write = [&](const std::string& model, const Trajectory& tr) {
    SeriesFile f{model, scratch.file(model + ".dat"), std::nullopt};
    std::ofstream out(scratch.path(f.path));
    auto row = [&](std::size_t i) {
      const Eigen::Vector3d k = axis_frame(tr.phi[i], tr.theta[i]).col(2);
      return fmt::format("{} {} {} {} {} {} {}\n", tr.t[i], tr.theta[i], tr.phi[i], angle_error(tr, c.nonlinear, i),
                         k.x(), k.y(), tilt(tr.theta[i], tr.phi[i]));
    };
    const std::vector<std::size_t> shown = display_samples(tr.size());
    std::size_t next = 0;  // into shown
    for (std::size_t i = 0; i < tr.size(); ++i) {
      if (!(std::abs(tr.theta[i]) <= r && std::abs(tr.phi[i]) <= r)) {
        f.leaves_at = tr.t[i];
        if (i > 0) {  // the line ends at the last sample inside, marked
          out << row(i - 1);
          std::ofstream(scratch.path(model + ".exit")) << row(i - 1);
        }
        break;
      }
      if (next < shown.size() && shown[next] == i) {
        // theta = atan2(k_xi, k_zeta) jumps by 2 pi when the axis passes below the horizontal:
        // a blank line breaks the curve there instead of drawing the jump as a wall.
        if (next > 0 && std::abs(tr.theta[i] - tr.theta[shown[next - 1]]) > std::numbers::pi) out << "\n";
        out << row(i);
        ++next;
      }
    }
    files.push_back(f);
  };
  for (const auto& m : c.models) write(m.model, m.trajectory);
  write("nonlinear", c.nonlinear);
  return files;
}

/// The plot command's list: one line per model, the truth last; a model that leaves the chart
/// says when in its title and ends in a cross.
std::string plot_list(const std::vector<SeriesFile>& files, const std::string& columns, bool skip_truth = false) {
  std::string list;
  for (const SeriesFile& f : files) {
    if (skip_truth && f.model == "nonlinear") continue;
    const std::string title = f.leaves_at ? fmt::format("{} (leaves the chart at {:.3g} s)", f.model, *f.leaves_at)
                                          : f.model == "nonlinear" ? std::string("nonlinear (truth)") : f.model;
    list += fmt::format("{}{} using {} with lines {} title {}", list.empty() ? "" : ", \\\n  ", gnuplot_string(f.path),
                        columns, line_style(f.model), gnuplot_string(title));
    if (f.leaves_at)
      list += fmt::format(", \\\n  {} using {} with points pt 2 ps 2.5 lw 3 lc rgb {} notitle",
                          gnuplot_string(f.model + ".exit"), columns, gnuplot_string(kStyles.at(f.model).color));
  }
  return list + "\n";
}

}  // namespace

std::string gnuplot_string(std::string_view text) {
  std::string out = "\"";
  bool after_octal = false;
  for (const char c : io::printable(text)) {
    // gnuplot reads every octal digit after a backslash into one escape: a digit that follows
    // an octal escape is one too.
    const bool octal = c == '`' || (after_octal && c >= '0' && c <= '7');
    if (octal) out += fmt::format("\\{:03o}", static_cast<unsigned char>(c));
    else if (c == '"' || c == '\\') out += {'\\', c};
    else out += c;
    after_octal = octal;
  }
  return out + "\"";
}

std::pair<const char*, const char*> diagram_words(const Body& body) {
  return body.length < 0.0 ? std::pair{"axis stays near the vertical", "axis swings out"} : std::pair{"stays up", "falls"};
}

std::vector<std::size_t> display_samples(std::size_t n) {
  const std::size_t stride = n > kDisplaySamples ? (n - 1 + kDisplaySamples - 2) / (kDisplaySamples - 1) : 1;
  std::vector<std::size_t> shown;
  for (std::size_t i = 0; i < n; i += stride) shown.push_back(i);
  if (n && shown.back() != n - 1) shown.push_back(n - 1);
  return shown;
}

AngleUnit angle_unit(const Comparison& c) {
  return angle_range(c) < 0.2 ? AngleUnit{1e3, "mrad"} : AngleUnit{1.0, "rad"};
}

double angle_error(const Trajectory& model, const Trajectory& truth, std::size_t i) {
  return std::max(std::abs(model.theta[i] - truth.theta[i]), std::abs(model.phi[i] - truth.phi[i]));
}

std::vector<Figure> plot_motion(const std::string& dir, const Comparison& c) {
  const Scratch scratch(dir);
  const double r = angle_range(c);
  const auto files = write_trajectories(c, r, scratch);  // once, for all three figures
  const AngleUnit unit = angle_unit(c);
  std::vector<Figure> figures;
  // The key in its own column right of the frames (long titles never reach into them).
  const char* key = "set key outside right top Left reverse width 1\nset rmargin at screen 0.68\n";

  // First what people read: the tilt from the vertical, in degrees (rad on the right axis).
  double largest_tilt = 0.0;
  for (std::size_t i = 0; i < c.nonlinear.size(); ++i)
    largest_tilt = std::max(largest_tilt, tilt(c.nonlinear.theta[i], c.nonlinear.phi[i]));
  const double tilt_top = std::min(largest_tilt > 0.0 ? 1.25 * largest_tilt : 1e-3, std::numbers::pi) * 180.0 /
                          std::numbers::pi;
  // Round ticks on both axes: rad at 1, 2 or 5 times a power of ten, about five of them.
  const double rad_top = tilt_top * std::numbers::pi / 180.0;
  const double decade = std::pow(10.0, std::floor(std::log10(rad_top / 5.0)));
  const double rad_step = rad_top / 5.0 / decade < 2.0 ? decade : rad_top / 5.0 / decade < 5.0 ? 2.0 * decade : 5.0 * decade;
  std::string tilts = fmt::format(
      "set title 'Tilt of the axis from the vertical: every model from the same start'\nset grid\n"
      "set key outside bottom center horizontal Left reverse width 2\n"
      "set yrange [0:{0}]\nset format y '%g'\nset ylabel 'tilt (degrees)'\nset y2tics {1:g}\nset format y2 '%g'\n"
      "set link y2 via y*pi/180 inverse y*180/pi\nset y2label 'tilt (rad)'\nset xlabel 't (s)'\nplot ",
      tilt_top, rad_step);
  tilts += plot_list(files, "1:($7*180/pi)");
  figures.push_back(render("tilt", "The tilt of the axis from the upward vertical against time (degrees on the left, "
                           "rad on the right); the nonlinear body (black, drawn on top) is the truth.",
                           tilts, scratch, 1500, 800));

  // From above (looking down zeta, xi to the right, eta up) the tip of the unit axis is at
  // (k_xi, k_eta) = (sin theta cos phi, -sin phi), to first order (theta, -phi): plotting
  // (theta, phi) would show the mirror image, the precession turning the wrong way.
  std::string path = fmt::format(
      "set title 'Path of the axis tip seen from above: nutation loops and cusps'\nset grid\nset size ratio -1\n"
      "{0}set xrange [{1}:{2}]\nset yrange [{1}:{2}]\nset format x '%g'\nset format y '%g'\n"
      "set xlabel {3}\nset ylabel {4}\nplot ",
      key, -std::min(r, 1.05) * unit.scale, std::min(r, 1.05) * unit.scale,  // |k_xi|, |k_eta| <= 1
      gnuplot_string(fmt::format("xi: k_{{xi}} ({}), about theta", unit.name)),
      gnuplot_string(fmt::format("eta: k_{{eta}} ({}), about -phi", unit.name)));
  path += plot_list(files, fmt::format("($5*{0}):($6*{0})", unit.scale));
  figures.push_back(render("axis-path", "The tip of the axis seen from above (xi to the right, eta up; to first order "
                           "(theta, -phi)), every model: the nutation loops and cusps as the precession carries them round.",
                           path, scratch, 1500, 1000));

  std::string angles = fmt::format(
      "set multiplot layout 2,1 title {3}\n"
      "set grid\n{0}set yrange [{1}:{2}]\nset format y '%g'\nset ylabel {4}\nunset xlabel\n",
      key, -r * unit.scale, r * unit.scale,
      gnuplot_string("The paper's angles theta, phi: every model from the same start"),
      gnuplot_string(fmt::format("theta ({})", unit.name)));
  const std::string theta = fmt::format("1:($2*{})", unit.scale), phi = fmt::format("1:($3*{})", unit.scale);
  angles += "plot " + plot_list(files, theta);
  angles += fmt::format("set ylabel {}\nset xlabel 't (s)'\nunset key\n", gnuplot_string(fmt::format("phi ({})", unit.name)));
  angles += "plot " + plot_list(files, phi);
  angles += "unset multiplot\n";
  figures.push_back(render("angles", "The paper's small angles theta(t) and phi(t) of every model (they swing "
                           "through zero as the axis goes round, while the tilt above stays put); the nonlinear body (black, drawn on top) is "
                           "the truth; a model that leaves the chart ends in a cross, its title says when.",
                           angles, scratch, 1500, 1000));

  std::string errors = std::string("set title 'Error of each model against the nonlinear body'\nset grid\nset logscale y\n"
                                   "set format y '10^{%L}'\n") + key +
                       "set xlabel 't (s)'\nset ylabel 'max(|d theta|, |d phi|) (rad)'\nplot ";
  // A model exact to rounding everywhere (the sleeping top: nothing moves) has no point to
  // draw on a log scale; then the chart says so instead of failing.
  double largest = 0.0;
  for (const auto& m : c.models)
    if (!m.diverged_at) largest = std::max(largest, m.max_angle_error);
  if (largest > 1e-17) errors += plot_list(files, "1:($4 > 1e-17 ? $4 : 1/0)", true);
  else errors += fmt::format("[0:{}] [1e-18:1e-15] 1e-17 with lines lc rgb '#888888' title 'every model: error below 1e-17 rad'\n",
                             c.nonlinear.t.empty() || c.nonlinear.t.back() <= 0.0 ? 1.0 : c.nonlinear.t.back());
  figures.push_back(render("errors", "The angle error of each model against time, on a log scale.", errors, scratch, 1500, 900));
  return figures;
}

Figure plot_stability_diagram(const std::string& dir, const Body& body, const InitialState& state, DiagramGrid* grid,
                              const Progress& progress) {
  const Scratch scratch(dir);
  // B/A over every value a real body allows with A and C held, |C - A| <= B <= C + A.
  const auto [lo, hi] = realizable_ratio_range(body);
  const int n = 300;
  double top = std::abs(state.spin);
  std::map<std::string, std::ofstream> ends;
  for (LinearModelKind kind : kLinearModels) ends[std::string(name(kind))].open(scratch.path(std::string(name(kind)) + ".ends"));
  for (int i = 0; i < n; ++i) {
    const double ratio = lo + (hi - lo) * i / (n - 1);
    Body b = body;
    b.B = ratio * body.A;
    for (LinearModelKind kind : kLinearModels) {
      for (const SpinInterval& iv : stable_spin_intervals(linear_model(kind, b))) {
        if (iv.lo > 0.0) ends[std::string(name(kind))] << fmt::format("{} {}\n", ratio, iv.lo);
        if (iv.hi) ends[std::string(name(kind))] << fmt::format("{} {}\n", ratio, *iv.hi);
        if (kind != LinearModelKind::BodyFixed) top = std::max(top, iv.hi ? *iv.hi : iv.lo);
      }
    }
  }
  for (auto& [model, file] : ends) file.close();
  top = top > 0.0 ? 1.6 * top : 1.0;

  // The practical verdict of the nonlinear body on a coarse grid.
  std::vector<SweepAxis> axes{{"B/A", lo + 0.02 * (hi - lo), hi - 0.02 * (hi - lo), 16}, {"spin", top / 15.0, top, 15}};
  InitialState start = state;
  start.theta0 = 1e-3;
  start.phi0 = start.theta_rate0 = start.phi_rate0 = 0.0;
  SweepOptions options;
  options.nonlinear = true;
  options.max_tilt = 0.5;
  const double scale = std::isfinite(gravity_time(body)) ? gravity_time(body) : 1.0;
  options.horizon = 300.0 * scale;
  // A verdict follows the body's phase over the horizon, so its cost grows as spin x horizon:
  // at 1.8e19 rad/s it ran for hours. Beyond a budget (the toy top to about 4e4 rad/s, some
  // ten seconds) the nonlinear verdicts are left out, and the figure says so.
  constexpr double kPhaseBudget = 1e6;  // rad, at the grid's fastest spin over the horizon
  options.nonlinear = top * options.horizon <= kPhaseBudget;
  options.integrator.rtol = options.integrator.atol = 1e-8;
  std::ofstream up(scratch.path("up.dat")), falls(scratch.path("falls.dat"));
  // In blocks, so that `progress` is called between them (sweep_verdicts takes none).
  std::vector<SweepVerdict> verdicts;
  for (std::size_t begin = 0, total = grid_size(axes); begin < total; begin += 256) {
    if (progress) progress(0.0);
    const auto block = sweep_verdicts(body, start, axes, options, begin, std::min(total, begin + 256));
    verdicts.insert(verdicts.end(), block.begin(), block.end());
  }
  for (std::size_t i = 0; i < verdicts.size() && options.nonlinear; ++i) {
    const auto point = grid_values(axes, i);
    (*verdicts[i].nonlinear ? up : falls) << fmt::format("{} {}\n", point[0], point[1]);
  }
  up.close();
  falls.close();
  if (grid)
    *grid = DiagramGrid{axes, options.nonlinear ? verdicts : std::vector<SweepVerdict>{}, start.theta0, options.max_tilt,
                        options.horizon};
  // "Stands up" is a top's word; a hanging body (R < 0) hangs, its axis stays near the vertical.
  const bool hanging = body.length < 0.0;

  std::string plot = fmt::format(
      "set title {}\n"
      "set grid\nset key outside below center maxrows 2 width -2\nset xlabel 'B/A'\nset ylabel 'spin w0 (rad/s)'\n"
      "set xrange [{}:{}]\nset yrange [0:{}]\n"
      "plot {} using 1:2 with points pt 7 ps 0.7 lc rgb '#1f77b4' title 'ends of stable spins: first-order (4)', \\\n"
      "  {} using 1:2 with points pt 7 ps 0.7 lc rgb '#ff7f0e' title 'body-fixed (5)', \\\n"
      "  {} using 1:2 with points pt 7 ps 0.7 lc rgb '#2ca02c' title 'linearized (exact)', \\\n"
      "{}"
      "  '-' using 1:2 with points pt 3 ps 3 lw 3 lc rgb 'black' title 'this body'\n{} {}\ne\n",
      gnuplot_string(fmt::format("{} (A = {:g}, C = {:g} kg m^2 held)",
                                 hanging ? "Where the hanging body spins steadily" : "Where the top stands up", body.A, body.C)),
      lo, hi, top, gnuplot_string(scratch.file("first-order.ends")), gnuplot_string(scratch.file("body-fixed.ends")),
      gnuplot_string(scratch.file("linearized.ends")),
      options.nonlinear
          ? fmt::format("  {} using 1:2 with points pt 6 ps 1.4 lw 2 lc rgb '#2ca02c' title {}, \\\n"
                        "  {} using 1:2 with points pt 2 ps 1.4 lw 2 lc rgb '#d62728' title {}, \\\n",
                        gnuplot_string(scratch.file("up.dat")), gnuplot_string(fmt::format("nonlinear: {}", diagram_words(body).first)),
                        gnuplot_string(scratch.file("falls.dat")),
                        gnuplot_string(fmt::format("nonlinear: {}", diagram_words(body).second)))
          : std::string("  1/0 with points pt 6 ps 1.4 lw 2 lc rgb '#888888' title 'nonlinear: not computed (spin too fast)', \\\n"),
      body.B / body.A, std::abs(state.spin));
  const std::string omitted =
      options.nonlinear ? ""
                        : fmt::format(" The nonlinear verdicts are left out: at spins up to {:.3g} rad/s over {:.3g} s each would "
                                      "follow more than {:g} rad of the body's phase (`heavytop simulate --model nonlinear` "
                                      "computes any one of them).",
                                      top, options.horizon, kPhaseBudget);
  return render("stability-diagram",
                "Ends of the stable spin intervals of each linear model as B/A varies, and the nonlinear body's "
                "verdict (started 1e-3 rad off vertical) on a grid: where (4) and the exact linearisation part, "
                "the paper's (9) is wrong (erratum E3)." + omitted,
                plot, scratch, 1500, 950);
}

Figure plot_wander(const std::string& dir, const Body& body, std::optional<double> critical_spin,
                   const Progress& progress) {
  const Scratch scratch(dir);
  const bool exact = is_symmetric(body);
  const double critical = critical_spin.value_or(0.0);
  const double top = critical > 0.0 ? 2.0 * critical : 10.0 / (std::isfinite(gravity_time(body)) ? gravity_time(body) : 1.0);
  const int n = exact ? 400 : 40;  // the integrated curve costs a nonlinear run a point
  Tolerances options;
  options.rtol = options.atol = 1e-9;
  const double horizon = 50.0 * (std::isfinite(gravity_time(body)) ? gravity_time(body) : 1.0);
  std::string plot_list;
  for (double delta : {1e-3, 1e-2}) {
    const std::string file = fmt::format("wander-{:g}.dat", delta);
    std::ofstream out(scratch.path(file));
    for (int i = 1; i <= n; ++i) {
      const InitialState start{.spin = top * i / n, .theta0 = delta};
      const Wander w = axis_wander(body, start, horizon, options, progress);
      if (w.max_tilt && *w.max_tilt > 0.0) out << fmt::format("{} {}\n", start.spin, *w.max_tilt);
    }
    plot_list += fmt::format("{}{} using 1:2 with linespoints pt 7 ps 0.5 lw 2 title {}, "
                             "{:g} with lines dt 2 lc rgb '#888888' title {}",
                             plot_list.empty() ? "" : ", ", gnuplot_string(file),
                             gnuplot_string(fmt::format("started {:g} rad off vertical", delta)), std::sqrt(2.0 * delta),
                             gnuplot_string(fmt::format("sqrt(2 x {:g})", delta)));
  }
  std::string plot = fmt::format(
      "set title {}\nset grid\nset logscale y\nset format y '10^{{%L}}'\n"
      "set key outside below center maxrows 2\nset xlabel 'spin w0 (rad/s)'\nset ylabel 'largest tilt (rad)'\n"
      "set xrange [0:{}]\nset yrange [1e-4:4]\n",
      gnuplot_string(fmt::format("How far the axis wanders ({})",
                                 exact ? "exact: the Lagrange top" : fmt::format("integrated over {:.3g} s", horizon))),
      top);
  if (critical > 0.0)
    plot += fmt::format("set arrow from {0},1e-4 to {0},4 nohead lc rgb '#d62728' lw 2\n"
                        "set label {1} at {0},2e-4 right offset -1,0 tc rgb '#d62728'\n",
                        critical, gnuplot_string(fmt::format("critical spin {:.6g} rad/s", critical)));
  plot += "plot " + plot_list + "\n";
  return render("wander",
                "The largest tilt of the axis against the spin for a start delta off vertical: above the critical "
                "spin it stays near delta; at the boundary of (9) the real top is still stable, its tilt bounded by "
                "about sqrt(2 delta) (dashed), although the linear models grow there; below it the axis swings out.",
                plot, scratch, 1500, 950);
}

Figure plot_sweep_map(const std::string& dir, const StabilityMap& map, const std::string& name,
                      const std::string& where) {
  const Scratch scratch(dir);
  const std::string data = scratch.file(name + ".dat");
  // Against the exact linearisation: the paper's (4), or the real body when the map has it.
  const bool truth = map.nonlinear;
  {
    std::ofstream out(scratch.path(data));
    const auto& [first, second] = std::pair{map.axes.at(0), map.axes.at(1)};
    for (std::size_t i = 0; i < map.verdicts.size(); ++i) {
      // 0 neither, 1 only the first (a false promise), 2 only the second (too strict), 3 both.
      const SweepVerdict& v = map.verdicts[i];
      const int category = truth ? int(v.linear[2]) + 2 * int(v.nonlinear.value_or(false))
                                 : int(v.linear[0]) + 2 * int(v.linear[2]);
      out << fmt::format("{} {} {}\n", first.values[i / second.values.size()], second.values[i % second.values.size()],
                         category);
      if ((i + 1) % second.values.size() == 0) out << "\n";
    }
  }
  auto label = [](const std::string& key) {
    return key == "spin" ? std::string("spin w0 (rad/s)") : key == "spin_rpm" ? std::string("spin w0 (rpm)")
         : key == "B/A" || key == "C/A" ? key
         : key == "length" ? std::string("length R (m)") : key == "mass" ? std::string("mass (kg)")
         : key == "gravity" ? std::string("gravity (m/s^2)") : key + " (kg m^2)";
  };
  const char* one = truth ? "the exact linearisation" : "the paper (4)";
  const char* two = truth ? "the real body" : "the exact linearisation";
  const std::string plot = fmt::format(
      "set title {}\n"
      "set xlabel {}\nset ylabel {}\nset tics out\nset autoscale fix\n"
      "set palette maxcolors 4\nset palette defined (0 '#d9d9d9', 1 '#d62728', 2 '#1f77b4', 3 '#2ca02c')\n"
      "set cbrange [-0.5:3.5]\n"
      "set cbtics ('both unstable' 0, {} 1.15, 'a false promise' 0.85, {} 2.15, "
      "{} 1.85, 'both stable' 3) scale 0\n"
      "set colorbox user origin 0.72,0.15 size 0.03,0.7\nset rmargin at screen 0.70\n"
      "plot {} using 1:2:3 with image notitle\n",
      gnuplot_string(fmt::format("Stability map{}: {} against {}", where.empty() ? "" : " " + where, one, two)),
      gnuplot_string(label(map.axes[0].key)), gnuplot_string(label(map.axes[1].key)),
      gnuplot_string(fmt::format("only {} stable:", truth ? "the linearisation" : "(4)")),
      gnuplot_string(fmt::format("only {} stable:", truth ? "the real body" : "the exact")),
      gnuplot_string(truth ? "(linearly unstable)" : "(9) too strict"), gnuplot_string(data));
  const std::string caption =
      truth ? fmt::format("Each grid point{} coloured by the verdicts of the exact linearisation and of the nonlinear "
                          "simulation: red where the linearisation promises a stability the real body does not keep "
                          "over the horizon, blue where the body stays up though linearly unstable.",
                          where.empty() ? "" : " " + where)
            : fmt::format("Each grid point{} coloured by the verdicts of (4) and of the exact linearisation: red where "
                          "the paper promises a stability that is not there, blue where it is too strict.",
                          where.empty() ? "" : " " + where);
  return render(name, caption, plot, scratch, 1500, 950);
}

Figure plot_lifetime(const std::string& dir, const Body& body, const InitialState& state, const Lifetime& life,
                     const Progress& progress) {
  const Scratch scratch(dir);
  // The run to a little past the fall (or over the horizon), sampled for the eye.
  const double end = life.fall_time ? std::min(life.horizon, 1.05 * *life.fall_time) : life.horizon;
  const Simulation run = simulate(Model::Nonlinear, body, state, sample_times(end, kDisplaySamples), {}, progress);
  const Trajectory& tr = run.trajectory;
  const std::vector<double>* axial = nullptr;
  for (const auto& [name, column] : tr.extra)
    if (name == "axial_momentum") axial = &column;
  const std::string data = scratch.file("lifetime.dat");
  {
    std::ofstream out(scratch.path(data));
    for (std::size_t i = 0; i < tr.size(); ++i) {
      // The tilt from the upward vertical, acos(k_zeta), k_zeta = cos theta cos phi (SPEC section 2).
      const double tilt = std::acos(std::clamp(std::cos(tr.theta[i]) * std::cos(tr.phi[i]), -1.0, 1.0));
      out << fmt::format("{} {} {}\n", tr.t[i], axial ? (*axial)[i] / body.C : state.spin, tilt);
    }
  }
  std::string marks;
  if (life.critical_spin && *life.critical_spin > 0.0)
    marks += fmt::format("{:g} axes x1y1 with lines dt 2 lw 2 lc rgb '#d62728' title {}, ", *life.critical_spin,
                         gnuplot_string(fmt::format("critical spin {:.4g} rad/s", *life.critical_spin)));
  std::string arrows;
  if (life.time_to_critical && *life.time_to_critical > 0.0)
    arrows += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead dt 3 lc rgb '#d62728'\n"
                          "set label {1} at {0},graph 0.95 left offset 0.5,0 tc rgb '#d62728'\n",
                          *life.time_to_critical,
                          gnuplot_string(fmt::format("spin law: critical at {:.4g} s", *life.time_to_critical)));
  if (life.fall_time)
    arrows += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead lw 2 lc rgb '#000000'\n"
                          "set label {1} at {0},graph 0.85 right offset -0.5,0\n",
                          *life.fall_time, gnuplot_string(fmt::format("falls at {:.4g} s", *life.fall_time)));
  const std::string plot = fmt::format(
      "set title 'How long it stays up'\nset grid\nset key outside below center maxrows 2\n"
      "set xlabel 't (s)'\nset ylabel 'spin w.k (rad/s)'\nset y2label 'tilt from the vertical (rad)'\n"
      "set ytics nomirror\nset y2tics\nset xrange [0:{}]\nset yrange [0:*]\nset y2range [0:*]\n{}"
      "plot {}{} using 1:2 axes x1y1 with lines lw 3 lc rgb '#1f77b4' title 'spin (integrated)', "
      "'' using 1:3 axes x1y2 with lines lw 2 lc rgb '#2ca02c' title 'tilt (nonlinear, damped)'\n",
      end, arrows, marks, gnuplot_string(data));
  return render("lifetime",
                "The spin and the tilt of the damped top against time: the spin decays by the torques of SPEC "
                "section 6 through the critical spin (dashed), after which the tilt grows until the top falls.",
                plot, scratch, 1500, 950);
}

}  // namespace heavytop::report

namespace heavytop::report {

namespace {

/// The column `name` of a table run (simulate_on_table's extra columns).
const std::vector<double>& table_column(const Trajectory& tr, std::string_view name) {
  for (const auto& [key, column] : tr.extra)
    if (key == name && column.size() == tr.size()) return column;
  throw InvalidInput("trajectory", fmt::format("a table run needs its '{}' column", name));
}

}  // namespace

std::vector<Figure> plot_table_motion(const std::string& dir, const TableRun& run, const TableAnswer& answer) {
  const Scratch scratch(dir);
  const Trajectory& tr = run.trajectory;
  const std::vector<double>& tilt = table_column(tr, "tilt");
  const std::vector<double>& spin = table_column(tr, "spin");
  const std::vector<double>& x = table_column(tr, "x");
  const std::vector<double>& y = table_column(tr, "y");
  // The track in mm when it stays within 10 cm of where it started (a tippe top's few mm), else m.
  double reach = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i) reach = std::max({reach, std::abs(x[i]), std::abs(y[i])});
  const bool mm = reach < 0.1;
  const double unit = mm ? 1e3 : 1.0;
  const char* unit_name = mm ? "mm" : "m";
  const std::string data = scratch.file("table.dat");
  {
    std::ofstream out(scratch.path(data));
    // Every sample (the run's 4001): the tilt's nutation and P's small loops would alias at fewer.
    for (std::size_t i = 0; i < tr.size(); ++i)
      out << fmt::format("{} {} {} {} {}\n", tr.t[i], tilt[i] * 180.0 / std::numbers::pi, spin[i], x[i] * unit,
                         y[i] * unit);
  }
  // The answer's events, each a vertical line on the tilt's figure and a point on the track.
  struct Event {
    double t;
    std::string words;
  };
  std::vector<Event> events;
  if (answer.turns_over_at) events.push_back({*answer.turns_over_at, "turns over"});
  if (answer.upright_at) events.push_back({*answer.upright_at, "upright"});
  if (answer.falls_at) events.push_back({*answer.falls_at, "falls"});
  if (answer.leaves_at) events.push_back({*answer.leaves_at, "leaves the table"});
  const double end = tr.size() ? tr.t.back() : 0.0;
  std::string arrows, points;
  std::size_t k = 0;
  for (const Event& e : events) {
    if (!(e.t >= 0.0 && e.t <= end)) continue;
    arrows += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead dt 2 lw 2 lc rgb '#d62728'\n"
                          "set label '{1} at {0:.4g} s' at {0},graph {2} left offset 0.5,0 tc rgb '#d62728'\n",
                          e.t, e.words, 0.95 - 0.07 * double(k));
    // P at the event (the nearest sample).
    const auto at = std::lower_bound(tr.t.begin(), tr.t.end(), e.t) - tr.t.begin();
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(at), tr.size() - 1);
    points += fmt::format("set label '{}' at {},{} point pt 9 ps 2.2 lc rgb '#d62728' offset 1,1 tc rgb '#d62728'\n",
                          e.words, x[i] * unit, y[i] * unit);
    ++k;
  }
  double top = 0.0;
  for (double v : tilt) top = std::max(top, v * 180.0 / std::numbers::pi);
  const bool past_quarter = top > 80.0;
  // The spin's axis from 0 (a small change of a fast spin reads as what it is).
  double spin_lo = 0.0, spin_hi = 0.0;
  for (double w : spin) spin_lo = std::min(spin_lo, w), spin_hi = std::max(spin_hi, w);
  const std::string tilt_plot = fmt::format(
      "set title 'The tilt on the table'\nset grid\nset key outside top center horizontal maxrows 1 samplen 2\n"
      "set xlabel 't (s)'\nset ylabel 'tilt from the upward vertical (degrees)'\nset y2label 'spin w.k (rad/s)'\n"
      "set ytics nomirror{}\nset y2tics\nset xrange [0:{}]\nset yrange [0:{}]\nset y2range [{}:{}]\n{}"
      "plot '{}' using 1:2 axes x1y1 with lines lw 2 lc rgb '#2ca02c' title 'tilt', "
      "'' using 1:3 axes x1y2 with lines lw 2 lc rgb '#1f77b4' title 'spin w.k'{}\n",
      past_quarter ? " 30" : "", end, past_quarter ? "180" : "*", 1.05 * spin_lo, spin_hi > 0.0 ? 1.05 * spin_hi : 1.0,
      arrows, data,
      past_quarter ? ", 90 axes x1y1 with lines dt 3 lw 1.5 lc rgb '#555555' title 'a quarter turn (90 degrees)'" : "");
  std::vector<Figure> out;
  out.push_back(render("tilt",
                       fmt::format("The tilt of the axis from the upward vertical (green, degrees) and the spin about "
                                   "the axis (blue, rad/s) against time over {:.4g} s{}.",
                                   end, events.empty() ? "" : ", the answer's events marked (red)"),
                       tilt_plot, scratch, 1500, 900));
  const std::string track_plot = fmt::format(
      "set title 'The track of the contact point P, seen from above'\nset grid\n"
      "set key outside top center horizontal maxrows 1 samplen 2\n"
      "set size ratio -1\nset xlabel 'x ({0})'\nset ylabel 'y ({0})'\nset offsets graph 0.05, graph 0.05, graph 0.05, "
      "graph 0.05\n{1}"
      "plot '{2}' using 4:5 with lines lw 2.5 lc rgb '#000000' title 'P on the table', "
      "'' every ::0::0 using 4:5 with points pt 7 ps 2 lc rgb '#2ca02c' title 'start (t = 0)', "
      "'' every ::{3}::{3} using 4:5 with points pt 5 ps 2 lc rgb '#1f77b4' title 'end (t = {4:.4g} s)'\n",
      unit_name, points, data, tr.size() - 1, end);
  // The canvas shaped like the track (x and y to the same scale), 1400 wide, 500 to 1400 high.
  double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i)
    x_lo = std::min(x_lo, x[i]), x_hi = std::max(x_hi, x[i]), y_lo = std::min(y_lo, y[i]), y_hi = std::max(y_hi, y[i]);
  const double aspect = (y_hi - y_lo) / std::max(x_hi - x_lo, 1e-12);
  const int track_height = static_cast<int>(std::clamp(1100.0 * aspect + 330.0, 500.0, 1400.0));
  out.push_back(render("track",
                       fmt::format("The contact point P on the table seen from above ({}, x and y to the same scale) "
                                   "over {:.4g} s: the start (green), the end (blue){}.",
                                   unit_name, end, events.empty() ? "" : ", the answer's events (red)"),
                       track_plot, scratch, 1400, track_height));
  return out;
}

}  // namespace heavytop::report

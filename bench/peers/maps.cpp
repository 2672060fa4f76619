// The nonlinear column of a 40 x 40 stability map (horizon 50 s, max tilt 0.5 rad) in heavytop
// against a GSL rk8pd loop, per core, side by side in one run (issue 31). Built and run by
// bench/peers/run.sh (by hand, not in CI).
//
// Maps (bench_sweep's two, on 40 x 40 grids):
//   plate  examples/asymmetric-plate.toml's body, B/A = 1.05:2.95:40 x spin = 0.5:4:40 rad/s
//   toy    examples/toy-top.toml's body (theta0 0.05 rad), C/A = 0.15:0.6:40 x spin = 50:400:40 rad/s
// Ways, each the verdict "tilt stays <= 0.5 rad over 50 s" at all 1600 points on one thread:
//   heavytop default   batch_tilt_verdicts() at the sweep's default rtol = atol = 1e-12 (today's
//                      `heavytop sweep` nonlinear column); its verdicts are the map's reference
//   heavytop decided   decided_tilt_verdicts() (verdicts.hpp, when this heavytop has it): each
//                      verdict at the loosest tolerance that decides it
//   GSL 1e-12          rk8pd on Euler-Poisson (gamma, w), the torque with gamma / |gamma|^2,
//                      control y_new(tol, tol), the tilt tested at each step's end (a GSL
//                      user's loop: rk8pd has no dense output at its order)
//   GSL loosest        the same at the loosest tolerance 10^(-k/4) (k = 8..48) whose map equals
//                      heavytop default's, point for point (the tolerance a GSL user who knew the
//                      answer would pick; found outside the timing)
// Times: CPU time of this thread, REPS rounds with the ways interleaved, medians; ratios of the
// medians of the same rounds.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "heavytop/heavytop.hpp"
#include "timing.hpp"
#if __has_include("heavytop/verdicts.hpp")
#include "heavytop/verdicts.hpp"
#define HEAVYTOP_PEERS_DECIDED 1
#endif

namespace {

using namespace heavytop;
using peers::cpu_seconds, peers::median, peers::warm_up;

constexpr double kHorizon = 50.0, kMaxTilt = 0.5;

struct Map {
  std::string name;
  std::vector<Body> bodies;
  std::vector<InitialState> starts;
};

Map map(int which) {
  Map m;
  Body base;
  InitialState start;
  std::vector<SweepAxis> axes;
  if (which == 0) {
    m.name = "plate";
    base.A = 0.010, base.B = 0.015, base.C = 0.020, base.mass = 1.0, base.length = 1.0193679918450561e-3;
    start.spin = 1.3, start.theta0 = 1e-4;
    axes = {parse_sweep_axis("B/A=1.05:2.95:40"), parse_sweep_axis("spin=0.5:4:40")};
  } else {
    m.name = "toy";
    base = example_toy_top();
    start.spin = 200.0, start.theta0 = 0.05;
    axes = {parse_sweep_axis("C/A=0.15:0.6:40"), parse_sweep_axis("spin=50:400:40")};
  }
  for (std::size_t i = 0; i < grid_size(axes); ++i) {
    Body b = base;
    InitialState s = start;
    apply_grid_point(axes, i, b, s);
    m.bodies.push_back(b), m.starts.push_back(s);
  }
  return m;
}

// ---- GSL: Euler-Poisson in body axes, x = (gamma, w), gamma the upward vertical ----
struct Params {
  double A, B, C, mgR;
};

int euler_poisson(double, const double x[], double d[], void* params) {
  const Params& p = *static_cast<const Params*>(params);
  const double g1 = x[0], g2 = x[1], g3 = x[2], w1 = x[3], w2 = x[4], w3 = x[5];
  d[0] = g2 * w3 - g3 * w2, d[1] = g3 * w1 - g1 * w3, d[2] = g1 * w2 - g2 * w1;
  const double k = p.mgR / (g1 * g1 + g2 * g2 + g3 * g3);
  d[3] = ((p.B - p.C) * w2 * w3 + k * g2) / p.A;
  d[4] = ((p.C - p.A) * w3 * w1 - k * g1) / p.B;
  d[5] = (p.A - p.B) * w1 * w2 / p.C;
  return GSL_SUCCESS;
}

// One point: true if the tilt stays <= kMaxTilt at every step end over the horizon.
bool gsl_verdict(const Body& body, const InitialState& start, double tol) {
  const RigidBodyVector v = to_vector(initial_rigid_body_state(start));
  const double qw = v[0], qx = v[1], qy = v[2], qz = v[3];
  double x[6] = {2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), qw * qw - qx * qx - qy * qy + qz * qz,
                 v[4], v[5], v[6]};
  Params params{body.A, body.B, body.C, body.mgR()};
  gsl_odeiv2_system sys{euler_poisson, nullptr, 6, &params};
  static thread_local gsl_odeiv2_step* step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 6);
  static thread_local gsl_odeiv2_evolve* evolve = gsl_odeiv2_evolve_alloc(6);
  gsl_odeiv2_control* control = gsl_odeiv2_control_y_new(tol, tol);
  gsl_odeiv2_step_reset(step);
  gsl_odeiv2_evolve_reset(evolve);
  const double cos_max = std::cos(kMaxTilt);
  double t = 0.0, h = 1e-3;
  bool stays = true;
  while (t < kHorizon) {
    if (gsl_odeiv2_evolve_apply(evolve, control, step, &sys, &t, kHorizon, &h, x) != GSL_SUCCESS) std::abort();
    if (x[2] < cos_max * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])) {
      stays = false;
      break;
    }
  }
  gsl_odeiv2_control_free(control);
  return stays;
}

std::vector<bool> gsl_map(const Map& m, double tol) {
  std::vector<bool> out(m.bodies.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = gsl_verdict(m.bodies[i], m.starts[i], tol);
  return out;
}

std::vector<bool> heavytop_default(const Map& m) {
  std::vector<TiltVerdict> v(m.bodies.size());
  batch_tilt_verdicts(m.bodies, m.starts, kHorizon, kMaxTilt, NonlinearOptions{}, v);
  std::vector<bool> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = !v[i].exceeded;
  return out;
}

#ifdef HEAVYTOP_PEERS_DECIDED
std::string decided_by;  // the last run's count of points per deciding tolerance
std::vector<bool> heavytop_decided(const Map& m) {
  std::vector<DecidedVerdict> v(m.bodies.size());
  decided_tilt_verdicts(m.bodies, m.starts, kHorizon, kMaxTilt, NonlinearOptions{}, v);
  std::vector<bool> out(v.size());
  std::size_t closed = 0, loose = 0, tight = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[i] = !v[i].exceeded;
    (v[i].tolerance == 0.0 ? closed : v[i].tolerance == kLooseTolerance ? loose : tight)++;
  }
  decided_by = "closed form " + std::to_string(closed) + ", loose " + std::to_string(loose) + ", 1e-12 " +
               std::to_string(tight);
  return out;
}
#endif

std::size_t differences(const std::vector<bool>& a, const std::vector<bool>& b) {
  std::size_t d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d += a[i] != b[i];
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 5;
  bool gsl_tight = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--no-gsl-tight")) gsl_tight = false;
  }
  gsl_set_error_handler_off();
  std::printf("| map | way | tolerance | points differing from heavytop default | stable | median CPU time | x heavytop default |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
  for (int which : {0, 1}) {
    const Map m = map(which);
    const std::vector<bool> reference = heavytop_default(m);
    // GSL's loosest tolerance giving the same map (and, said beside it, whether the next two
    // tighter ones do too: a loose tolerance may match by luck).
    double loosest = 0.0;
    int k_loosest = 0;
    for (int k = 8; k <= 48 && loosest == 0.0; ++k)
      if (differences(gsl_map(m, std::pow(10.0, -k / 4.0)), reference) == 0) loosest = std::pow(10.0, -k / 4.0), k_loosest = k;
    std::string note;
    if (loosest > 0.0)
      for (int k = k_loosest + 1; k <= k_loosest + 2; ++k) {
        const std::size_t d = differences(gsl_map(m, std::pow(10.0, -k / 4.0)), reference);
        if (d) note += " (" + std::to_string(d) + " differ at 10^(-" + std::to_string(k) + "/4))";
      }

    struct Way {
      std::string name, tolerance;
      std::function<std::vector<bool>()> run;
      std::vector<double> times;
      std::vector<bool> verdicts;
    };
    std::vector<Way> ways;
    ways.push_back({"heavytop default", "1e-12", [&] { return heavytop_default(m); }, {}, {}});
#ifdef HEAVYTOP_PEERS_DECIDED
    heavytop_decided(m);
    ways.push_back({"heavytop decided", "per point (" + decided_by + ")", [&] { return heavytop_decided(m); }, {}, {}});
#endif
    if (gsl_tight) ways.push_back({"GSL rk8pd loop", "1e-12", [&] { return gsl_map(m, 1e-12); }, {}, {}});
    if (loosest > 0.0) {
      char t[64];
      std::snprintf(t, sizeof t, "%.2e (loosest same map)%s", loosest, note.c_str());
      ways.push_back({"GSL rk8pd loop", t, [&, loosest] { return gsl_map(m, loosest); }, {}, {}});
    }
    // Each timed run after untimed ones of the same way (warm_up), but for runs of more than
    // 50 ms, whose start-up is a small part of them (peers.cpp's rule).
    for (int r = 0; r < reps; ++r)
      for (Way& w : ways) {
        if (w.times.empty() || w.times.back() < 0.05) warm_up([&] { w.run(); });
        const double t0 = cpu_seconds();
        w.verdicts = w.run();
        w.times.push_back(cpu_seconds() - t0);
      }
    const double base = median(ways[0].times);
    for (const Way& w : ways) {
      const double med = median(w.times);
      std::size_t stable = 0;
      for (bool v : w.verdicts) stable += v;
      std::printf("| %s | %s | %s | %zu | %zu / %zu | %.1f ms | %.2f |\n", m.name.c_str(), w.name.c_str(),
                  w.tolerance.c_str(), differences(w.verdicts, reference), stable, w.verdicts.size(), 1e3 * med,
                  med / base);
    }
    std::fflush(stdout);
  }
  return 0;
}

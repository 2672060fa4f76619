// heavytop's integrators against other libraries' on the two problems of issue 14, at equal
// error. Built and run by bench/peers/run.sh (by hand, not in CI).
//
// Problems (SI units):
//   toy:  heavytop::example_toy_top() spun at 200 rad/s, theta0 = 0.05 rad, over 10 s;
//   asym: A = 1, B = 1.5, C = 2 kg m^2, m = 1 kg, g = 9.81 m/s^2, R = 0.1 m, spin 10 rad/s,
//         theta0 = 0.2 rad, over 20 s.
// Error: the largest angle between the computed and the reference spin axis over 101 samples
// t_i = i T / 100 (rad). Reference: lagrange-exact (toy; closed form), and for asym
// Bulirsch-Stoer in long double at 1e-19 on this file's own right-hand side (independent of
// heavytop's code), checked against heavytop's Taylor integrator at 1e-15.
// Peers integrate the plain state (quaternion body-to-fixed, body-axes w) with this file's
// right-hand side; GSL and odeint step to each sample time (they have no dense output, or
// none at their order); heavytop samples its dense output.
// What is timed is each library's own output at the samples: the peers' axis k (a few products
// of their state), heavytop's trajectory (SPEC's angles and rates, tilt, azimuth, E, L_zeta,
// C w3 and their drifts). The axis k of heavytop's angles, which the error needs, is formed
// after the clock stops (two sines and cosines a sample: SPEC's output is angles, not k).
// Equal error: for each method the loosest tolerance on the grid 10^(-k/4) (k = 8..60) whose
// error and that of the next 8 tighter ones (two decades) are at most the level is used; then every method is timed at its tolerance, the
// methods interleaved, REPS rounds (each timed run after an untimed one of the same method),
// and the median CPU time (of the thread) reported.
// (*) marks a tolerance that reaches the level although some tighter one does not (a method
// whose rounding floor is near the level): the loosest tolerance reaching it at all.
// MuJoCo (built with -DHEAVYTOP_PEERS_MUJOCO): a fixed-step RK4; its column gives the step.
// Output: one table (stdout, Markdown), and with --csv FILE the same rows as CSV.

#include <algorithm>
#include <array>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <boost/numeric/odeint.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "heavytop/heavytop.hpp"
#include "timing.hpp"

#ifdef HEAVYTOP_PEERS_MUJOCO
#include <mujoco/mujoco.h>
#include <unistd.h>
#endif

namespace {

namespace odeint = boost::numeric::odeint;
using peers::cpu_seconds, peers::median, peers::warm_up;

struct Problem {
  std::string name;
  heavytop::Body body;
  heavytop::InitialState start;
  double horizon;
};

// The plain rigid-body equations, written again here so that the peers do not run heavytop's
// code: q' = q (x) (0, w) / 2, I w' = (I w) x w + m g R (gamma x e3), gamma = R(q)^T e_zeta.
template <class T>
struct Rhs {
  T A, B, C, mgR;
  void operator()(const std::array<T, 7>& x, std::array<T, 7>& d, T /*t*/) const {
    const T qw = x[0], qx = x[1], qy = x[2], qz = x[3], w1 = x[4], w2 = x[5], w3 = x[6];
    d[0] = T(0.5) * (-qx * w1 - qy * w2 - qz * w3);
    d[1] = T(0.5) * (qw * w1 + qy * w3 - qz * w2);
    d[2] = T(0.5) * (qw * w2 + qz * w1 - qx * w3);
    d[3] = T(0.5) * (qw * w3 + qx * w2 - qy * w1);
    const T n2 = qw * qw + qx * qx + qy * qy + qz * qz;
    const T g1 = T(2) * (qx * qz - qw * qy) / n2, g2 = T(2) * (qy * qz + qw * qx) / n2;
    d[4] = ((B - C) * w2 * w3 + mgR * g2) / A;
    d[5] = ((C - A) * w3 * w1 - mgR * g1) / B;
    d[6] = (A - B) * w1 * w2 / C;
  }
};

// The same body in Poisson form (no quaternion): the body-axes images of the fixed frame's
// zeta and xi axes, gamma = R^T e_zeta and alpha = R^T e_xi, each fixed in space
// (v' = v x w), and w: x = (gamma, alpha, w). The torque uses gamma / |gamma|^2 (the
// normalised right-hand side: |gamma| = 1 for the exact flow, and the division keeps the
// torque's size when rounding drifts |gamma|). The axis k = R e3 = (alpha_3, beta_3, gamma_3)
// with beta = R^T e_eta = gamma x alpha. Nine variables against the quaternion form's seven,
// but no quadratic gamma(q): the cheapest right-hand side here.
template <class T>
struct PoissonRhs {
  T A, B, C, mgR;
  template <class X>
  void operator()(const X& x, X& d, T /*t*/) const {
    const T g1 = x[0], g2 = x[1], g3 = x[2], a1 = x[3], a2 = x[4], a3 = x[5], w1 = x[6], w2 = x[7], w3 = x[8];
    d[0] = g2 * w3 - g3 * w2, d[1] = g3 * w1 - g1 * w3, d[2] = g1 * w2 - g2 * w1;
    d[3] = a2 * w3 - a3 * w2, d[4] = a3 * w1 - a1 * w3, d[5] = a1 * w2 - a2 * w1;
    const T k = mgR / (g1 * g1 + g2 * g2 + g3 * g3);
    d[6] = ((B - C) * w2 * w3 + k * g2) / A;
    d[7] = ((C - A) * w3 * w1 - k * g1) / B;
    d[8] = (A - B) * w1 * w2 / C;
  }
};

using Axis = Eigen::Vector3d;
using Axes = std::vector<Axis>;

template <class T>
Axis axis_of_state(const std::array<T, 7>& x) {  // k = R(q) e3
  const double qw = double(x[0]), qx = double(x[1]), qy = double(x[2]), qz = double(x[3]);
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  return Axis(2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx), qw * qw - qx * qx - qy * qy + qz * qz) / n2;
}

template <class T>
Axis axis_of_poisson(const std::array<T, 9>& x) {  // k = (alpha_3, (gamma x alpha)_3, gamma_3)
  const double g1 = double(x[0]), g2 = double(x[1]), g3 = double(x[2]);
  const double a1 = double(x[3]), a2 = double(x[4]), a3 = double(x[5]);
  return Axis(a3, g1 * a2 - g2 * a1, g3);
}

Axis axis_of_angles(double theta, double phi) {  // SPEC section 2
  return Axis(std::cos(phi) * std::sin(theta), -std::sin(phi), std::cos(phi) * std::cos(theta));
}

Axes axes_of(const heavytop::Trajectory& tr) {
  Axes a;
  for (std::size_t i = 0; i < tr.size(); ++i) a.push_back(axis_of_angles(tr.theta[i], tr.phi[i]));
  return a;
}

double max_angle(const Axes& a, const Axes& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::atan2(a[i].cross(b[i]).norm(), a[i].dot(b[i])));
  return e;
}

template <class T>
std::array<T, 7> initial(const Problem& p) {
  const heavytop::RigidBodyVector v = heavytop::to_vector(heavytop::initial_rigid_body_state(p.start));
  std::array<T, 7> x;
  for (int i = 0; i < 7; ++i) x[i] = T(v[i]);
  return x;
}

// The Poisson state of the same start: gamma and alpha the third and first rows of R(q).
template <class T>
std::array<T, 9> initial_poisson(const Problem& p) {
  const std::array<double, 7> q = initial<double>(p);
  const double qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const std::array<double, 9> x = {2 * (qx * qz - qw * qy) / n2, 2 * (qy * qz + qw * qx) / n2,
                                   (qw * qw - qx * qx - qy * qy + qz * qz) / n2,
                                   (qw * qw + qx * qx - qy * qy - qz * qz) / n2, 2 * (qx * qy - qw * qz) / n2,
                                   2 * (qx * qz + qw * qy) / n2, q[4], q[5], q[6]};
  std::array<T, 9> out;
  for (int i = 0; i < 9; ++i) out[i] = T(x[i]);
  return out;
}

std::vector<double> times_of(const Problem& p) { return heavytop::sample_times(p.horizon, 101); }

// ---- The methods: each maps a tolerance to the axes at the 101 samples ----

// A method's output at the samples: the axes (peers), or heavytop's trajectory.
struct Output {
  Axes axes;
  heavytop::Trajectory trajectory;
  bool failed = false;
  Output() = default;
  Output(Axes a) : axes(std::move(a)), failed(axes.empty()) {}  // NOLINT: the peers return Axes
};

Axes axes_of(const Output& o) {
  if (o.failed) return {};
  return o.axes.empty() ? axes_of(o.trajectory) : o.axes;
}

struct Method {
  std::string name;
  std::function<Output(const Problem&, double)> run;
  // For a fixed-step method: the step (s) the tolerance stands for; else null.
  std::function<double(const Problem&, double)> step = nullptr;
};

Output heavytop_run(const Problem& p, double tol, heavytop::Integrator integrator) {
  heavytop::SimulateOptions o;
  o.integrator = integrator;
  o.adaptive.rtol = o.adaptive.atol = tol;
  o.adaptive.max_steps = 20'000'000;
  const heavytop::Simulation s = heavytop::simulate(heavytop::Model::Nonlinear, p.body, p.start, times_of(p), o);
  Output out;
  out.failed = !s.summary.ok();
  out.trajectory = std::move(s.trajectory);
  return out;
}

template <class R, std::size_t N>
int gsl_rhs(double, const double y[], double f[], void* params) {
  const auto& rhs = *static_cast<const R*>(params);
  std::array<double, N> x, d;
  std::copy(y, y + N, x.begin());
  rhs(x, d, 0.0);
  std::copy(d.begin(), d.end(), f);
  return GSL_SUCCESS;
}

// GSL's rk8pd stepping to each sample time on the right-hand side `rhs` from x (N variables).
template <class R, std::size_t N, class AxisOf>
Axes gsl_run(const Problem& p, double tol, R rhs, std::array<double, N> x, AxisOf axis_of) {
  gsl_odeiv2_system sys{gsl_rhs<R, N>, nullptr, N, &rhs};
  gsl_odeiv2_step* step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, N);
  gsl_odeiv2_control* control = gsl_odeiv2_control_y_new(tol, tol);
  gsl_odeiv2_evolve* evolve = gsl_odeiv2_evolve_alloc(N);
  double t = 0.0, h = 1e-3;
  Axes out;
  std::size_t steps = 0;
  for (double ti : times_of(p)) {
    while (t < ti) {
      if (gsl_odeiv2_evolve_apply(evolve, control, step, &sys, &t, ti, &h, x.data()) != GSL_SUCCESS ||
          ++steps > 20'000'000) {
        out.clear();
        ti = 1e300;
        break;
      }
    }
    if (ti == 1e300) break;
    out.push_back(axis_of(x));
  }
  gsl_odeiv2_evolve_free(evolve);
  gsl_odeiv2_control_free(control);
  gsl_odeiv2_step_free(step);
  return out;
}

Rhs<double> quaternion_rhs(const Problem& p) { return {p.body.A, p.body.B, p.body.C, p.body.mgR()}; }
PoissonRhs<double> poisson_rhs(const Problem& p) { return {p.body.A, p.body.B, p.body.C, p.body.mgR()}; }

Axes gsl_rk8pd(const Problem& p, double tol) {
  return gsl_run(p, tol, quaternion_rhs(p), initial<double>(p), axis_of_state<double>);
}
Axes gsl_rk8pd_poisson(const Problem& p, double tol) {
  return gsl_run(p, tol, poisson_rhs(p), initial_poisson<double>(p), axis_of_poisson<double>);
}

template <class R, class State, class Stepper, class AxisOf>
Axes odeint_run(const Problem& p, Stepper stepper, R rhs, State x, AxisOf axis_of) {
  const std::vector<double> times = times_of(p);
  Axes out;
  odeint::integrate_times(stepper, rhs, x, times.begin(), times.end(), 1e-3,
                          [&](const State& y, double) { out.push_back(axis_of(y)); });
  return out;
}

using Q7 = std::array<double, 7>;
using P9 = std::array<double, 9>;

Axes odeint_rkf78(const Problem& p, double tol) {
  return odeint_run(p, odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<Q7>()), quaternion_rhs(p),
                    initial<double>(p), axis_of_state<double>);
}
Axes odeint_bulirsch_stoer(const Problem& p, double tol) {
  return odeint_run(p, odeint::bulirsch_stoer<Q7>(tol, tol), quaternion_rhs(p), initial<double>(p),
                    axis_of_state<double>);
}
Axes odeint_rkf78_poisson(const Problem& p, double tol) {
  return odeint_run(p, odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<P9>()), poisson_rhs(p),
                    initial_poisson<double>(p), axis_of_poisson<double>);
}
Axes odeint_bulirsch_stoer_poisson(const Problem& p, double tol) {
  return odeint_run(p, odeint::bulirsch_stoer<P9>(tol, tol), poisson_rhs(p), initial_poisson<double>(p),
                    axis_of_poisson<double>);
}

#ifdef HEAVYTOP_PEERS_MUJOCO
// MuJoCo 2.2.2 (Debian's libmujoco-dev): the body on a ball joint at the origin, its inertia
// about the centre of mass (A - m R^2, B - m R^2, C) at R on body z, gravity -g zeta, no
// contacts, the RK4 integrator at a fixed step. The "tolerance" t stands for the step
// h = 0.1 s t^0.3 (2.5e-2 s at t = 1e-2, 3.2e-6 s at 1e-15), cut to divide the sample
// interval T/100; a run of more than 4e6 steps is not made.
double mujoco_step(const Problem& p, double tol) {
  const double interval = p.horizon / 100.0;
  const double n = std::ceil(interval / (0.1 * std::pow(tol, 0.3)));
  return interval / n;
}

Axes mujoco_rk4(const Problem& p, double tol) {
  const double h = mujoco_step(p, tol);
  const double steps_per_sample = std::round(p.horizon / 100.0 / h);
  if (100.0 * steps_per_sample > 4e6) return {};  // beyond the budget of a run
  const heavytop::Body& b = p.body;
  const double mr2 = b.mass * b.length * b.length;
  // The toy top is a flat disc about its centre of mass (A + B = C exactly); MuJoCo refuses
  // A + B < C, which rounding can give: C is lowered to A + B (a change of ~1e-16 relative).
  const double a = b.A - mr2, bb = b.B - mr2, c = std::min(b.C, a + bb);
  char xml[2048];
  std::snprintf(xml, sizeof xml,
                "<mujoco><option gravity=\"0 0 %.17g\" timestep=\"%.17g\" integrator=\"RK4\">"
                "<flag contact=\"disable\"/></option><worldbody><body name=\"top\">"
                "<joint type=\"ball\" damping=\"0\" armature=\"0\"/>"
                "<inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>"
                "</body></worldbody></mujoco>",
                -b.gravity, h, b.length, b.mass, a, bb, c);
  char path[] = "/tmp/heavytop-peers-XXXXXX.xml";
  const int fd = mkstemps(path, 4);
  if (fd < 0 || write(fd, xml, std::strlen(xml)) < 0) std::abort();
  close(fd);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path, nullptr, error, sizeof error);
  unlink(path);
  if (!m) {
    std::fprintf(stderr, "mujoco: %s\n", error);
    std::abort();
  }
  mjData* d = mj_makeData(m);
  const std::array<double, 7> x0 = initial<double>(p);
  for (int i = 0; i < 4; ++i) d->qpos[i] = x0[i];      // body-to-world quaternion (w, x, y, z)
  for (int i = 0; i < 3; ++i) d->qvel[i] = x0[4 + i];  // ball joint: angular velocity, body axes
  Axes out;
  for (int sample = 0; sample <= 100; ++sample) {
    if (sample > 0)
      for (int k = 0; k < steps_per_sample; ++k) mj_step(m, d);
    out.push_back(axis_of_state(std::array<double, 7>{d->qpos[0], d->qpos[1], d->qpos[2], d->qpos[3], 0, 0, 0}));
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}
#endif

Axes reference(const Problem& p) {
  if (p.body.A == p.body.B) return axes_of(heavytop::simulate_lagrange_exact(p.body, p.start, times_of(p)));
  using LD = long double;
  Rhs<LD> rhs{p.body.A, p.body.B, p.body.C, p.body.mgR()};
  std::array<LD, 7> x = initial<LD>(p);
  const std::vector<double> times = times_of(p);
  std::vector<LD> ld_times(times.begin(), times.end());
  Axes out;
  odeint::integrate_times(odeint::bulirsch_stoer<std::array<LD, 7>, LD>(1e-19L, 1e-19L), rhs, x, ld_times.begin(),
                          ld_times.end(), LD(1e-3), [&](const std::array<LD, 7>& y, LD) { out.push_back(axis_of_state(y)); });
  return out;
}

}  // namespace

#ifndef HEAVYTOP_PEERS_LIBRARY  // paired.cpp includes this file for its methods
int main(int argc, char** argv) {
  int reps = 15;
  const char* csv_path = nullptr;
  const char* reference_path = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else if (!std::strcmp(argv[i], "--reference") && i + 1 < argc) reference_path = argv[++i];
  }
  // --reference FILE: the reference axes (problem, sample, x, y, z) for the Python peers.
  FILE* reference_file = reference_path ? std::fopen(reference_path, "w") : nullptr;
  gsl_set_error_handler_off();

  heavytop::Body asym;
  asym.A = 1.0, asym.B = 1.5, asym.C = 2.0, asym.mass = 1.0, asym.gravity = 9.81, asym.length = 0.1;
  heavytop::InitialState toy_start, asym_start;
  toy_start.spin = 200.0, toy_start.theta0 = 0.05;
  asym_start.spin = 10.0, asym_start.theta0 = 0.2;
  const std::vector<Problem> problems = {{"toy", heavytop::example_toy_top(), toy_start, 10.0},
                                         {"asym", asym, asym_start, 20.0}};
  using heavytop::Integrator;
  const std::vector<Method> methods = {
      {"heavytop taylor", [](const Problem& p, double t) { return heavytop_run(p, t, Integrator::Taylor); }},
      {"heavytop dop853", [](const Problem& p, double t) { return heavytop_run(p, t, Integrator::Dop853); }},
      {"heavytop dopri5", [](const Problem& p, double t) { return heavytop_run(p, t, Integrator::Adaptive); }},
      {"GSL rk8pd", gsl_rk8pd},
      {"GSL rk8pd (Poisson)", gsl_rk8pd_poisson},
      {"odeint rkf78", odeint_rkf78},
      {"odeint rkf78 (Poisson)", odeint_rkf78_poisson},
      {"odeint bulirsch_stoer", odeint_bulirsch_stoer},
      {"odeint bulirsch_stoer (Poisson)", odeint_bulirsch_stoer_poisson},
#ifdef HEAVYTOP_PEERS_MUJOCO
      {"MuJoCo 2.2.2 RK4 (ball joint)", mujoco_rk4, mujoco_step},
#endif
  };
  const std::vector<double> levels = {1e-6, 1e-9, 1e-12};

  FILE* csv = csv_path ? std::fopen(csv_path, "w") : nullptr;
  if (csv) std::fprintf(csv, "problem,level,method,tolerance,error,median_us\n");
  std::printf("| problem | error level | method | tolerance | error (rad) | median CPU time | x heavytop's fastest |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Problem& p : problems) {
    const Axes ref = reference(p);
    if (reference_file)
      for (std::size_t i = 0; i < ref.size(); ++i)
        std::fprintf(reference_file, "%s %zu %.17g %.17g %.17g\n", p.name.c_str(), i, ref[i].x(), ref[i].y(), ref[i].z());
    if (p.body.A != p.body.B) {
      const double check = max_angle(ref, axes_of(heavytop_run(p, 1e-15, Integrator::Taylor)));
      std::fprintf(stderr, "%s: long-double reference against heavytop taylor at 1e-15: %.2e rad\n", p.name.c_str(), check);
    }
    // Each method's error at every tolerance of the grid, measured (once for all levels): a
    // level's tolerance and error below are a measured pair, never interpolated.
    std::vector<std::vector<double>> grid_errors(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m)
      for (int k = 8; k <= 60; ++k) {
        const Axes a = axes_of(methods[m].run(p, std::pow(10.0, -k / 4.0)));
        grid_errors[m].push_back(a.size() == ref.size() ? max_angle(a, ref) : 1e300);
      }
    for (double level : levels) {
      // Calibrate: the loosest tolerance on the grid that reaches the level and stays there
      // for the next two decades tighter (an error that dips below the level at one lucky
      // tolerance does not count).
      std::vector<double> tol(methods.size(), 0.0), err(methods.size(), 0.0);
      std::vector<bool> lucky(methods.size(), false);
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const std::vector<double>& errors = grid_errors[m];
        for (std::size_t i = 0; i < errors.size(); ++i) {
          bool stays = true;
          for (std::size_t j = i; j < std::min(errors.size(), i + 9); ++j) stays = stays && errors[j] <= level;
          if (stays) {
            tol[m] = std::pow(10.0, -static_cast<double>(i + 8) / 4.0), err[m] = errors[i];
            break;
          }
        }
        // A method whose rounding floor lies near the level: the loosest tolerance that
        // reaches it at all (marked in the table).
        if (tol[m] == 0.0)
          for (std::size_t i = 0; i < errors.size(); ++i)
            if (errors[i] <= level) {
              tol[m] = std::pow(10.0, -static_cast<double>(i + 8) / 4.0), err[m] = errors[i], lucky[m] = true;
              break;
            }
      }
      // Time, interleaved. Each timed run follows untimed ones of the same method (warm_up; a
      // run of more than 50 ms, whose start-up is a small part of it, is not repeated).
      std::vector<std::vector<double>> times(methods.size());
      for (int r = 0; r < reps; ++r)
        for (std::size_t m = 0; m < methods.size(); ++m) {
          if (tol[m] == 0.0) continue;
          if (times[m].empty() || times[m].back() < 5e4) warm_up([&] { methods[m].run(p, tol[m]); });
          const double t0 = cpu_seconds();
          const Output a = methods[m].run(p, tol[m]);
          const double t1 = cpu_seconds();
          if (a.failed) std::abort();
          times[m].push_back((t1 - t0) * 1e6);
        }
      double fastest_heavytop = 1e300;
      std::vector<double> med(methods.size(), 0.0);
      for (std::size_t m = 0; m < methods.size(); ++m) {
        if (tol[m] == 0.0) continue;
        med[m] = median(times[m]);
        if (methods[m].name.rfind("heavytop", 0) == 0) fastest_heavytop = std::min(fastest_heavytop, med[m]);
      }
      for (std::size_t m = 0; m < methods.size(); ++m) {
        if (tol[m] == 0.0) {
          std::printf("| %s | %.0e | %s | - | not reached | - | - |\n", p.name.c_str(), level,
                      methods[m].name.c_str());
          continue;
        }
        char setting[64];
        if (methods[m].step) std::snprintf(setting, sizeof setting, "h = %.3g s", methods[m].step(p, tol[m]));
        else std::snprintf(setting, sizeof setting, "%.2e%s", tol[m], lucky[m] ? " (*)" : "");
        std::printf("| %s | %.0e | %s | %s | %.2e | %.1f us | %.2f |\n", p.name.c_str(), level,
                    methods[m].name.c_str(), setting, err[m], med[m], med[m] / fastest_heavytop);
        if (csv)
          std::fprintf(csv, "%s,%g,%s,%g,%g,%g\n", p.name.c_str(), level, methods[m].name.c_str(), tol[m], err[m],
                       med[m]);
      }
      std::fflush(stdout);
    }
  }
  if (csv) std::fclose(csv);
  if (reference_file) std::fclose(reference_file);
  return 0;
}
#endif

// Friedl's tippe top (examples/tippe-top.toml) in MuJoCo 2.2.2 (Debian's libmujoco-dev), as a
// MuJoCo user would model it: a 15 mm sphere on a free joint above a plane, its 6 g with the
// centre of mass 3 mm below the sphere's centre (an inertial element: A_G = 8e-7, C = 7e-7 kg m^2),
// sliding friction 0.3 on both geoms (MuJoCo combines a pair's by the larger), everything else
// MuJoCo's defaults (soft contacts, pyramidal cone, condim 3). Spun at 180 rad/s about its axis
// tilted 0.1 rad, the sphere touching the plane. MuJoCo's contact is soft and its friction is a
// Coulomb cone, not Cohen's viscous law: the motion is MuJoCo's own, not heavytop's equations'.
// Built by bench/CMakeLists.txt when MuJoCo is found; run by bench/scipy_table.py --mujoco
// (docs/table-performance.md), or by hand:
//   build/bench/mujoco_tippe_top [--reps N] [--horizon S] [--watch S] [--json] [INTEGRATOR:STEP ...]
// For each integrator (RK4, Euler) and timestep: the CPU time of --horizon s of motion (median
// of N runs, each after an untimed one; Jellett's integral and the energy evaluated after every
// step inside the clock, as heavytop's drifts are on every accepted step), Jellett's largest
// drift and the energy's change over heavytop's scales (TableSummary), the largest rise of the
// energy above its running minimum (friction only removes energy: a rise is the method's or the
// soft contact's), the steps that end with the sphere off the plane (MuJoCo's ball hops while
// it turns over) and its largest lift and penetration, and, over --watch s (untimed), when the
// tilt first passes pi/2 and whether MuJoCo's step became unstable (its bad-acceleration
// warning: it then resets the state, so the watch stops there).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "timing.hpp"

namespace {

using peers::cpu_seconds, peers::median;

constexpr double kMass = 0.006, kRadius = 0.015, kLength = -0.003, kAG = 8e-7, kC = 7e-7;
constexpr double kGravity = 9.81, kSpin = 180.0, kTilt0 = 0.1, kQuarter = std::numbers::pi / 2;

struct Config {
  std::string integrator;  // "RK4" or "Euler"
  double timestep;         // s
};

struct Result {
  double cpu_ms = 0.0;             // median
  long steps = 0;
  double jellett_drift = 0.0;      // max |J - J0| / (|L_G(0)| (|l| + r))
  double energy_change = 0.0;      // max |E - E0| / (T(0) + m g |l| + m g r)
  double energy_rise = 0.0;        // max (E - min_{s <= t} E(s)) over the same scale
  long off_plane = 0;              // steps ending with the sphere above the plane (no contact)
  double max_lift = 0.0;           // m, the sphere's largest height above the plane
  double max_sink = 0.0;           // m, its largest penetration into it (the soft contact)
  double end_tilt = 0.0;           // rad, at the horizon
  double end_spin = 0.0;           // rad/s, w . k at the horizon
  double turns_over_at = -1.0;     // s, the tilt first passes pi/2 within --watch (-1: never)
  double max_tilt = 0.0;           // rad, over --watch
  double unstable_at = -1.0;       // s, MuJoCo found a bad acceleration and reset the state (-1: never)
  bool unstable_in_horizon = false;
};

mjModel* load(const Config& c) {
  char xml[2048];
  std::snprintf(xml, sizeof xml,
                "<mujoco model=\"tippe top\">"
                "<option timestep=\"%.17g\" integrator=\"%s\" gravity=\"0 0 %.17g\"/>"
                "<worldbody>"
                "<geom name=\"table\" type=\"plane\" size=\"1 1 0.1\" friction=\"0.3\"/>"
                "<body name=\"top\" pos=\"0 0 %.17g\" quat=\"%.17g 0 %.17g 0\">"
                "<freejoint/>"
                "<geom name=\"ball\" type=\"sphere\" size=\"%.17g\" friction=\"0.3\"/>"
                "<inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>"
                "</body></worldbody></mujoco>",
                c.timestep, c.integrator.c_str(), -kGravity, kRadius, std::cos(0.5 * kTilt0),
                std::sin(0.5 * kTilt0), kRadius, kLength, kMass, kAG, kAG, kC);
  // MuJoCo 2.2 reads MJCF from a file or its virtual file system (mjVFS is ~2 MB: the heap).
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const int size = static_cast<int>(std::strlen(xml));
  if (mj_makeEmptyFileVFS(vfs.get(), "tippe-top.xml", size) != 0) std::abort();
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "tippe-top.xml")], xml, static_cast<std::size_t>(size));
  char error[1000] = "";
  mjModel* m = mj_loadXML("tippe-top.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!m) {
    std::fprintf(stderr, "mujoco: %s\n", error);
    std::exit(2);
  }
  return m;
}

// The free joint's state, read straight from qpos/qvel: after mj_step MuJoCo's derived
// quantities (xpos, xipos, cvel) are those of the step's start, not of the new state.
// qpos = (O, quaternion body to world), qvel = (O's velocity in world axes, w in body axes).
struct Watched {
  double jellett, energy, tilt, spin;
  double lift;  // m, the sphere's lowest point above the plane (< 0: sunk into it, in contact)
};

Watched watch(const mjData* d) {
  double R[9];
  mju_quat2Mat(R, d->qpos + 3);  // row-major, body to world
  const double* vO = d->qvel;
  const double* wb = d->qvel + 3;
  const double k[3] = {R[2], R[5], R[8]};  // the body's axis in world axes
  double w[3];
  mju_rotVecMat(w, wb, R);
  const double GO[3] = {kLength * k[0], kLength * k[1], kLength * k[2]};  // G - O
  double wxGO[3];
  mju_cross(wxGO, w, GO);
  const double vG[3] = {vO[0] + wxGO[0], vO[1] + wxGO[1], vO[2] + wxGO[2]};
  const double Lb[3] = {kAG * wb[0], kAG * wb[1], kC * wb[2]};
  double L[3];
  mju_rotVecMat(L, Lb, R);
  // G - P, P the sphere's lowest point (O - r e_z), not MuJoCo's contact point (mid-penetration).
  const double s[3] = {GO[0], GO[1], GO[2] + kRadius};
  const double zG = d->qpos[2] + GO[2];
  Watched out;
  out.jellett = mju_dot3(L, s);
  out.energy = 0.5 * kMass * mju_dot3(vG, vG) + 0.5 * mju_dot3(Lb, wb) + kMass * kGravity * zG;
  out.tilt = std::atan2(std::hypot(k[0], k[1]), k[2]);
  out.spin = mju_dot3(w, k);
  out.lift = d->qpos[2] - kRadius;
  return out;
}

void start(const mjModel* m, mjData* d) {
  mj_resetData(m, d);  // qpos0: the body's pos and quat from the MJCF
  d->qvel[5] = kSpin;  // about the body's axis; O (on the axis) at rest, so G too
  mj_forward(m, d);
}

Result run(const Config& c, int reps, double horizon, double watch_for) {
  mjModel* m = load(c);
  mjData* d = mj_makeData(m);
  const long n = std::lround(horizon / c.timestep);
  start(m, d);
  const Watched w0 = watch(d);
  const double L0 = std::hypot(kAG * d->qvel[3], kAG * d->qvel[4], kC * d->qvel[5]);
  const double jellett_scale = L0 * (std::abs(kLength) + kRadius);
  const double kinetic0 = w0.energy - kMass * kGravity * (kRadius + kLength * std::cos(kTilt0));
  const double energy_scale = kinetic0 + kMass * kGravity * (std::abs(kLength) + kRadius);
  Result r;
  r.steps = n;
  std::vector<double> times;
  for (int rep = 0; rep <= reps; ++rep) {  // rep 0 untimed: the caches and the allocator warm
    start(m, d);
    double jd = 0.0, ec = 0.0, rise = 0.0, lowest = w0.energy, lift = 0.0, sink = 0.0;
    long off = 0;
    const double t0 = cpu_seconds();
    for (long i = 0; i < n; ++i) {
      mj_step(m, d);
      const Watched w = watch(d);
      jd = std::max(jd, std::abs(w.jellett - w0.jellett));
      ec = std::max(ec, std::abs(w.energy - w0.energy));
      lowest = std::min(lowest, w.energy);
      rise = std::max(rise, w.energy - lowest);
      off += w.lift > 0.0;  // MuJoCo's sphere-plane contact exists only where they overlap
      lift = std::max(lift, w.lift);
      sink = std::max(sink, -w.lift);
    }
    const double t1 = cpu_seconds();
    if (rep > 0) times.push_back(t1 - t0);
    r.unstable_in_horizon = d->warning[mjWARN_BADQACC].number > 0;
    r.jellett_drift = jd / jellett_scale;
    r.energy_change = ec / energy_scale;
    r.energy_rise = rise / energy_scale;
    r.off_plane = off;
    r.max_lift = lift;
    r.max_sink = sink;
    const Watched end = watch(d);
    r.end_tilt = end.tilt;
    r.end_spin = end.spin;
  }
  r.cpu_ms = 1e3 * median(times);
  // Turning over, untimed, over watch_for s: the first step whose tilt passes pi/2, its time
  // interpolated linearly between the steps.
  start(m, d);
  double prev_tilt = watch(d).tilt;
  r.max_tilt = prev_tilt;
  const long nw = std::lround(watch_for / c.timestep);
  for (long i = 0; i < nw; ++i) {
    mj_step(m, d);
    if (d->warning[mjWARN_BADQACC].number > 0) {  // mj_step has reset the state to the model's
      r.unstable_at = static_cast<double>(i + 1) * c.timestep;
      break;
    }
    const double tilt = watch(d).tilt;
    r.max_tilt = std::max(r.max_tilt, tilt);
    if (r.turns_over_at < 0.0 && tilt > kQuarter && prev_tilt <= kQuarter)
      r.turns_over_at = (static_cast<double>(i) + (kQuarter - prev_tilt) / (tilt - prev_tilt)) * c.timestep;
    prev_tilt = tilt;
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 5;  // at least 1
  double horizon = 5.0, watch_for = 20.0;
  bool json = false;
  std::vector<Config> configs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reps" && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--horizon" && i + 1 < argc) horizon = std::atof(argv[++i]);
    else if (a == "--watch" && i + 1 < argc) watch_for = std::atof(argv[++i]);
    else if (a == "--json") json = true;
    else if (const auto colon = a.find(':'); colon != std::string::npos && a[0] != '-')
      configs.push_back({a.substr(0, colon), std::atof(a.c_str() + colon + 1)});
    else {
      std::fprintf(stderr, "usage: %s [--reps N] [--horizon S] [--watch S] [--json] [RK4|Euler:STEP ...]\n", argv[0]);
      return 2;
    }
  }
  if (configs.empty())  // the default RK4 step, MuJoCo's default integrator, and smaller steps
    for (const char* integrator : {"RK4", "Euler"})
      for (double h : {2e-3, 1e-3, 5e-4, 2e-4, 1e-4}) configs.push_back({integrator, h});
  for (const Config& c : configs) {
    const Result r = run(c, reps, horizon, watch_for);
    // A time or JSON's null for "never".
    const auto when = [](double t) { return t < 0.0 ? std::string("null") : std::to_string(t); };
    if (json)
      std::printf("{\"mujoco\": \"%s\", \"integrator\": \"%s\", \"timestep\": %g, \"horizon\": %g, \"cpu_ms\": %.6g, "
                  "\"reps\": %d, \"steps\": %ld, \"jellett_drift\": %.6g, \"energy_change\": %.6g, "
                  "\"energy_rise\": %.6g, \"off_plane\": %ld, \"max_lift\": %.6g, \"max_sink\": %.6g, \"end_tilt\": %.10g, \"end_spin\": %.10g, \"unstable_in_horizon\": %s, "
                  "\"watch\": %g, \"max_tilt\": %.10g, \"turns_over_at\": %s, \"unstable_at\": %s}\n",
                  mj_versionString(), c.integrator.c_str(), c.timestep, horizon, r.cpu_ms, reps, r.steps,
                  r.jellett_drift, r.energy_change, r.energy_rise, r.off_plane, r.max_lift, r.max_sink, r.end_tilt,
                  r.end_spin, r.unstable_in_horizon ? "true" : "false", watch_for, r.max_tilt, when(r.turns_over_at).c_str(),
                  when(r.unstable_at).c_str());
    else
      std::printf("MuJoCo %s %-5s h = %-6g: %9.3f ms CPU (median of %d), %ld steps, Jellett drift %.2e, energy "
                  "change %.2e (rise %.2e), %ld steps off the plane (up to %.1e m; sunk up to %.1e m), tilt %.4f rad at "
                  "%g s%s; over %g s: passes pi/2 at %s s, max tilt "
                  "%.4f rad, unstable at %s s\n",
                  mj_versionString(), c.integrator.c_str(), c.timestep, r.cpu_ms, reps, r.steps, r.jellett_drift,
                  r.energy_change, r.energy_rise, r.off_plane, r.max_lift, r.max_sink, r.end_tilt, horizon,
                  r.unstable_in_horizon ? " (UNSTABLE)" : "",
                  watch_for, when(r.turns_over_at).c_str(), r.max_tilt, when(r.unstable_at).c_str());
    std::fflush(stdout);
  }
}

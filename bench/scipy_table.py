#!/usr/bin/python3
"""Friedl's tippe top turning over (examples/tippe-top.toml, the first 5 s) in SciPy's DOP853,
side by side with heavytop's bench_table and MuJoCo's tippe top, in one run
(docs/table-performance.md).

SciPy integrates the same equations (docs/table.md: the attitude quaternion, the angular
velocity in body axes and the centre of mass's horizontal position and velocity; the normal
force from the height constraint, Cohen's viscous friction), written here again in NumPy-free
Python floats from the page's formulas, not from heavytop's code: an independent check of the
equations too. Each run's end state (tilt, spin w . k, P's position) is compared with a tight
reference (heavytop's simulate at rtol = atol = 1e-13), and Jellett's integral's and the
energy's drifts are measured on every accepted step over heavytop's scales (TableSummary:
|L_G(0)| (|l| + r) and T(0) + m g |l| + m g r), so the columns compare.

Equal error: for each SciPy tolerance, the loosest heavytop tolerance (decades 1e-6 to 1e-13)
whose end error is at most SciPy's (to 1 %: both run Hairer's DOP853 with the same step control,
so at one tolerance they take the same steps and their errors differ in the third digit, by
rounding), and the ratio of their median CPU times.

MuJoCo (bench/peers/mujoco_tippe_top.cpp, built where libmujoco-dev is installed) models the
top its own way (soft contact, Coulomb friction): its rows give time, Jellett's drift and
whether it turns over, not an error against the reference.

Run with Debian's interpreter (python3-scipy), from the repository root:
    /usr/bin/python3 bench/scipy_table.py --heavytop build/heavytop [--bench build/bench/bench_table]
        [--mujoco build/bench/mujoco_tippe_top]
"""

import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import time

import scipy
from scipy.integrate import solve_ivp

M, G, L, R, C, AG = 0.006, 9.81, -0.003, 0.015, 7e-7, 8e-7
MU, SLIP = 0.3, 1.0
SPIN, THETA0, HORIZON = 180.0, 0.1, 5.0


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotation(q):
    w, x, y, z = q
    n2 = w * w + x * x + y * y + z * z
    s = 2.0 / n2
    return ((1 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)),
            (s * (x * y + w * z), 1 - s * (x * x + z * z), s * (y * z - w * x)),
            (s * (x * z - w * y), s * (y * z + w * x), 1 - s * (x * x + y * y)))


def motion(y):
    """omega', G's acceleration (body axes), N, gamma, s, L_G for the state y."""
    q, om = y[0:4], y[4:7]
    Rm = rotation(q)
    gam = Rm[2]  # the upward vertical in body axes
    s = (R * gam[0], R * gam[1], L + R * gam[2])  # G - P = l e3 + r gamma
    gdot = cross(gam, om)
    zrate = L * gdot[2]
    vf = (y[9], y[10], zrate)
    v = tuple(sum(Rm[i][j] * vf[i] for i in range(3)) for j in range(3))  # R^T vf
    wxs = cross(om, s)
    vp = tuple(v[i] - wxs[i] for i in range(3))
    vn = sum(vp[i] * gam[i] for i in range(3))
    phi = tuple(-MU / SLIP * (vp[i] - vn * gam[i]) for i in range(3))
    inertia = (AG, AG, C)
    Lg = tuple(inertia[i] * om[i] for i in range(3))
    wIw = cross(om, Lg)
    wd0 = tuple(-wIw[i] / inertia[i] for i in range(3))
    arm = tuple(-x for x in s)
    t1 = cross(arm, tuple(gam[i] + phi[i] for i in range(3)))
    wd1 = tuple(t1[i] / inertia[i] for i in range(3))
    cdd0 = cross(gdot, om)[2] + cross(gam, wd0)[2]
    cdd1 = cross(gam, wd1)[2]
    N = (G + L * cdd0) / (1.0 / M - L * cdd1)
    wd = tuple(wd0[i] + N * wd1[i] for i in range(3))
    acc = tuple(N * (gam[i] + phi[i]) / M - G * gam[i] for i in range(3))
    return Rm, wd, acc, gam, s, Lg


def rhs(_, y):
    Rm, wd, acc, _, _, _ = motion(y)
    w, x, yy, z = y[0:4]
    w1, w2, w3 = y[4:7]
    af = tuple(sum(Rm[i][j] * acc[j] for j in range(3)) for i in range(3))
    return [0.5 * (-x * w1 - yy * w2 - z * w3), 0.5 * (w * w1 + yy * w3 - z * w2),
            0.5 * (w * w2 + z * w1 - x * w3), 0.5 * (w * w3 + x * w2 - yy * w1),
            wd[0], wd[1], wd[2], y[9], y[10], af[0], af[1]]


def jellett(y):
    _, _, _, _, s, Lg = motion(y)
    return sum(Lg[i] * s[i] for i in range(3))


def energy(y):
    """Kinetic energy (G's velocity: its horizontal part in the state, the vertical l c') and
    potential m g z_G, z_G = r + l c."""
    _, _, _, gam, _, Lg = motion(y)
    om = y[4:7]
    zrate = L * cross(gam, om)[2]
    kinetic = 0.5 * M * (y[9] ** 2 + y[10] ** 2 + zrate ** 2) + 0.5 * sum(Lg[i] * om[i] for i in range(3))
    return kinetic + M * G * (R + L * gam[2])


def scales(y0):
    """heavytop's drift scales (TableSummary): |L_G(0)| (|l| + r) and T(0) + m g |l| + m g r."""
    _, _, _, gam, _, Lg = motion(y0)
    kinetic = energy(y0) - M * G * (R + L * gam[2])
    return math.sqrt(sum(x * x for x in Lg)) * (abs(L) + R), kinetic + M * G * (abs(L) + R)


def start():
    # SPEC 2: the axes on Q(0, theta0) (a rotation about eta), spin about k; P at the origin and
    # O at rest horizontally.
    h = 0.5 * THETA0
    q = (math.cos(h), 0.0, math.sin(h), 0.0)
    y = list(q) + [0.0, 0.0, SPIN, 0.0, 0.0, 0.0, 0.0]
    Rm = rotation(q)
    gam = Rm[2]
    s = (R * gam[0], R * gam[1], L + R * gam[2])
    Gf = [sum(Rm[i][j] * s[j] for j in range(3)) for i in range(3)]
    v = cross((0.0, 0.0, SPIN), (0.0, 0.0, L))  # omega x (G - O) in body axes: 0 here
    vf = [sum(Rm[i][j] * v[j] for j in range(3)) for i in range(3)]
    y[7], y[8], y[9], y[10] = Gf[0], Gf[1], vf[0], vf[1]
    return y


def reference(heavytop):
    """heavytop's end state at 1e-13: tilt, spin, x, y (the columns)."""
    out = subprocess.run([heavytop, "simulate", "--config", "examples/tippe-top.toml", "--t-end", str(HORIZON),
                          "--samples", "2", "--rtol", "1e-13", "--atol", "1e-13", "--format", "json"],
                         check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    return d["tilt"][-1], d["spin"][-1], d["x"][-1], d["y"][-1]


def turns_over_at(heavytop):
    """s, when heavytop's `stability` (its default tolerances, 100 s) finds the tilt passing pi/2."""
    out = subprocess.run([heavytop, "stability", "--config", "examples/tippe-top.toml", "--format", "json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["answer"]["table"]["turns_over_at"]


def end_columns(y):
    Rm, _, _, _, s, _ = motion(y)
    k = (Rm[0][2], Rm[1][2], Rm[2][2])
    tilt = math.atan2(math.hypot(k[0], k[1]), k[2])
    P = [y[7] - sum(Rm[0][j] * s[j] for j in range(3)), y[8] - sum(Rm[1][j] * s[j] for j in range(3))]
    return tilt, y[6], P[0], P[1]


def end_error(end, ref):
    """The largest of the tilt's error (rad), the spin's and P's (relative to the reference's)."""
    return max(abs(end[0] - ref[0]), abs(end[1] - ref[1]) / abs(ref[1]),
               math.hypot(end[2] - ref[2], end[3] - ref[3]) / math.hypot(ref[2], ref[3]))


def scipy_runs(ref, exponents, repeats):
    y0 = start()
    j0, e0 = jellett(y0), energy(y0)
    j_scale, e_scale = scales(y0)
    rows = {}
    for exponent in exponents:
        tol = 10.0 ** -exponent
        times = []
        for _ in range(repeats):
            t0 = time.process_time()
            sol = solve_ivp(rhs, (0.0, HORIZON), y0, method="DOP853", rtol=tol, atol=tol)
            times.append(time.process_time() - t0)
        states = [sol.y[:, i] for i in range(sol.y.shape[1])]
        rows[exponent] = {
            "ms": statistics.median(times) * 1e3, "steps": sol.t.size - 1,
            "jellett": max(abs(jellett(y) - j0) for y in states) / j_scale,
            "energy": max(abs(energy(y) - e0) for y in states) / e_scale,
            "error": end_error(end_columns(sol.y[:, -1]), ref)}
    return rows


def heavytop_runs(bench, ref, repeats):
    out = subprocess.run([bench, "--benchmark_filter=TippeTop", f"--benchmark_repetitions={repeats}",
                          "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    rows = {}
    for b in json.loads(out)["benchmarks"]:
        if b["aggregate_name"] == "median":
            exponent = int(b["run_name"].rsplit("/", 1)[1])
            end = (b["end_tilt"], b["end_spin"], b["end_x"], b["end_y"])
            rows[exponent] = {"ms": b["cpu_time"], "steps": b["steps"], "jellett": b["jellett_drift"],
                              "energy": b["energy_drift"], "error": end_error(end, ref)}
    return rows


def mujoco_runs(mujoco, repeats):
    # From a scratch folder: MuJoCo writes its warnings to MUJOCO_LOG.TXT in the current one.
    folder = os.path.dirname(os.path.abspath(mujoco))
    out = subprocess.run([os.path.abspath(mujoco), "--json", "--reps", str(repeats), "--horizon", str(HORIZON)],
                         check=True, capture_output=True, text=True, cwd=folder).stdout
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def table(title, rows):
    print(f"\n{title}\n")
    print("| tolerance | CPU ms (median) | steps | Jellett drift | energy change | end error |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for exponent, r in sorted(rows.items()):
        print(f"| 1e-{exponent} | {r['ms']:.3f} | {r['steps']:.0f} | {r['jellett']:.2e} | {r['energy']:.3f} | "
              f"{r['error']:.2e} |")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--heavytop", default="build/heavytop")
    parser.add_argument("--bench", default=None, help="build/bench/bench_table")
    parser.add_argument("--mujoco", default=None, help="build/bench/mujoco_tippe_top")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    model = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")),
                 platform.processor())
    print(f"machine: {model}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; "
          f"Python {platform.python_version()}, SciPy {scipy.__version__}")
    ref = reference(args.heavytop)
    print(f"reference (heavytop simulate, rtol = atol = 1e-13): tilt {ref[0]:.12f} rad, spin {ref[1]:.10f} rad/s, "
          f"P ({ref[2]:.12f}, {ref[3]:.12f}) m at t = {HORIZON} s")
    print(f"heavytop stability: the tilt passes pi/2 at t = {turns_over_at(args.heavytop):.3f} s")
    print("drifts: largest |Q(t) - Q(0)| over the accepted steps, over |L_G(0)| (|l| + r) (Jellett) and "
          "T(0) + m g (|l| + r) (energy; friction removes it: the change is the motion's, not an error)")
    print("end error: the largest of |tilt - ref| (rad), |spin - ref| / |ref|, |P - P_ref| / |P_ref|")
    sp = scipy_runs(ref, range(6, 14), args.repeats)
    table(f"SciPy {scipy.__version__} DOP853 (solve_ivp, right-hand side in Python floats), median of "
          f"{args.repeats}", sp)
    if args.bench:
        ht = heavytop_runs(args.bench, ref, args.repeats)
        table(f"heavytop (bench_table, simulate_on_table, DOP853), median of {args.repeats}", ht)
        print("\nequal error: for each SciPy tolerance, the loosest heavytop tolerance with an end error at most "
              "SciPy's (to 1 %)\n")
        print("| SciPy tolerance | SciPy end error | SciPy CPU ms | heavytop tolerance | heavytop end error | "
              "heavytop CPU ms | SciPy / heavytop |")
        print("| --- | ---: | ---: | --- | ---: | ---: | ---: |")
        for exponent, s in sorted(sp.items()):
            match = next(((e, h) for e, h in sorted(ht.items()) if h["error"] <= 1.01 * s["error"]), None)
            if match is None:
                print(f"| 1e-{exponent} | {s['error']:.2e} | {s['ms']:.1f} | none reaches it | | | |")
                continue
            e, h = match
            print(f"| 1e-{exponent} | {s['error']:.2e} | {s['ms']:.1f} | 1e-{e} | {h['error']:.2e} | {h['ms']:.3f} | "
                  f"{s['ms'] / h['ms']:.0f}x |")
    if args.mujoco:
        mj = mujoco_runs(args.mujoco, args.repeats)
        print(f"\nMuJoCo {mj[0]['mujoco']} (its own model: soft contact, Coulomb friction 0.3), {HORIZON} s timed, "
              f"median of {args.repeats}; turning over watched over {mj[0]['watch']:g} s\n")
        print("energy rise: the largest rise of the energy above its running minimum (friction only removes it); "
              "off the plane: steps ending with the sphere above the plane (no contact), and its largest lift\n")
        print("| integrator | step s | CPU ms (median) | steps | Jellett drift | energy change | energy rise | "
              "off the plane | tilt at 5 s | passes pi/2 at | unstable at |")
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for r in mj:
            def when(t):
                return "never" if t is None else f"{t:.3f} s"
            print(f"| {r['integrator']} | {r['timestep']:g} | {r['cpu_ms']:.3f} | {r['steps']} | "
                  f"{r['jellett_drift']:.2e} | {r['energy_change']:.3f} | {r['energy_rise']:.2e} | "
                  f"{r['off_plane']} ({r['max_lift'] * 1e6:.1f} um) | {r['end_tilt']:.4f} | {when(r['turns_over_at'])} | {when(r['unstable_at'])} |")
    print(f"\nload average at the end: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

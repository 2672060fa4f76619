#!/usr/bin/python3
"""Friedl's tippe top turning over (examples/tippe-top.toml, the first 5 s) in SciPy's DOP853,
side by side with heavytop's bench_table.

SciPy integrates the same equations (docs/table.md: the attitude quaternion, the angular
velocity in body axes and the centre of mass's horizontal position and velocity; the normal
force from the height constraint, Cohen's viscous friction), written here again in NumPy-free
Python floats from the page's formulas, not from heavytop's code: an independent check of the
equations too. Each run's end state is compared with a tight reference (heavytop's simulate at
rtol = atol = 1e-13), and Jellett's integral's drift is measured on every accepted step.

Run with Debian's interpreter (python3-scipy), from the repository root:
    /usr/bin/python3 bench/scipy_table.py --heavytop build/heavytop [--bench build/bench/bench_table]
"""

import argparse
import json
import math
import statistics
import subprocess
import time

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


def end_columns(y):
    Rm, _, _, gam, s, _ = motion(y)
    k = (Rm[0][2], Rm[1][2], Rm[2][2])
    tilt = math.atan2(math.hypot(k[0], k[1]), k[2])
    P = [y[7] - sum(Rm[0][j] * s[j] for j in range(3)), y[8] - sum(Rm[1][j] * s[j] for j in range(3))]
    return tilt, y[6], P[0], P[1]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--heavytop", default="build/heavytop")
    parser.add_argument("--bench", default=None)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    ref = reference(args.heavytop)
    print(f"reference (heavytop, 1e-13): tilt {ref[0]:.12f} rad, spin {ref[1]:.10f} rad/s at t = {HORIZON} s")
    y0 = start()
    j0 = jellett(y0)
    for exponent in (8, 9, 10, 11, 12):
        tol = 10.0 ** -exponent
        times = []
        for _ in range(args.repeats):
            t0 = time.process_time()
            sol = solve_ivp(rhs, (0.0, HORIZON), y0, method="DOP853", rtol=tol, atol=tol)
            times.append(time.process_time() - t0)
        drift = max(abs(jellett(sol.y[:, i]) - j0) for i in range(sol.y.shape[1])) / abs(j0)
        end = end_columns(sol.y[:, -1])
        err = max(abs(end[0] - ref[0]), abs(end[1] - ref[1]) / abs(ref[1]))
        print(f"scipy DOP853 tol 1e-{exponent}: {statistics.median(times) * 1e3:9.1f} ms CPU (median of "
              f"{args.repeats}), {sol.t.size - 1} steps, Jellett drift {drift:.2e}, end error {err:.2e}")
    if args.bench:
        out = subprocess.run([args.bench, "--benchmark_filter=TippeTop", "--benchmark_repetitions=5",
                              "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                             check=True, capture_output=True, text=True).stdout
        for b in json.loads(out)["benchmarks"]:
            if b["aggregate_name"] == "median":
                print(f"heavytop {b['run_name']}: {b['cpu_time']:.3f} ms CPU (median), {b['steps']:.0f} steps, "
                      f"Jellett drift {b['jellett_drift']:.2e}")


if __name__ == "__main__":
    main()

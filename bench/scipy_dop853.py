#!/usr/bin/python3
"""The nonlinear model's benchmark problem in SciPy's DOP853, side by side with heavytop.

The problem is bench_nonlinear's: the built-in toy top (heavytop::example_toy_top()) spun at
200 rad/s and started 0.05 rad off vertical, integrated over 10 s at rtol = atol = 1e-10.
SciPy integrates the very equations heavytop integrates (the attitude quaternion with the
spin factored out, docs/nonlinear.md), with the right-hand side in plain Python floats (the
fastest way to write a 8-variable right-hand side for solve_ivp). Both end states are
compared with one tight reference (DOP853 at rtol = 3e-14), itself checked against the
textbook body-frame formulation.

Run with Debian's interpreter (python3-scipy), from the repository root:
    /usr/bin/python3 bench/scipy_dop853.py --bench build-nl/bench/bench_nonlinear
Without --bench only the SciPy side is measured.
"""

import argparse
import json
import math
import statistics
import subprocess
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

# heavytop::example_toy_top() (src/body/body.cpp), SI units.
MASS, GRAVITY, LENGTH = 0.060, 9.81, 0.025
C = 1.2e-5
A = B = 6.0e-6 + 3.75e-5
MGR = MASS * GRAVITY * LENGTH
SPIN, THETA0 = 200.0, 0.05


def initial_factored():
    """SPEC section 2 with phi0 = 0 and zero rates: attitude R_eta(theta0), w = spin e3 (body).
    State: p (w, x, y, z), v1, v2 (transverse angular velocity in the non-spinning frame),
    w3, psi."""
    return [math.cos(THETA0 / 2), 0.0, math.sin(THETA0 / 2), 0.0, 0.0, 0.0, SPIN, 0.0]


def rhs_factored(_t, y):
    """heavytop's symmetric right-hand side (src/integrators/dopri5/nonlinear.cpp, Equations<true>)."""
    w, qx, qy, qz, v1, v2, w3, _psi = y.tolist()
    inv = 1.0 / (w * w + qx * qx + qy * qy + qz * qz)
    g1 = 2.0 * (qx * qz - w * qy) * inv
    g2 = 2.0 * (qy * qz + w * qx) * inv
    n = C / A * w3
    k = MGR / A
    return [-0.5 * (qx * v1 + qy * v2), 0.5 * (w * v1 - qz * v2), 0.5 * (w * v2 + qz * v1),
            0.5 * (qx * v2 - qy * v1), -n * v2 + k * g2, n * v1 - k * g1, 0.0, w3]


def rhs_body(_t, y):
    """The textbook form: q' = 1/2 q (x) (0, w), Euler's equations in body axes."""
    w, qx, qy, qz, o1, o2, o3 = y.tolist()
    inv = 1.0 / (w * w + qx * qx + qy * qy + qz * qz)
    g1 = 2.0 * (qx * qz - w * qy) * inv
    g2 = 2.0 * (qy * qz + w * qx) * inv
    return [-0.5 * (qx * o1 + qy * o2 + qz * o3), 0.5 * (w * o1 + qy * o3 - qz * o2),
            0.5 * (w * o2 + qz * o1 - qx * o3), 0.5 * (w * o3 + qx * o2 - qy * o1),
            ((B - C) * o2 * o3 + MGR * g2) / A, ((C - A) * o3 * o1 - MGR * g1) / B,
            (A - B) * o1 * o2 / C]


def angles(y):
    """theta, phi of SPEC section 2 from the quaternion's axis k = R e3."""
    w, qx, qy, qz = y[:4]
    nn = w * w + qx * qx + qy * qy + qz * qz
    kx = 2.0 * (qx * qz + w * qy) / nn
    ky = 2.0 * (qy * qz - w * qx) / nn
    kz = (w * w - qx * qx - qy * qy + qz * qz) / nn
    return math.atan2(kx, kz), -math.asin(max(-1.0, min(1.0, ky)))


def end_angles(rhs, y0, horizon, tol, atol=None):
    sol = solve_ivp(rhs, (0.0, horizon), y0, method="DOP853", rtol=tol,
                    atol=tol if atol is None else atol)
    if sol.status != 0:
        sys.exit(f"scipy_dop853: solve_ivp failed: {sol.message}")
    return angles(sol.y[:, -1]), sol.nfev


def angle_error(a, b):
    return max(abs(a[0] - b[0]), abs(a[1] - b[1]))


def run_bench(path, tol_exp, repetitions):
    """heavytop's side: bench_nonlinear's headline case, its median counters from JSON."""
    name = f"BM_NonlinearToyTop/samples:2/tol_exp:{tol_exp}/asym:0/real_time"
    out = subprocess.run(
        [path, f"--benchmark_filter=^{name}$", f"--benchmark_repetitions={repetitions}",
         "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    for entry in json.loads(out)["benchmarks"]:
        if entry.get("aggregate_name") == "median":
            return entry
    sys.exit(f"scipy_dop853: no median of {name} in the output of {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", help="path to the bench_nonlinear binary (optional)")
    parser.add_argument("--tol-exp", type=int, default=10, help="rtol = atol = 10^-N (10)")
    parser.add_argument("--horizon", type=float, default=10.0, help="s (10, as bench_nonlinear)")
    parser.add_argument("--repeat", type=int, default=7, help="timed runs; the median counts (7)")
    args = parser.parse_args()
    tol = 10.0 ** -args.tol_exp
    horizon = args.horizon

    print(f"SciPy {scipy.__version__}, NumPy {np.__version__}, Python {sys.version.split()[0]}")
    print(f"problem: toy top, spin {SPIN} rad/s, theta0 {THETA0} rad, horizon {horizon} s, "
          f"rtol = atol = {tol:g}")

    # The reference, and a check of it by the other formulation.
    ref, _ = end_angles(rhs_factored, initial_factored(), horizon, 3e-14, 1e-16)
    y0_body = initial_factored()[:4] + [0.0, 0.0, SPIN]
    ref_body, _ = end_angles(rhs_body, y0_body, horizon, 3e-14, 1e-16)
    print(f"reference (DOP853, rtol 3e-14): theta {ref[0]:.15f} phi {ref[1]:.15f}; "
          f"body-frame formulation differs by {angle_error(ref, ref_body):.2e} rad")

    walls, result, nfev = [], None, 0
    for _ in range(args.repeat):
        start = time.perf_counter()
        result, nfev = end_angles(rhs_factored, initial_factored(), horizon, tol)
        walls.append(time.perf_counter() - start)
    wall = statistics.median(walls)
    scipy_rate = horizon / wall
    scipy_error = angle_error(result, ref)
    print(f"SciPy DOP853: median wall {wall * 1e3:.1f} ms of {args.repeat}, "
          f"{scipy_rate:.1f} simulated s per wall s, {nfev} evaluations "
          f"({wall / nfev * 1e9:.0f} ns each), end angle error {scipy_error:.2e} rad")

    start = time.perf_counter()
    (body_result, body_nfev) = end_angles(rhs_body, y0_body, horizon, tol)
    body_wall = time.perf_counter() - start
    print(f"SciPy DOP853, textbook body-frame equations (for context): {horizon / body_wall:.1f} "
          f"simulated s per wall s, {body_nfev} evaluations, end angle error "
          f"{angle_error(body_result, ref):.2e} rad")

    if args.bench:
        entry = run_bench(args.bench, args.tol_exp, args.repeat)
        ours_rate = entry["sim_s_per_wall_s"]
        ours_error = angle_error((entry["theta_end"], entry["phi_end"]), ref)
        print(f"heavytop (dopri5, {args.bench}): median {ours_rate:.0f} simulated s per wall s, "
              f"{entry['rhs']:.0f} evaluations ({entry['time_per_rhs'] * 1e9:.1f} ns each), "
              f"end angle error {ours_error:.2e} rad")
        print(f"speed ratio heavytop / SciPy DOP853 at rtol = atol = {tol:g}: "
              f"{ours_rate / scipy_rate:.0f}x")


if __name__ == "__main__":
    main()

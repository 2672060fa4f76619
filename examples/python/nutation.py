#!/usr/bin/env python3
"""heavytop from Python: the built-in toy top's nutation, and the paper's stability condition (9)
against the exact linearisation's threshold. Writes two PNG figures.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/nutation.py [OUTPUT_FOLDER]

OUTPUT_FOLDER defaults to this script's folder. Runs headless (matplotlib's Agg backend).

nutation.png    the built-in example (a wooden toy top spun at 200 rad/s, started 0.05 rad off
                vertical): the spin axis's tilt over time and its path seen from above, the
                full body (nonlinear) against the paper's first-order model (4).
thresholds.png  an asymmetric body (A : C = 1 : 2, m g R = 0.01 N m, the asymmetric-plate
                example's) as B/A varies: the spins at which the exact linearisation is
                stable (shaded, from heavytop.sweep), its critical spin, and the paper's (9).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

try:
    import heavytop  # noqa: E402
except ImportError:  # run from the source tree without PYTHONPATH: try the default build folder
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "python"))
    try:
        import heavytop  # noqa: E402
    except ImportError:
        sys.exit("nutation.py: cannot import heavytop; build it (cmake --build build --target heavytop_python) "
                 "and run with PYTHONPATH=build/python /usr/bin/python3 (the Python with NumPy)")


def nutation_figure(path):
    top = heavytop.example_toy_top()
    motion = heavytop.example_motion()  # spin 200 rad/s, theta0 0.05 rad
    t_end, samples = 1.0, 4001
    runs = {
        "nonlinear (the full body)": heavytop.simulate(top, "nonlinear", **motion, t_end=t_end, samples=samples),
        "first-order, the paper's (4)": heavytop.simulate(top, "first-order", **motion, t_end=t_end, samples=samples),
    }
    styles = [dict(color="black", lw=1.6), dict(color="tab:orange", lw=1.2, ls="--")]
    compared = heavytop.compare(top, **motion, t_end=t_end, samples=samples)
    truth = compared["nonlinear"]
    path_end = min(t_end, 2 * np.pi / abs(truth["precession_rate"]))  # one turn of precession

    fig, (ax_tilt, ax_path) = plt.subplots(1, 2, figsize=(12, 5.2), gridspec_kw=dict(width_ratios=[1.5, 1]))
    for (label, m), style in zip(runs.items(), styles):
        theta, phi = m["theta"], m["phi"]
        tilt = np.arccos(np.cos(theta) * np.cos(phi))  # angle of the axis from the upward vertical
        ax_tilt.plot(m["t"], 1e3 * tilt, label=label, **style)
        k_xi, k_eta = np.sin(theta) * np.cos(phi), -np.sin(phi)  # SPEC section 2
        one_turn = m["t"] <= path_end
        ax_path.plot(1e3 * k_xi[one_turn], 1e3 * k_eta[one_turn], label=label, **style)
    ax_tilt.set_xlabel("time t (s)")
    ax_tilt.set_ylabel("tilt of the spin axis from the vertical (mrad)")
    ax_tilt.set_title(f"Nutation: {truth['nutation_frequency']:.1f} rad/s, precession "
                      f"{truth['precession_rate']:.2f} rad/s (nonlinear)")
    low, high = ax_tilt.get_ylim()
    ax_tilt.set_ylim(low, high + 0.25 * (high - low))  # room for the legend above the peaks
    ax_tilt.legend(loc="upper center", ncol=2)
    ax_tilt.grid(alpha=0.3)
    ax_tilt.set_xlim(0, 0.5)

    ax_path.plot([0], [0], marker="+", color="grey", ms=12)
    ax_path.set_aspect("equal")
    ax_path.set_xlabel("k_xi: axis towards xi (mrad)")
    ax_path.set_ylabel("k_eta: axis towards eta (mrad)")
    ax_path.set_title(f"Seen from above: one precession ({path_end:.2f} s)")
    ax_path.grid(alpha=0.3)
    error = compared["models"]["first-order"]["max_angle_error"]
    fig.suptitle(f"The built-in toy top (A = B = {top.A:.3g} kg m^2, C = {top.C:.3g} kg m^2, m g R = {top.mgR:.3g} N m) "
                 f"at {motion['spin']:g} rad/s, started {motion['theta0']:g} rad off vertical\n"
                 f"the paper's first-order model (4) is off the full body by at most {1e3 * error:.2f} mrad "
                 f"over {t_end:g} s", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def thresholds_figure(path):
    base = heavytop.Body(0.010, 0.015, 0.020, mass=1.0, length=1.0193679918450561e-3)  # examples/asymmetric-plate.toml
    ratios = heavytop.grid_values(1.0, 3.0, 401)  # B/A: a real body needs C - A <= B <= A + C
    spins = heavytop.grid_values(0.0, 3.0, 301)   # rad/s
    grid = heavytop.sweep(base, {"B/A": ratios, "spin": spins})
    stable = grid["linearized"].reshape(len(ratios), len(spins))
    paper = [heavytop.stability(heavytop.Body(**dict(base.to_dict(), B=r * base.A)), 0.0)["models"] for r in ratios]
    condition_9 = np.array([m["first-order"]["critical_spin"] for m in paper])
    linearized = np.array([np.nan if m["linearized"]["critical_spin"] is None else m["linearized"]["critical_spin"]
                           for m in paper])

    fig, ax = plt.subplots(figsize=(9, 6))
    ax.contourf(ratios, spins, stable.T.astype(float), levels=[0.5, 1.5], colors=["#b8d8b8"])
    ax.plot([], [], color="#b8d8b8", lw=8, label="stable by the exact linearisation (sweep)")
    ax.plot(ratios, linearized, color="tab:green", lw=2, label="its critical spin (none where C is intermediate)")
    ax.plot(ratios, condition_9, color="tab:red", lw=2, ls="--", label="the paper's (9): $\\omega_0^2 > (\\sqrt{A}+\\sqrt{B})^2\\,mgR/C^2$")
    ax.plot([1.5], [1.3], marker="o", color="black", ls="none",
            label="examples/asymmetric-plate.toml: (9) says stable, it falls")
    ax.axvline(2.0, color="grey", lw=0.8, ls=":")
    ax.text(2.02, 2.85, "B > C: C is the intermediate moment", fontsize=9, color="dimgrey", va="top")
    ax.set_xlabel("B/A (A = 0.01 kg m^2, C = 0.02 kg m^2 held)")
    ax.set_ylabel("spin $\\omega_0$ (rad/s)")
    ax.set_title("Where a spinning asymmetric top stands (m g R = 0.01 N m): (9) against the exact linearisation")
    ax.set_xlim(ratios[0], ratios[-1])
    ax.set_ylim(spins[0], spins[-1])
    ax.legend(loc="lower right", fontsize=9, framealpha=0.95)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(folder, exist_ok=True)
    for name, draw in (("nutation.png", nutation_figure), ("thresholds.png", thresholds_figure)):
        path = os.path.join(folder, name)
        draw(path)
        print(f"nutation.py: wrote {path}")


if __name__ == "__main__":
    main()

"""heavytop's functions: their defaults and documentation, over heavytop._core (which binds the
C++ library) and the typed results of heavytop.results."""
from __future__ import annotations

import json
import os
import re
from collections.abc import Mapping, Sequence as SequenceOf
from typing import Any, Dict, List, Literal, Optional, Tuple

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import Body, Table
from .results import (BodyReport, Comparison, Configuration, ReportView, DecayFit, Derivation, DerivationCheck, Lifetime,
                      Precession, Rotations, Stability, StabilityMap, Trajectory)
from .results import MotionView, SimulationSummary, TableAnalysis, TableSummary, TableTrajectory

__all__ = ["stability", "simulate", "compare", "sweep", "read_map", "derive", "derive_rotations", "derive_check", "body_from_parts",
           "body_report", "precession", "rpm", "lifetime", "fit_decay", "load", "report", "show", "explore"]

ModelName = Literal["first-order", "body-fixed", "linearized", "nonlinear", "lagrange-exact"]
LinearMethod = Literal["analytic", "numeric"]
IntegratorName = Literal["auto", "taylor", "dop853", "dopri5", "adaptive", "splitting"]
SweepIntegratorName = Literal["auto", "taylor", "dop853", "dopri5", "adaptive"]
DeriveMethod = Literal["euler-moving", "euler-fixed", "euler-body", "lagrange"]
Sequence = Literal["phi-theta", "theta-phi"]


def stability(body: Body, spin: Optional[float] = None, *, spin_rpm: Optional[float] = None, theta0: float = 0.0, phi0: float = 0.0, theta_rate0: float = 0.0,
              phi_rate0: float = 0.0, horizon: float = 100.0, max_tilt: float = 1.0,
              lifetime_horizon: Optional[float] = None, table: Optional[Table] = None) -> "Stability | TableAnalysis":
    """Linear stability of the first-order, body-fixed and linearized models at spin w0, the
    real body's Lyapunov verdict (SPEC section 7) and how far its axis wanders.

        body         Body (SI units)
        spin         rad/s, the spin w0 about the body axis (or spin_rpm, in rpm; not both)
        theta0, phi0, theta_rate0, phi_rate0
                     rad, rad/s: the state the wander starts from (SPEC section 2); all 0 (the
                     upright rotation, which never tilts) by default
        horizon      s, > 0: for A != B the wander is the largest tilt of a nonlinear run this
                     long (A = B: exact, from the Lagrange top's cubic); the answer's run when
                     the Lyapunov verdict does not prove it stable
        max_tilt     rad, in (0, pi]: the tilt past which the answer says it has fallen
        lifetime_horizon
                     s, > 0: a damped body's run (None: lifetime()'s, 10 times the time to the
                     critical spin)                                   [--lifetime-horizon]
        table        Table: the body on a table (SPEC section 16; None or Table("pivot"): on its
                     pivot), its shape where it touches Body's tip_radius, rim_radius (m)  [[table]]

    The motion's defaults are those of a configuration file without [motion] (SPEC section
    4): every key 0, spin included; the command line uses the same rule as soon as a body is
    described (only its built-in example brings its own motion).

    Returns a Stability whose repr() (and _repr_html_ in a notebook) starts with .answer, the
    answer in words (SPEC section 14: "Stays up. Spinning at 200 rad/s (1910 rpm) ...");
    .answer.verdict, .proven, .max_tilt, .falls_at, .horizon, .min_spin, .lifetime are
    result["answer"].

    Also: .body, .spin (rad/s), .models[NAME] (NAME first-order, body-fixed,
    linearized) with .stable, .critical_spin (rad/s or None), .stable_spin_intervals
    ((lo, hi or None) pairs, rad/s), .eigenvalues (complex, 1/s), .frequencies (rad/s, when
    stable), .reason. It is also a Mapping: result["models"] and result.to_dict() are
    json.loads of `heavytop stability --format json` for the same input, {"body": {...},
    "spin": w0, "models": {"first-order": {"stable": bool, "critical_spin": ...,
    "stable_spin_intervals": [[lo, hi], ...], "eigenvalues": [[re, im], ...],
    "frequencies": [...], "reason": str}, "body-fixed": {...}, "linearized": {...}}}. The
    linearized model's eigenvalues are those of its body-frame system.
    .lyapunov (a Lyapunov: .verdict "stable" | "unstable" | "undecided", .certificate,
    .energy_index 0 | 1 | 2, .stable_spin_intervals (rad/s), .superfast_spin (rad/s or None),
    .normal_form: for an asymmetric body of index 2 that is linearly stable, a NormalForm
    (.frequencies (w1, w2) rad/s, .c20, .c11, .c02, .D, .resonance, .a13) on which Arnold's
    theorem decides ("kam"; "kam-markeev" or "resonance" at 1:3; "undecided" at D = 0 or 1:1),
    else None) and .wander (a Wander: .max_tilt rad or None, .method
    "closed form" | "integrated", .horizon s or None) are result["lyapunov"] and result["wander"].

    On a table (table=Table("sliding", friction=0.3), say) it returns a TableAnalysis instead:
    `heavytop stability --format json` with [table]. .answer (a TableAnswer: .verdict "leaves the
    table" | "falls" | "turns over" | "stays up" | "stays up for the horizon", .proven, .reason,
    .text, and the table's .upright_at, .turns_over_at, .leaves_at (s or None), .track (m),
    .final_tilt (rad), .final_spin (rad/s)) from the motion followed over `horizon`;
    .table (a TableStability: .contact, .friction, .friction_law, .slip_speed, .tip_radius,
    .rim_radius, and .upright, .inverted: SpinningState with .stable, .asymptotically,
    .critical_spin (rad/s), .stable_spin_intervals, .eigenvalues (1/s), .growth_rate; None for a
    rim); .models (the same body's linear models on a pivot). No .lyapunov, .wander there.

    Bad input raises InvalidInput (a ValueError): "motion.spin: must be a finite number",
    "body.tip_radius: must be >= 0 (m)", "damping.axial: ..." (on a table).

    Given an array of spins (spin=np.linspace(100, 300, 21), or spin_rpm=[...]), it answers each
    and returns a pandas DataFrame, one row per spin in the given order: spin (rad/s), spin_rpm,
    verdict, proven, max_tilt (rad), falls_at (s or NaN), min_spin (rad/s or NaN) from each
    answer, and critical_spin (rad/s or NaN: the linearized model's; on a table the upright
    state's), each row the scalar call's.
    """
    spins = spin if spin_rpm is None else spin_rpm
    if spins is not None and not np.isscalar(spins):
        rows = []
        for value in np.asarray(spins, dtype=float).ravel():
            one = {"spin": float(value)} if spin_rpm is None else {"spin_rpm": float(value)}
            rows.append(_stability_row(stability(body, **one, theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                                                 phi_rate0=phi_rate0, horizon=horizon, max_tilt=max_tilt,
                                                 lifetime_horizon=lifetime_horizon, table=table)))
        import pandas as pd
        return pd.DataFrame(rows, columns=["spin", "spin_rpm", "verdict", "proven", "max_tilt", "falls_at", "min_spin",
                                           "critical_spin"])
    data, words = _core.stability(body, _spin(spin, spin_rpm), theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                                  phi_rate0=phi_rate0, horizon=horizon, max_tilt=max_tilt,
                                  lifetime_horizon=lifetime_horizon, table=table)
    if table is not None and table.on_table:
        return TableAnalysis.from_json(data, words, body)
    return Stability.from_json(data, words)


def simulate(body: Body, model: ModelName = "nonlinear", *, spin: Optional[float] = None,
             spin_rpm: Optional[float] = None, theta0: float = 0.0,
             phi0: float = 0.0, theta_rate0: float = 0.0, phi_rate0: float = 0.0, t_end: float = 10.0,
             samples: int = 1001, method: Optional[LinearMethod] = None,
             integrator: Optional[IntegratorName] = None, rtol: Optional[float] = None,
             atol: Optional[float] = None, step: Optional[float] = None, order: Optional[Literal[2, 4]] = None,
             max_steps: Optional[int] = None, table: Optional[Table] = None) -> Trajectory:
    """The motion of one model: t, theta, phi and their rates (SI units), as NumPy arrays.

    The same computation as `heavytop simulate --format csv`, column for column (the
    command's options in brackets):

        body          Body: A, B, C (kg m^2), mass (kg), length R (m), gravity (m/s^2)
        model         "first-order" | "body-fixed" | "linearized" | "nonlinear" (default)
                      | "lagrange-exact" (A = B)                                  [--model]

      Motion (keyword only):
        spin          rad/s, spin w0 about the body axis (default 0)
        spin_rpm      rpm, the same in revolutions per minute (instead of spin)   [--spin-rpm]
        theta0        rad, initial theta (tilt towards xi)
        phi0          rad, initial phi (tilt about xi)
        theta_rate0   rad/s, initial theta'
        phi_rate0     rad/s, initial phi'

      Options (keyword only):
        t_end         s, end of the simulated interval (> 0; default 10)          [--t-end]
        samples       rows, at t_i = i t_end / (samples - 1) (>= 2; default 1001)  [--samples]
        method        linear models: "analytic" (closed form, the default) |
                      "numeric" (matrix exponential); linear models only          [--method]
        integrator    nonlinear: "auto" (the default: the fastest for the body and
                      tolerance, docs/integrators.md) | "taylor" (Taylor series) |
                      "dop853" (Dormand-Prince 8(5,3)) | "dopri5" or "adaptive"
                      (Dormand-Prince 5(4); the one that takes damping) |
                      "splitting" (fixed step, structure-preserving: bounded
                      energy error over long runs)                                [--integrator]
        rtol          nonlinear: relative tolerance per step (default 1e-12)      [--rtol]
        atol          nonlinear: absolute tolerance per step (default 1e-12)      [--atol]
        step          s, splitting: the fixed step (default 1e-3)                 [--step]
        order         splitting: 2 (Strang, the default) or 4 (Suzuki)            [--order]
        max_steps     nonlinear: the most steps a run may take before it fails
                      (default 1e8 adaptive, 1e9 splitting)
        table         Table: the body on a table (SPEC section 16; None or Table("pivot"): on its
                      pivot), its shape Body's tip_radius, rim_radius (m); the nonlinear
                      model only, integrated by dop853 (integrator "auto" or "dop853") [[table]]

    Returns a Trajectory: float64 arrays of length `samples`, in the CSV's column order, as
    attributes and by name (result.theta is result["theta"]):
        t (s), theta (rad), phi (rad), theta_rate (rad/s), phi_rate (rad/s),
    and for "nonlinear" also energy (J), vertical_momentum (kg m^2/s, about zeta),
    axial_momentum (kg m^2/s, C w3; conserved only when A == B), energy_drift,
    vertical_momentum_drift, axial_momentum_drift (each minus its value at t = 0);
    .columns (their names), .summary (a SimulationSummary: the solver, its steps, the drift of
    the first integrals), .to_dict() (the dict of arrays). theta, phi are SPEC section 2's exact
    angles of the spin axis for every model.

    The arrays are filled in C++ with the GIL released; Ctrl-C (a Jupyter interrupt) stops a
    run within 0.1 s and raises KeyboardInterrupt. Bad input raises InvalidInput (a
    ValueError) naming the keyword argument, or the body's and motion's key as the
    configuration file does: "motion.spin: must be a finite number", "samples: must be an
    integer in [2, 100000000]", "rtol: must be a finite number in [1e-15, 1]". A run that
    fails (an integrator that cannot meet its tolerance, or exceeds max_steps) raises
    RuntimeError with the summary's message (the error's .summary holds the summary).

    On a table it returns a TableTrajectory: SPEC's seven columns, then x, y (m: the contact
    point P), height (m: O above the table), normal_force (N), slip_speed (m/s), spin (rad/s:
    w.k), energy (J), jellett (kg m^3/s), vertical_momentum (kg m^2/s), as the CSV of `heavytop
    simulate` with [table]; .summary a TableSummary (.end "completed" | "leaves the table",
    .end_time s, .steps, .switches, the drifts: the JSON's "summary"). When the normal force
    reaches 0 the columns end there. Painleve's paradox raises RuntimeError naming the time.
    """
    columns, summary, settings = _core.simulate(body, model, spin=_spin(spin, spin_rpm), theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                                      phi_rate0=phi_rate0, t_end=t_end, samples=samples, method=method,
                                      integrator=integrator, rtol=rtol, atol=atol, step=step, order=order,
                                      max_steps=max_steps, table=table)
    if settings is not None:  # on a table (SPEC section 16)
        return TableTrajectory(columns, TableSummary.from_json(summary), body, _spin(spin, spin_rpm), table, settings)
    summary = SimulationSummary.from_json(summary)
    if not summary.ok:
        error = RuntimeError(summary.message)
        error.summary = summary  # type: ignore[attr-defined]
        raise error
    return Trajectory(columns, summary, body, _spin(spin, spin_rpm))


def compare(body: Body, *, spin: Optional[float] = None, spin_rpm: Optional[float] = None, theta0: float = 0.0,
            phi0: float = 0.0, theta_rate0: float = 0.0,
            phi_rate0: float = 0.0, t_end: float = 10.0, samples: int = 10001, rtol: Optional[float] = None,
            atol: Optional[float] = None) -> Comparison:
    """Every approximate model against the full nonlinear body, from one state over one horizon.

        body                      Body (SI units)
        spin, theta0, phi0,       the initial state (rad/s, rad, rad, rad/s, rad/s; keyword only,
        theta_rate0, phi_rate0    default 0)
        spin_rpm                  rpm, the spin in revolutions per minute (instead of spin)
        t_end                     s, horizon (> 0; default 10)                     [--t-end]
        samples                   samples over the horizon (3 to 2000000: every model's whole
                                  trajectory is held; default 10001)             [--samples]
        rtol, atol                nonlinear: tolerances per step (default 1e-12)   [--rtol, --atol]

    Returns a Comparison: .nonlinear (the truth: .nutation_frequency, .precession_rate (rad/s),
    .steps, .max_relative_energy_drift) and .models[NAME] (first-order, body-fixed,
    linearized, and lagrange-exact when A = B) with .max_angle_error, .final_angle_error (rad,
    the larger of |d theta| and |d phi|), .nutation_frequency, .precession_rate (rad/s),
    .nutation_relative_error, .precession_relative_error, or .diverged_at (s) for a linear model
    whose angles passed 1 rad (its errors after that and frequencies are None). As a Mapping and by .to_dict() it is
    json.loads of `heavytop compare --format json`. Runs with the GIL released; Ctrl-C stops it.
    Bad input raises InvalidInput (a ValueError): "samples: must be an integer in [3, 2000000]".
    """
    return Comparison.from_json(_core.compare(body, spin=_spin(spin, spin_rpm), theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                                              phi_rate0=phi_rate0, t_end=t_end, samples=samples, rtol=rtol,
                                              atol=atol))


def sweep(body: Body, vary: Mapping[str, npt.ArrayLike], *, spin: float = 0.0, theta0: float = 0.0,
          phi0: float = 0.0, theta_rate0: float = 0.0, phi_rate0: float = 0.0, nonlinear: bool = False,
          horizon: float = 100.0, max_tilt: float = 0.5, rtol: Optional[float] = None,
          atol: Optional[float] = None,
          integrator: Optional[SweepIntegratorName] = None) -> StabilityMap:
    """A stability map: each model's verdict over a grid of one, two or three parameters.

    The computation of `heavytop sweep --vary KEY=START:STOP:COUNT [--vary ...]`, in C++ on every
    core with the GIL released.

        body        Body (SI units): the base the grid varies
        vary        {KEY: values} with one to three keys, each a body key (A, B, C, mass, gravity,
                    length), "spin", "spin_rpm" (values in rpm: the column "spin" in rad/s, as
                    the command line's spin_rpm), or a ratio "B/A" or "C/A" (the numerator
                    changes, the denominator is held at the body's value); values a 1-D array
                    (SI units).
                    The grid is the product of the arrays, the first key slowest (dict order).
      Motion (keyword only): spin (rad/s), theta0, phi0 (rad), theta_rate0, phi_rate0 (rad/s),
                    the base state (default 0)
      Options (keyword only):
        nonlinear   also judge each point by a nonlinear simulation (needs a tilted start)
        horizon     s, simulated time of each nonlinear run (> 0; default 100)   [--horizon]
        max_tilt    rad, a nonlinear run is stable if its tilt stays <= this
                    (default 0.5)                                                [--max-tilt]
        rtol, atol  nonlinear: tolerances per step (default 1e-12)              [--rtol, --atol]
        integrator  nonlinear: "auto" (the default: the Taylor integrator on several
                    points at a time, docs/integrators.md "Batched sweeps") | "taylor"
                    (the same) | "dopri5" | "dop853" (one point at a time)      [--integrator]

    Returns a StabilityMap, one array per CSV column, one element per grid point (row-major, the
    first key slowest): each key's values (float64), then "first-order", "body-fixed",
    "linearized", "lyapunov" (proven Lyapunov stable, SPEC section 7) and, when asked,
    "nonlinear" (bool: stable); result["linearized"],
    .parameters, .verdicts, .shape (the grid's), .grid(NAME) (a column reshaped to the grid),
    .to_dict() (the dict of arrays).

    Any values are judged exactly as given. When every array is the command line's
    START:STOP:COUNT grid (grid_values(start, stop, count), bit for bit) the sweep makes the
    command line's own calls (heavytop::sweep_verdicts over blocks of the grid); otherwise each
    point is judged by that same routine as a grid of one point. Either way the points run in
    parallel, one thread per core, and the verdicts are the same at the same values. Ctrl-C (a
    Jupyter interrupt) stops it within a block and raises KeyboardInterrupt.
    Bad input raises InvalidInput (ValueError) naming the keyword argument ("vary: unknown key
    'D'", "max_tilt: must exceed the initial tilt").
    """
    if isinstance(vary, Mapping):
        vary = dict(vary)
    columns = _core.sweep(body, vary, spin=spin, theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                          phi_rate0=phi_rate0, nonlinear=nonlinear, horizon=horizon, max_tilt=max_tilt, rtol=rtol,
                          atol=atol, integrator=integrator)
    shape = tuple(int(np.size(values)) for values in vary.values())  # checked by the core: 1-D arrays
    return StabilityMap(columns, shape)


def read_map(path: "os.PathLike[str] | str") -> StabilityMap:
    """A stability map written by `heavytop sweep --output FILE` (CSV, or HDF5 with --format hdf5),
    read back as sweep() returns one: a StabilityMap of one array per CSV column (the varied
    keys' values in SI units, float64; a bool array per model; the certificates as strings),
    shaped by .grid(NAME) to the map's grid (one to three keys, the first slowest).

    A three-parameter map's heat maps are its slices: read_map("map.h5").slice("C/A", 2.0)
    holds C/A at its grid value nearest 2.0, and .plot("nonlinear") draws it (matplotlib).
    The file is read in C++ (no h5py needed); a file that is not a sweep's map raises
    InvalidInput naming `path` and what is wrong ("path: row 7 has 5 columns, the header 7").
    """
    columns, shape = _core.read_map(os.fspath(path))
    return StabilityMap(columns, shape)


def derive(method: DeriveMethod = "euler-moving", sequence: Sequence = "phi-theta",
           order: Literal[1, 2] = 1) -> Derivation:
    """The paper's linear model derived symbolically (GiNaC): M q'' + G q' + K q = 0, q = (phi, theta).

        method     "euler-moving" (default) | "euler-fixed" | "euler-body" | "lagrange"
        sequence   "phi-theta" (default) | "theta-phi": the order of the small rotations
        order      1 | 2: order of smallness kept in the kinematics

    Returns a Derivation: .M, .G, .K (2x2 tuples of strings), .characteristic_polynomial,
    .stability_condition; every entry a string in A, B, C (kg m^2), m (kg), g (m/s^2), R (m),
    omega0 (rad/s) (and lambda, 1/s), `^` for powers (sympy reads them after ^ -> **). As a Mapping and by .to_dict() it is
    json.loads of `heavytop derive --method M --sequence S --order N --format json`. Bad input
    raises InvalidInput (a ValueError): "order: must be 1 or 2"; built without GiNaC
    (HAS_DERIVE false), RuntimeError.
    """
    return Derivation.from_json(_core.derive(method, sequence, order))


def derive_rotations(order: Literal[1, 2] = 1) -> Rotations:
    """The paper's small-rotation matrices to `order` (1 or 2): .A1, .A2, .A3, .A1A2, .A2A1,
    .commutator (= A1A2 - A2A1), 3x3 tuples of strings in the small angles phi, theta, psi (rad;
    rows i, j, k in terms of l, m, n, dimensionless); as a Mapping, json.loads of `heavytop derive --rotations --format json`.
    """
    return Rotations.from_json(_core.derive_rotations(order))


def derive_check(order: Optional[Literal[1, 2]] = None) -> DerivationCheck:
    """Every route and rotation sequence at `order` (1, 2, or None for both), the matrices in the
    symbols A, B, C (kg m^2), m (kg), g (m/s^2), R (m), omega0 (rad/s): .rows (each with
    .method, .sequence, .order, .M, .G, .K, .model, .expected, .as_expected, .why) and
    .all_as_expected; as a Mapping, json.loads of `heavytop derive --check --format json`.
    """
    return DerivationCheck.from_json(_core.derive_check(order))


def lifetime(body: Body, *, spin: float, theta0: float = 0.0, phi0: float = 0.0, theta_rate0: float = 0.0,
             phi_rate0: float = 0.0, horizon: Optional[float] = None, max_tilt: float = 1.0,
             rtol: Optional[float] = None, atol: Optional[float] = None,
             max_steps: Optional[int] = None) -> Lifetime:
    """How long the top stays up (SPEC section 8), with the body's damping (Body(...,
    transverse_damping=, axial_damping=, friction=, driven=)).

        spin, theta0, phi0, theta_rate0, phi_rate0
                     rad/s, rad: the initial state (SPEC section 2)
        horizon      s, > 0: the longest nonlinear run; None: 10 times the time to the
                     critical spin (1000 s when that is None or 0)
        max_tilt     rad, in (0, pi]: the tilt from the upward vertical past which it has fallen
        rtol, atol, max_steps
                     the nonlinear integrator's settings (None: the command line's defaults)

    Returns a Lifetime: .critical_spin (rad/s, the linearized model's without damping; None
    if no spin holds it up), .time_to_critical (s, by the closed-form spin law C w' = -d_a w
    - tau0 sign(w); 0 if already below; None if never), .fall_time (s) and .fall_spin (rad/s,
    the integrated w.k) or None if it does not fall within .horizon, .max_tilt. As a Mapping
    it is json.loads of `heavytop lifetime --format json`. Ctrl-C stops it.
    """
    return Lifetime.from_json(_core.lifetime(body, spin=spin, theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                                             phi_rate0=phi_rate0, horizon=horizon, max_tilt=max_tilt, rtol=rtol,
                                             atol=atol, max_steps=max_steps), body=body, spin=spin)
def rpm(value: float) -> float:
    """rad/s of a spin given in rpm (SPEC section 9): rpm(3000) == 100 pi. Every function taking
    a spin in rad/s takes rpm(x) for a spin of x rpm, exactly as the command line's --spin-rpm."""
    return _core.rad_per_s_from_rpm(value)


def _invalid(key: str, rule: str) -> Exception:
    error = _core.InvalidInput(f"{key}: {rule}")
    error.key, error.rule = key, rule  # type: ignore[attr-defined]
    return error


def _parts_toml(parts: SequenceOf[Mapping[str, Any]]) -> str:
    if isinstance(parts, Mapping) or isinstance(parts, str) or not isinstance(parts, SequenceOf):
        raise _invalid("parts", "must be a list of dicts, one per part")
    lines: List[str] = []
    for i, part in enumerate(parts):
        if not isinstance(part, Mapping):
            raise _invalid(f"body.part[{i}]", "must be a dict of the part's keys (shape, radius, ...)")
        lines.append("[[body.part]]")
        for key, value in part.items():
            if not isinstance(key, str) or not re.fullmatch(r"[A-Za-z0-9_]+", key):
                raise _invalid(f"body.part[{i}].{key!s}", "unknown key")
            if isinstance(value, str):
                lines.append(f"{key} = {json.dumps(value)}")  # a JSON string is a TOML basic string
            elif isinstance(value, (int, float)) and not isinstance(value, bool):
                lines.append(f"{key} = {float(value)!r}")
            else:
                raise _invalid(f"body.part[{i}].{key}", "must be a number or a string")
    return "\n".join(lines) + "\n"


def _assemble(parts: SequenceOf[Mapping[str, Any]], gravity: float, folder: str,
              allow_general: bool) -> Tuple[Dict[str, Any], Optional[Body]]:
    # The configuration's own parser reads them: the same keys, defaults and messages as a file.
    # A relative mesh path is relative to `folder` (a file's are to the file's folder).
    return _core.assemble_parts(_parts_toml(parts), os.path.join(folder, "parts"), gravity, allow_general)


def body_from_parts(parts: SequenceOf[Mapping[str, Any]], *, gravity: float = 9.81, folder: str = ".") -> Body:
    """The Body (A, B, C in kg m^2 about O, mass kg, length m) that parts make (SPEC section 10).

        parts    a list of dicts, each a [[body.part]] of a configuration file: shape ("cylinder",
                 "tube", "cone", "sphere", "mesh"), radius, inner_radius (tube), height (m), z0 (m,
                 its lowest point above O), apex ("down" | "up", cone), density (kg/m^3) or mass
                 (kg); a mesh: file (STL, OBJ, PLY), units ("m" | "mm")
        gravity  m/s^2 (default 9.81)
        folder   where a relative mesh path starts (default: the working folder)

    Bad parts raise InvalidInput naming the part as the command line does ("body.part[0].radius
    (cone): must be a finite number > 0"). Parts off the axis make SPEC section 11's general body
    (the centre of mass off z, or z not a principal axis: body.general, .offset_x, .offset_y, .Ixy,
    .Ixz, .Iyz), the tensor about the parts' own axes as `simulate --model nonlinear --config`
    takes it: simulate(body, "nonlinear") integrates it, the other analyses refuse it.
    """
    body = _assemble(parts, gravity, folder, True)[1]
    assert body is not None
    return body


def body_report(parts: "SequenceOf[Mapping[str, Any]] | Body", *, gravity: float = 9.81,
                folder: str = ".") -> BodyReport:
    """The mass properties these parts make, a BodyReport (.A, .B, .C kg m^2, .mass kg, .length m,
    .general) whose to_dict() is json.loads of `heavytop body --format json` (see body_from_parts): {"A", "B",
    "C" (kg m^2 about O), "mass" (kg), "length" (m), "gravity" (m/s^2), "products": {"xy", "xz", "yz"}
    (kg m^2), "offset": {"x", "y"} (m), "principal_axis_tilt" (rad), "general" (bool), "parts": [{"name",
    "mass", "centre_of_mass", "inertia"}]}. A general body is reported, not refused.

        parts    a list of [[body.part]] dicts (body_from_parts), or a Body given by its keys (its
                 offsets and products of inertia too: `heavytop body` of a [body] section)
        gravity  m/s^2, for parts (a Body keeps its own)
        folder   where a relative mesh path starts (default: the working folder)
    """
    if isinstance(parts, Body):
        return BodyReport.from_json(_core.body_json(parts))
    return BodyReport.from_json(_assemble(parts, gravity, folder, True)[0])


def precession(body: Body, tilt: float, spin: Optional[float] = None, *, spin_rpm: Optional[float] = None) -> Precession:
    """Steady motions at a tilt (rad), a Precession (.slow, .fast: each a SteadyPrecession with
    .rate rad/s, .period s, .nutation_frequency rad/s, .state, or None; .min_spin rad/s) whose
    to_dict() is json.loads of `heavytop precession --tilt TILT --format json`.

        body      Body (SI units)
        tilt      rad, the axis's angle from the upward vertical, in (0, pi)
        spin      rad/s, w3 = w.k (or spin_rpm in rpm; not both; default 0)

    to_dict() is {"body", "tilt", "spin", "steady_precession": {"slow", "fast" (each {"rate" rad/s,
    "period" s, "nutation_frequency" rad/s, "state": the SPEC section 2 state on it} or None),
    "min_spin" (rad/s or None), "slow_limit", "fast_limit"} (None for A != B),
    "permanent_rotations": [{"plane", "rate", "period", "stable", "eigenvalues", "state"}]}.
    """
    return Precession.from_json(_core.precession(body, tilt, _spin(spin, spin_rpm)))


def chaos(body: Body, spin: Optional[float] = None, *, spin_rpm: Optional[float] = None, theta0: float = 0.0,
          phi0: float = 0.0, theta_rate0: float = 0.0, phi_rate0: float = 0.0, horizon: float = 1000.0,
          precision: Optional[float] = None, renormalisation_interval: float = 1.0,
          section: bool = False) -> Dict[str, Any]:
    """How chaotic the motion from this start is (SPEC 17, docs/chaos.md): json.loads of
    `heavytop chaos --format json`, {"lyapunov_exponent" (1/s), "lyapunov_error" (1/s),
    "history" ([t, l(t)] rows), "spectrum" (six, 1/s, descending), "megno", "prediction_horizon"
    (s, or None when not chaotic), "precision", "chaotic"}; with section=True that of
    `chaos --section --format json`, the Poincare section psi = 0 (t s, tilt rad, tilt_rate rad/s).

        body        Body (SI units): conservative, on a pivot (the general body too)
        spin, theta0, phi0, theta_rate0, phi_rate0
                    the start (SPEC section 2; spin or spin_rpm)
        horizon     s, > 0: the run's length T                               [--horizon]
        precision   the relative precision delta in (0, 1) to which the start is known (None:
                    1e-15): the prediction horizon is ln(1e-2 / delta) / lambda  [--precision]
        renormalisation_interval
                    s, > 0: Benettin's renormalisation   [--renormalisation-interval]
    """
    return _core.chaos(body, _spin(spin, spin_rpm), theta0=theta0, phi0=phi0, theta_rate0=theta_rate0,
                       phi_rate0=phi_rate0, horizon=horizon, precision=precision,
                       renormalisation_interval=renormalisation_interval, section=section)


def example_file(name: str) -> str:
    """The path of one of the examples the package ships: the repository's examples/ folder,
    copied into the installed package (heavytop/examples/), so that a notebook or script runs
    from any folder, e.g. a copy of examples/notebooks/tour.ipynb:

        heavytop.load(heavytop.example_file("toy-top.toml"))         # as --config examples/toy-top.toml
        t, w = np.loadtxt(heavytop.example_file("spin-decay.csv"), delimiter=",", skiprows=5, unpack=True)

        name        the file's name in examples/: a configuration file (*.toml, SI units: kg m^2,
                    kg, m, rad/s), spin-decay.csv (a measured spin decay: t in s, spin in rad/s)
                    or meshes/spinning-top.stl

    An unknown name raises InvalidInput naming the examples ("name: no example 'x.toml'; the
    examples: asymmetric-plate.toml, ...")."""
    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "examples")
    shipped = sorted(os.path.relpath(os.path.join(d, f), folder).replace(os.sep, "/")
                     for d, _, files in os.walk(folder) for f in files)
    name = os.fspath(name)
    if name not in shipped:
        listing = ", ".join(shipped) if shipped else "none (this package was built without them)"
        raise _invalid("name", f"no example {name!r}; the examples: {listing}")
    return os.path.join(folder, *name.split("/"))


def load(path: "os.PathLike[str] | str") -> Configuration:
    """A configuration file (TOML, SPEC section 4), read by the command line's own reader:
    a Configuration with .body (a Body: [body] or its [[body.part]], and [damping]; SI units),
    .motion (the [motion] keys as simulate()'s keyword arguments: spin rad/s, theta0, phi0 rad,
    theta_rate0, phi_rate0 rad/s; 0 where not given), .options (the further sections'
    values, "simulate.t_end": 10.0) and .section(NAME).

        cfg = heavytop.load("examples/toy-top.toml")
        heavytop.stability(cfg.body, **cfg.motion)

    A [table] (SPEC section 16) is .table (a Table; Table("pivot") when absent), the body's
    tip_radius and rim_radius (m) in .body:

        cfg = heavytop.load("examples/tippe-top.toml")
        heavytop.stability(cfg.body, **cfg.motion, table=cfg.table).answer.verdict   # "turns over"

    Bad files raise InvalidInput with the command line's message for `--config FILE`, the
    file's key first ("motion.spni: unknown key in FILE", "body.B: is required in [body], ...",
    "table.friction: must be a finite number >= 0"), or "path: cannot read 'FILE': no such
    file". A general body (SPEC section 11) is refused as every analysis but `simulate --model
    nonlinear` refuses it; on a table a general or damped body is refused naming its key.
    """
    path = os.fspath(path)
    body, motion, options, given, from_parts, table = _core.load_configuration(path)
    return Configuration(path=path, body=body, motion=dict(motion), options=dict(options), given=tuple(given),
                         from_parts=bool(from_parts), table=table)


def _stability_row(result: "Stability | TableAnalysis") -> Dict[str, Any]:
    """One row of stability()'s frame: the answer's numbers and the critical spin (NaN for None)."""
    data = result.to_dict()
    answer = data["answer"]
    nan = float("nan")
    number = lambda x: nan if x is None else float(x)
    critical = (data["table"]["upright"] or {}).get("critical_spin") if "table" in data \
        else data["models"]["linearized"]["critical_spin"]
    spin = float(data["spin"])
    return {"spin": spin, "spin_rpm": spin * 30.0 / np.pi, "verdict": answer["verdict"], "proven": answer["proven"],
            "max_tilt": number(answer["max_tilt"]), "falls_at": number(answer["falls_at"]),
            "min_spin": number(answer["min_spin"]), "critical_spin": number(critical)}


def _refuse_table(configuration: Configuration, command: str) -> None:
    """As the command line refuses [table] for a command that is the pivot's (SPEC section 16)."""
    if configuration.table.on_table:
        raise _invalid("table.contact", f"{command}() is for a body on a pivot; on a table (contact = "
                                        f"\"{configuration.table.contact}\") use simulate() or stability() with table=")


def _spin(spin: Optional[float], spin_rpm: Optional[float]) -> float:
    if spin is not None and spin_rpm is not None:
        raise _invalid("spin_rpm", "give spin or spin_rpm, not both")
    return rpm(spin_rpm) if spin_rpm is not None else (0.0 if spin is None else spin)


_MAX_DECAY_POINTS = (32 << 20) // 4  # kMaxDecayDataBytes / the shortest row, "0,0\n"


def fit_decay(t: npt.ArrayLike, spin: npt.ArrayLike, body: Optional[Body] = None, *,
              spin0: Optional[float] = None) -> DecayFit:
    """The axial damping d_a and the dry friction tau0 of a top ([damping] axial, friction),
    fitted to a measured spin decay: `heavytop fit-decay --format json` for the same points.

        t        s, the times (>= 0, non-decreasing)                        [CSV column t]
        spin     rad/s, the spin's magnitude at each time (>= 0; 0 once dry
                 friction has stopped it; rpm * pi / 30 for rpm)             [CSV column spin]
        body     Body: only C (kg m^2, about the spin axis) enters; default the
                 built-in toy top, as the command line without --config
        spin0    rad/s: the spin at t = 0 when known; None (default) fits it  [--known-spin0]

    Least squares on the spin (unweighted) through the law C w' = -d_a w - tau0 sign(w), exact
    for a free symmetric body (A = B; a warning says so otherwise), with Eigen's
    Levenberg-Marquardt; d_a and tau0 are bounded below by 0. At least 4 points (3 with spin0).

    Returns a DecayFit: .axial (N m s), .friction (N m), .spin0 (rad/s), each a
    FittedParameter (.value, .uncertainty, .fitted, .at_bound); .rms_residual (rad/s),
    .points, .converged, .correlation, .C (kg m^2), .stop_time (s or None), .termination,
    .warnings. Bad input raises InvalidInput (a ValueError): "data: point 3: t must be >= 0
    and non-decreasing", "spin0: must be a finite number > 0 ...", "body.C: ...". A fit that
    does not converge raises RuntimeError (its .result holds the DecayFit).
    """
    for key, values in (("t", t), ("spin", spin)):  # refused before NumPy allocates them (range(10**12))
        try:
            count = len(values)
        except TypeError:
            continue
        if count > _MAX_DECAY_POINTS:
            raise _invalid(key, f"{count} points; at most {_MAX_DECAY_POINTS} (the rows fit-decay's largest CSV, 32 MiB, holds)")
    fit = DecayFit.from_json(_core.fit_decay(np.asarray(t, dtype=np.float64).ravel().tolist(),
                                             np.asarray(spin, dtype=np.float64).ravel().tolist(),
                                             body if body is not None else _core.example_toy_top(), spin0=spin0))
    if not fit.converged:
        error = RuntimeError(f"fit_decay: the fit did not converge: {fit.termination}")
        error.result = fit  # type: ignore[attr-defined]
        raise error
    return fit


def report(body: "Body | Configuration", folder: "os.PathLike[str] | str", *, spin: Optional[float] = None,
           spin_rpm: Optional[float] = None, theta0: Optional[float] = None, phi0: Optional[float] = None,
           theta_rate0: Optional[float] = None, phi_rate0: Optional[float] = None, t_end: Optional[float] = None,
           map: "os.PathLike[str] | str | None" = None,
           slice: Optional[Tuple[str, SequenceOf[float]]] = None, title: Optional[str] = None) -> str:
    """Writes the report folder of `heavytop report --output FOLDER` (SPEC section 5): report.html
    (the answer first, the 3D view, the models, the motion), its figures (PNG, SVG, by gnuplot)
    and data (CSV, JSON); returns the path of FOLDER/report.html.

        body        a Body (SI units), or a Configuration from load(): its body, its motion (the
                    keywords below override it) and its file named in the title, as --config
        folder      where to write (created if needed)
        spin, theta0, phi0, theta_rate0, phi_rate0
                    rad/s, rad: the initial state (default 0, or the Configuration's); spin_rpm in rpm
        t_end       s, > 0: the motion's horizon (None: up to the fall and a fifth more when it
                    falls, else a few precession periods)                         [--t-end]
        map         a sweep's file (CSV or HDF5, `heavytop sweep --output`) to draw   [--map]
        slice       (KEY, [V1, ...]): a three-key map's heat maps hold KEY at its grid values
                    nearest these (default: the last key at its first, middle, last)  [--slice]
        title       the title's first words; None: the Configuration's file, "A body given in
                    Python", or for example_toy_top() the built-in example's title

    Runs with the GIL released. Bad input raises InvalidInput naming the argument ("t_end: must
    be finite and > 0", "map: ...", "slice: ..."); a figure gnuplot cannot draw raises RuntimeError.
    """
    source = ""
    state = {"spin": 0.0, "theta0": 0.0, "phi0": 0.0, "theta_rate0": 0.0, "phi_rate0": 0.0}
    if isinstance(body, Configuration):
        _refuse_table(body, "report")
        source, state, body = body.path, dict(body.motion), body.body
    elif body != _core.example_toy_top():
        source = "A body given in Python"  # the default title names the built-in example, which this is not
    if title is not None:
        source = str(title)
    given = {"theta0": theta0, "phi0": phi0, "theta_rate0": theta_rate0, "phi_rate0": phi_rate0}
    state.update({k: v for k, v in given.items() if v is not None})
    if spin is not None or spin_rpm is not None:
        state["spin"] = _spin(spin, spin_rpm)
    held, values = "", []
    if slice is not None:
        if isinstance(slice, str) or len(slice) != 2:
            raise _invalid("slice", "must be (KEY, [V1, V2, ...])")
        held, values = str(slice[0]), [float(v) for v in np.atleast_1d(slice[1])]
    folder = os.fspath(folder)
    _core.write_report(folder, body, state["spin"], state["theta0"], state["phi0"], state["theta_rate0"],
                       state["phi_rate0"], t_end, "" if map is None else os.fspath(map), held, values, source)
    return os.path.join(folder, "report.html")


def show(body: "Body | Configuration | Trajectory", folder: "os.PathLike[str] | str | None" = None, *,
         height: int = 720, **options: Any) -> "ReportView | MotionView":
    """Shows a body's report, or one trajectory's motion, inline in a notebook (offline).

    show(body or Configuration, folder=None, **options): the report (report(), the same keywords:
    spin rad/s, theta0 rad, ..., t_end s, map), a ReportView whose HTML is the report's page with
    its three.js view of the body moving in 3D, its plots and figures inlined (a few MB; in an
    iframe `height` pixels tall, scrolled to the 3D view). The folder is written to `folder`, or
    to a new temporary folder; the title names the Configuration's file, else "A body given in
    Python" (title= to choose). A temporary folder (folder=None; the view's .folder) is removed
    when the Python process (the notebook's kernel) exits, or at once if the report fails; a
    folder given is the caller's and is kept.

    show(trajectory): that motion (simulate()'s Trajectory, any model) in the report's 3D view,
    a MotionView (trajectory.view(height); the trajectory's own HTML shows it too).
    """
    if isinstance(body, Trajectory):
        if folder is not None or options:
            raise _invalid("show", "a trajectory takes only height=")
        return body.view(height)
    if folder is not None:
        folder = os.fspath(folder)
        report(body, folder, **options)
        return ReportView(folder, height)
    folder = _temporary_folder("heavytop-report-")
    try:
        report(body, folder, **options)
        return ReportView(folder, height)
    except BaseException:
        _remove_folder(folder)
        raise


def _remove_folder(folder: str, owner: Optional[int] = None) -> None:
    import shutil
    if owner is None or owner == os.getpid():  # not from a forked child that exits
        shutil.rmtree(folder, ignore_errors=True)


def _temporary_folder(prefix: str) -> str:
    """A new folder in the temporary directory ($TMPDIR), removed when this process exits."""
    import atexit
    import tempfile
    folder = tempfile.mkdtemp(prefix=prefix)
    atexit.register(_remove_folder, folder, os.getpid())
    return folder


def _explorer_page_file() -> str:
    # Where `heavytop explore` finds it: beside an installed package, in this build tree (web/),
    # or where `cmake --install` puts it (PREFIX/share/heavytop); "" when it was not built.
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "heavytop-explore.html"), _core.BUILT_EXPLORER_PAGE,
                      os.path.join(sys.prefix, "share", "heavytop", "heavytop-explore.html")):
        if candidate and os.path.isfile(candidate):
            return candidate
    return ""


def explore(body: "Body | Configuration", path: "os.PathLike[str] | str", *, spin: Optional[float] = None,
            spin_rpm: Optional[float] = None, theta0: Optional[float] = None, phi0: Optional[float] = None,
            theta_rate0: Optional[float] = None, phi_rate0: Optional[float] = None) -> str:
    """Writes the explorer page of `heavytop explore --output PATH` (SPEC section 15): one
    self-contained HTML file (the core in WebAssembly inside it; no network, opens from file://)
    whose inputs start at this body, its damping and this motion; returns PATH.

        body        a Body (SI units: A, B, C kg m^2, mass kg, length m, gravity m/s^2, damping
                    N m s and N m), or a Configuration from load() (its body and its motion)
        path        the page's file, written as --output writes it: through a temporary name
                    beside it and a rename, so that a failed write leaves an existing file as it
                    was (a device or pipe is written directly; a folder raises InvalidInput,
                    a write that fails OSError)
        spin        rad/s, the spin w0 (or spin_rpm in rpm; not both); theta0, phi0 rad and
                    theta_rate0, phi_rate0 rad/s: the initial state (default 0, or the
                    Configuration's)

    The page is built by Emscripten with the rest (./scripts/build.sh --web, the CMake target
    heavytop_web); without it this raises InvalidInput with the command line's message
    ("explore: this heavytop was built without the explorer page, ..."), as bad input does
    ("body.A: must be > 0"; a general body, SPEC section 11, is refused as the command refuses
    it), and writes nothing.
    """
    state = {"spin": 0.0, "theta0": 0.0, "phi0": 0.0, "theta_rate0": 0.0, "phi_rate0": 0.0}
    if isinstance(body, Configuration):
        _refuse_table(body, "explore")
        state, body = dict(body.motion), body.body
    given = {"theta0": theta0, "phi0": phi0, "theta_rate0": theta_rate0, "phi_rate0": phi_rate0}
    state.update({k: v for k, v in given.items() if v is not None})
    if spin is not None or spin_rpm is not None:
        state["spin"] = _spin(spin, spin_rpm)
    page = _core.explorer_page(_explorer_page_file(), body, state["spin"], state["theta0"], state["phi0"],
                               state["theta_rate0"], state["phi_rate0"])
    path = os.fspath(path)
    _core.write_file(os.fsencode(path), page, "path")  # as --output: a temporary name, then a rename
    return path

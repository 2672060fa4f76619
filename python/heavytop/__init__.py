"""heavytop: the heavy top (a rigid body turning about a fixed point O in uniform gravity,
spinning fast about its axis), its approximate models, their stability and motion.

Units are SI everywhere: kg, m, s, rad (rates rad/s). The conventions are those of docs/contract.md in heavytop's repository:

  Fixed frame (xi, eta, zeta), zeta vertical and up. Body frame: principal axes x, y, z
  through O, z the spin axis. k = the unit vector of the spin axis, and the paper's angles are
      phi   = -asin(k_eta)   (tilt about xi)
      theta = atan2(k_xi, k_zeta)   (tilt towards xi)
  so k = (sin theta cos phi, -sin phi, cos theta cos phi). The initial state (spin w0,
  theta0, phi0, theta_rate0, phi_rate0) starts the body with its axes the columns of
  Q(phi0, theta0) and angular velocity phi_rate0 (cos theta0, 0, -sin theta0)
  + theta_rate0 (0, 1, 0) + spin k0 in the fixed frame (the linear models take
  (phi, theta, phi', theta') as given).

Models (MODELS): "first-order" (the paper's (4)), "body-fixed" (the paper's (5)), "linearized"
(the exact linearisation about the upright rotation), "nonlinear" (the full body, the truth),
"lagrange-exact" (a symmetric body, A = B, only: the nonlinear motion in closed form).

Functions return typed results (heavytop.results) that hold what the command line prints:
stability(), compare() and derive() results have attributes (result.models["linearized"]
.critical_spin) and read as json.loads of `heavytop stability|compare|derive --format json`
(result["models"], result.to_dict()); simulate() and sweep() results hold NumPy arrays, one
per CSV column of `heavytop simulate|sweep` (result.theta, result["theta"]). Bad input raises
heavytop.InvalidInput (a ValueError) with a one-line "<key>: <rule>", the key being the
keyword argument's name ("rtol: must be a finite number in [1e-15, 1]", "t_end: ...") or, for
the body and the motion, the configuration file's key ("body.A", "motion.spin").

Functions, one a line (each a command of the command line, in brackets; help(heavytop.NAME) for
its arguments and their units):

    stability(body, spin)        does it stay up: the answer, each model's verdict    [stability]
    simulate(body, model)        one model's motion as NumPy arrays (s, rad, rad/s)   [simulate]
    compare(body)                every model against the nonlinear body (rad, rad/s)  [compare]
    sweep(body, vary)            a stability map over a grid of parameters            [sweep]
    read_map(path)               a map `heavytop sweep --output` wrote                [sweep]
    grid_values(start, stop, n)  the command line's START:STOP:COUNT grid (SI units)  [--vary]
    lifetime(body, spin=)        how long a damped top stays up (s)                   [lifetime]
    fit_decay(t, spin)           damping (N m s, N m) fitted to a spin decay          [fit-decay]
    precession(body, tilt)       steady precessions at a tilt (rad/s)                 [precession]
    chaos(body, spin=)           Lyapunov exponents, MEGNO, the prediction horizon   [chaos]
    body_from_parts(parts)       the Body that [[body.part]] tables make (kg m^2, m)  [body]
    body_report(parts or body)   the mass properties of parts or of a body            [body]
    load(path)                   a configuration file: body, motion, options          [--config]
    report(body, folder)         the report folder                                    [report]
    show(body or trajectory)     inline in a notebook: the report, or a motion in 3D  [report]
    explore(body, path)          the explorer page: the core in WebAssembly, offline  [explore]
    derive()                     the paper's linear model derived symbolically        [derive]
    derive_rotations()           the small-rotation matrices, symbolically            [derive --rotations]
    derive_check()               every route and rotation sequence checked            [derive --check]
    rpm(x)                       rad/s of x rpm                                       [--spin-rpm]
    example_toy_top()            the built-in example's Body (kg m^2, kg, m)          [no --config]
    example_motion()             the built-in example's start (rad/s, rad)            [no --config]
    example_file(name)           a file of examples/: a configuration, spin-decay.csv [--config examples/NAME]

On a table (SPEC section 16): heavytop.Table(contact, friction=, friction_law=, slip_speed=) and
the Body's tip_radius, rim_radius (m), given to simulate(..., table=) (a TableTrajectory: x, y,
height, normal_force, slip_speed, spin, energy, jellett, vertical_momentum) and stability(...,
table=) (a TableAnalysis: the table's answer, "turns over" ..., and its spinning states).

In a notebook every result shows itself (the answer first), and trajectories, comparisons,
maps and lifetimes have .to_dataframe() (pandas) and .plot() (matplotlib, returns the figure);
examples/notebooks/tour.ipynb is a tour.

    import heavytop
    top = heavytop.example_toy_top()
    heavytop.stability(top, 200.0).models["linearized"].critical_spin           # rad/s
    m = heavytop.simulate(top, "nonlinear", spin=200.0, theta0=0.05, t_end=1.0, samples=2001)
    m.t, m.theta                                                               # s, rad
"""
from . import _arguments  # noqa: F401 - one-line TypeErrors from _core, before anything takes its functions
from ._core import HAS_DERIVE, MODELS, Body, InvalidInput, Table, __version__, example_motion, example_toy_top, grid_values
from ._api import (body_from_parts, body_report, chaos, compare, example_file, derive, derive_check, derive_rotations, fit_decay, lifetime,
                   explore, load, precession, read_map, report, rpm, show, simulate, stability, sweep)
from . import results
from .results import (CheckRow, Comparison, DecayFit, Derivation, DerivationCheck, FittedParameter, Lifetime, Lyapunov, NormalForm,
                      ModelComparison, ModelStability, NonlinearReference, Rotations, SimulationSummary, Stability,
                      StabilityMap, Trajectory, Wander, Answer, BodyReport, Precession, SteadyPrecession,
                      Configuration, ReportView, MotionView, SpinningState, TableStability, TableAnswer, TableAnalysis,
                      TableSummary, TableTrajectory)

__all__ = [
    "__version__", "HAS_DERIVE", "MODELS", "Body", "Table", "InvalidInput", "example_toy_top", "example_motion",
    "example_file", "stability", "simulate", "compare", "sweep", "read_map", "lifetime", "grid_values", "derive", "derive_rotations", "derive_check",
    "body_from_parts", "body_report", "precession", "rpm", "chaos",
    "results", "Answer", "Stability", "ModelStability", "Comparison", "ModelComparison", "NonlinearReference", "Trajectory",
    "SimulationSummary", "StabilityMap", "Derivation", "Rotations", "DerivationCheck", "CheckRow", "Lyapunov", "NormalForm",
    "Wander", "Lifetime", "fit_decay", "DecayFit", "FittedParameter",
    "load", "report", "show", "explore", "ReportView", "MotionView", "Configuration", "Precession", "SteadyPrecession", "BodyReport",
    "SpinningState", "TableStability", "TableAnswer", "TableAnalysis", "TableSummary", "TableTrajectory",
]

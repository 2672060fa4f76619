"""Typed results of heavytop's functions.

Every result has attributes (typed, SI units) and reads like what the command line prints:

* stability(), compare() and derive*() results are Mappings over json.loads of the command's
  JSON (`heavytop stability|compare|derive --format json`): ``result["models"]`` is the JSON
  object (plain dicts and lists), ``result.to_dict()`` the whole of it, and the attributes
  the same values typed (``result.models["linearized"].critical_spin``).
* simulate() and sweep() results are Mappings over the CSV's columns as NumPy arrays
  (``result["theta"]``, ``result.theta``); ``to_dict()`` gives the dict of arrays.
"""
from __future__ import annotations

import copy
from collections.abc import Mapping
from dataclasses import dataclass, field
import html
from typing import Any, Dict, Iterator, Optional, Tuple

import numpy as np
import numpy.typing as npt

from ._core import Body

__all__ = [
    "JsonResult", "ModelStability", "Lyapunov", "Wander", "Answer", "Stability", "NonlinearReference", "ModelComparison", "Comparison",
    "Derivation", "Rotations", "CheckRow", "DerivationCheck", "SimulationSummary", "Trajectory",
    "StabilityMap", "FittedParameter", "DecayFit",
]

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
#: A matrix of expressions (strings), row by row.
Matrix = Tuple[Tuple[str, ...], ...]


class JsonResult(Mapping[str, Any]):
    """A result that reads like the command line's JSON object: ``result[key]`` and
    ``to_dict()`` give json.loads of the command's output (copies: changing them changes
    nothing here); the attributes give the same values typed."""

    _data: Dict[str, Any]

    def __getitem__(self, key: str) -> Any:
        return copy.deepcopy(self._data[key])

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def to_dict(self) -> Dict[str, Any]:
        """json.loads of the command line's JSON for the same input."""
        return copy.deepcopy(self._data)

    def _repr_pretty_(self, printer: Any, cycle: bool) -> None:  # IPython
        printer.text(repr(self))


def _matrix(rows: Any) -> Matrix:
    return tuple(tuple(row) for row in rows)


# ---- stability -------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class ModelStability(JsonResult):
    """One linear model's stability at the spin asked (SPEC section 3)."""

    stable: bool
    """Every eigenvalue has real part <= 0 and those on the imaginary axis are semisimple
    (without damping every real part is then 0)."""
    critical_spin: Optional[float]
    """rad/s, the lo of the unbounded stable interval; 0 when stable at every spin, None when
    no spin stabilises the model."""
    stable_spin_intervals: Tuple[Tuple[float, Optional[float]], ...]
    """rad/s, the spins w0 >= 0 where the model is stable, as (lo, hi) pairs; hi None: and above."""
    eigenvalues: Tuple[complex, ...]
    """1/s, the four eigenvalues (the linearized model's are those of its body-frame system)."""
    frequencies: Tuple[float, ...]
    """rad/s, the distinct |Im| of the eigenvalues, ascending; empty unless stable."""
    growth_rate: float
    """1/s, the largest real part of the eigenvalues: > 0, the motion grows like
    exp(growth_rate t); < 0 (damped), it decays; 0, neither."""
    reason: str
    """Why, in a few words for a person."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "ModelStability":
        return cls(stable=data["stable"], critical_spin=data["critical_spin"],
                   stable_spin_intervals=tuple((lo, hi) for lo, hi in data["stable_spin_intervals"]),
                   eigenvalues=tuple(complex(re, im) for re, im in data["eigenvalues"]),
                   frequencies=tuple(data.get("frequencies", ())), growth_rate=data["growth_rate"],
                   reason=data.get("reason", ""), _data=data)


@dataclass(frozen=True, eq=False)
class NormalForm(JsonResult):
    """The order-4 Birkhoff normal form of the reduced system (SPEC section 7):
    H = w1 r1 - w2 r2 + c20 r1^2 + c11 r1 r2 + c02 r2^2 + ..., r_i the mode actions (J s)."""

    frequencies: Tuple[float, float]
    """rad/s, (w1, w2): w1 the mode of positive Krein signature, w2 the other."""
    c20: float
    """1/(J s^2), coefficient of r1^2."""
    c11: float
    """1/(J s^2), coefficient of r1 r2."""
    c02: float
    """1/(J s^2), coefficient of r2^2."""
    D: float
    """1/(J s^4), c20 w2^2 + c11 w1 w2 + c02 w1^2 (Arnold's determinant)."""
    resonance: Optional[str]
    """None | "1:2" | "1:3"."""
    a13: Optional[float]
    """1/(J s^2), the resonant harmonic's amplitude at 1:3; None otherwise."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "NormalForm":
        return cls(frequencies=(data["frequencies"][0], data["frequencies"][1]), c20=data["c20"], c11=data["c11"],
                   c02=data["c02"], D=data["D"], resonance=data["resonance"], a13=data["a13"], _data=data)


@dataclass(frozen=True, eq=False)
class Lyapunov(JsonResult):
    """The real body's Lyapunov verdict at the spin asked (SPEC section 7; conservative body,
    upright permanent rotation). An asymmetric body of energy index 2 whose linearisation is
    stable is decided on its order-4 Birkhoff normal form (Arnold; Markeev at 1:3)."""

    verdict: str
    """"stable" | "unstable" | "undecided"."""
    certificate: str
    """"energy-casimir" | "chetaev" | "critical-quartic" | "kam" | "kam-markeev" | "odd-index" |
    "linear-instability" | "resonance" | "none"."""
    energy_index: int
    """The number of negative stiffnesses among s1 = (C - A) w0^2 - m g R, s2 = (C - B) w0^2 - m g R (N m)."""
    stable_spin_intervals: Tuple[Tuple[float, Optional[float]], ...]
    """rad/s, the spins the verdict proves stable, as (lo, hi) pairs; hi None: and above."""
    superfast_spin: Optional[float]
    """rad/s, the smallest spin above which the energy index stays 0; None when it never does."""
    normal_form: Optional[NormalForm]
    """Index 2 with a stable linearisation: the normal form the verdict rests on; else None."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Lyapunov":
        nf = data.get("normal_form")
        return cls(verdict=data["verdict"], certificate=data["certificate"], energy_index=data["energy_index"],
                   stable_spin_intervals=tuple((lo, hi) for lo, hi in data["stable_spin_intervals"]),
                   superfast_spin=data["superfast_spin"],
                   normal_form=None if nf is None else NormalForm.from_json(nf), _data=data)


@dataclass(frozen=True, eq=False)
class Wander(JsonResult):
    """How far the axis wanders in the full nonlinear motion from the state given."""

    max_tilt: Optional[float]
    """rad, the largest angle of the axis from the upward vertical; None if it could not be
    computed (``note`` says why)."""
    method: str
    """"closed form" (A = B: the Lagrange top's cubic; or the upright rotation) | "integrated"."""
    horizon: Optional[float]
    """s, the integration's horizon; None for the closed form."""
    note: str
    """Why max_tilt is None, else empty."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Wander":
        return cls(max_tilt=data["max_tilt"], method=data["method"], horizon=data["horizon"],
                   note=data.get("note", ""), _data=data)


@dataclass(frozen=True, eq=False)
class Lifetime(JsonResult):
    """How long the top stays up: `heavytop lifetime --format json` (SPEC section 8)."""

    critical_spin: Optional[float]
    """rad/s, the linearized model's critical spin without damping (None: no spin holds it up)."""
    time_to_critical: Optional[float]
    """s, when the closed-form spin law brings the spin down to the critical spin (0: already
    below; None: never, driven, or stable at every spin)."""
    fall_time: Optional[float]
    """s, the first time the nonlinear body's tilt passes max_tilt; None within the horizon."""
    fall_spin: Optional[float]
    """rad/s, the integrated spin w.k at the fall (None with fall_time)."""
    max_tilt: float
    """rad, the fall's threshold."""
    horizon: float
    """s, the nonlinear run's horizon."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Lifetime":
        decay, fall = data["spin_decay"], data["fall"]
        return cls(critical_spin=decay["critical_spin"], time_to_critical=decay["time_to_critical"],
                   fall_time=fall["time"], fall_spin=fall["spin"], max_tilt=fall["max_tilt"],
                   horizon=data["horizon"], _data=data)


@dataclass(frozen=True, eq=False)
class Answer(JsonResult):
    """Does it stay up, and for how long (SPEC section 14): result["answer"] of `heavytop
    stability --format json`; ``text`` is the paragraph the command line's text opens with."""

    verdict: str
    """"stays up" (proven) | "falls" (a computed fall) | "stays up for the horizon" (not proven)."""
    proven: bool
    """True for a Lyapunov proof or a computed fall."""
    reason: str
    """One sentence in plain words."""
    max_tilt: Optional[float]
    """rad, the largest tilt from the vertical (the wander when proven stable)."""
    falls_at: Optional[float]
    """s, when the tilt first passes the fall's threshold (None: it does not fall)."""
    horizon: float
    """s, the horizon of the run that decided (or would have)."""
    min_spin: Optional[float]
    """rad/s, the smallest spin proven stable (Lyapunov); None when none is."""
    lifetime: Optional[float]
    """s, a damped body's fall time; None otherwise."""
    text: str
    """The answer in words: spins in rad/s and rpm, angles in degrees and rad."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any], text: str) -> "Answer":
        return cls(verdict=data["verdict"], proven=data["proven"], reason=data["reason"], max_tilt=data["max_tilt"],
                   falls_at=data["falls_at"], horizon=data["horizon"], min_spin=data["min_spin"],
                   lifetime=data["lifetime"], text=text, _data=data)

    def __repr__(self) -> str:
        return self.text

    def _repr_html_(self) -> str:
        colour = "#c62828" if self.verdict == "falls" else "#1a7f1a" if self.proven else "#f9a825"
        return (f"<p style='border-left: 5px solid {colour}; padding: .3em .8em; font-size: 1.1em'>"
                f"{html.escape(self.text)}</p>")


def _optional(value: Optional[float], unit: str) -> str:
    return "none" if value is None else f"{value:.6g} {unit}"


@dataclass(frozen=True, eq=False)
class Stability(JsonResult):
    """Linear stability of the first-order, body-fixed and linearized models at one spin:
    `heavytop stability --format json` (``to_dict()`` is json.loads of it)."""

    body: Body
    """The body analysed."""
    spin: float
    """rad/s, the spin w0 analysed."""
    models: Dict[str, ModelStability]
    """By SPEC name: "first-order", "body-fixed", "linearized"."""
    lyapunov: Lyapunov
    """The real body's verdict beyond the linearisation (SPEC section 7)."""
    wander: Wander
    """The largest tilt of the motion from the state given."""
    answer: Answer
    """Does it stay up, and for how long (SPEC section 14): the first thing repr() says."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any], answer_text: str) -> "Stability":
        b = data["body"]
        body = Body(b["A"], b["B"], b["C"], mass=b["mass"], length=b["length"], gravity=b["gravity"])
        return cls(body=body, spin=data["spin"],
                   models={name: ModelStability.from_json(m) for name, m in data["models"].items()},
                   lyapunov=Lyapunov.from_json(data["lyapunov"]), wander=Wander.from_json(data["wander"]),
                   answer=Answer.from_json(data["answer"], answer_text), _data=data)

    def _rows(self) -> Tuple[Tuple[str, str, str], ...]:
        rows = tuple((name, "stable" if m.stable else "unstable", _optional(m.critical_spin, "rad/s"))
                     for name, m in self.models.items())
        return rows + (("real body (Lyapunov)", f"{self.lyapunov.verdict} ({self.lyapunov.certificate})",
                        _optional(self.answer.min_spin, "rad/s")),)

    def __repr__(self) -> str:
        lines = [self.answer.text, "", f"{'model':<22} {'verdict':<28} critical spin"]
        lines += [f"{name:<22} {verdict:<28} {critical}" for name, verdict, critical in self._rows()]
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><td>{html.escape(n)}</td><td>{html.escape(v)}</td><td>{html.escape(c)}</td></tr>"
                       for n, v, c in self._rows())
        return (self.answer._repr_html_() + "<table><tr><th>model</th><th>verdict</th><th>critical spin</th></tr>"
                + rows + "</table>")


# ---- compare ---------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class NonlinearReference(JsonResult):
    """The nonlinear body (the truth) of a comparison: its measured frequencies and work."""

    nutation_frequency: Optional[float]
    """rad/s, 2 pi / mean time between tilt maxima (None if the tilt is constant)."""
    precession_rate: Optional[float]
    """rad/s, mean rate of the axis's azimuth over whole nutation periods."""
    steps: int
    """Accepted steps of the integrator."""
    max_relative_energy_drift: float
    """max |E(t) - E(0)| / E_scale over every accepted step."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "NonlinearReference":
        return cls(nutation_frequency=data["nutation_frequency"], precession_rate=data["precession_rate"],
                   steps=data["steps"], max_relative_energy_drift=data["max_relative_energy_drift"], _data=data)


@dataclass(frozen=True, eq=False)
class ModelComparison(JsonResult):
    """One approximate model against the nonlinear body."""

    max_angle_error: float
    """rad, max over the samples of the larger of |d theta| and |d phi| (until diverged_at)."""
    final_angle_error: Optional[float]
    """rad, the same at the last sample (None when the model diverged)."""
    nutation_frequency: Optional[float]
    """rad/s, measured from the model's own trajectory."""
    precession_rate: Optional[float]
    """rad/s, measured from the model's own trajectory."""
    nutation_relative_error: Optional[float]
    """|nutation - truth| / truth."""
    precession_relative_error: Optional[float]
    """|precession - truth| / |truth|."""
    diverged_at: Optional[float]
    """s, when a linear model's angles passed 1 rad (beyond any small-motion meaning), or None."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "ModelComparison":
        return cls(max_angle_error=data["max_angle_error"], final_angle_error=data["final_angle_error"],
                   nutation_frequency=data["nutation_frequency"], precession_rate=data["precession_rate"],
                   nutation_relative_error=data["nutation_relative_error"],
                   precession_relative_error=data["precession_relative_error"],
                   diverged_at=data.get("diverged_at"), _data=data)


@dataclass(frozen=True, eq=False)
class Comparison(JsonResult):
    """Every approximate model against the nonlinear body: `heavytop compare --format json`."""

    nonlinear: NonlinearReference
    """The truth."""
    models: Dict[str, ModelComparison]
    """By SPEC name: first-order, body-fixed, linearized, and lagrange-exact when A = B."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Comparison":
        return cls(nonlinear=NonlinearReference.from_json(data["nonlinear"]),
                   models={name: ModelComparison.from_json(m) for name, m in data["models"].items()}, _data=data)


# ---- derive ----------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Derivation(JsonResult):
    """M q'' + G q' + K q = 0, q = (phi, theta), derived symbolically: `heavytop derive
    --format json`. Every entry a string in A, B, C, m, g, R, omega0 (and lambda), `^` for
    powers."""

    M: Matrix
    G: Matrix
    K: Matrix
    characteristic_polynomial: str
    """In lambda."""
    stability_condition: str
    """Relations joined by `&`, or True / False."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Derivation":
        return cls(M=_matrix(data["M"]), G=_matrix(data["G"]), K=_matrix(data["K"]),
                   characteristic_polynomial=data["characteristic_polynomial"],
                   stability_condition=data["stability_condition"], _data=data)


@dataclass(frozen=True, eq=False)
class Rotations(JsonResult):
    """The paper's small-rotation matrices, 3x3 strings in phi, theta, psi: `heavytop derive
    --rotations --format json`."""

    A1: Matrix
    A2: Matrix
    A3: Matrix
    A1A2: Matrix
    A2A1: Matrix
    commutator: Matrix
    """A1A2 - A2A1."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Rotations":
        names = ("A1", "A2", "A3", "A1A2", "A2A1", "commutator")
        return cls(**{n: _matrix(data[n]) for n in names}, _data=data)


@dataclass(frozen=True, eq=False)
class CheckRow(JsonResult):
    """One route and rotation sequence of the derivation check."""

    method: str
    sequence: str
    order: int
    M: Matrix
    G: Matrix
    K: Matrix
    model: Optional[str]
    """The paper's model it gives, or None."""
    expected: Optional[str]
    """The model the paper says it gives, or None."""
    as_expected: bool
    why: str
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "CheckRow":
        return cls(method=data["method"], sequence=data["sequence"], order=data["order"], M=_matrix(data["M"]),
                   G=_matrix(data["G"]), K=_matrix(data["K"]), model=data["model"], expected=data["expected"],
                   as_expected=data["as_expected"], why=data["why"], _data=data)


@dataclass(frozen=True, eq=False)
class DerivationCheck(JsonResult):
    """Every route and rotation sequence: `heavytop derive --check --format json`."""

    rows: Tuple[CheckRow, ...]
    all_as_expected: bool
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "DerivationCheck":
        return cls(rows=tuple(CheckRow.from_json(r) for r in data["rows"]), all_as_expected=data["all_as_expected"],
                   _data=data)


# ---- simulate --------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class SimulationSummary(JsonResult):
    """What simulate() did: the solver, its work, and the drift of the first integrals."""

    model: str
    """SPEC name of the model."""
    solver: str
    """E.g. "closed form", "Dormand-Prince 5(4)", "splitting, order 4, step 0.001 s"."""
    termination: str
    """"success" (every sample computed) or "failure" (simulate() then raises RuntimeError)."""
    message: str
    """One line: why it failed, or empty."""
    samples: int
    """Samples computed."""
    steps: int
    """Integrator steps (0 for closed forms)."""
    rejected_steps: int
    """Steps rejected by the error control."""
    rhs_evaluations: int
    """Evaluations of the equations of motion (kicks for the splitting)."""
    max_relative_energy_drift: Optional[float]
    """Relative drift of the energy over the run; None for models that do not monitor it."""
    max_relative_vertical_momentum_drift: Optional[float]
    """Relative drift of L_zeta over the run; None for models that do not monitor it."""
    max_relative_axial_momentum_drift: Optional[float]
    """Relative drift of C w3 over the run (conserved only when A == B); None if not monitored."""
    report: str
    """One line for people."""
    _data: Dict[str, Any] = field(repr=False)

    @property
    def ok(self) -> bool:
        """True if every sample was computed."""
        return self.termination == "success"

    def __str__(self) -> str:
        return self.report

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "SimulationSummary":
        return cls(**data, _data=data)


# ---- fit_decay -------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class FittedParameter(JsonResult):
    """One parameter of fit_decay(): its estimate and standard uncertainty (same unit)."""

    value: float
    """The estimate (N m s for axial, N m for friction, rad/s for spin0)."""
    uncertainty: Optional[float]
    """Standard uncertainty, sqrt of the diagonal of s^2 (J^T J)^-1, s^2 = RSS / (n' - p), n' the
    points not read as 0 where the fitted law has stopped too; None when the data do not determine it; 0 for a parameter given, not fitted. At the bound: the
    spread it would have if it were free."""
    fitted: bool
    """False for spin0 when it was given (spin0=...)."""
    at_bound: bool
    """True when the data prefer a value below 0 and it is held at 0 (not identified)."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "FittedParameter":
        return cls(**data, _data=data)


@dataclass(frozen=True, eq=False)
class DecayFit(JsonResult):
    """fit_decay(): the [damping] axial and friction fitted to a measured spin decay through the
    law C w' = -d_a w - tau0 sign(w) (exact for a free symmetric body, A = B); ``to_dict()`` is
    json.loads of `heavytop fit-decay --format json`."""

    axial: FittedParameter
    """d_a, N m s: [damping] axial."""
    friction: FittedParameter
    """tau0, N m: [damping] friction."""
    spin0: FittedParameter
    """w0, rad/s: the spin at t = 0."""
    rms_residual: float
    """rad/s, sqrt(RSS / n)."""
    points: int
    """n, the number of data points."""
    converged: bool
    """The least-squares solver met its tolerances (fit_decay() raises RuntimeError otherwise)."""
    correlation: Optional[float]
    """Correlation coefficient of axial and friction (dimensionless); None if undetermined."""
    C: float
    """kg m^2, the body's axial moment the fit assumed."""
    stop_time: Optional[float]
    """s, when the fitted dry friction stops the spin; None without friction."""
    termination: str
    """One line: why the solver stopped."""
    warnings: Tuple[str, ...]
    """One line each: a parameter at its bound or within 2 uncertainties of 0, the torques
    not separated by the data, A != B, ..."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "DecayFit":
        return cls(axial=FittedParameter.from_json(data["axial"]), friction=FittedParameter.from_json(data["friction"]),
                   spin0=FittedParameter.from_json(data["spin0"]), rms_residual=data["rms_residual"],
                   points=data["points"], converged=data["converged"], correlation=data["correlation"], C=data["C"],
                   stop_time=data["stop_time"], termination=data["termination"], warnings=tuple(data["warnings"]),
                   _data=data)


def _column(name: str, doc: str) -> property:
    def get(self: "Trajectory") -> FloatArray:
        try:
            return self._columns[name]
        except KeyError:
            raise AttributeError(f"a {self.model} trajectory has no column {name!r} "
                                 f"(its columns: {', '.join(self.columns)})") from None
    return property(get, doc=doc)


class _Columns(Mapping[str, npt.NDArray[Any]]):
    """Named NumPy columns in the CSV's order, as a read-only Mapping (the arrays themselves)."""

    __slots__ = ("_columns",)
    _columns: Dict[str, npt.NDArray[Any]]

    def __getitem__(self, name: str) -> npt.NDArray[Any]:
        return self._columns[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    def __contains__(self, name: object) -> bool:
        return name in self._columns

    def to_dict(self) -> Dict[str, npt.NDArray[Any]]:
        """Every column by name, in the CSV's order (the arrays themselves, not copies)."""
        return dict(self._columns)


class Trajectory(_Columns):
    """The motion of one model, column by column as `heavytop simulate --format csv` prints it:
    float64 NumPy arrays, one element per sample. ``result["theta"]`` and ``result.theta``
    are the same array; ``to_dict()`` is the dict of every column, in the CSV's order."""

    __slots__ = ("_model", "_summary")

    def __init__(self, columns: Dict[str, FloatArray], summary: SimulationSummary) -> None:
        self._columns = dict(columns)
        self._summary = summary
        self._model = summary.model

    t = _column("t", "s, the sample times")
    theta = _column("theta", "rad, theta = atan2(k_xi, k_zeta): the spin axis's tilt towards xi")
    phi = _column("phi", "rad, phi = -asin(k_eta): the spin axis's tilt about xi")
    theta_rate = _column("theta_rate", "rad/s, theta'")
    phi_rate = _column("phi_rate", "rad/s, phi'")
    tilt = _column("tilt", "rad, in [0, pi]: the angle of the spin axis from the upward vertical, acos(k_zeta)")
    azimuth = _column("azimuth", "rad, the direction the axis leans to, atan2(k_eta, k_xi), continuous in time")
    energy = _column("energy", "J, E (nonlinear only)")
    vertical_momentum = _column("vertical_momentum", "kg m^2/s, L_zeta (nonlinear only)")
    axial_momentum = _column("axial_momentum", "kg m^2/s, C w3, conserved only when A == B (nonlinear only)")
    energy_drift = _column("energy_drift", "J, E(t) - E(0) (nonlinear only)")
    vertical_momentum_drift = _column("vertical_momentum_drift", "kg m^2/s, L_zeta(t) - L_zeta(0) (nonlinear only)")
    axial_momentum_drift = _column("axial_momentum_drift", "kg m^2/s, C w3(t) - C w3(0) (nonlinear only)")

    @property
    def model(self) -> str:
        """SPEC name of the model simulated."""
        return self._model

    @property
    def summary(self) -> SimulationSummary:
        """What the solver did."""
        return self._summary

    @property
    def columns(self) -> Tuple[str, ...]:
        """The column names in the CSV's order: t, theta, phi, theta_rate, phi_rate, tilt,
        azimuth, then the model's extra columns."""
        return tuple(self._columns)

    @property
    def extra(self) -> Dict[str, FloatArray]:
        """The columns after the first seven (the nonlinear model's conserved quantities, the
        damping's columns)."""
        return {name: column for i, (name, column) in enumerate(self._columns.items()) if i >= 7}

    def __repr__(self) -> str:
        return (f"Trajectory(model={self._model!r}, samples={len(self._columns['t'])}, "
                f"columns={self.columns!r}, summary={self._summary.report!r})")


# ---- sweep -----------------------------------------------------------------------------------

class StabilityMap(_Columns):
    """Each model's verdict over a grid, column by column as `heavytop sweep` prints it: the
    varied values (float64), then a bool column per model (and `lyapunov_certificate`, the
    certificate behind each Lyapunov verdict, as strings), one element per grid point
    (row-major, the first key slowest). ``to_dict()`` is the dict of every column."""

    __slots__ = ("_shape",)

    def __init__(self, columns: Dict[str, Any], shape: Tuple[int, ...]) -> None:
        self._columns = dict(columns)
        self._shape = tuple(shape)

    @property
    def columns(self) -> Tuple[str, ...]:
        """The column names in the CSV's order."""
        return tuple(self._columns)

    @property
    def shape(self) -> Tuple[int, ...]:
        """The grid's shape: the number of values of each varied key, in order."""
        return self._shape

    @property
    def parameters(self) -> Dict[str, FloatArray]:
        """The varied keys' values at every grid point (SI units), in order."""
        return {name: column for i, (name, column) in enumerate(self._columns.items()) if i < len(self._shape)}

    @property
    def verdicts(self) -> Dict[str, BoolArray]:
        """Stable? at every grid point, by model: first-order, body-fixed, linearized, lyapunov
        (proven Lyapunov stable, SPEC section 7) and, when asked, nonlinear."""
        return {name: column for i, (name, column) in enumerate(self._columns.items())
                if i >= len(self._shape) and name != "lyapunov_certificate"}

    @property
    def certificates(self) -> npt.NDArray[np.str_]:
        """The certificate behind each point's Lyapunov verdict (SPEC section 7's names)."""
        return self._columns["lyapunov_certificate"]

    def grid(self, name: str) -> npt.NDArray[Any]:
        """Column `name` as an array of the grid's shape (a view)."""
        return self._columns[name].reshape(self._shape)

    def slice(self, key: str, value: float) -> "StabilityMap":
        """The map with varied key `key` held at its grid value nearest `value` (SI units): one
        key fewer, the others in their order (a three-parameter map's slice is a heat map's
        grid). The held key's column is dropped. Raises InvalidInput ("slice: ...") if `key`
        is not varied or `value` is not finite; as `heavytop report --map FILE --slice`."""
        from ._core import InvalidInput
        keys = list(self.parameters)
        if key not in keys:
            raise InvalidInput(f"slice: '{key}' is not a varied key of the map")
        if not np.isfinite(value):
            raise InvalidInput(f"slice: the value of '{key}' must be finite")
        axis = keys.index(key)
        along = np.moveaxis(self.grid(key), axis, 0).reshape(self._shape[axis], -1)[:, 0]  # the key's grid values
        nearest = int(np.argmin(np.abs(along - value)))
        columns = {name: np.ascontiguousarray(np.take(self.grid(name), nearest, axis=axis)).reshape(-1)
                   for name in self._columns if name != key}
        return StabilityMap(columns, self._shape[:axis] + self._shape[axis + 1:])

    def plot(self, name: str = "linearized", ax: Any = None) -> Any:
        """A heat map of column `name` (stable in colour, unstable grey) over a two-parameter map
        (a three-parameter map's slice()), the first key across, with matplotlib; returns the
        Axes. Raises ValueError unless the map has two keys."""
        if len(self._shape) != 2:
            raise ValueError(f"plot: a heat map needs two varied keys, this map has {len(self._shape)} (take a slice())")
        import matplotlib.pyplot as plt
        from matplotlib.colors import ListedColormap
        if ax is None:
            ax = plt.figure().add_subplot()
        first, second = list(self.parameters)
        x, y = self.grid(first)[:, 0], self.grid(second)[0, :]
        ax.pcolormesh(x, y, self.grid(name).T.astype(float), cmap=ListedColormap(["#d9d9d9", "#2ca02c"]),
                      vmin=0, vmax=1, shading="nearest")
        ax.set_xlabel(first)
        ax.set_ylabel(second)
        ax.set_title(f"{name}: stable (green) or not (grey)")
        return ax

    def __repr__(self) -> str:
        return f"StabilityMap(shape={self._shape!r}, columns={self.columns!r})"

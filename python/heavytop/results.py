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
import os
from typing import Any, Dict, Iterator, Optional, Tuple

import numpy as np
import numpy.typing as npt

from ._core import Body, Table
from . import _views

__all__ = [
    "JsonResult", "ModelStability", "Lyapunov", "Wander", "Answer", "Stability", "NonlinearReference", "ModelComparison", "Comparison",
    "Derivation", "Rotations", "CheckRow", "DerivationCheck", "SimulationSummary", "Trajectory",
    "StabilityMap", "FittedParameter", "DecayFit", "UNITS", "SteadyPrecession", "Precession", "BodyReport",
    "Configuration", "ReportView", "MotionView",
    "SpinningState", "TableStability", "TableAnswer", "TableAnalysis", "TableSummary", "TableTrajectory",
]

FloatArray = npt.NDArray[np.float64]
#: The SI unit of every trajectory and map column by name ("tilt": "rad", "t": "s", ...).
UNITS = _views.UNITS
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

    def _repr_html_(self) -> str:
        """A notebook's view: a compact table of the result's numbers (nested keys as "a.b")."""
        return _views.html_table(("key", "value"), _views.flat_rows(self._data), caption=type(self).__name__)


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
    body: Optional[Body] = field(default=None, repr=False)
    """The body (with its damping) whose lifetime this is; None when not known (from_json alone)."""
    spin: Optional[float] = field(default=None, repr=False)
    """rad/s, the initial spin; None when not known."""

    @classmethod
    def from_json(cls, data: Dict[str, Any], body: Optional[Body] = None,
                  spin: Optional[float] = None) -> "Lifetime":
        decay, fall = data["spin_decay"], data["fall"]
        return cls(critical_spin=decay["critical_spin"], time_to_critical=decay["time_to_critical"],
                   fall_time=fall["time"], fall_spin=fall["spin"], max_tilt=fall["max_tilt"],
                   horizon=data["horizon"], _data=data, body=body, spin=spin)

    @property
    def headline(self) -> str:
        """One sentence: whether and when it falls (s) and when the spin reaches the critical spin."""
        if self.fall_time is not None:
            first = (f"Falls after {self.fall_time:.4g} s: the tilt passes {self.max_tilt:.4g} rad "
                     f"({np.degrees(self.max_tilt):.3g}°)"
                     + (f" with the spin at {self.fall_spin:.4g} rad/s." if self.fall_spin is not None else "."))
        else:
            first = f"Stays up for the horizon, {self.horizon:.4g} s (the tilt stays below {self.max_tilt:.4g} rad)."
        if self.critical_spin is None:
            return first + " No spin holds it up."
        if self.time_to_critical is None:
            return first + f" The spin never falls to the critical spin, {self.critical_spin:.4g} rad/s."
        return first + f" The spin law reaches the critical spin, {self.critical_spin:.4g} rad/s, at {self.time_to_critical:.4g} s."

    def spin_law(self, t: npt.ArrayLike) -> FloatArray:
        """rad/s, the closed-form spin law C w' = -d_a w - tau0 sign(w) from the initial spin at times
        t (s), 0 once dry friction stops it (a driven body keeps its spin). Needs .body and .spin
        (lifetime() sets them)."""
        if self.body is None or self.spin is None:
            raise ValueError("spin_law: this Lifetime does not know its body and spin (lifetime() sets them)")
        b = self.body
        return _views.spin_law(np.asarray(t, dtype=np.float64), self.spin, b.C, b.axial_damping, b.friction, b.driven)

    def to_dataframe(self) -> Any:
        """A one-row pandas DataFrame: critical_spin (rad/s), time_to_critical (s), fall_time (s),
        fall_spin (rad/s), max_tilt (rad), horizon (s); None as NaN."""
        import pandas as pd
        row = {"critical_spin": self.critical_spin, "time_to_critical": self.time_to_critical,
               "fall_time": self.fall_time, "fall_spin": self.fall_spin, "max_tilt": self.max_tilt,
               "horizon": self.horizon}
        return pd.DataFrame([{k: (np.nan if v is None else float(v)) for k, v in row.items()}])

    def plot(self, samples: int = 400) -> Any:
        """The spin law over the run (rad/s against s) with the critical spin and the fall marked;
        returns the matplotlib Figure. Needs .body and .spin (lifetime() sets them)."""
        end = max(1.1 * (self.fall_time or 0.0), 1.2 * (self.time_to_critical or 0.0))
        end = min(end, self.horizon) if end > 0 else self.horizon
        t = np.linspace(0.0, end, samples)
        figure, (ax,) = _views.new_figure(1)
        ax.plot(t, self.spin_law(t), lw=1.5, label="spin law C w' = -d_a w - tau0 sign(w)")
        if self.critical_spin is not None:
            ax.axhline(self.critical_spin, color="#c62828", ls="--", lw=1, label=f"critical spin {self.critical_spin:.4g} rad/s")
        if self.time_to_critical:
            ax.axvline(self.time_to_critical, color="#c62828", ls=":", lw=1, label=f"reaches it at {self.time_to_critical:.4g} s")
        if self.fall_time is not None:
            ax.axvline(self.fall_time, color="black", lw=1.2, label=f"falls at {self.fall_time:.4g} s")
        ax.set_xlabel(_views.label("t"))
        ax.set_ylabel(_views.label("spin"))
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="lower left", fontsize="small")
        ax.set_title("How long it stays up")
        return figure

    def __repr__(self) -> str:
        return self.headline

    def _repr_html_(self) -> str:
        f = _views.fmt
        rows = (("critical spin", f(self.critical_spin, "rad/s")), ("time to critical", f(self.time_to_critical, "s")),
                ("fall time", f(self.fall_time, "s")), ("spin at the fall", f(self.fall_spin, "rad/s")),
                ("max tilt", f(self.max_tilt, "rad")), ("horizon", f(self.horizon, "s")))
        return f"<p>{html.escape(self.headline)}</p>" + _views.html_table(("", "value"), rows)


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
        body = Body(b["A"], b["B"], b["C"], mass=b["mass"], length=b["length"], gravity=b["gravity"],
                    tip_radius=b.get("tip_radius", 0.0), rim_radius=b.get("rim_radius", 0.0))
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


# ---- on a table (SPEC section 16) ----------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class SpinningState(JsonResult):
    """The body spinning about its vertical axis standing on the table, linearised (SPEC section
    16's "upright", tilt 0, or "inverted", tilt pi: the body on the other side of its sphere)."""

    stable: bool
    """Every eigenvalue has real part <= 0 (to rounding), none repeated on the imaginary axis."""
    asymptotically: bool
    """Every eigenvalue but the spin family's zeros has real part < 0: nearby motions come back."""
    critical_spin: Optional[float]
    """rad/s, the slowest spin above which it is stable; None when none is."""
    stable_spin_intervals: Tuple[Tuple[float, Optional[float]], ...]
    """rad/s, the spins where it is stable, as (lo, hi) pairs; hi None: and above."""
    eigenvalues: Tuple[complex, ...]
    """1/s, of the body-frame linearisation at the spin asked, sorted."""
    growth_rate: float
    """1/s, the largest real part of the eigenvalues."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "SpinningState":
        return cls(stable=data["stable"], asymptotically=data["asymptotically"], critical_spin=data["critical_spin"],
                   stable_spin_intervals=tuple((lo, hi) for lo, hi in data["stable_spin_intervals"]),
                   eigenvalues=tuple(complex(re, im) for re, im in data["eigenvalues"]),
                   growth_rate=data["growth_rate"], _data=data)


@dataclass(frozen=True, eq=False)
class TableStability(JsonResult):
    """The table's block of `heavytop stability --format json` (result["table"]): the contact, its
    law, the body's radii and the spinning states on it."""

    contact: str
    """"frictionless" | "rolling" | "sliding"."""
    friction: Optional[float]
    """mu (dimensionless), "sliding" only (else None)."""
    friction_law: Optional[str]
    """"viscous" | "coulomb", "sliding" only (else None)."""
    slip_speed: Optional[float]
    """m/s, the viscous law's reference speed, "sliding" only (else None)."""
    tip_radius: float
    """m, the radius of the sphere about O that touches the table."""
    rim_radius: float
    """m, the radius of the ring about the axis that touches it (0: none)."""
    upright: Optional[SpinningState]
    """Tilt 0; None for a rim (a disc with a vertical axis lies flat)."""
    inverted: Optional[SpinningState]
    """Tilt pi; None for a rim."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "TableStability":
        def state(name: str) -> Optional[SpinningState]:
            value = data[name]
            return None if value is None else SpinningState.from_json(value)
        return cls(contact=data["contact"], friction=data.get("friction"), friction_law=data.get("friction_law"),
                   slip_speed=data.get("slip_speed"), tip_radius=data["tip_radius"], rim_radius=data["rim_radius"],
                   upright=state("upright"), inverted=state("inverted"), _data=data)


@dataclass(frozen=True, eq=False)
class TableAnswer(Answer):
    """The answer on a table (SPEC sections 14 and 16): result["answer"] of `heavytop stability
    --format json` with [table]; ``text`` is the paragraph the command line's text opens with.
    The verdict is "leaves the table" | "falls" | "turns over" | "stays up" (it rose: not
    proven) | "stays up for the horizon"; the computed events are proven."""

    upright_at: Optional[float] = None
    """s, from then on the tilt stays below 0.01 rad (it rose and sleeps); None otherwise."""
    turns_over_at: Optional[float] = None
    """s, when the tilt passes pi/2; None if it does not."""
    leaves_at: Optional[float] = None
    """s, when the normal force reaches 0; None if it does not."""
    track: float = 0.0
    """m, the largest distance of the contact point P from where it started."""
    final_tilt: float = 0.0
    """rad, the tilt at the run's end."""
    final_spin: float = 0.0
    """rad/s, w.k at the run's end."""

    @classmethod
    def from_json(cls, data: Dict[str, Any], text: str) -> "TableAnswer":
        t = data["table"]
        return cls(verdict=data["verdict"], proven=data["proven"], reason=data["reason"], max_tilt=data["max_tilt"],
                   falls_at=data["falls_at"], horizon=data["horizon"], min_spin=data["min_spin"],
                   lifetime=data["lifetime"], text=text, _data=data, upright_at=t["upright_at"],
                   turns_over_at=t["turns_over_at"], leaves_at=t["leaves_at"], track=t["track"],
                   final_tilt=t["final_tilt"], final_spin=t["final_spin"])

    def _repr_html_(self) -> str:
        colour = ("#c62828" if self.verdict in ("falls", "leaves the table") else "#1a7f1a" if self.proven
                  else "#f9a825")
        return (f"<p style='border-left: 5px solid {colour}; padding: .3em .8em; font-size: 1.1em'>"
                f"{html.escape(self.text)}</p>")


@dataclass(frozen=True, eq=False)
class TableAnalysis(JsonResult):
    """stability(body, spin, table=...) on a table: `heavytop stability --format json` with
    [table] (``to_dict()`` is json.loads of it). The pivot's "lyapunov" and "wander" are not
    computed on a table."""

    body: Body
    """The body analysed (with its tip_radius and rim_radius)."""
    spin: float
    """rad/s, the spin w0 analysed."""
    models: Dict[str, ModelStability]
    """The linear models of the same body on a pivot (SPEC section 3), by name."""
    table: TableStability
    """The contact, its law, the radii and the spinning states on the table."""
    answer: TableAnswer
    """What the motion on the table does (SPEC section 16): the first thing repr() says."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any], answer_text: str, body: Body) -> "TableAnalysis":
        return cls(body=body, spin=data["spin"],
                   models={name: ModelStability.from_json(m) for name, m in data["models"].items()},
                   table=TableStability.from_json(data["table"]), answer=TableAnswer.from_json(data["answer"], answer_text),
                   _data=data)

    def _rows(self) -> Tuple[Tuple[str, str, str], ...]:
        rows = []
        for name, state in (("upright", self.table.upright), ("inverted", self.table.inverted)):
            if state is None:
                rows.append((name, "none (a rim)", ""))
            else:
                verdict = ("stable, asymptotically" if state.asymptotically else "stable") if state.stable else "unstable"
                rows.append((name, verdict, _optional(state.critical_spin, "rad/s")))
        return tuple(rows)

    def __repr__(self) -> str:
        lines = [self.answer.text, "", f"{'on the table (' + self.table.contact + ')':<26} {'verdict':<24} critical spin"]
        lines += [f"{name:<26} {verdict:<24} {critical}" for name, verdict, critical in self._rows()]
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><td>{html.escape(n)}</td><td>{html.escape(v)}</td><td>{html.escape(c)}</td></tr>"
                       for n, v, c in self._rows())
        return (self.answer._repr_html_() + f"<table><tr><th>on the table ({html.escape(self.table.contact)})</th>"
                "<th>verdict</th><th>critical spin</th></tr>" + rows + "</table>")


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

    _FRAME_COLUMNS = ("nutation_frequency", "precession_rate", "max_angle_error", "final_angle_error",
                      "nutation_relative_error", "precession_relative_error", "diverged_at")

    def to_dataframe(self) -> Any:
        """A pandas DataFrame, one row per model ("nonlinear", the truth, first), indexed by the
        model's name: nutation_frequency, precession_rate (rad/s), max_angle_error,
        final_angle_error (rad), nutation_relative_error, precession_relative_error (1),
        diverged_at (s); None as NaN (the truth has no errors)."""
        import pandas as pd
        rows = {"nonlinear": {"nutation_frequency": self.nonlinear.nutation_frequency,
                              "precession_rate": self.nonlinear.precession_rate}}
        rows.update({name: {c: getattr(m, c) for c in self._FRAME_COLUMNS} for name, m in self.models.items()})
        frame = pd.DataFrame.from_dict(rows, orient="index", columns=list(self._FRAME_COLUMNS), dtype=float)
        frame.index.name = "model"
        return frame

    def plot(self) -> Any:
        """Bars, one per approximate model: its largest angle error (rad, log scale) and its
        nutation and precession frequencies' relative errors against the nonlinear body;
        returns the matplotlib Figure."""
        figure, axes = _views.new_figure(2, height=2.4)
        names = list(self.models)
        x = np.arange(len(names))
        errors = [m.max_angle_error for m in self.models.values()]
        axes[0].bar(x, errors, color="#1f77b4")
        axes[0].set_yscale("log")
        axes[0].set_ylabel("max angle error (rad)")
        axes[0].set_title("Each model against the nonlinear body")
        for i, m in enumerate(self.models.values()):
            if m.diverged_at is not None:
                axes[0].annotate(f"diverged at {m.diverged_at:.3g} s", (i, errors[i]), ha="center", va="bottom",
                                 fontsize="small")
        width = 0.38
        nut = [np.nan if m.nutation_relative_error is None else m.nutation_relative_error for m in self.models.values()]
        pre = [np.nan if m.precession_relative_error is None else m.precession_relative_error for m in self.models.values()]
        axes[1].bar(x - width / 2, nut, width, label="nutation frequency")
        axes[1].bar(x + width / 2, pre, width, label="precession rate")
        if np.any(np.array(nut + pre) > 0):
            axes[1].set_yscale("log")
        axes[1].set_ylabel("relative error (dimensionless)")
        axes[1].legend(fontsize="small")
        for ax in axes:
            ax.set_xticks(x, names)
            ax.grid(True, axis="y", alpha=0.3)
        return figure

    def __repr__(self) -> str:
        lines = [f"nonlinear body: nutation {_views.fmt(self.nonlinear.nutation_frequency, 'rad/s')}, "
                 f"precession {_views.fmt(self.nonlinear.precession_rate, 'rad/s')}", "",
                 f"{'model':<16} {'max angle error':<20} {'nutation error':<16} precession error"]
        for name, m in self.models.items():
            lines.append(f"{name:<16} {_views.fmt(m.max_angle_error, 'rad'):<20} "
                         f"{_views.fmt(m.nutation_relative_error):<16} {_views.fmt(m.precession_relative_error)}"
                         + (f"  (diverged at {m.diverged_at:.4g} s)" if m.diverged_at is not None else ""))
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        f = _views.fmt
        # lagrange-exact is the nonlinear motion in closed form: the closest of the approximations.
        approximate = {n: m for n, m in self.models.items() if n != "lagrange-exact"} or self.models
        best = min(approximate.items(), key=lambda item: item[1].max_angle_error)[0]
        head = (f"<p>Closest to the nonlinear body: <b>{html.escape(best)}</b> (max angle error "
                f"{html.escape(f(self.models[best].max_angle_error, 'rad'))}). The nonlinear body nutates at "
                f"{html.escape(f(self.nonlinear.nutation_frequency, 'rad/s'))} and precesses at "
                f"{html.escape(f(self.nonlinear.precession_rate, 'rad/s'))}.</p>")
        rows = [(name, f(m.max_angle_error, "rad"), f(m.nutation_frequency, "rad/s"), f(m.precession_rate, "rad/s"),
                 f(m.nutation_relative_error), f(m.precession_relative_error), f(m.diverged_at, "s"))
                for name, m in self.models.items()]
        return head + _views.html_table(("model", "max angle error", "nutation", "precession", "nutation rel. error",
                                         "precession rel. error", "diverged at"), rows)


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


@dataclass(frozen=True, eq=False)
class TableSummary(JsonResult):
    """What simulate() did on a table: the "summary" of `heavytop simulate --format json` with
    [table] (``to_dict()``), the integrator's work and the largest relative drifts of the quantities the
    contact keeps (docs/table.md)."""

    end: str
    """"completed" (every sample computed) | "leaves the table" (the normal force reached 0 at
    end_time: the trajectory ends there, its last row at that time)."""
    end_time: float
    """s, the last sample's time."""
    steps: int
    """Accepted steps."""
    rhs_evaluations: int
    """Evaluations of the equations of motion."""
    switches: int
    """Coulomb's law: the contact's switches between sticking and slipping (0 otherwise)."""
    integrator: str
    """The one that ran: "dop853", or "rosenbrock4" (implicit: viscous sliding made stiff by a
    small slip_speed; docs/table.md)."""
    max_relative_energy_drift: float
    """The largest |E(t) - E(0)| over the steps, relative (the energy falls while it slides)."""
    max_relative_jellett_drift: float
    """The same for Jellett's integral (kept on a sphere by any contact)."""
    max_relative_vertical_momentum_drift: float
    """The same for the vertical angular momentum about G."""
    _data: Dict[str, Any] = field(repr=False)
    losses: Optional[Dict[str, float]] = None
    """With the body's own losses (Table.has_losses): J, the energy each took over the run,
    {"sliding", "drilling", "rolling", "air"}; None otherwise."""

    @property
    def model(self) -> str:
        """"nonlinear": the only model on a table."""
        return "nonlinear"

    @property
    def ok(self) -> bool:
        """True: a run that fails raises instead (leaving the table is an end, not a failure)."""
        return True

    @property
    def report(self) -> str:
        """One line for people: how it ended and the work."""
        method = "Rosenbrock 4" if self.integrator == "rosenbrock4" else "Dormand-Prince 8(5,3)"
        return (f"on the table, {method}: {self.end} at t = {self.end_time:.9g} s, {self.steps} steps, "
                f"{self.rhs_evaluations} evaluations" + (f", {self.switches} switches" if self.switches else ""))

    def __str__(self) -> str:
        return self.report

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "TableSummary":
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

    def spin_law(self, t: npt.ArrayLike) -> FloatArray:
        """rad/s, the fitted law C w' = -d_a w - tau0 sign(w) from spin0 at times t (s), 0 once the
        friction has stopped it: the curve the residuals are measured from."""
        return _views.spin_law(np.asarray(t, dtype=np.float64), self.spin0.value, self.C, self.axial.value,
                               self.friction.value, False)

    def _repr_html_(self) -> str:
        def pm(p: FittedParameter, unit: str) -> str:
            spread = "" if p.uncertainty is None else f" ± {p.uncertainty:.2g}"
            return f"{p.value:.4g}{spread} {unit}" + (" (at its bound)" if p.at_bound else "")
        head = (f"<p>Fitted: axial damping d_a = {html.escape(pm(self.axial, 'N m s'))}, dry friction tau0 = "
                f"{html.escape(pm(self.friction, 'N m'))}, spin at t = 0 {html.escape(pm(self.spin0, 'rad/s'))}; "
                f"rms residual {self.rms_residual:.3g} rad/s over {self.points} points."
                + "".join(f"<br>⚠ {html.escape(w)}" for w in self.warnings) + "</p>")
        return head + JsonResult._repr_html_(self)

    def plot(self, t: npt.ArrayLike, spin: npt.ArrayLike) -> Any:
        """The measured points (t in s, spin in rad/s) and the fitted law through them; returns the
        matplotlib Figure."""
        t = np.asarray(t, dtype=np.float64)
        figure, (ax,) = _views.new_figure(1)
        ax.plot(t, np.asarray(spin, dtype=np.float64), ".", ms=4, label="measured")
        fine = np.linspace(0.0, float(np.max(t)), 500)
        ax.plot(fine, self.spin_law(fine), lw=1.5,
                label=f"fit: d_a = {self.axial.value:.3g} N m s, tau0 = {self.friction.value:.3g} N m")
        ax.set_xlabel(_views.label("t"))
        ax.set_ylabel(_views.label("spin"))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
        ax.set_title(f"Spin decay fitted (rms residual {self.rms_residual:.3g} rad/s)")
        return figure


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

    __slots__ = ("_model", "_summary", "_body", "_spin")

    def __init__(self, columns: Dict[str, FloatArray], summary: SimulationSummary, body: Optional[Body] = None,
                 spin: float = 0.0) -> None:
        self._columns = dict(columns)
        self._summary = summary
        self._model = summary.model
        self._body = body
        self._spin = float(spin)

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
    def body(self) -> Optional[Body]:
        """The Body simulated (None for a Trajectory made by hand)."""
        return self._body

    def view(self, height: int = 720) -> "MotionView":
        """This motion in 3D, inline in a notebook: the report's own 3D view (three.js, from the
        page script heavytop's build embeds; works offline), the body drawn as the uniform
        ellipsoid of its mass and moments turning at its spin angle, the axis's tip path traced,
        an inset from above. A MotionView (an iframe `height` pixels tall; .save(path) writes
        the page). heavytop.show(trajectory) is the same; the trajectory's own HTML shows it."""
        if self._body is None:
            raise ValueError("view: this trajectory has no body (simulate() makes one that has)")
        return MotionView(self, height)

    def _view_html(self) -> str:
        return self.view()._repr_html_()

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

    def to_dataframe(self) -> Any:
        """A pandas DataFrame of every column, in the CSV's order (t in s, angles in rad, rates in
        rad/s; the units of each column in heavytop.results.UNITS), one row per sample."""
        return _views.dataframe(self._columns)

    def to_records(self) -> npt.NDArray[np.void]:
        """A NumPy structured array, one record per sample, one float64 field per column in the
        CSV's order: r["tilt"], r[0]["t"] (copies of the columns)."""
        return _views.records(self._columns)

    def plot(self, columns: Tuple[str, ...] = ("tilt", "azimuth")) -> Any:
        """One panel per column against t (s), with matplotlib; angles (theta, phi, tilt, azimuth)
        in degrees with a second axis in rad, the others in their SI unit. Returns the Figure
        (a notebook shows it). Raises ValueError naming an unknown column."""
        if isinstance(columns, str):
            columns = (columns,)
        for name in columns:
            if name not in self._columns or name == "t":
                raise ValueError(f"plot: a {self._model} trajectory has no column {name!r} to plot "
                                 f"(its columns: {', '.join(self.columns[1:])})")
        return _views.plot_columns(self._columns["t"], self._columns, tuple(columns), f"{self._model} model")

    def _repr_html_(self) -> str:
        t, tilt = self._columns["t"], self._columns["tilt"]
        top = int(np.argmax(tilt))
        head = (f"<p>{html.escape(self._model)} model, {len(t)} samples over {t[-1]:.4g} s: the tilt from the vertical "
                f"goes from {np.degrees(tilt[0]):.3g}° to at most {np.degrees(tilt[top]):.3g}° "
                f"({tilt[top]:.3g} rad, at {t[top]:.4g} s).</p>")
        columns = list(self._columns)
        picks = sorted(set([0, 1, 2, len(t) // 2, len(t) - 2, len(t) - 1]) & set(range(len(t))))
        rows = []
        for i, k in enumerate(picks):
            if i and k - picks[i - 1] > 1:
                rows.append(["…"] * len(columns))
            rows.append([f"{self._columns[c][k]:.6g}" for c in columns])
        header = [_views.label(c) for c in columns]
        view = self._view_html() if self._body is not None and len(t) >= 2 else ""
        return (head + view + _views.html_table(header, rows)
                + f"<p style='font-size: .85em'>{html.escape(self._summary.report)}</p>")


class TableTrajectory(Trajectory):
    """The motion of the body on a table (SPEC section 16), column by column as `heavytop
    simulate --format csv` with [table] prints it: SPEC's seven columns, then x, y (m: the
    contact point P on the table), height (m: O above the table), normal_force (N), slip_speed
    (m/s), spin (rad/s: w.k), energy (J), jellett (kg m^3/s: -L_G.(P - G)), vertical_momentum
    (kg m^2/s: L_G.e_zeta). ``summary`` is a TableSummary; ``table`` the Table; ``settings`` the
    JSON's "table" object (the contact, its law, the radii). When the body leaves the table the
    columns end at that time (summary.end == "leaves the table")."""

    __slots__ = ("_table", "_settings")

    def __init__(self, columns: Dict[str, FloatArray], summary: "TableSummary", body: Optional[Body] = None,
                 spin: float = 0.0, table: Optional[Table] = None, settings: Optional[Dict[str, Any]] = None) -> None:
        super().__init__(columns, summary, body, spin)  # type: ignore[arg-type]
        self._table = table
        self._settings = dict(settings or {})

    x = _column("x", "m, the contact point P's xi on the table (P starts at the origin)")
    y = _column("y", "m, the contact point P's eta on the table")
    height = _column("height", "m, O above the table: tip_radius + rim_radius sin(tilt)")
    normal_force = _column("normal_force", "N, the table's normal force at P")
    slip_speed = _column("slip_speed", "m/s, the speed of the body's material point at P (0 when rolling)")
    spin = _column("spin", "rad/s, w.k: the spin about the body's axis")
    jellett = _column("jellett", "kg m^3/s, Jellett's integral -L_G.(P - G)")
    energy = _column("energy", "J, the energy (falls while the contact slides)")
    vertical_momentum = _column("vertical_momentum", "kg m^2/s, L_G.e_zeta: the vertical angular momentum about G")

    @property
    def summary(self) -> "TableSummary":  # type: ignore[override]
        """What DOP853 did, how the run ended and the drifts (a TableSummary)."""
        return self._summary  # type: ignore[return-value]

    @property
    def table(self) -> Optional[Table]:
        """The Table the body ran on."""
        return self._table

    @property
    def settings(self) -> Dict[str, Any]:
        """The JSON's "table" object: {"contact", "friction", "friction_law", "slip_speed" (sliding
        only), "tip_radius", "rim_radius"} (m)."""
        return copy.deepcopy(self._settings)

    def view(self, height: int = 720) -> "MotionView":
        """Not yet on a table (docs/table.md: the report's 3D view is the pivot's); raises ValueError.
        plot() draws the motion (e.g. plot(("tilt", "spin")) or the track: x against y)."""
        raise ValueError("view: the 3D view is the pivot's; a body on a table is not drawn yet (docs/table.md); "
                         "plot() draws its columns")

    def _view_html(self) -> str:
        return ""

    def __repr__(self) -> str:
        return (f"TableTrajectory(contact={self._settings.get('contact')!r}, samples={len(self._columns['t'])}, "
                f"columns={self.columns!r}, summary={self._summary.report!r})")


def _save(path: "os.PathLike[str] | str", page: str) -> str:
    from . import _core
    path = os.fspath(path)
    _core.write_file(os.fsencode(path), page.encode("utf-8"), "path")
    return path


class MotionView:
    """One trajectory in the report's 3D view, as one self-contained HTML document (the report's
    page script heavytop-report.js, three.js inside, and the motion's data inlined): shown inline
    by a notebook in an iframe, offline. Trajectory.view() and heavytop.show(trajectory) make it;
    .html is the page, .save(path) writes it. In a build without the page script (no npm when it
    was built) the page says so instead."""

    __slots__ = ("html", "height")

    def __init__(self, trajectory: "Trajectory", height: int = 720) -> None:
        from . import _core
        self.height = int(height)
        body = trajectory.body
        script, missing = _core.page_script()
        if script is None:
            self.html = (f"<p class='note'>No 3D view in this build: {html.escape(str(missing))}. "
                         f"trajectory.plot() draws the same motion.</p>")
            return
        data = _core.motion_view_data(body, trajectory._spin, trajectory.to_dict())
        t = trajectory.t
        words = (f"The {html.escape(trajectory.model)} model's motion over {t[-1]:.4g} s, the body drawn as the uniform "
                 f"ellipsoid with its mass and moments (centre of mass at R = {body.length:.4g} m on the spin axis), "
                 f"turning at its spin angle (the red sector on its rim). Black: the fixed point O, the vertical "
                 f"(dashed), the path of the axis's tip. Drag to turn, scroll to zoom. Inset: straight down on the "
                 f"tip, <span id='inset-scale'></span> from centre to edge.")
        if body.general:  # SPEC section 11: drawn on its axis; its spin angle from (I w).e3 / C
            words += (" This general body's centre-of-mass offset and products of inertia are not drawn, and its "
                      "spin angle is taken from (I w).e3 / C, which they change slightly.")
        self.html = (
            "<!doctype html><html><head><meta charset='utf-8'><style>" + _MOTION_VIEW_STYLE + "</style></head><body>"
            "<section id='interactive'><p>" + words + "</p><div id='scene'></div>"
            "<div class='controls'><button id='play'>Pause</button>"
            "<label>speed <input type='range' id='speed' min='0' max='1' step='1'> <span id='speed-value'></span></label>"
            "<label>time <input type='range' id='scrub' min='0' max='10000' value='0' step='1'></label>"
            " <span id='time'></span></div>"
            "<p class='controls'><label class='exaggerate'><input type='checkbox' id='exaggerate'> "
            "<b>exaggerate tilt x10</b> (not to scale)</label></p>"
            "<p class='note' id='spin-note' hidden></p></section>"
            # The page script also draws the report's plots and map; this page has neither.
            "<div id='interactive-plots' hidden><div id='plots'></div></div>"
            "<script>" + data.replace("</script", "<\\/script") + "</script>"
            # The page script sizes its view once, from the scene's width when it runs: in a
            # notebook's iframe that is 0 until the frame is laid out, so it runs only then.
            "<script type='text/plain' id='page-script'>" + script.decode("utf-8").replace("</script", "<\\/script")
            + "</script><script>(function start() { const scene = document.getElementById('scene');"
            " if (!(scene.clientWidth > 0)) { requestAnimationFrame(start); return; }"
            " const s = document.createElement('script'); s.textContent = document.getElementById('page-script').textContent;"
            " document.body.appendChild(s); })();</script></body></html>")

    def save(self, path: "os.PathLike[str] | str") -> str:
        """Writes the self-contained page to `path` (one file, opens offline); returns path. As
        the command line writes --output: through a temporary name beside it and a rename (a
        failed write leaves an existing file as it was); a folder raises InvalidInput."""
        return _save(path, self.html)

    def _repr_html_(self) -> str:
        if not self.html.startswith("<!doctype"):
            return self.html
        return (f"<iframe srcdoc=\"{html.escape(self.html, quote=True)}\" style=\"width: 100%; height: {self.height}px; "
                f"border: 1px solid #ddd\" sandbox=\"allow-scripts\"></iframe>")

    def __repr__(self) -> str:
        return f"MotionView({len(self.html)} characters)"


_MOTION_VIEW_STYLE = (
    "body { font-family: sans-serif; margin: .5em; color: #222; font-size: 14px; } #scene { width: 100%; } "
    "#scene canvas { display: block; border: 1px solid #ddd; } "
    ".controls { display: flex; flex-wrap: wrap; gap: .6em 1.4em; align-items: center; margin: .6em 0; } "
    "label.exaggerate { background: #fff3e0; border: 1px solid #f0b070; padding: .2em .6em; border-radius: 4px; } "
    ".note { background: #fff8e1; border-left: 4px solid #f9a825; padding: .5em 1em; } #scrub { width: 18em; }")


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
        (a three-parameter map's slice()), the first key across, each axis labelled with its unit,
        with matplotlib, into `ax` or a new Figure; returns the Axes (.figure is the Figure).
        Raises ValueError unless the map has two keys."""
        if len(self._shape) != 2:
            raise ValueError(f"plot: a heat map needs two varied keys, this map has {len(self._shape)} (take a slice())")
        from matplotlib.colors import ListedColormap
        if ax is None:  # a Figure of its own, outside pyplot's state (a notebook shows it once)
            ax = _views.new_figure(1, height=4.0)[1][0]
        first, second = list(self.parameters)
        x, y = self.grid(first)[:, 0], self.grid(second)[0, :]
        ax.pcolormesh(x, y, self.grid(name).T.astype(float), cmap=ListedColormap(["#d9d9d9", "#2ca02c"]),
                      vmin=0, vmax=1, shading="nearest")
        ax.set_xlabel(_views.label(first))
        ax.set_ylabel(_views.label(second))
        ax.set_title(f"{name}: stable (green) or not (grey)")
        return ax

    def __repr__(self) -> str:
        return f"StabilityMap(shape={self._shape!r}, columns={self.columns!r})"

    def to_dataframe(self) -> Any:
        """A pandas DataFrame, one row per grid point in the CSV's order (the first key slowest):
        the varied keys' values (SI units), a bool column per model, lyapunov_certificate."""
        return _views.dataframe(self._columns)

    def _repr_html_(self) -> str:
        keys = self.parameters
        ranges = ", ".join(f"{html.escape(_views.label(k))} {np.min(v):.4g} to {np.max(v):.4g} ({n} values)"
                           for (k, v), n in zip(keys.items(), self._shape))
        total = int(np.prod(self._shape))
        rows = [(name, f"{int(np.count_nonzero(v))} of {total}", f"{100.0 * np.count_nonzero(v) / max(total, 1):.1f}%")
                for name, v in self.verdicts.items()]
        return (f"<p>A stability map over {ranges}.</p>"
                + _views.html_table(("model", "stable points", "share"), rows))


# ---- precession, body, load ------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class SteadyPrecession(JsonResult):
    """One steady precession of a symmetric top at a tilt (SPEC section 12's "slow" or "fast")."""

    rate: float
    """rad/s, the precession rate W (the axis turns about the vertical at W)."""
    period: float
    """s, 2 pi / |W|."""
    nutation_frequency: float
    """rad/s, the frequency of small nutations about it."""
    state: Dict[str, float]
    """The SPEC section 2 state on it (spin, theta0, phi0, theta_rate0, phi_rate0): simulate(body, **state)."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "SteadyPrecession":
        return cls(rate=data["rate"], period=data["period"], nutation_frequency=data["nutation_frequency"],
                   state=dict(data["state"]), _data=data)


@dataclass(frozen=True, eq=False)
class Precession(JsonResult):
    """Steady motions at a tilt: `heavytop precession --tilt TILT --format json` (``to_dict()``)."""

    tilt: float
    """rad, the axis's angle from the upward vertical."""
    spin: float
    """rad/s, w3 = w.k."""
    slow: Optional[SteadyPrecession]
    """The slow steady precession; None when there is none (or A != B)."""
    fast: Optional[SteadyPrecession]
    """The fast steady precession; None when there is none (or A != B)."""
    min_spin: Optional[float]
    """rad/s, the least spin with a steady precession at this tilt (None for A != B)."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "Precession":
        steady = data.get("steady_precession") or {}
        def one(name: str) -> Optional[SteadyPrecession]:
            value = steady.get(name)
            return None if value is None else SteadyPrecession.from_json(value)
        return cls(tilt=data["tilt"], spin=data["spin"], slow=one("slow"), fast=one("fast"),
                   min_spin=steady.get("min_spin"), _data=data)

    def __repr__(self) -> str:
        f = _views.fmt
        lines = [f"At tilt {self.tilt:.4g} rad ({np.degrees(self.tilt):.3g}°), spin {self.spin:.6g} rad/s:"]
        for name, p in (("slow", self.slow), ("fast", self.fast)):
            lines.append(f"  {name}: " + ("none" if p is None else
                         f"precession {f(p.rate, 'rad/s')} (period {f(p.period, 's')}), nutation {f(p.nutation_frequency, 'rad/s')}"))
        lines.append(f"  least spin for a steady precession: {f(self.min_spin, 'rad/s')}")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        f = _views.fmt
        rows = [(name, "none", "", "") if p is None else
                (name, f(p.rate, "rad/s"), f(p.period, "s"), f(p.nutation_frequency, "rad/s"))
                for name, p in (("slow", self.slow), ("fast", self.fast))]
        return (f"<p>{html.escape(repr(self).splitlines()[0])} least spin for a steady precession "
                f"{html.escape(f(self.min_spin, 'rad/s'))}.</p>"
                + _views.html_table(("precession", "rate", "period", "nutation"), rows))


@dataclass(frozen=True, eq=False)
class BodyReport(JsonResult):
    """A body's mass properties: `heavytop body --format json` (``to_dict()``)."""

    A: float
    """kg m^2, about body x through O."""
    B: float
    """kg m^2, about body y through O."""
    C: float
    """kg m^2, about the spin axis z through O."""
    mass: float
    """kg."""
    length: float
    """m, the centre of mass's height along z above O."""
    general: bool
    """True for SPEC section 11's general body (centre of mass off z, or z not a principal axis)."""
    _data: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, data: Dict[str, Any]) -> "BodyReport":
        return cls(A=data["A"], B=data["B"], C=data["C"], mass=data["mass"], length=data["length"],
                   general=bool(data.get("general", False)), _data=data)

    def __repr__(self) -> str:
        return (f"BodyReport(A={self.A!r}, B={self.B!r}, C={self.C!r}, mass={self.mass!r}, length={self.length!r}, "
                f"general={self.general!r}, parts={len(self._data.get('parts', []))})")

    def _repr_html_(self) -> str:
        f, d = _views.fmt, self._data
        kind = ("a general body (SPEC section 11: the centre of mass off z, or z not a principal axis)"
                if self.general else "z a principal axis with the centre of mass on it")
        head = (f"<p>{self.mass * 1e3:.4g} g, the centre of mass {self.length * 1e3:.4g} mm above O along z; "
                f"{html.escape(kind)}.</p>")
        rows = [("A", f(self.A, "kg m^2")), ("B", f(self.B, "kg m^2")), ("C", f(self.C, "kg m^2")),
                ("mass", f(self.mass, "kg")), ("length", f(self.length, "m")), ("gravity", f(d.get("gravity"), "m/s^2"))]
        if self.general:
            rows += [(f"products.{k}", f(v, "kg m^2")) for k, v in d.get("products", {}).items()]
            rows += [(f"offset.{k}", f(v, "m")) for k, v in d.get("offset", {}).items()]
        table = _views.html_table(("", "value"), rows)
        parts = d.get("parts") or []
        if parts:
            table += _views.html_table(("part", "mass", "centre of mass z"),
                                       [(p.get("name", ""), f(p.get("mass"), "kg"),
                                         f((p.get("centre_of_mass") or [None] * 3)[2], "m")) for p in parts])
        return head + table


@dataclass(frozen=True, eq=False)
class Configuration:
    """A configuration file read by heavytop.load(): the body, the motion and the other sections'
    options, as the command line reads them (``--config FILE``)."""

    path: str
    """The file read."""
    body: Body
    """The body of [body] (its moments, or those its [[body.part]] make), with [damping]."""
    motion: Dict[str, float]
    """[motion]: spin (rad/s), theta0, phi0 (rad), theta_rate0, phi_rate0 (rad/s); 0 where not given
    (spin_rpm read as spin in rad/s): simulate(cfg.body, **cfg.motion)."""
    options: Dict[str, Any]
    """The further sections' values by "section.key" ("simulate.t_end": 10.0), as TOML typed them."""
    given: Tuple[str, ...]
    """The body and motion keys the file gives ("body.A", "motion.spin", ...)."""
    from_parts: bool
    """True when [[body.part]] describe the body."""
    table: Table = field(default_factory=Table)
    """[table] (SPEC section 16): the pivot (Table()) when absent. simulate(cfg.body, **cfg.motion,
    table=cfg.table) and stability(cfg.body, **cfg.motion, table=cfg.table) take it."""

    def section(self, name: str) -> Dict[str, Any]:
        """The options of section `name` by key: cfg.section("simulate") == {"t_end": 10.0, ...}."""
        prefix = name + "."
        return {k[len(prefix):]: v for k, v in self.options.items() if k.startswith(prefix)}

    def _repr_html_(self) -> str:
        rows = [("body", repr(self.body))] + [(f"motion.{k}", _views.fmt(v)) for k, v in self.motion.items()]
        if self.table.on_table:
            rows.append(("table", repr(self.table)))
        rows += [(k, _views.fmt(v)) for k, v in self.options.items()]
        return _views.html_table(("key", "value"), rows, caption=self.path)


class ReportView:
    """The report's page (report.html of `heavytop report`) as one self-contained HTML document:
    its scripts (the three.js bundle heavytop-report.js and its data report-data.js) and figures
    inlined, so that a notebook shows it, the body moving in 3D included, offline, in an iframe.
    show() makes it; .folder is the report folder it was read from (show()'s temporary folder,
    when given none, is removed as the Python process exits: .html holds everything)."""

    __slots__ = ("folder", "html", "height")

    def __init__(self, folder: str, height: int = 720) -> None:
        import base64
        import re
        self.folder = folder
        self.height = int(height)
        with open(os.path.join(folder, "report.html"), encoding="utf-8") as f:
            page = f.read()

        def script(name: str) -> str:
            path = os.path.join(folder, name)
            if not os.path.exists(path):
                return ""
            with open(path, encoding="utf-8") as f:
                return "<script>" + f.read().replace("</script", "<\\/script") + "</script>"

        page = page.replace("<script src='report-data.js'></script>", script("report-data.js"))
        bundle = script("heavytop-report.js")  # deferred in the page: it runs once the body is parsed
        page = page.replace("<script src='heavytop-report.js' defer></script>", "")
        page = page.replace("</body>", bundle + "</body>") if bundle else page

        def image(match: "re.Match[str]") -> str:
            name = match.group(1)
            with open(os.path.join(folder, name), "rb") as f:
                data = base64.b64encode(f.read()).decode("ascii")
            kind = "image/svg+xml" if name.endswith(".svg") else "image/png"
            return f"src='data:{kind};base64,{data}'"
        self.html = re.sub(r"src='([A-Za-z0-9_.-]+\.(?:svg|png))'", image, page)

    def save(self, path: "os.PathLike[str] | str") -> str:
        """Writes the self-contained page to `path` (one file, opens offline); returns path. As
        the command line writes --output: through a temporary name beside it and a rename (a
        failed write leaves an existing file as it was); a folder raises InvalidInput."""
        return _save(path, self.html)

    def _repr_html_(self) -> str:
        # In the notebook's frame, opened at the 3D view (the page's answer is above it).
        scroll = ("<script>window.addEventListener('load', () => { const e = document.getElementById('scene'); "
                  "if (e) e.scrollIntoView({block: 'center'}); });</script>")
        page = self.html.replace("</body>", scroll + "</body>", 1) if "</body>" in self.html else self.html + scroll
        return (f"<iframe srcdoc=\"{html.escape(page, quote=True)}\" style=\"width: 100%; height: {self.height}px; "
                f"border: 1px solid #ddd\" sandbox=\"allow-scripts\"></iframe>")

    def __repr__(self) -> str:
        return f"ReportView(folder={self.folder!r}, {len(self.html)} characters)"

"""Frames, plots and HTML of heavytop's results (heavytop.results calls these): pandas and
matplotlib are imported only when a function that needs them is called."""
from __future__ import annotations

import html
import math
from typing import Any, Dict, Iterable, Mapping, Optional, Sequence, Tuple

import numpy as np

#: The unit of every column simulate() and sweep() can give (SI; angles in rad).
UNITS: Dict[str, str] = {
    "t": "s", "theta": "rad", "phi": "rad", "theta_rate": "rad/s", "phi_rate": "rad/s", "tilt": "rad",
    "azimuth": "rad", "energy": "J", "vertical_momentum": "kg m^2/s", "axial_momentum": "kg m^2/s",
    "energy_drift": "J", "vertical_momentum_drift": "kg m^2/s", "axial_momentum_drift": "kg m^2/s",
    "dissipated_work": "J", "vertical_momentum_loss": "kg m^2/s", "axial_momentum_loss": "kg m^2/s",
    "motor_torque": "N m",
    # on a table (SPEC section 16)
    "x": "m", "y": "m", "height": "m", "normal_force": "N", "slip_speed": "m/s", "jellett": "kg m^3/s",
    # sweep's varied keys
    "A": "kg m^2", "B": "kg m^2", "C": "kg m^2", "mass": "kg", "length": "m", "gravity": "m/s^2",
    "spin": "rad/s", "B/A": "", "C/A": "",
}

#: Columns drawn in degrees (with a second axis in rad).
ANGLES = frozenset({"theta", "phi", "tilt", "azimuth"})


def label(name: str) -> str:
    """An axis label with its unit: "spin (rad/s)", "B/A (dimensionless)"."""
    unit = UNITS.get(name)
    if unit is None:
        return name
    return f"{name} ({unit or 'dimensionless'})"


def dataframe(columns: Mapping[str, Any], index: Optional[str] = None) -> Any:
    import pandas as pd
    frame = pd.DataFrame({name: np.asarray(column) for name, column in columns.items()})
    if index is not None:
        frame = frame.set_index(index, drop=False)
        frame.index.name = None
    return frame


def records(columns: Mapping[str, np.ndarray]) -> np.ndarray:
    """A structured array, one field per column, one record per sample."""
    arrays = [np.asarray(c) for c in columns.values()]
    dtype = [(name, a.dtype) for name, a in zip(columns, arrays)]
    out = np.empty(len(arrays[0]) if arrays else 0, dtype=dtype)
    for name, a in zip(columns, arrays):
        out[name] = a
    return out


def new_figure(rows: int = 1, sharex: bool = False, height: float = 2.6) -> Tuple[Any, Any]:
    # matplotlib.figure.Figure, not pyplot: no global state, shown by Jupyter's repr of the figure.
    from matplotlib.figure import Figure
    figure = Figure(figsize=(7.0, 1.2 + height * rows), layout="constrained")
    axes = figure.subplots(rows, 1, sharex=sharex, squeeze=False)[:, 0]
    return figure, axes


def plot_columns(t: np.ndarray, columns: Mapping[str, np.ndarray], names: Sequence[str], title: str) -> Any:
    figure, axes = new_figure(len(names), sharex=True)
    for ax, name in zip(axes, names):
        values = np.asarray(columns[name])
        if name in ANGLES:
            ax.plot(t, np.degrees(values), lw=1.0)
            ax.set_ylabel(f"{name} (°)")
            rad = ax.secondary_yaxis("right", functions=(np.radians, np.degrees))
            rad.set_ylabel(f"{name} (rad)")
        else:
            ax.plot(t, values, lw=1.0)
            ax.set_ylabel(label(name))
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(label("t"))
    axes[0].set_title(title)
    return figure


def fmt(value: Any, unit: str = "") -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        text = f"{value:.6g}"
    else:
        text = str(value)
    return f"{text} {unit}".strip()


def html_table(header: Sequence[str], rows: Iterable[Sequence[Any]], caption: str = "") -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows)
    cap = f"<caption style='text-align: left'>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def spin_law(t: np.ndarray, spin0: float, C: float, axial: float, friction: float, driven: bool) -> np.ndarray:
    """The closed-form spin law C w' = -d_a w - tau0 sign(w) (SPEC section 8) from w(0) = spin0 >= 0,
    held at 0 once dry friction stops it; a driven body keeps its spin."""
    t = np.asarray(t, dtype=np.float64)
    if driven or (axial == 0.0 and friction == 0.0):
        return np.full_like(t, spin0)
    sign, w0 = (1.0 if spin0 >= 0 else -1.0), abs(spin0)
    if axial > 0.0:
        floor = friction / axial
        w = (w0 + floor) * np.exp(-axial / C * t) - floor
    else:
        w = w0 - friction / C * t
    return sign * np.maximum(w, 0.0)


def flat_rows(data: Mapping[str, Any], prefix: str = "", depth: int = 2) -> Iterable[Tuple[str, str]]:
    """(key, value) rows of a JSON object's scalars, nested objects as "a.b", lists summarised."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            if depth > 1:
                yield from flat_rows(value, name + ".", depth - 1)
        elif isinstance(value, (list, tuple)):
            if len(value) <= 4 and all(not isinstance(v, (list, dict)) for v in value):
                yield name, ", ".join(fmt(v) for v in value)
            else:
                yield name, f"[{len(value)} items]"
        else:
            yield name, fmt(value)

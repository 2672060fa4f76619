"""heavytop in a notebook: DataFrames, structured arrays, plots and HTML of the results, each
holding the command line's numbers (CSV and JSON) for the same input."""
import io
import math
import os

import numpy as np
import pytest

import heavytop
from conftest import BODIES, body_options, cli_json, motion_options, run_cli

pd = pytest.importorskip("pandas")
matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

TOP = heavytop.example_toy_top()
DECAY = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                     "examples", "spin-decay.csv")
MOTION = dict(spin=200.0, theta0=0.05)


def damped(**damping):
    return heavytop.Body(TOP.A, TOP.B, TOP.C, TOP.mass, TOP.length, TOP.gravity, **damping)


def damping_options(body):
    return ["--transverse-damping", repr(body.transverse_damping), "--axial-damping", repr(body.axial_damping),
            "--friction", repr(body.friction), "--driven", "true" if body.driven else "false"]


def cli_csv(*args):
    return pd.read_csv(io.StringIO(run_cli(*args, "--format", "csv").stdout), float_precision="round_trip")


@pytest.mark.parametrize("model,body,motion", [
    ("nonlinear", TOP, MOTION),
    ("linearized", BODIES["asymmetric-plate"], dict(spin=1.3, theta0=1e-4, phi_rate0=1e-3)),
    ("nonlinear", damped(transverse_damping=1e-6, axial_damping=2e-7), MOTION),
])
def test_trajectory_frame_and_records_are_the_cli_csv(model, body, motion):
    result = heavytop.simulate(body, model, **motion, t_end=0.5, samples=101)
    expected = cli_csv("simulate", *body_options(body), *damping_options(body), *motion_options(**motion),
                       "--model", model, "--t-end", "0.5", "--samples", "101")
    frame = result.to_dataframe()
    assert list(frame.columns) == list(expected.columns) == list(result.columns)
    assert frame.shape == (101, len(result.columns))
    np.testing.assert_allclose(frame.to_numpy(), expected.to_numpy(), rtol=0, atol=1e-15)
    records = result.to_records()
    assert records.dtype.names == tuple(expected.columns) and records.shape == (101,)
    for name in expected.columns:
        np.testing.assert_allclose(records[name], expected[name].to_numpy(), rtol=0, atol=1e-15, err_msg=name)
    assert records[37]["tilt"] == result.tilt[37] and records["t"][-1] == 0.5


def test_comparison_frame_is_the_cli_json():
    expected = cli_json("compare", *body_options(TOP), *motion_options(**MOTION), "--t-end", "1", "--samples", "1001")
    frame = heavytop.compare(TOP, **MOTION, t_end=1.0, samples=1001).to_dataframe()
    assert list(frame.index) == ["nonlinear", *expected["models"]]
    assert frame.loc["nonlinear", "nutation_frequency"] == expected["nonlinear"]["nutation_frequency"]
    assert frame.loc["nonlinear", "precession_rate"] == expected["nonlinear"]["precession_rate"]
    assert math.isnan(frame.loc["nonlinear", "max_angle_error"])
    for name, model in expected["models"].items():
        for column in ("max_angle_error", "nutation_frequency", "precession_rate", "precession_relative_error"):
            assert frame.loc[name, column] == model[column], (name, column)


def test_map_frame_is_the_cli_csv():
    vary = {"spin": heavytop.grid_values(0.0, 300.0, 7), "length": heavytop.grid_values(0.005, 0.03, 4)}
    result = heavytop.sweep(TOP, vary)
    expected = cli_csv("sweep", *body_options(TOP), "--vary", "spin=0:300:7", "--vary", "length=0.005:0.03:4")
    frame = result.to_dataframe()
    assert list(frame.columns) == list(expected.columns) and len(frame) == 28
    for name in expected.columns:
        if name == "lyapunov_certificate":
            assert list(frame[name]) == list(expected[name])
        elif frame[name].dtype == bool:
            assert list(frame[name]) == [bool(v) for v in expected[name]], name
        else:
            np.testing.assert_array_equal(frame[name].to_numpy(), expected[name].to_numpy(), err_msg=name)
    html = result._repr_html_()
    stable = int(np.count_nonzero(result["linearized"]))
    assert f"<td>linearized</td><td>{stable} of 28</td>" in html and "spin (rad/s)" in html


def test_lifetime_frame_law_and_plot_are_the_cli_s():
    body = damped(axial_damping=2e-7, friction=1e-6)
    life = heavytop.lifetime(body, spin=200.0, theta0=0.05)
    expected = cli_json("lifetime", *body_options(body), *damping_options(body), *motion_options(**MOTION))
    frame = life.to_dataframe()
    assert frame.shape == (1, 6)
    assert frame.loc[0, "critical_spin"] == expected["spin_decay"]["critical_spin"]
    assert frame.loc[0, "time_to_critical"] == expected["spin_decay"]["time_to_critical"]
    assert frame.loc[0, "fall_time"] == expected["fall"]["time"]
    assert frame.loc[0, "fall_spin"] == expected["fall"]["spin"]
    assert frame.loc[0, "horizon"] == expected["horizon"]
    # The closed-form law the plot draws reaches the critical spin when the core says it does.
    assert life.spin_law([0.0])[0] == 200.0
    assert life.spin_law([life.time_to_critical])[0] == pytest.approx(life.critical_spin, rel=1e-9)
    figure = life.plot()
    ax = figure.axes[0]
    assert ax.get_xlabel() == "t (s)" and ax.get_ylabel() == "spin (rad/s)"
    assert [line.get_xdata()[0] for line in ax.lines[2:]] == [life.time_to_critical, life.fall_time]
    assert repr(life).startswith(f"Falls after {life.fall_time:.4g} s")
    assert life._repr_html_().startswith("<p>Falls after")


def test_trajectory_plot_has_units_and_degrees():
    m = heavytop.simulate(TOP, "nonlinear", **MOTION, t_end=0.5, samples=201)
    figure = m.plot()
    tilt_ax, azimuth_ax = figure.axes[:2]
    assert tilt_ax.get_ylabel() == "tilt (°)" and azimuth_ax.get_ylabel() == "azimuth (°)"
    assert azimuth_ax.get_xlabel() == "t (s)"
    np.testing.assert_allclose(tilt_ax.lines[0].get_ydata(), np.degrees(m.tilt))
    assert [a.get_ylabel() for ax in (tilt_ax, azimuth_ax) for a in ax.child_axes] == ["tilt (rad)", "azimuth (rad)"]
    energy = m.plot(("energy", "phi_rate")).axes
    assert [a.get_ylabel() for a in energy] == ["energy (J)", "phi_rate (rad/s)"]
    with pytest.raises(ValueError, match="no column 'energy'"):
        heavytop.simulate(TOP, "linearized", **MOTION, t_end=0.1, samples=11).plot(("energy",))


def test_map_plot_labels_have_units():
    vary = {"spin": np.linspace(0.0, 300.0, 5), "C/A": np.linspace(1.2, 1.8, 3)}
    ax = heavytop.sweep(TOP, vary).plot()
    assert ax.get_xlabel() == "spin (rad/s)" and ax.get_ylabel() == "C/A (dimensionless)"


def test_comparison_plot_and_html():
    c = heavytop.compare(TOP, **MOTION, t_end=0.5, samples=501)
    figure = c.plot()
    bars = [p.get_height() for p in figure.axes[0].patches]
    assert bars == [m.max_angle_error for m in c.models.values()]
    assert figure.axes[0].get_ylabel() == "max angle error (rad)"
    best = min((n for n in c.models if n != "lagrange-exact"), key=lambda n: c.models[n].max_angle_error)
    assert c._repr_html_().startswith(f"<p>Closest to the nonlinear body: <b>{best}</b>")
    assert repr(c).startswith("nonlinear body: nutation")


def test_every_result_has_html_answer_first():
    s = heavytop.stability(TOP, 200.0)
    assert s._repr_html_().index(s.answer.text.split(".")[0]) < s._repr_html_().index("<table>")
    m = heavytop.simulate(TOP, "nonlinear", **MOTION, t_end=0.5, samples=51)
    html = m._repr_html_()
    assert html.startswith("<p>nonlinear model, 51 samples over 0.5 s") and "<th>tilt (rad)</th>" in html
    assert f"at most {np.degrees(m.tilt.max()):.3g}°" in html
    fit = heavytop.fit_decay([0, 1, 2, 3, 4], [200, 190, 180.5, 171.5, 163], TOP)
    assert f"<td>axial.value</td><td>{fit.axial.value:.6g}</td>" in fit._repr_html_()


def test_decay_fit_law_gives_its_residual_and_plot():
    data = np.loadtxt(DECAY, delimiter=",", comments="#", skiprows=5)
    t, w = data[:, 0], data[:, 1]
    fit = heavytop.fit_decay(t, w)
    expected = cli_json("fit-decay", "--data", DECAY)
    assert fit.to_dict() == expected
    law = fit.spin_law(t)
    assert law[0] == fit.spin0.value
    assert np.sqrt(np.mean((law - w) ** 2)) == pytest.approx(fit.rms_residual, rel=1e-9)
    if fit.stop_time is not None:
        assert fit.spin_law([fit.stop_time * (1 - 1e-9)])[0] < 1e-3 and fit.spin_law([fit.stop_time * 1.01])[0] == 0.0
    ax = fit.plot(t, w).axes[0]
    assert ax.get_xlabel() == "t (s)" and ax.get_ylabel() == "spin (rad/s)"
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), w)


def test_help_lists_every_function_and_each_documents_units():
    import inspect
    functions = [n for n in heavytop.__all__ if inspect.isroutine(getattr(heavytop, n))]
    assert {"load", "report", "stability", "simulate", "lifetime", "fit_decay"} <= set(functions)
    for name in functions:
        assert f"{name}(" in heavytop.__doc__, name
        doc = getattr(heavytop, name).__doc__ or ""
        if name not in ("derive", "derive_rotations", "derive_check", "example_toy_top", "example_motion", "grid_values"):
            assert any(u in doc for u in ("rad", "kg", " m", " s,", "SI")), name

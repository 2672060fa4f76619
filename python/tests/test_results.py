"""Typed results: attributes, and a Mapping / to_dict() that is what the command line prints."""
import io
import math
import pickle

import numpy as np
import pytest

import heavytop
from conftest import BODIES, body_options, cli_json, motion_options, needs_derive, run_cli
from test_errors import cli_error

TOP = heavytop.example_toy_top()
MOTION = heavytop.example_motion()


def test_stability_attributes_are_the_json_typed():
    body = BODIES["asymmetric-plate"]
    result = heavytop.stability(body, 1.3)
    expected = cli_json("stability", *body_options(body), *motion_options(spin=1.3))
    assert isinstance(result, heavytop.Stability)
    assert result.to_dict() == expected and result == expected
    assert list(result) == list(expected) and len(result) == len(expected) and "models" in result
    assert result.body == body and result.spin == 1.3
    assert list(result.models) == ["first-order", "body-fixed", "linearized"]
    for name, model in result.models.items():
        json = expected["models"][name]
        assert isinstance(model, heavytop.ModelStability)
        assert model.stable is json["stable"] and model.critical_spin == json["critical_spin"]
        assert model.stable_spin_intervals == tuple(tuple(i) for i in json["stable_spin_intervals"])
        assert model.eigenvalues == tuple(complex(re, im) for re, im in json["eigenvalues"])
        assert model.frequencies == tuple(json.get("frequencies", ()))
        assert model.reason == json["reason"]
        assert model.to_dict() == json and model == json
    # Indexing gives copies of the JSON: changing them changes nothing.
    result["models"]["linearized"]["stable"] = "changed"
    assert result.to_dict() == expected
    assert pickle.loads(pickle.dumps(result)) == expected


def test_closed_form_critical_spin_of_the_symmetric_top():
    # C^2 w0^2 > 4 A m g R: the sleeping-top criterion.
    critical = heavytop.stability(TOP, 200.0).models["linearized"].critical_spin
    assert critical == pytest.approx(math.sqrt(4 * TOP.A * TOP.mgR) / TOP.C, rel=1e-12)


def test_compare_attributes_are_the_json_typed():
    result = heavytop.compare(TOP, **MOTION, t_end=0.5, samples=501)
    expected = cli_json("compare", *body_options(TOP), *motion_options(**MOTION), "--t-end", "0.5", "--samples", "501")
    assert isinstance(result, heavytop.Comparison) and result.to_dict() == expected
    assert result.nonlinear.steps == expected["nonlinear"]["steps"]
    assert result.nonlinear.precession_rate == expected["nonlinear"]["precession_rate"]
    assert list(result.models) == list(expected["models"]) == ["first-order", "body-fixed", "linearized",
                                                               "lagrange-exact"]
    for name, model in result.models.items():
        for key, value in expected["models"][name].items():
            assert getattr(model, key) == value, (name, key)
    assert result.models["lagrange-exact"].max_angle_error < 1e-8


def test_trajectory_attributes_are_its_columns():
    result = heavytop.simulate(TOP, "nonlinear", **MOTION, t_end=0.5, samples=101, integrator="dopri5")
    assert isinstance(result, heavytop.Trajectory)
    assert result.columns == tuple(result) == tuple(result.to_dict())
    for name in result.columns:
        assert getattr(result, name) is result[name] is result.to_dict()[name]
    assert list(result.columns[5:7]) == ["tilt", "azimuth"]
    assert list(result.extra) == list(result.columns[7:]) == ["energy", "vertical_momentum", "axial_momentum",
                                                               "energy_drift", "vertical_momentum_drift",
                                                               "axial_momentum_drift"]
    assert result.model == "nonlinear" and len(result) == 13 and "energy" in result
    summary = result.summary
    assert isinstance(summary, heavytop.SimulationSummary)
    assert summary.ok and summary.termination == "success" and summary.message == ""
    assert summary.model == "nonlinear" and summary.solver == "Dormand-Prince 5(4)" and summary.samples == 101
    assert summary.steps > 0 and summary.rhs_evaluations > summary.steps
    assert 0 <= summary.max_relative_energy_drift < 1e-12
    assert str(summary) == summary.report and summary.report.startswith("nonlinear (Dormand-Prince 5(4)): 101 samples")

    linear = heavytop.simulate(TOP, "first-order", **MOTION, t_end=0.5, samples=101)
    assert linear.columns == ("t", "theta", "phi", "theta_rate", "phi_rate", "tilt", "azimuth") and linear.extra == {}
    assert linear.summary.solver == "closed form" and linear.summary.max_relative_energy_drift is None
    with pytest.raises(AttributeError, match="first-order trajectory has no column 'energy'"):
        linear.energy


def test_splitting_integrator_equals_the_cli():
    options = dict(integrator="splitting", step=2e-3, order=4)
    result = heavytop.simulate(TOP, **MOTION, t_end=1.0, samples=11, **options)
    csv = run_cli("simulate", *body_options(TOP), *motion_options(**MOTION), "--integrator", "splitting",
                  "--step", "0.002", "--order", "4", "--t-end", "1", "--samples", "11", "--format", "csv").stdout
    header = csv.splitlines()[0].split(",")
    data = np.loadtxt(io.StringIO(csv), delimiter=",", skiprows=1, ndmin=2)
    assert list(result.columns) == header
    for i, name in enumerate(header):
        np.testing.assert_array_equal(result[name] + 0.0, data[:, i], err_msg=name)
    assert result.summary.solver == "splitting, order 4, step 0.002 s" and result.summary.steps == 500
    adaptive = heavytop.simulate(TOP, **MOTION, t_end=1.0, samples=11)
    np.testing.assert_allclose(result.theta, adaptive.theta, rtol=0, atol=1e-6)


def test_a_failed_run_raises_runtime_error_with_the_summarys_message():
    with pytest.raises(RuntimeError, match="max_steps") as error:
        heavytop.simulate(TOP, **MOTION, t_end=10.0, samples=11, max_steps=10)
    summary = error.value.summary
    assert not summary.ok and summary.termination == "failure"
    assert str(error.value) == summary.message and summary.message in summary.report
    # The same cap on the splitting integrator: the core refuses the step as too small instead.
    with pytest.raises(ValueError, match="^step: too small"):
        heavytop.simulate(TOP, **MOTION, t_end=10.0, samples=11, integrator="splitting", max_steps=10)


@pytest.mark.parametrize("kwargs,cli_args", [
    (dict(integrator="splitting", order=3), ["--integrator", "splitting", "--order", "3"]),
    (dict(integrator="splitting", step=0.0), ["--integrator", "splitting", "--step", "0"]),
    (dict(integrator="splitting", step=math.inf), ["--integrator", "splitting", "--step", "inf"]),
])
def test_integrator_options_are_refused_as_the_cli(kwargs, cli_args):
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.simulate(TOP, **kwargs)
    assert str(error.value) == cli_error("simulate", *body_options(TOP), *cli_args)


@pytest.mark.parametrize("kwargs,message", [
    (dict(integrator="leapfrog"), "integrator: must be auto, taylor, dop853, dopri5 (adaptive), splitting or rosenbrock4"),
    (dict(model="first-order", integrator="adaptive"), 'integrator: applies to model="nonlinear" only'),
    (dict(model="linearized", step=1e-3), 'step: applies to model="nonlinear" only'),
    (dict(model="lagrange-exact", max_steps=10), 'max_steps: applies to model="nonlinear" only'),
    (dict(step=1e-3), 'step: applies to integrator="splitting" only'),
    (dict(integrator="adaptive", order=4), 'order: applies to integrator="splitting" only'),
    (dict(max_steps=0), "max_steps: must be > 0"),
    (dict(max_steps=-5), "max_steps: must be > 0"),
    (dict(integrator="splitting", max_steps=0), "max_steps: must be > 0"),
])
def test_integrator_options_name_the_keyword(kwargs, message):
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.simulate(TOP, **kwargs)
    assert str(error.value) == message and error.value.key == message.split(":")[0]


def test_sweep_result_is_a_stability_map():
    ratios, spins = heavytop.grid_values(0.9, 1.1, 3), heavytop.grid_values(100, 300, 5)
    result = heavytop.sweep(TOP, {"B/A": ratios, "spin": spins}, spin=200.0)
    assert isinstance(result, heavytop.StabilityMap)
    assert result.columns == ("B/A", "spin", "first-order", "body-fixed", "linearized", "lyapunov",
                              "lyapunov_certificate") == tuple(result)
    assert result.shape == (3, 5) and list(result.parameters) == ["B/A", "spin"]
    assert list(result.verdicts) == ["first-order", "body-fixed", "linearized", "lyapunov"]
    assert result.to_dict().keys() == dict(result).keys()
    grid = result.grid("linearized")
    assert grid.shape == (3, 5) and (result.grid("spin")[1] == spins).all() and (result.grid("B/A")[:, 0] == ratios).all()
    for i, ratio in enumerate(ratios):
        for j, spin in enumerate(spins):
            body = heavytop.Body(**dict(TOP.to_dict(), B=ratio * TOP.A))
            assert grid[i, j] == heavytop.stability(body, spin).models["linearized"].stable
            assert result.grid("lyapunov")[i, j] == (heavytop.stability(body, spin).lyapunov.verdict == "stable")
            assert result.certificates.reshape(3, 5)[i, j] == heavytop.stability(body, spin).lyapunov.certificate


def test_grid_values_name_their_arguments():
    for args, message in [((math.nan, 1.0, 3), "start: must be a finite number"),
                          ((0.0, math.inf, 3), "stop: must be a finite number"),
                          ((0.0, 1.0, 0), "count: must be an integer in [1, 100000000]")]:
        with pytest.raises(heavytop.InvalidInput) as error:
            heavytop.grid_values(*args)
        assert str(error.value) == message


@needs_derive
def test_derivations_are_typed():
    result = heavytop.derive("lagrange", "phi-theta", 2)
    expected = cli_json("derive", "--method", "lagrange", "--sequence", "phi-theta", "--order", "2")
    assert isinstance(result, heavytop.Derivation) and result.to_dict() == expected
    assert result.M == tuple(tuple(row) for row in expected["M"]) and len(result.K) == 2
    assert result.stability_condition == expected["stability_condition"]
    rotations = heavytop.derive_rotations(2)
    assert rotations.commutator == tuple(tuple(row) for row in rotations["commutator"])
    check = heavytop.derive_check(1)
    assert check.all_as_expected is True and len(check.rows) == len(check["rows"])
    assert all(row.order == 1 and row.as_expected for row in check.rows)


@pytest.mark.parametrize("name,motion", [
    ("toy-top", dict(spin=200.0, theta0=0.05)),                      # A = B: the cubic's root
    ("reference", dict(spin=1.2, theta0=1e-3, phi_rate0=0.01)),      # A != B: integrated
    ("hanging", dict(spin=0.0, theta0=0.2)),
    ("intermediate-C", dict(spin=3.0)),
])
def test_stability_lyapunov_and_wander_are_the_clis(name, motion):
    body = BODIES[name]
    result = heavytop.stability(body, motion["spin"], horizon=20.0,
                                **{k: v for k, v in motion.items() if k != "spin"})
    expected = cli_json("stability", *body_options(body), *motion_options(**motion), "--horizon", "20")
    assert result == expected
    assert list(expected)[-2:] == ["lyapunov", "wander"]
    lyapunov, json = result.lyapunov, expected["lyapunov"]
    assert isinstance(lyapunov, heavytop.results.Lyapunov)
    assert (lyapunov.verdict, lyapunov.certificate, lyapunov.energy_index, lyapunov.superfast_spin) == (
        json["verdict"], json["certificate"], json["energy_index"], json["superfast_spin"])
    assert lyapunov.stable_spin_intervals == tuple(tuple(i) for i in json["stable_spin_intervals"])
    wander = result.wander
    assert isinstance(wander, heavytop.results.Wander)
    assert (wander.max_tilt, wander.method, wander.horizon) == (
        expected["wander"]["max_tilt"], expected["wander"]["method"], expected["wander"]["horizon"])
    symmetric = body.A == body.B
    assert wander.method == ("closed form" if symmetric or motion.get("theta0", 0) == 0 else "integrated")


def test_lyapunov_values():
    # The toy top: Chetaev above 133.344 rad/s, never superfast; its wander from 0.05 rad is
    # acos(u_min) of the Lagrange cubic, within the integrated maximum.
    top = heavytop.example_toy_top()
    result = heavytop.stability(top, 200.0, theta0=0.05)
    assert (result.lyapunov.verdict, result.lyapunov.certificate) == ("stable", "chetaev")
    assert result.lyapunov.superfast_spin is None
    ((lo, hi),) = result.lyapunov.stable_spin_intervals
    assert abs(lo - 2 * math.sqrt(top.A * top.mass * top.gravity * top.length) / top.C) < 1e-12 * lo
    assert hi is None and abs(lo - 133.344) < 5e-4
    assert 0.05 < result.wander.max_tilt < 0.1 and result.wander.horizon is None
    # E3's body: index 1 between 1 and sqrt 2, superfast above.
    body = heavytop.Body(1.0, 1.5, 2.0, mass=1.0, length=1.0, gravity=1.0)
    mid = heavytop.stability(body, 1.2).lyapunov
    assert (mid.verdict, mid.certificate, mid.energy_index) == ("unstable", "odd-index", 1)
    assert heavytop.stability(body, 1.5).lyapunov.superfast_spin == math.sqrt(2.0)
    # Index 2, linearly stable, A != B: Arnold's theorem on the normal form (kam).
    hanging = heavytop.Body(1.0, 1.2, 0.7, mass=1.0, length=-1.0, gravity=1.0)
    kam = heavytop.stability(hanging, 2.0).lyapunov
    assert (kam.verdict, kam.certificate, kam.energy_index) == ("stable", "kam", 2)
    nf = kam.normal_form
    assert isinstance(nf, heavytop.NormalForm) and nf.to_dict() == kam["normal_form"]
    w1, w2 = nf.frequencies
    assert abs(nf.D - (nf.c20 * w2 ** 2 + nf.c11 * w1 * w2 + nf.c02 * w1 ** 2)) < 1e-12 * abs(nf.D)
    assert nf.resonance is None and nf.a13 is None
    # E7's worked example (paper-notes): the printed digits.
    e7 = heavytop.stability(heavytop.Body(1.0, 1.5, 0.5, mass=1.0, length=1.0, gravity=1.0), 6.0).lyapunov.normal_form
    assert [round(x, 6) for x in (*e7.frequencies, e7.c20, e7.c11, e7.c02)] == [5.604869, 3.862483, 1.213458, -0.68126, 0.604105]
    assert round(e7.D, 4) == 22.3326
    assert heavytop.stability(top, 200.0).lyapunov.normal_form is None  # Chetaev: no normal form needed
    with pytest.raises(heavytop.InvalidInput, match="horizon"):
        heavytop.stability(top, 200.0, horizon=0.0)


def test_stability_over_an_array_of_spins_is_a_frame_of_the_scalar_answers():
    """Issue 45: stability(top, spin=array) answers each spin, one row each, as the scalar call does."""
    top = heavytop.example_toy_top()
    spins = np.array([100.0, 120.0, 134.0, 200.0])
    frame = heavytop.stability(top, spin=spins, theta0=0.05)
    assert list(frame.columns) == ["spin", "spin_rpm", "verdict", "proven", "max_tilt", "falls_at", "min_spin",
                                   "critical_spin"]
    assert list(frame.spin) == list(spins)
    for row, w in zip(frame.itertuples(), spins):
        one = heavytop.stability(top, spin=float(w), theta0=0.05)
        assert (row.verdict, row.proven) == (one.answer.verdict, one.answer.proven)
        assert row.max_tilt == one.answer.max_tilt
        assert row.critical_spin == one.models["linearized"].critical_spin
        assert (np.isnan(row.falls_at) and one.answer.falls_at is None) or row.falls_at == one.answer.falls_at
    # Above the critical spin 2 sqrt(A m g l) / C = 133.34 rad/s it stays up, proven; below, it falls
    # (100 rad/s) or nutates within 52 degrees for the 100 s computed (120 rad/s), not proven.
    assert list(frame.verdict) == ["falls", "stays up for the horizon", "stays up", "stays up"]
    assert list(frame.proven) == [True, False, True, True]
    rpm = heavytop.stability(top, spin_rpm=[1500.0, 2000.0], theta0=0.05)
    assert np.allclose(rpm.spin_rpm, [1500.0, 2000.0], rtol=1e-15) and np.allclose(rpm.spin * 30 / np.pi, rpm.spin_rpm)

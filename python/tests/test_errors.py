"""Bad input raises heavytop.InvalidInput, a ValueError whose message is the command line's
"<key>: <rule>" (the CLI prints "heavytop: error: <key>: <rule>" and exits 2), the key spelled
as Python spells it: the keyword argument's name where the CLI names its flag (rtol for --rtol,
t_end for --t-end), the configuration file's key for the body and the motion (body.A,
motion.spin) as the CLI does."""
import math
import pickle

import numpy as np
import pytest

import heavytop
from conftest import BODIES, body_options, cli_error, motion_options, needs_derive, run_cli

GOOD = dict(A=1.0, B=1.3, C=2.0, mass=1.0, length=1.0, gravity=1.0)


@pytest.mark.parametrize("key,value", [
    ("A", 0.0), ("B", -1.0), ("C", math.nan), ("mass", 0.0), ("mass", math.inf),
    ("gravity", -9.81), ("length", math.nan), ("C", 3.0), ("A", 4.0), ("B", 5.0),
])
def test_body_is_validated_as_the_cli_does(key, value):
    values = dict(GOOD, **{key: value})
    with pytest.raises(ValueError) as error:
        heavytop.Body(**values)
    assert isinstance(error.value, heavytop.InvalidInput)
    message = str(error.value)
    assert message.startswith("body.")
    assert message == f"{error.value.key}: {error.value.rule}"
    options = [f"--{k}={v!r}" for k, v in values.items()]
    assert message == cli_error("stability", *options, "--spin", "1")


def test_the_message_of_a_bad_mass():
    with pytest.raises(ValueError, match=r"^body\.mass: must be > 0$"):
        heavytop.Body(1, 1, 1, mass=0, length=1)


def test_body_is_immutable():
    body = BODIES["reference"]
    with pytest.raises(AttributeError):
        body.mass = 2.0
    assert body.mgR == body.mass * body.gravity * body.length
    assert body == heavytop.Body(**body.to_dict()) and hash(body) == hash(heavytop.Body(**body.to_dict()))
    assert pickle.loads(pickle.dumps(body)) == body


@pytest.mark.parametrize("kwargs,cli_args,key", [
    (dict(spin=math.nan), ["--spin", "nan"], "motion.spin"),
    (dict(theta0=math.inf), ["--theta0", "inf"], "motion.theta0"),
    (dict(samples=1), ["--samples", "1"], "samples"),
    (dict(samples=200_000_000), ["--samples", "200000000"], "samples"),
    (dict(t_end=0.0), ["--t-end", "0"], "t_end"),
    (dict(t_end=math.nan), ["--t-end", "nan"], "t_end"),
    (dict(rtol=-1.0), ["--rtol", "-1"], "rtol"),
    (dict(atol=0.0), ["--atol", "0"], "atol"),
    (dict(method="numeric"), ["--method", "numeric"], "method"),  # nonlinear has no method
    (dict(model="quadratic"), ["--model", "quadratic"], "model"),
    (dict(model="lagrange-exact"), ["--model", "lagrange-exact"], "body.B"),  # needs A = B
])
def test_simulate_refuses_bad_input_naming_the_key(kwargs, cli_args, key):
    body = BODIES["reference"]
    with pytest.raises(ValueError) as error:
        heavytop.simulate(body, **kwargs)
    assert error.value.key == key
    assert str(error.value).startswith(key + ": ")
    if kwargs.get("model") == "quadratic":  # the CLI's parser refuses it before the command runs
        return
    assert str(error.value) == cli_error("simulate", *body_options(body), *cli_args)


def test_method_must_be_analytic_or_numeric():
    with pytest.raises(ValueError, match=r"^method: must be analytic or numeric$"):
        heavytop.simulate(BODIES["reference"], "first-order", method="exact")


def test_stability_and_compare_refuse_bad_input():
    body = BODIES["reference"]
    with pytest.raises(ValueError, match=r"^motion\.spin: must be a finite number$"):
        heavytop.stability(body, math.nan)
    with pytest.raises(ValueError, match=r"^samples: must be an integer in \[3, 2000000\]$"):
        heavytop.compare(body, spin=1.0, theta0=0.01, samples=2)
    with pytest.raises(ValueError, match=r"^motion\.phi_rate0: "):
        heavytop.compare(body, spin=1.0, phi_rate0=math.nan)


@needs_derive
@pytest.mark.parametrize("kwargs,cli_args", [
    (dict(order=3), ["--order", "3"]),
    (dict(method="euler"), ["--method", "euler"]),
    (dict(sequence="psi-phi"), ["--sequence", "psi-phi"]),
])
def test_derive_refuses_bad_input_as_the_cli(kwargs, cli_args):
    with pytest.raises(ValueError) as error:
        heavytop.derive(**kwargs)
    assert str(error.value) == cli_error("derive", *cli_args, "--format", "json")
    with pytest.raises(ValueError, match=r"^order: must be 1 or 2$"):
        heavytop.derive_rotations(0)


def test_sweep_refuses_bad_input_naming_the_key():
    body = BODIES["reference"]
    values = np.linspace(0.5, 1.5, 3)
    cases = [
        (dict(vary={}), "vary: give 1 to 3 parameters"),
        (dict(vary={"A": values, "B": values, "C": values, "mass": values}), "vary: give 1 to 3 parameters"),
        (dict(vary={"D": values}), "vary: unknown key 'D'"),
        (dict(vary={"spin": []}), "vary: the values of 'spin' must be a 1-D array"),
        (dict(vary={"spin": np.ones((2, 2))}), "vary: the values of 'spin' must be a 1-D array"),
        (dict(vary={"spin": ["fast"]}), "vary: the values of 'spin' must be a 1-D array"),
        (dict(vary={"spin": [1.0, math.nan]}), "vary: at spin=nan the body breaks motion.spin: must be a finite number"),
        (dict(vary={"C/A": [1.0, 2.5]}), "vary: at C/A=2.5 the body breaks body.C: a real body has A + B >= C"),
        (dict(vary={"spin": values}, horizon=0.0, nonlinear=True), "horizon: must be finite and > 0"),
        (dict(vary={"spin": values}, nonlinear=True), "motion.theta0: a nonlinear sweep needs a tilted start"),
        (dict(vary={"spin": values}, theta0=0.6, nonlinear=True), "max_tilt: must exceed the initial tilt"),
    ]
    for kwargs, message in cases:
        with pytest.raises(ValueError) as error:
            heavytop.sweep(body, **kwargs)
        assert str(error.value).startswith(message), (kwargs, str(error.value))


def test_sweep_grid_errors_equal_the_cli():
    body = BODIES["reference"]
    with pytest.raises(ValueError) as error:
        heavytop.sweep(body, {"C/A": heavytop.grid_values(1.0, 3.0, 3)}, spin=1.0)
    assert str(error.value) == cli_error("sweep", *body_options(body), *motion_options(spin=1.0),
                                         "--vary", "C/A=1:3:3")

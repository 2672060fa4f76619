"""Shared helpers: the heavytop package and the command-line binary it is checked against.

Run by ctest (test `python`), which sets PYTHONPATH to the build tree's folder that holds the
package heavytop/ (build/python) and HEAVYTOP to the binary. By hand:
    PYTHONPATH=build/python HEAVYTOP=build/heavytop /usr/bin/python3 -m pytest python/tests
"""
import json
import os
import subprocess

import pytest

import heavytop

BODY_KEYS = ("A", "B", "C", "mass", "gravity", "length")
MOTION_KEYS = ("spin", "theta0", "phi0", "theta_rate0", "phi_rate0")

# Bodies of the examples (SI units): symmetric, asymmetric (erratum E3), hanging, flat, equal moments.
BODIES = {
    "toy-top": heavytop.example_toy_top(),
    "reference": heavytop.Body(1.0, 1.3, 2.0, mass=1.0, length=1.0, gravity=1.0),
    "asymmetric-plate": heavytop.Body(0.010, 0.015, 0.020, mass=1.0, length=1.0193679918450561e-3),
    "hanging": heavytop.Body(2e-3, 2e-3, 3e-3, mass=0.5, length=-0.1),
    "equal-moments": heavytop.Body(1.0, 1.0, 1.0, mass=1.0, length=1.0, gravity=1.0),
    "intermediate-C": heavytop.Body(1.0, 2.5, 1.5, mass=1.0, length=1.0, gravity=1.0),
}


needs_derive = pytest.mark.skipif(not heavytop.HAS_DERIVE, reason="built without HEAVYTOP_BUILD_SYMBOLIC")


def cli_binary():
    path = os.environ.get("HEAVYTOP")
    if not path:
        pytest.skip("HEAVYTOP (the heavytop binary) is not set; ctest sets it")
    return path


def body_options(body):
    """The command-line options that give `body` (repr: the shortest string that reads back exactly)."""
    args = []
    for key in BODY_KEYS:
        args += [f"--{key}", repr(float(getattr(body, key)))]
    return args


def motion_options(**motion):
    args = []
    for key in MOTION_KEYS:
        args += [f"--{key}", repr(float(motion.get(key, 0.0)))]
    return args


def run_cli(*args, check=True):
    """Runs the binary; returns its stdout (text). With check, a non-zero exit fails the test."""
    result = subprocess.run([cli_binary(), *args], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"heavytop {' '.join(args)} exited {result.returncode}: {result.stderr}")
    return result


def cli_json(*args):
    return json.loads(run_cli(*args, "--format", "json").stdout)


@pytest.fixture
def cli():
    cli_binary()
    return run_cli


# The command line's flags and the keyword arguments that are the same setting in Python.
PYTHON_NAME = {"--samples": "samples", "--t-end": "t_end", "--rtol": "rtol", "--atol": "atol",
               "--max-steps": "max_steps", "--method": "method", "--model": "model", "--integrator": "integrator",
               "--step": "step", "--order": "order", "--sequence": "sequence", "--vary": "vary",
               "--horizon": "horizon", "--max-tilt": "max_tilt", "--lifetime-horizon": "lifetime_horizon",
               "--tilt": "tilt", "--known-spin0": "spin0", "--map": "map", "--slice": "slice"}


def cli_error(*args):
    """The CLI's one-line message for `args`, its key in Python's spelling ("--t-end: ..." ->
    "t_end: ..."); the rest of the line unchanged."""
    result = run_cli(*args, check=False)
    assert result.returncode == 2, (args, result.returncode, result.stderr)
    # One error line, last; a warning the command gave first (on its own line) may precede it.
    lines = result.stderr.strip().splitlines()
    line = lines[-1]
    assert line.startswith("heavytop: error: "), result.stderr
    assert all(w.startswith("heavytop: warning: ") for w in lines[:-1]), result.stderr
    message = line[len("heavytop: error: "):]
    key, colon, rule = message.partition(": ")
    assert colon, message
    if key.startswith("--"):
        assert key in PYTHON_NAME, f"no Python name for the CLI's {key}"
        key = PYTHON_NAME[key]
    return f"{key}: {rule}"

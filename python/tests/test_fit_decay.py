"""heavytop.fit_decay: the command line's fit-decay in Python (same JSON, typed), a noiseless
curve recovered, and bad input named."""
import json
import math
import os

import numpy as np
import pytest

import heavytop
from conftest import run_cli

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "spin-decay.csv")


def law(C, axial, friction, spin0, t):
    """C w' = -d_a w - tau0 (w > 0), then 0: the closed form, written out independently here."""
    if axial == 0.0:
        return np.maximum(spin0 - friction * t / C, 0.0)
    offset = friction / axial
    return np.maximum((spin0 + offset) * np.exp(-axial * t / C) - offset, 0.0)


def test_same_as_the_cli_on_the_example():
    rows = [line.split(",") for line in open(EXAMPLE) if not line.startswith("#")]
    assert rows[0] == ["t", "spin\n"]
    t, spin = np.array(rows[1:], dtype=float).T
    fit = heavytop.fit_decay(t, spin)
    cli = json.loads(run_cli("fit-decay", "--data", EXAMPLE, "--format", "json").stdout)
    assert fit.to_dict() == cli
    assert isinstance(fit, heavytop.DecayFit) and isinstance(fit.axial, heavytop.FittedParameter)
    assert fit.axial.value == cli["axial"]["value"] and fit.friction.uncertainty == cli["friction"]["uncertainty"]
    assert fit.points == 56 and fit.converged and fit.C == heavytop.example_toy_top().C


def test_recovers_a_noiseless_curve():
    top = heavytop.Body(2e-3, 2e-3, 3e-3, mass=0.5, length=0.05)
    t = np.linspace(0.0, 40.0, 81)
    spin = law(top.C, 1e-4, 2e-3, 50.0, t)  # stops at C/d_a ln(1 + d_a w0 / tau0) = 30 ln 3.5 = 37.6 s
    fit = heavytop.fit_decay(t, spin, top)
    assert math.isclose(fit.axial.value, 1e-4, rel_tol=1e-8)
    assert math.isclose(fit.friction.value, 2e-3, rel_tol=1e-8)
    assert math.isclose(fit.spin0.value, 50.0, rel_tol=1e-8)
    assert math.isclose(fit.stop_time, 30.0 * math.log(3.5), rel_tol=1e-8)
    known = heavytop.fit_decay(t, spin, top, spin0=50.0)
    assert not known.spin0.fitted and known.spin0.uncertainty == 0.0
    assert math.isclose(known.axial.value, 1e-4, rel_tol=1e-8)


def test_bad_input_names_the_key():
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.fit_decay([0.0, 2.0, 1.0, 3.0], [4.0, 3.0, 2.0, 1.0])
    assert str(e.value) == "data: point 2: t must be >= 0 and non-decreasing" and e.value.key == "data"
    with pytest.raises(heavytop.InvalidInput, match=r"^data: needs at least 4 points"):
        heavytop.fit_decay([0.0, 1.0, 2.0], [3.0, 2.0, 1.0])
    with pytest.raises(heavytop.InvalidInput, match=r"^spin0: must be a finite number > 0"):
        heavytop.fit_decay([0.0, 1.0, 2.0], [3.0, 2.0, 1.0], spin0=-1.0)

"""Damping, friction and the lifetime (SPEC sections 6 and 8) from Python: the same numbers
as the command line, the body's damping carried through pickling and equality."""
import math
import pickle

import pytest

import heavytop
from conftest import body_options, cli_json, motion_options

TOP = heavytop.example_toy_top()


def damped_top(**damping):
    return heavytop.Body(TOP.A, TOP.B, TOP.C, TOP.mass, TOP.length, TOP.gravity, **damping)


def damping_options(body):
    return ["--transverse-damping", repr(body.transverse_damping), "--axial-damping", repr(body.axial_damping),
            "--friction", repr(body.friction), "--driven", "true" if body.driven else "false"]


def test_the_body_carries_its_damping():
    body = damped_top(transverse_damping=1e-6, axial_damping=2e-7, friction=1e-6, driven=True)
    assert (body.transverse_damping, body.axial_damping, body.friction, body.driven) == (1e-6, 2e-7, 1e-6, True)
    assert pickle.loads(pickle.dumps(body)) == body and body != TOP and hash(body) != hash(TOP)
    assert "axial_damping=2e-07" in repr(body) and "driven=True" in repr(body)
    with pytest.raises(heavytop.InvalidInput, match="damping.axial: must be >= 0"):
        damped_top(axial_damping=-1.0)


def test_damped_stability_is_the_cli_s():
    body = damped_top(transverse_damping=1e-6)
    result = heavytop.stability(body, 200.0)
    expected = cli_json("stability", *body_options(body), *damping_options(body), *motion_options(spin=200.0))
    assert result.to_dict() == expected
    linearized = result.models["linearized"]
    assert not linearized.stable and linearized.growth_rate > 0 and linearized.critical_spin is None
    assert linearized.growth_rate == max(z.real for z in linearized.eigenvalues)


def test_lifetime_is_the_cli_s_and_the_law_s():
    body = damped_top(axial_damping=2e-7)
    life = heavytop.lifetime(body, spin=200.0, theta0=0.01)
    expected = cli_json("lifetime", *body_options(body), *damping_options(body), *motion_options(spin=200.0, theta0=0.01))
    assert life.to_dict() == expected
    assert isinstance(life, heavytop.Lifetime)
    t = TOP.C / 2e-7 * math.log(200.0 / life.critical_spin)
    assert life.time_to_critical == pytest.approx(t, rel=1e-12)
    assert life.fall_time > life.time_to_critical and life.fall_spin < life.critical_spin
    with pytest.raises(heavytop.InvalidInput, match="max_tilt: must be in"):
        heavytop.lifetime(body, spin=200.0, max_tilt=0.0)


def test_a_damped_simulation_balances_its_energy():
    body = damped_top(transverse_damping=1e-7, axial_damping=2e-7)
    m = heavytop.simulate(body, "nonlinear", spin=200.0, theta0=0.05, t_end=10.0, samples=11)
    scale = m["energy"][0]
    assert max(abs(e + w) for e, w in zip(m["energy_drift"], m["dissipated_work"])) < 1e-10 * scale
    assert m["dissipated_work"][-1] > 1e-3 * scale

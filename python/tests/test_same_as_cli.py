"""stability(), compare() and derive*() return exactly what the command line prints as JSON."""
import pytest

import heavytop
from conftest import BODIES, body_options, cli_json, motion_options, needs_derive


@pytest.mark.parametrize("name", sorted(BODIES))
@pytest.mark.parametrize("spin", [0.0, 1.3, 1.4142135623730951, 2.5, 200.0])
def test_stability_equals_cli(name, spin):
    body = BODIES[name]
    expected = cli_json("stability", *body_options(body), *motion_options(spin=spin))
    assert heavytop.stability(body, spin) == expected


def test_stability_at_the_papers_threshold_equals_cli():
    # On the boundary of (9): a Jordan block, unstable (erratum E2).
    body = BODIES["reference"]
    spin = heavytop.stability(body, 0.0)["models"]["first-order"]["critical_spin"]
    result = heavytop.stability(body, spin)
    assert result == cli_json("stability", *body_options(body), *motion_options(spin=spin))
    assert result["models"]["first-order"]["stable"] is False


@pytest.mark.parametrize("name,motion", [
    ("toy-top", dict(spin=200.0, theta0=0.05)),
    ("reference", dict(spin=3.0, theta0=0.01, phi0=-0.02, theta_rate0=0.03, phi_rate0=0.04)),
    ("asymmetric-plate", dict(spin=1.3, theta0=1e-4)),
])
def test_compare_equals_cli(name, motion):
    body = BODIES[name]
    expected = cli_json("compare", *body_options(body), *motion_options(**motion),
                        "--t-end", "2", "--samples", "2001")
    result = heavytop.compare(body, **motion, t_end=2.0, samples=2001)
    assert result == expected
    assert ("lagrange-exact" in result["models"]) == (body.A == body.B)


def test_compare_tolerances_equal_cli():
    body = BODIES["toy-top"]
    expected = cli_json("compare", *body_options(body), *motion_options(spin=200.0, theta0=0.05),
                        "--t-end", "0.5", "--samples", "501", "--rtol", "1e-8", "--atol", "1e-9")
    assert heavytop.compare(body, spin=200.0, theta0=0.05, t_end=0.5, samples=501, rtol=1e-8, atol=1e-9) == expected


@needs_derive
@pytest.mark.parametrize("method", ["euler-moving", "euler-fixed", "euler-body", "lagrange"])
@pytest.mark.parametrize("sequence", ["phi-theta", "theta-phi"])
@pytest.mark.parametrize("order", [1, 2])
def test_derive_equals_cli(method, sequence, order):
    expected = cli_json("derive", "--method", method, "--sequence", sequence, "--order", str(order))
    result = heavytop.derive(method, sequence, order)
    assert result == expected
    assert list(result) == ["M", "G", "K", "characteristic_polynomial", "stability_condition"]


@needs_derive
def test_derive_defaults_are_the_papers_model_4():
    assert heavytop.derive() == cli_json("derive")
    assert heavytop.derive()["stability_condition"] == "omega0^2 > (sqrt(A)+sqrt(B))^2*m*g*R/C^2"


@needs_derive
@pytest.mark.parametrize("order", [1, 2])
def test_derive_rotations_equals_cli(order):
    result = heavytop.derive_rotations(order)
    assert result == cli_json("derive", "--rotations", "--order", str(order))
    assert list(result) == ["A1", "A2", "A3", "A1A2", "A2A1", "commutator"]


@needs_derive
def test_derive_check_equals_cli():
    result = heavytop.derive_check()
    assert result == cli_json("derive", "--check")
    assert result["all_as_expected"] is True
    assert heavytop.derive_check(2) == cli_json("derive", "--check", "--order", "2")

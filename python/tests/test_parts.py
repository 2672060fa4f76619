"""Real bodies from Python (SPEC sections 9, 10): the parts make the body `heavytop body` makes,
rpm is the command line's --spin-rpm, precession() is `heavytop precession`."""
import math

import pytest

import heavytop
from conftest import body_options, cli_json

PARTS = [
    {"shape": "cone", "radius": 0.02, "height": 0.02, "density": 700.0},
    {"shape": "cylinder", "radius": 0.02, "height": 0.005, "z0": 0.02, "density": 700.0},
    {"shape": "tube", "radius": 0.003, "inner_radius": 0.001, "height": 0.03, "z0": 0.025, "mass": 0.002},
    {"shape": "sphere", "radius": 0.004, "z0": 0.055, "mass": 0.003},
    {"shape": "cone", "apex": "up", "radius": 0.01, "height": 0.004, "z0": -0.004, "density": 7800},
]


def toml_of(parts):
    lines = []
    for p in parts:
        lines.append("[[body.part]]")
        lines += [f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"' for k, v in p.items()]
    return "\n".join(lines) + "\n"


def test_parts_make_the_body_the_command_line_makes(tmp_path):
    config = tmp_path / "top.toml"
    config.write_text(toml_of(PARTS))
    assert heavytop.body_report(PARTS) == cli_json("body", "--config", str(config))
    body = heavytop.body_from_parts(PARTS)
    report = heavytop.body_report(PARTS)
    assert (body.A, body.B, body.C, body.mass, body.length) == tuple(report[k] for k in ("A", "B", "C", "mass", "length"))
    # The cone's closed form: C = 3 m a^2 / 10, its tip at O, its centroid 3 h / 4 above it.
    cone = heavytop.body_from_parts(PARTS[:1])
    m = 700.0 * math.pi * 0.02 ** 2 * 0.02 / 3
    assert cone.mass == pytest.approx(m, rel=1e-14)
    assert cone.C == pytest.approx(0.3 * m * 0.02 ** 2, rel=1e-14)
    assert cone.length == pytest.approx(0.015, rel=1e-14)


def test_bad_parts_name_the_key():
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.body_from_parts([{"shape": "cone", "radius": -1.0, "height": 0.02, "density": 700.0}])
    assert e.value.key == "body.part[0].radius (cone)" and "> 0" in e.value.rule
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.body_from_parts([{"shape": "cylinder", "radius": 1.0, "height": 1.0, "density": 1.0, "mass": 1.0}])
    assert e.value.key == "body.part[0].mass (cylinder)"
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.body_from_parts([{"shape": "pyramid"}])
    assert e.value.key == "body.part[0].shape"
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.body_from_parts([{"shape": "sphere", "radius": 1.0, "density": [1]}])
    assert e.value.key == "body.part[0].density"


def test_rpm_is_the_command_lines():
    top = heavytop.example_toy_top()
    assert heavytop.rpm(3000.0) == pytest.approx(100 * math.pi, rel=1e-15)
    by_rpm = heavytop.stability(top, spin_rpm=3000.0).to_dict()
    assert by_rpm == heavytop.stability(top, heavytop.rpm(3000.0)).to_dict()
    assert by_rpm == cli_json("stability", *body_options(top), "--theta0", "0", "--spin-rpm", "3000")
    a = heavytop.simulate(top, "first-order", spin_rpm=2000.0, theta0=0.05, t_end=0.1, samples=11)
    b = heavytop.simulate(top, "first-order", spin=heavytop.rpm(2000.0), theta0=0.05, t_end=0.1, samples=11)
    assert (a.theta == b.theta).all()
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.stability(top, 1.0, spin_rpm=2.0)
    assert e.value.key == "spin_rpm"


def test_precession_is_the_command_lines():
    top = heavytop.example_toy_top()
    result = heavytop.precession(top, 0.3, 200.0)
    assert result == cli_json("precession", *body_options(top), "--tilt", "0.3", "--spin", "200")
    slow = result["steady_precession"]["slow"]
    # The slow rate solves A cos(theta) W^2 - C w3 W + m g R = 0.
    W = slow["rate"]
    assert top.A * math.cos(0.3) * W * W - top.C * 200.0 * W + top.mgR == pytest.approx(0.0, abs=1e-15)
    assert slow["state"]["phi_rate0"] == pytest.approx(-W * math.sin(0.3), rel=1e-15)

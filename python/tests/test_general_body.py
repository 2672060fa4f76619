"""SPEC section 11's general body from Python: Body(..., offset_x=, Ixy=, ...), parts off the axis,
load() of a file with the general keys; simulate(model="nonlinear") equals the CLI's CSV, and the
analyses that cannot take it refuse it."""
import io
import pickle

import numpy as np
import pytest

import heavytop
from conftest import run_cli

GENERAL = dict(offset_x=0.002, offset_y=-0.001, Ixy=1e-6, Ixz=-2e-6, Iyz=5e-7)
BODY_TOML = "[body]\nA = 4.35e-5\nB = 4.5e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n"
MOTION = dict(spin=200.0, theta0=0.05)


def general_toml():
    return BODY_TOML + "".join(f"{k} = {v!r}\n" for k, v in GENERAL.items()) + "[motion]\nspin = 200.0\ntheta0 = 0.05\n"


def csv_columns(text):
    header = text.splitlines()[0].split(",")
    data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def test_the_body_carries_the_general_terms():
    body = heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025, **GENERAL)
    assert body.general and (body.offset_x, body.offset_y, body.Ixy, body.Ixz, body.Iyz) == tuple(GENERAL.values())
    assert pickle.loads(pickle.dumps(body)) == body and body != heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025)
    assert "offset_x=0.002" in repr(body) and "Iyz=5e-07" in repr(body)
    assert body.to_dict()["Ixz"] == -2e-6
    assert not heavytop.example_toy_top().general and "Ixy" not in heavytop.example_toy_top().to_dict()
    with pytest.raises(heavytop.InvalidInput, match="^body.Ixy"):
        heavytop.Body(1.0, 1.0, 1.0, 1.0, 1.0, Ixy=5.0)  # not positive definite


def test_simulate_nonlinear_on_a_general_body_is_the_cli_s(tmp_path):
    path = tmp_path / "general.toml"
    path.write_text(general_toml())
    config = heavytop.load(path)
    body = heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025, **GENERAL)
    assert config.body == body
    result = heavytop.simulate(body, "nonlinear", **MOTION, t_end=0.5, samples=51)
    expected = csv_columns(run_cli("simulate", "--config", str(path), "--model", "nonlinear", "--t-end", "0.5",
                                   "--samples", "51", "--format", "csv").stdout)
    assert list(result) == list(expected)
    for name, column in expected.items():
        np.testing.assert_array_equal(result[name] + 0.0, column, err_msg=name)
    # The general terms matter: the ordinary body with the same moments moves otherwise.
    plain = heavytop.simulate(heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025), "nonlinear", **MOTION, t_end=0.5,
                              samples=51)
    assert np.max(np.abs(plain.tilt - result.tilt)) > 1e-3


def test_other_analyses_refuse_a_general_body():
    body = heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025, **GENERAL)
    for call in (lambda: heavytop.stability(body, 200.0), lambda: heavytop.simulate(body, "linearized", spin=200.0),
                 lambda: heavytop.lifetime(body, spin=200.0), lambda: heavytop.precession(body, 0.3, 200.0)):
        with pytest.raises(heavytop.InvalidInput, match="general body"):
            call()


def cube_stl(path, lo, hi):
    """An ASCII STL of the box [lo, hi] (m), outward normals."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    lines = ["solid box"]
    for a, b, c, d in quads:
        for tri in ((a, b, c), (a, c, d)):
            lines.append(" facet normal 0 0 0\n  outer loop")
            lines += [f"   vertex {v[i][0]!r} {v[i][1]!r} {v[i][2]!r}" for i in tri]
            lines.append("  endloop\n endfacet")
    lines.append("endsolid box")
    path.write_text("\n".join(lines) + "\n")


def test_parts_off_the_axis_make_the_cli_s_general_body(tmp_path):
    # A disc on the axis and a small steel block off it (a mesh: the solids of revolution stay on z).
    cube_stl(tmp_path / "block.stl", (0.008, -0.002, 0.02), (0.012, 0.002, 0.024))
    parts = [{"shape": "cylinder", "radius": 0.02, "height": 0.005, "z0": 0.02, "density": 700.0},
             {"shape": "mesh", "file": "block.stl", "units": "m", "density": 7800.0}]
    report = heavytop.body_report(parts, folder=str(tmp_path))
    assert report.general and report["offset"]["x"] > 1e-4
    body = heavytop.body_from_parts(parts, folder=str(tmp_path))
    assert body.general and body.offset_x == report["offset"]["x"] and body.Ixz == report["products"]["xz"]
    toml = "".join("[[body.part]]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in p.items())
                   for p in parts) + "[motion]\nspin = 200.0\ntheta0 = 0.05\n"
    path = tmp_path / "parts.toml"
    path.write_text(toml)
    assert heavytop.load(path).body == body
    result = heavytop.simulate(body, "nonlinear", **MOTION, t_end=0.2, samples=21)
    expected = csv_columns(run_cli("simulate", "--config", str(path), "--model", "nonlinear", "--t-end", "0.2",
                                   "--samples", "21", "--format", "csv").stdout)
    for name, column in expected.items():
        np.testing.assert_array_equal(result[name] + 0.0, column, err_msg=name)

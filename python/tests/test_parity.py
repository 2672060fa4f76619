"""Every command of `heavytop --help` has its Python function, and for the same input the Python
result is the command line's output: to_dict() equals json.loads of `--format json` (the CSV
for trajectories and maps, the same bytes for the report's folder and the explorer's page), on
two bodies given to the command line by one configuration file each:

  DAMPED   the toy top with every damping term (SPEC section 6) and a tilted start;
  GENERAL  SPEC section 11's general body: its centre of mass off the axis and products of
           inertia (only `simulate --model nonlinear` and `body` take it; every other command
           refuses it, and Python refuses it with the same one-line message).

The same bad input gives the same one-line message ("<key>: <rule>", the CLI's flag spelt as
Python's keyword: --t-end is t_end). Fast: short horizons, few samples."""
import io
import json
import os
import re

import numpy as np
import pytest

import heavytop
from conftest import cli_error, run_cli

TOP = heavytop.example_toy_top()
DAMPING = dict(transverse_damping=2e-7, axial_damping=1e-7, friction=5e-7)
DAMPED = heavytop.Body(TOP.A, TOP.B, TOP.C, TOP.mass, TOP.length, TOP.gravity, **DAMPING)
GENERAL_TERMS = dict(offset_x=0.002, offset_y=-0.001, Ixy=1e-6, Ixz=-2e-6, Iyz=5e-7)
GENERAL = heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, mass=0.06, length=0.025, **GENERAL_TERMS)
MOTION = dict(spin=150.0, theta0=0.05, phi0=-0.02, theta_rate0=0.1, phi_rate0=-0.3)
BODIES = {"damped": DAMPED, "general": GENERAL}

# Every command of the command line and the test(s) below that hold Python to it. derive has no
# body: test_same_as_cli.py holds derive(), derive_rotations() and derive_check() to it.
COVERED = {"stability", "simulate", "compare", "sweep", "report", "body", "precession", "lifetime", "fit-decay",
           "explore", "derive", "chaos"}


def config(tmp_path, body, motion=MOTION, name=None):
    """The configuration file that gives `body` and `motion` to the command line (SPEC sections
    4, 6, 11): every key Python's Body holds, written as repr() (the shortest exact decimal)."""
    lines = ["[body]"] + [f"{k} = {float(getattr(body, k))!r}" for k in ("A", "B", "C", "mass", "gravity", "length")]
    lines += [f"{k} = {float(getattr(body, k))!r}" for k in GENERAL_TERMS if getattr(body, k)]
    lines += ["[damping]"] + [f"{k} = {float(getattr(body, f'{k}_damping' if k != 'friction' else k))!r}"
                              for k in ("transverse", "axial", "friction")]
    lines += ["[motion]"] + [f"{k} = {float(v)!r}" for k, v in motion.items()]
    if body.driven:
        lines.append("driven = true")
    path = tmp_path / (name or f"body-{abs(hash(body))}.toml")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def cli_json(*args):
    return json.loads(run_cli(*args, "--format", "json").stdout)


def csv_columns(text):
    header = text.splitlines()[0].split(",")
    data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def same_message(call, *cli_args):
    """The Python call raises InvalidInput with the CLI's one-line message for cli_args."""
    with pytest.raises(heavytop.InvalidInput) as error:
        call()
    assert str(error.value) == cli_error(*cli_args)
    return str(error.value)


def test_every_command_is_covered():
    help_text = run_cli("--help").stdout
    commands = set(re.findall(r"^  ([a-z][a-z-]+)\s", help_text.split("Subcommands:")[1], re.M))
    assert "stability" in commands and "explore" in commands, help_text
    assert commands == COVERED, commands ^ COVERED


# ---- stability -----------------------------------------------------------------------------------

def test_stability_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    assert heavytop.stability(DAMPED, **MOTION) == cli_json("stability", "--config", path)
    options = ["--horizon", "3", "--max-tilt", "0.5", "--lifetime-horizon", "4"]
    result = heavytop.stability(DAMPED, **MOTION, horizon=3.0, max_tilt=0.5, lifetime_horizon=4.0)
    assert result == cli_json("stability", "--config", path, *options)
    assert result.answer.horizon == 4.0  # a damped body is followed over the lifetime's horizon


def test_stability_refuses_as_the_cli(tmp_path):
    path = config(tmp_path, DAMPED)
    same_message(lambda: heavytop.stability(DAMPED, **MOTION, horizon=0.0), "stability", "--config", path, "--horizon", "0")
    same_message(lambda: heavytop.stability(DAMPED, **MOTION, max_tilt=4.0), "stability", "--config", path, "--max-tilt", "4")
    same_message(lambda: heavytop.stability(DAMPED, **MOTION, lifetime_horizon=-1.0), "stability", "--config", path,
                 "--lifetime-horizon", "-1")
    same_message(lambda: heavytop.stability(GENERAL, **MOTION), "stability", "--config", config(tmp_path, GENERAL))


# ---- simulate ------------------------------------------------------------------------------------

@pytest.mark.parametrize("model", ["first-order", "body-fixed", "linearized", "nonlinear", "lagrange-exact"])
def test_simulate_damped(tmp_path, model):
    path = config(tmp_path, DAMPED)
    options = ["--model", model, "--t-end", "0.5", "--samples", "101"]
    if model == "lagrange-exact":  # the conservative top's closed form: refused, in the same words
        message = same_message(lambda: heavytop.simulate(DAMPED, model, **MOTION, t_end=0.5, samples=101),
                               "simulate", "--config", path, *options)
        assert message.startswith("model: lagrange-exact is the conservative symmetric top")
        return
    mine = heavytop.simulate(DAMPED, model, **MOTION, t_end=0.5, samples=101)
    csv = csv_columns(run_cli("simulate", "--config", path, *options).stdout)
    assert list(mine) == list(csv)
    for name in csv:
        np.testing.assert_array_equal(mine[name], csv[name], err_msg=name)
    as_json = cli_json("simulate", "--config", path, *options)
    assert as_json["columns"] == list(mine.columns)
    for name in mine.columns:
        assert as_json[name] == mine[name].tolist(), name
    if model == "nonlinear":  # damping's columns: the work the torques took out
        assert {"dissipated_work", "vertical_momentum_loss", "axial_momentum_loss"} <= set(mine.columns)
        summary = as_json["summary"]
        for key in ("steps", "rejected_steps", "rhs_evaluations"):
            assert getattr(mine.summary, key) == summary[key], key


def test_simulate_general(tmp_path):
    path = config(tmp_path, GENERAL)
    mine = heavytop.simulate(GENERAL, "nonlinear", **MOTION, t_end=0.5, samples=101)
    csv = csv_columns(run_cli("simulate", "--config", path, "--t-end", "0.5", "--samples", "101").stdout)
    assert list(mine) == list(csv)
    for name in csv:
        np.testing.assert_array_equal(mine[name], csv[name], err_msg=name)
    for model in ("first-order", "body-fixed", "linearized"):
        same_message(lambda: heavytop.simulate(GENERAL, model, **MOTION), "simulate", "--config", path, "--model", model)


def test_simulate_refuses_as_the_cli(tmp_path):
    path = config(tmp_path, DAMPED)
    same_message(lambda: heavytop.simulate(DAMPED, **MOTION, t_end=-1.0), "simulate", "--config", path, "--t-end", "-1")
    same_message(lambda: heavytop.simulate(DAMPED, **MOTION, samples=1), "simulate", "--config", path, "--samples", "1")
    same_message(lambda: heavytop.simulate(DAMPED, **MOTION, integrator="splitting"), "simulate", "--config", path,
                 "--integrator", "splitting")


# ---- compare -------------------------------------------------------------------------------------

def test_compare_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    mine = heavytop.compare(DAMPED, **MOTION, t_end=0.5, samples=501)
    assert mine == cli_json("compare", "--config", path, "--t-end", "0.5", "--samples", "501")
    same_message(lambda: heavytop.compare(DAMPED, **MOTION, samples=2), "compare", "--config", path, "--samples", "2")
    same_message(lambda: heavytop.compare(GENERAL, **MOTION), "compare", "--config", config(tmp_path, GENERAL))


# ---- precession ----------------------------------------------------------------------------------

def test_precession_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    with pytest.warns(UserWarning) as warned:
        mine = heavytop.precession(DAMPED, 0.3, MOTION["spin"])
    result = run_cli("precession", "--config", path, "--tilt", "0.3", "--format", "json")
    assert mine == json.loads(result.stdout)
    # The command line's warning, word for word: its steady motions are the conservative body's.
    assert [f"heavytop: warning: {w.message}" for w in warned] == result.stderr.strip().splitlines()
    with pytest.warns(UserWarning):  # as the command line, which warns, then refuses the tilt
        same_message(lambda: heavytop.precession(DAMPED, 4.0, MOTION["spin"]), "precession", "--config", path,
                     "--tilt", "4")
    same_message(lambda: heavytop.precession(GENERAL, 0.3, MOTION["spin"]), "precession", "--config",
                 config(tmp_path, GENERAL), "--tilt", "0.3")


# ---- body ----------------------------------------------------------------------------------------

PARTS_OFF_AXIS = [
    dict(shape="cylinder", radius=0.02, height=0.004, z0=0.02, density=7800.0),
    dict(shape="mesh", file="block.stl", density=2700.0),
]


def cube_stl(path, lo, hi):
    """An ASCII STL of the box lo..hi (m): off the axis, it makes the body general."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    faces = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4), (2, 6, 3), (3, 6, 7),
             (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    text = ["solid block"]
    for a, b, c in faces:
        text += ["facet normal 0 0 0", "outer loop"] + [f"vertex {v[i][0]!r} {v[i][1]!r} {v[i][2]!r}" for i in (a, b, c)]
        text += ["endloop", "endfacet"]
    path.write_text("\n".join(text + ["endsolid block"]) + "\n")


def test_body_general(tmp_path):
    # Parts off the axis: body_report is `heavytop body` of the same [[body.part]] tables.
    cube_stl(tmp_path / "block.stl", (0.005, -0.004, 0.02), (0.012, 0.004, 0.03))
    toml = []
    for part in PARTS_OFF_AXIS:
        toml.append("[[body.part]]")
        toml += [f"{k} = {json.dumps(v) if isinstance(v, str) else repr(v)}" for k, v in part.items()]
    (tmp_path / "parts.toml").write_text("\n".join(toml) + "\n")
    mine = heavytop.body_report(PARTS_OFF_AXIS, folder=str(tmp_path))
    assert mine == cli_json("body", "--config", str(tmp_path / "parts.toml"))
    assert mine.general
    # A body given by its keys (the general ones too): body_report(Body) is `heavytop body --config`.
    assert heavytop.body_report(GENERAL) == cli_json("body", "--config", config(tmp_path, GENERAL))
    assert heavytop.body_report(DAMPED) == cli_json("body", *body_keys(DAMPED))


def body_keys(body):
    return [arg for k in ("A", "B", "C", "mass", "gravity", "length") for arg in (f"--{k}", repr(float(getattr(body, k))))]


def test_body_refuses_as_the_cli(tmp_path):
    bad = [dict(shape="cone", radius=-0.02, height=0.02, density=700.0)]
    (tmp_path / "bad.toml").write_text("[[body.part]]\nshape = \"cone\"\nradius = -0.02\nheight = 0.02\ndensity = 700.0\n")
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.body_report(bad)
    assert str(error.value) == cli_error("body", "--config", str(tmp_path / "bad.toml")).replace(
        f" in {tmp_path / 'bad.toml'}", "")


# ---- lifetime ------------------------------------------------------------------------------------

def test_lifetime_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    mine = heavytop.lifetime(DAMPED, **MOTION, horizon=5.0, max_tilt=0.8)
    assert mine == cli_json("lifetime", "--config", path, "--horizon", "5", "--max-tilt", "0.8")
    same_message(lambda: heavytop.lifetime(DAMPED, **MOTION, max_tilt=4.0), "lifetime", "--config", path, "--max-tilt", "4")
    same_message(lambda: heavytop.lifetime(DAMPED, **MOTION, horizon=0.0), "lifetime", "--config", path, "--horizon", "0")
    same_message(lambda: heavytop.lifetime(GENERAL, **MOTION), "lifetime", "--config", config(tmp_path, GENERAL))


# ---- fit-decay -----------------------------------------------------------------------------------

def test_fit_decay_damped(tmp_path):
    # The damped top's own spin decay (its nonlinear run: w.k = axial_momentum / C), fitted back.
    run = heavytop.simulate(DAMPED, "nonlinear", spin=150.0, t_end=20.0, samples=41)
    spin = run.axial_momentum / DAMPED.C
    data = tmp_path / "decay.csv"
    data.write_text("t,spin\n" + "".join(f"{t!r},{w!r}\n" for t, w in zip(run.t, spin)))
    path = config(tmp_path, DAMPED)
    mine = heavytop.fit_decay(run.t, spin, DAMPED)
    assert mine == cli_json("fit-decay", "--config", path, "--data", str(data))
    np.testing.assert_allclose([mine.axial.value, mine.friction.value], [DAMPED.axial_damping, DAMPED.friction], rtol=1e-6)
    known = heavytop.fit_decay(run.t, spin, DAMPED, spin0=150.0)
    assert known == cli_json("fit-decay", "--config", path, "--data", str(data), "--known-spin0", "150")
    same_message(lambda: heavytop.fit_decay(run.t, spin, DAMPED, spin0=-1.0), "fit-decay", "--config", path, "--data",
                 str(data), "--known-spin0", "-1")
    same_message(lambda: heavytop.fit_decay(run.t, spin, GENERAL), "fit-decay", "--config", config(tmp_path, GENERAL),
                 "--data", str(data))


# ---- sweep ---------------------------------------------------------------------------------------

def test_sweep_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    vary = {"spin": heavytop.grid_values(20.0, 300.0, 8), "B/A": heavytop.grid_values(0.8, 1.2, 3)}
    mine = heavytop.sweep(DAMPED, vary, **MOTION)
    csv = run_cli("sweep", "--config", path, "--vary", "spin=20:300:8", "--vary", "B/A=0.8:1.2:3").stdout
    header = csv.splitlines()[0].split(",")
    assert list(mine) == header
    rows = [line.split(",") for line in csv.splitlines()[1:]]
    for i, name in enumerate(header):
        column = [row[i] for row in rows]
        if mine[name].dtype == bool:
            assert mine[name].tolist() == [c == "1" for c in column], name
        elif mine[name].dtype.kind == "f":
            assert mine[name].tolist() == [float(c) for c in column], name
        else:
            assert mine[name].tolist() == column, name
    same_message(lambda: heavytop.sweep(DAMPED, {"D": [1.0]}, **MOTION), "sweep", "--config", path, "--vary", "D=1:2:2")
    same_message(lambda: heavytop.sweep(GENERAL, {"spin": heavytop.grid_values(1.0, 2.0, 2)}, **MOTION), "sweep",
                 "--config", config(tmp_path, GENERAL), "--vary", "spin=1:2:2")


# ---- report --------------------------------------------------------------------------------------

def files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, names in os.walk(folder) for f in names)


def test_report_damped(tmp_path):
    path = config(tmp_path, DAMPED, name="damped.toml")
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    heavytop.report(heavytop.load(path), mine, t_end=1.0)
    run_cli("report", "--config", path, "--t-end", "1", "--output", str(theirs))
    assert files(mine) == files(theirs) and "lifetime.json" in files(mine)
    for name in files(mine):
        if name.endswith((".json", ".csv", ".html", ".js")):
            assert (mine / name).read_bytes() == (theirs / name).read_bytes(), name
    same_message(lambda: heavytop.report(DAMPED, tmp_path / "r", **MOTION, t_end=0.0), "report", "--config", path,
                 "--t-end", "0", "--output", str(tmp_path / "r2"))
    same_message(lambda: heavytop.report(GENERAL, tmp_path / "r", **MOTION), "report", "--config",
                 config(tmp_path, GENERAL), "--output", str(tmp_path / "r3"))
    assert not (tmp_path / "r").exists() and not (tmp_path / "r2").exists()


# ---- explore -------------------------------------------------------------------------------------

def test_explore_damped(tmp_path):
    path = config(tmp_path, DAMPED)
    theirs = tmp_path / "cli.html"
    result = run_cli("explore", "--config", path, "--output", str(theirs), check=False)
    if result.returncode == 2:  # built without the page: the same message, no file
        same_message(lambda: heavytop.explore(DAMPED, tmp_path / "py.html", **MOTION), "explore", "--config", path,
                     "--output", str(theirs))
        assert not (tmp_path / "py.html").exists()
        pytest.skip("this build has no explorer page (Emscripten): " + result.stderr.strip())
    assert result.returncode == 0, result.stderr
    mine = heavytop.explore(DAMPED, tmp_path / "py.html", **MOTION)
    assert mine == str(tmp_path / "py.html")
    assert (tmp_path / "py.html").read_bytes() == theirs.read_bytes()
    same_message(lambda: heavytop.explore(GENERAL, tmp_path / "g.html", **MOTION), "explore", "--config",
                 config(tmp_path, GENERAL), "--output", str(tmp_path / "g2.html"))
    assert not (tmp_path / "g.html").exists()


# ---- chaos (SPEC 17) ---------------------------------------------------------------------------------

def test_chaos_is_the_cli_s(tmp_path):
    """heavytop.chaos() is json.loads of `heavytop chaos --format json`, its section's too."""
    top = heavytop.example_toy_top()
    motion = {"spin": 150.0, "theta0": 0.1}
    path = config(tmp_path, top, motion)
    result = heavytop.chaos(top, **motion, horizon=20.0, precision=1e-9)
    assert result == cli_json("chaos", "--config", path, "--horizon", "20", "--precision", "1e-9")
    assert result["chaotic"] is False and result["prediction_horizon"] is None and len(result["spectrum"]) == 6
    section = heavytop.chaos(top, **motion, horizon=20.0, section=True)
    assert section == cli_json("chaos", "--config", path, "--horizon", "20", "--section")
    with pytest.raises(heavytop.InvalidInput, match="precision"):
        heavytop.chaos(top, **motion, precision=2.0)

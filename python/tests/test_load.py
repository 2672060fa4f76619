"""heavytop.load() reads a configuration file as `--config FILE` does (the same body, motion and
messages); precession() and body_report() are typed results whose to_dict() is the CLI's JSON."""
import os

import pytest

import heavytop
from conftest import body_options, cli_json, run_cli

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "examples")


@pytest.mark.parametrize("name", ["toy-top.toml", "asymmetric-plate.toml", "mesh-top.toml", "hanging-gyroscope.toml"])
def test_load_gives_the_cli_s_body_and_motion(name):
    path = os.path.join(EXAMPLES, name)
    config = heavytop.load(path)
    expected = cli_json("stability", "--config", path)
    assert {k: expected["body"][k] for k in ("A", "B", "C", "mass", "length", "gravity")} == \
        {k: getattr(config.body, k) for k in ("A", "B", "C", "mass", "length", "gravity")}
    assert heavytop.stability(config.body, **config.motion) == expected
    assert config.from_parts == (name == "mesh-top.toml")


def test_load_reads_the_motion_and_other_sections(tmp_path):
    path = tmp_path / "top.toml"
    path.write_text("[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n"
                    "[damping]\naxial = 2e-7\n[motion]\nspin_rpm = 3000\ntheta0 = 0.05\n"
                    "[simulate]\nt_end = 2.5\nsamples = 11\nmodel = \"linearized\"\n")
    config = heavytop.load(path)
    assert config.motion == {"spin": heavytop.rpm(3000.0), "theta0": 0.05, "phi0": 0.0, "theta_rate0": 0.0,
                             "phi_rate0": 0.0}
    assert config.body.axial_damping == 2e-7
    assert config.options == {"simulate.t_end": 2.5, "simulate.samples": 11, "simulate.model": "linearized"}
    assert config.section("simulate") == {"t_end": 2.5, "samples": 11, "model": "linearized"}
    assert "motion.spin" in config.given and "body.A" in config.given
    life = heavytop.lifetime(config.body, **config.motion)
    assert life == cli_json("lifetime", "--config", str(path))
    s = config.section("simulate")
    m = heavytop.simulate(config.body, s["model"], **config.motion, t_end=s["t_end"], samples=s["samples"])
    csv = run_cli("simulate", "--config", str(path), "--format", "csv").stdout.splitlines()
    assert len(csv) == 12 and float(csv[-1].split(",")[1]) == m.theta[-1]


def cli_message(*args):
    result = run_cli(*args, check=False)
    assert result.returncode != 0
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("heavytop: error: ")
    return line[len("heavytop: error: "):]


@pytest.mark.parametrize("text,key", [
    ("[body]\nA = 1\n", "body.B"),
    ("[body]\nA = 1\nB = 1\nC = 1\nmass = 1\nlength = -1\n[motion]\nspni = 3\n", "motion.spni"),
    ("[body]\nA = 1\nB = 1\nC = 3\nmass = 1\nlength = 1\n", "body.C"),
    ("[body]\nA = 1\nB = 1\nC = 1\nmass = 1\nlength = 1\n[motion]\nspin = \"fast\"\n", "motion.spin"),
    ("[body\n", "path"),
])
def test_bad_files_give_the_cli_s_message(tmp_path, text, key):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(heavytop.InvalidInput) as e:
        heavytop.load(path)
    expected = cli_message("stability", "--config", str(path))
    if key == "body.B":  # the command line also offers its option --B
        assert expected == "body.B: is required in [body] (or give --B), unless [[body.part]] describe the body"
        assert str(e.value) == "body.B: is required in [body], unless [[body.part]] describe the body"
    elif key == "path":  # the file's own name for it: --config on the command line, path here
        assert expected.startswith("--config: ") and str(e.value) == "path: " + expected[len("--config: "):]
    else:
        assert str(e.value) == expected and expected.startswith(key + ":")


def test_unreadable_files_give_the_cli_s_message(tmp_path):
    for path in (str(tmp_path / "missing.toml"), str(tmp_path)):
        with pytest.raises(heavytop.InvalidInput) as e:
            heavytop.load(path)
        assert str(e.value) == "path: " + cli_message("stability", "--config", path)[len("--config: "):]


def test_precession_is_typed_and_the_cli_s():
    top = heavytop.example_toy_top()
    result = heavytop.precession(top, 0.3, 200.0)
    expected = cli_json("precession", *body_options(top), "--tilt", "0.3", "--spin", "200")
    assert isinstance(result, heavytop.Precession) and result.to_dict() == expected
    slow = expected["steady_precession"]["slow"]
    assert (result.slow.rate, result.slow.period, result.slow.nutation_frequency) == \
        (slow["rate"], slow["period"], slow["nutation_frequency"])
    assert result.fast.rate == expected["steady_precession"]["fast"]["rate"]
    assert result.min_spin == expected["steady_precession"]["min_spin"]
    m = heavytop.simulate(top, "nonlinear", **result.slow.state, t_end=0.5, samples=101)
    assert max(abs(m.tilt - 0.3)) < 1e-6  # a steady precession keeps its tilt
    assert repr(result).startswith("At tilt 0.3 rad") and "<table>" in result._repr_html_()
    below = heavytop.precession(top, 0.3, 100.0)  # below min_spin: none
    assert below.slow is None and below.fast is None


def test_body_report_is_typed_and_the_cli_s():
    path = os.path.join(EXAMPLES, "mesh-top.toml")
    config = heavytop.load(path)
    expected = cli_json("body", "--config", path)
    parts = [{"shape": "mesh", "file": "meshes/spinning-top.stl", "units": "mm", "density": 700.0}]
    report = heavytop.body_report(parts, folder=EXAMPLES)
    assert isinstance(report, heavytop.BodyReport) and report.to_dict() == expected
    assert (report.A, report.C, report.mass, report.length, report.general) == \
        (expected["A"], expected["C"], expected["mass"], expected["length"], False)
    assert (config.body.A, config.body.C, config.body.mass) == (report.A, report.C, report.mass)


def test_body_report_html_has_units_and_parts():
    parts = [{"shape": "cone", "radius": 0.02, "height": 0.02, "density": 700.0},
             {"shape": "cylinder", "radius": 0.003, "height": 0.03, "z0": 0.02, "density": 700.0}]
    report = heavytop.body_report(parts)
    html = report._repr_html_()
    assert f"<td>C</td><td>{report.C:.6g} kg m^2</td>" in html and f"{report.mass * 1e3:.4g} g" in html
    assert html.count("<td>body.part[") == 2


def test_a_body_on_a_table_is_loaded_with_its_table():
    # [table] (SPEC section 16) is read, not refused: the body with its radii and the Table, which
    # stability() and simulate() take (test_table.py holds them to the command line).
    config = heavytop.load(os.path.join(EXAMPLES, "tippe-top.toml"))
    assert config.table == heavytop.Table("sliding", friction=0.3, friction_law="viscous")
    assert (config.body.tip_radius, config.body.rim_radius) == (0.015, 0.0)
    expected = cli_json("stability", "--config", os.path.join(EXAMPLES, "tippe-top.toml"))
    assert heavytop.stability(config.body, **config.motion, table=config.table) == expected

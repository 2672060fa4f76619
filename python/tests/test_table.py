"""The body on a table (SPEC section 16) in Python: heavytop.Table and the Body's radii, simulate()
and stability() with table=, load() of a [table] file. Each result is the command line's for the
same input (its JSON's names and values, its words), each bad input its one-line message."""
import io
import os
import pickle

import numpy as np
import pytest

import heavytop
from conftest import cli_json, run_cli

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIPPE = os.path.join(ROOT, "examples", "tippe-top.toml")

# examples/tippe-top.toml as keyword arguments: Friedl's tippe top on its ball.
TIPPE_BODY = heavytop.Body(8.54e-7, 8.54e-7, 7e-7, mass=0.006, length=-0.003, tip_radius=0.015)
TIPPE_MOTION = {"spin": 180.0, "theta0": 0.1}
TIPPE_TABLE = heavytop.Table("sliding", friction=0.3, friction_law="viscous")

TABLE_COLUMNS = ("x", "y", "height", "normal_force", "slip_speed", "spin", "energy", "jellett", "vertical_momentum")


def cli_message(*args):
    """The CLI's one-line message (exit 2) for `args`."""
    result = run_cli(*args, check=False)
    assert result.returncode == 2, (args, result.returncode, result.stderr)
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("heavytop: error: "), result.stderr
    return line[len("heavytop: error: "):]


def write(tmp_path, text, name="top.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


# ---- the table and the body's radii ----------------------------------------------------------------

def test_a_table_holds_the_contact_and_its_law():
    t = heavytop.Table("sliding", friction=0.3, friction_law="viscous", slip_speed=1.0)
    assert (t.contact, t.friction, t.friction_law, t.slip_speed, t.on_table) == ("sliding", 0.3, "viscous", 1.0, True)
    assert t == TIPPE_TABLE and hash(t) == hash(TIPPE_TABLE)
    assert t.to_dict() == {"contact": "sliding", "friction": 0.3, "friction_law": "viscous", "slip_speed": 1.0}
    assert pickle.loads(pickle.dumps(t)) == t
    assert eval(repr(t), {"heavytop": heavytop}) == t
    pivot = heavytop.Table()
    assert (pivot.contact, pivot.on_table, pivot.to_dict()) == ("pivot", False, {"contact": "pivot"})
    assert heavytop.Table("rolling") != heavytop.Table("frictionless")
    with pytest.raises(AttributeError):
        t.friction = 0.5  # immutable, like Body


def test_the_body_holds_its_radii():
    b = heavytop.Body(8.54e-7, 8.54e-7, 7e-7, mass=0.006, length=-0.003, tip_radius=0.015, rim_radius=0.002)
    assert (b.tip_radius, b.rim_radius) == (0.015, 0.002)
    assert b.to_dict()["tip_radius"] == 0.015 and b.to_dict()["rim_radius"] == 0.002
    assert "tip_radius=0.015" in repr(b) and eval(repr(b), {"heavytop": heavytop}) == b
    assert pickle.loads(pickle.dumps(b)) == b and b != TIPPE_BODY
    assert "tip_radius" not in heavytop.example_toy_top().to_dict()  # the JSON's "body" names them only when given


@pytest.mark.parametrize("table,key", [
    ('contact = "sliding"\nfriction = -1.0', "table.friction"),
    ('contact = "sliding"\nslip_speed = 0.0', "table.slip_speed"),
    ('contact = "skating"', "table.contact"),
    ('contact = "sliding"\nfriction_law = "dry"', "table.friction_law"),
    ('contact = "rolling"\nfriction = 0.3', "table.friction"),
    ('friction = 0.3', "table.friction"),
])
def test_a_bad_table_raises_the_cli_s_message(tmp_path, table, key):
    path = write(tmp_path, f"[body]\nA = 8.54e-7\nB = 8.54e-7\nC = 7e-7\nmass = 0.006\nlength = -0.003\n"
                           f"tip_radius = 0.015\n[motion]\nspin = 180.0\ntheta0 = 0.1\n[table]\n{table}\n")
    expected = cli_message("stability", "--config", path, "--format", "json")
    assert expected.startswith(key + ": ")
    keywords = {}
    for line in table.splitlines():
        name, value = (part.strip() for part in line.split("="))
        keywords[name] = value.strip('"') if value.startswith('"') else float(value)
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.Table(**keywords)
    assert str(error.value) == expected and error.value.key == key
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.load(path)
    assert str(error.value) == expected


@pytest.mark.parametrize("body,key", [
    ("tip_radius = -0.001", "body.tip_radius"),
    ("tip_radius = 0.015\n[damping]\naxial = 1e-7", "damping.axial"),
])
def test_a_body_the_table_cannot_take_raises_the_cli_s_message(tmp_path, body, key):
    path = write(tmp_path, f"[body]\nA = 8.54e-7\nB = 8.54e-7\nC = 7e-7\nmass = 0.006\nlength = -0.003\n{body}\n"
                           f"[motion]\nspin = 180.0\ntheta0 = 0.1\n[table]\ncontact = \"sliding\"\nfriction = 0.3\n")
    expected = cli_message("stability", "--config", path, "--format", "json")
    assert expected.startswith(key + ": "), expected
    assert cli_message("simulate", "--config", path, "--t-end", "0.1") == expected
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.load(path)
    assert str(error.value) == expected
    radius = -0.001 if key == "body.tip_radius" else 0.015
    damping = 1e-7 if key == "damping.axial" else 0.0
    with pytest.raises(heavytop.InvalidInput) as error:
        body = heavytop.Body(8.54e-7, 8.54e-7, 7e-7, mass=0.006, length=-0.003, tip_radius=radius,
                             axial_damping=damping)
        heavytop.stability(body, table=TIPPE_TABLE, **TIPPE_MOTION)
    assert str(error.value) == expected
    if key == "damping.axial":
        with pytest.raises(heavytop.InvalidInput) as error:
            heavytop.simulate(body, table=TIPPE_TABLE, **TIPPE_MOTION, t_end=0.1, samples=3)
        assert str(error.value) == expected


def test_a_rim_started_vertical_raises_the_cli_s_message(tmp_path):
    path = write(tmp_path, "[body]\nA = 1e-5\nB = 1e-5\nC = 2e-5\nmass = 0.01\nlength = 0.0\nrim_radius = 0.02\n"
                           "[motion]\nspin = 10.0\n[table]\ncontact = \"rolling\"\n")
    expected = cli_message("simulate", "--config", path, "--t-end", "0.1")
    cfg = heavytop.load(path)
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.simulate(cfg.body, **cfg.motion, table=cfg.table, t_end=0.1, samples=3)
    assert str(error.value) == expected and expected.startswith("motion.theta0: ")


# ---- load --------------------------------------------------------------------------------------------

def test_load_reads_the_table_and_the_radii():
    cfg = heavytop.load(TIPPE)
    assert cfg.body == TIPPE_BODY and cfg.table == TIPPE_TABLE
    assert cfg.motion == {"spin": 180.0, "theta0": 0.1, "phi0": 0.0, "theta_rate0": 0.0, "phi_rate0": 0.0}
    assert cfg.section("table") == {"contact": "sliding", "friction": 0.3, "friction_law": "viscous"}
    assert heavytop.load(os.path.join(ROOT, "examples", "toy-top.toml")).table == heavytop.Table()


def test_the_pivot_s_commands_refuse_a_file_on_a_table(tmp_path):
    cfg = heavytop.load(TIPPE)
    for call in (lambda: heavytop.report(cfg, tmp_path / "report"), lambda: heavytop.explore(cfg, tmp_path / "e.html")):
        with pytest.raises(heavytop.InvalidInput) as error:
            call()
        assert error.value.key == "table.contact" and 'on a table (contact = "sliding")' in str(error.value)
    assert not os.path.exists(tmp_path / "report") and not os.path.exists(tmp_path / "e.html")


# ---- simulate ----------------------------------------------------------------------------------------

def test_simulate_on_a_table_is_the_cli_s_json():
    expected = cli_json("simulate", "--config", TIPPE, "--t-end", "1", "--samples", "11")
    cfg = heavytop.load(TIPPE)
    m = heavytop.simulate(cfg.body, "nonlinear", **cfg.motion, table=cfg.table, t_end=1.0, samples=11)
    assert isinstance(m, heavytop.TableTrajectory) and isinstance(m, heavytop.Trajectory)
    assert list(m.columns) == expected["columns"]
    assert m.columns[7:] == TABLE_COLUMNS
    for name in expected["columns"]:
        assert np.array_equal(m[name], np.array(expected[name])), name
    assert m.summary.to_dict() == expected["summary"]
    s = m.summary
    assert isinstance(s, heavytop.TableSummary)
    assert (s.end, s.end_time, s.switches, s.steps) == ("completed", 1.0, 0, expected["summary"]["steps"])
    assert s.max_relative_jellett_drift == expected["summary"]["max_relative_jellett_drift"] < 1e-8
    assert m.settings == expected["table"] and m.table == TIPPE_TABLE
    # The columns by attribute, as the CSV names them.
    assert m.normal_force is m["normal_force"] and m.jellett is m["jellett"] and m.spin is m["spin"]
    assert m.x[0] == 0.0 and m.height[0] == pytest.approx(0.015)


def test_stiff_sliding_takes_the_implicit_integrator_as_the_cli_does():
    # At slip_speed 1e-6 m/s the viscous law is stiff: integrator="rosenbrock4" (and auto at this
    # tolerance) is the command line's Rosenbrock 4, number for number; a pivot refuses it.
    args = ("--slip-speed", "1e-6", "--rtol", "1e-9", "--atol", "1e-9", "--t-end", "0.1", "--samples", "3")
    expected = cli_json("simulate", "--config", TIPPE, *args)
    table = heavytop.Table("sliding", friction=0.3, friction_law="viscous", slip_speed=1e-6)
    for integrator in ("rosenbrock4", "auto"):
        m = heavytop.simulate(TIPPE_BODY, table=table, **TIPPE_MOTION, t_end=0.1, samples=3, rtol=1e-9, atol=1e-9,
                              integrator=integrator)
        assert m.summary.integrator == expected["summary"]["integrator"] == "rosenbrock4"
        assert np.array_equal(m["tilt"], np.array(expected["tilt"]))
        assert "Rosenbrock 4" in m.summary.report
    with pytest.raises(heavytop.InvalidInput, match="^integrator: rosenbrock4 integrates a body on a table"):
        heavytop.simulate(TIPPE_BODY, **TIPPE_MOTION, t_end=0.1, integrator="rosenbrock4")


def test_simulate_on_a_table_is_the_cli_s_csv():
    text = run_cli("simulate", "--config", TIPPE, "--t-end", "0.5", "--samples", "6").stdout
    header = text.splitlines()[0].split(",")
    data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    m = heavytop.simulate(TIPPE_BODY, table=TIPPE_TABLE, **TIPPE_MOTION, t_end=0.5, samples=6)
    assert list(m.columns) == header
    frame = m.to_dataframe()
    assert list(frame.columns) == header
    for i, name in enumerate(header):
        assert np.allclose(m[name], data[:, i], rtol=1e-15, atol=0.0), name  # the CSV's 17 digits


def test_simulate_under_coulomb_s_law_counts_the_switches():
    table = heavytop.Table("sliding", friction=0.3, friction_law="coulomb")
    expected = cli_json("simulate", "--config", TIPPE, "--friction-law", "coulomb", "--t-end", "0.2",
                        "--samples", "5")
    m = heavytop.simulate(TIPPE_BODY, table=table, **TIPPE_MOTION, t_end=0.2, samples=5)
    assert m.summary.to_dict() == expected["summary"] and m.settings == expected["table"]
    assert np.array_equal(m.tilt, np.array(expected["tilt"]))


def test_the_pivot_is_the_table_given_as_pivot():
    top = heavytop.example_toy_top()
    a = heavytop.simulate(top, spin=200.0, theta0=0.05, t_end=0.2, samples=5)
    b = heavytop.simulate(top, spin=200.0, theta0=0.05, t_end=0.2, samples=5, table=heavytop.Table("pivot"))
    assert type(b) is heavytop.Trajectory and np.array_equal(a.theta, b.theta)
    assert type(heavytop.stability(top, 200.0, table=heavytop.Table())) is heavytop.Stability


def test_simulate_on_a_table_refuses_the_pivot_s_options():
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.simulate(TIPPE_BODY, "linearized", table=TIPPE_TABLE, **TIPPE_MOTION, t_end=0.1)
    assert str(error.value).startswith('table.contact: model="linearized" is the pivot\'s (SPEC section 16)')
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.simulate(TIPPE_BODY, table=TIPPE_TABLE, **TIPPE_MOTION, t_end=0.1, integrator="taylor")
    cli = cli_message("simulate", "--config", TIPPE, "--t-end", "0.1", "--integrator", "taylor")
    assert cli.startswith("--integrator: ") and str(error.value) == "integrator: " + cli[len("--integrator: "):]


def test_a_table_trajectory_is_not_drawn_on_a_pivot():
    m = heavytop.simulate(TIPPE_BODY, table=TIPPE_TABLE, **TIPPE_MOTION, t_end=0.1, samples=3)
    with pytest.raises(ValueError, match="not drawn yet"):
        m.view()
    html = m._repr_html_()
    assert "<iframe" not in html and "<table>" in html and "normal_force (N)" in html
    assert repr(m).startswith("TableTrajectory(contact='sliding'")


# ---- stability ---------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def tippe_stability():
    return cli_json("stability", "--config", TIPPE)


def test_stability_on_a_table_is_the_cli_s_json(tippe_stability):
    expected = tippe_stability
    cfg = heavytop.load(TIPPE)
    s = heavytop.stability(cfg.body, **cfg.motion, table=cfg.table)
    assert isinstance(s, heavytop.TableAnalysis)
    assert s.to_dict() == expected
    a = s.answer
    assert isinstance(a, heavytop.TableAnswer) and isinstance(a, heavytop.Answer)
    assert (a.verdict, a.proven) == ("turns over", True)
    assert a.turns_over_at == pytest.approx(expected["answer"]["table"]["turns_over_at"], rel=1e-12, abs=0)
    assert 5.1 < a.turns_over_at < 5.2
    assert a.reason == expected["answer"]["reason"]
    for key in ("upright_at", "turns_over_at", "leaves_at", "track", "final_tilt", "final_spin"):
        assert getattr(a, key) == expected["answer"]["table"][key], key
    t = s.table
    assert isinstance(t, heavytop.TableStability)
    assert (t.contact, t.friction, t.friction_law, t.slip_speed, t.tip_radius, t.rim_radius) == \
        ("sliding", 0.3, "viscous", 1.0, 0.015, 0.0)
    for name in ("upright", "inverted"):
        state, json = getattr(t, name), expected["table"][name]
        assert isinstance(state, heavytop.SpinningState)
        assert (state.stable, state.asymptotically, state.critical_spin, state.growth_rate) == \
            (json["stable"], json["asymptotically"], json["critical_spin"], json["growth_rate"])
        assert state.stable_spin_intervals == tuple(tuple(i) for i in json["stable_spin_intervals"])
        assert state.eigenvalues == tuple(complex(re, im) for re, im in json["eigenvalues"])
    assert set(s.models) == {"first-order", "body-fixed", "linearized"}
    assert s.body == TIPPE_BODY and s.spin == 180.0


def test_stability_on_a_table_says_the_cli_s_words(tippe_stability):
    s = heavytop.stability(TIPPE_BODY, table=TIPPE_TABLE, **TIPPE_MOTION)
    text = run_cli("stability", "--config", TIPPE).stdout
    assert s.answer.text == text.split("\n\n")[0]  # table_answer_text, the text's first paragraph
    assert s.answer.text.startswith("Turns over.") and s.answer.reason in s.answer.text
    assert repr(s).startswith(s.answer.text) and "upright" in repr(s)
    assert s.answer.text in s._repr_html_().replace("&#x27;", "'")


def test_stability_on_a_table_at_a_shorter_horizon_is_the_cli_s(tmp_path):
    # A rolling top: a different contact, a horizon given, a tilted start with rates.
    path = write(tmp_path, "[body]\nA = 8.54e-7\nB = 8.54e-7\nC = 7e-7\nmass = 0.006\nlength = -0.003\n"
                           "tip_radius = 0.015\n[table]\ncontact = \"rolling\"\n")
    expected = cli_json("stability", "--config", path, "--spin", "180", "--theta0", "0.1", "--horizon", "2",
                        "--max-tilt", "0.5", "--phi0", "0.02", "--theta-rate0", "0.1")
    s = heavytop.stability(TIPPE_BODY, 180.0, theta0=0.1, phi0=0.02, theta_rate0=0.1, horizon=2.0, max_tilt=0.5,
                           table=heavytop.Table("rolling"))
    assert s.to_dict() == expected
    assert s.table.friction is None and s.table.slip_speed is None


# ---- the body's own losses (docs/table.md) ---------------------------------------------------------

WOODEN = os.path.join(ROOT, "examples", "wooden-top-on-table.toml")


def test_a_table_with_the_body_s_own_losses_is_the_cli_s():
    t = heavytop.Table("sliding", friction=0.3, friction_law="contensou", tip_material="steel", material=(1.6e9, 0.35),
                       rolling_resistance=1e-4, air=True)
    assert (t.friction_law, t.rolling_resistance, t.air, t.has_losses) == ("contensou", 1e-4, True, True)
    assert pickle.loads(pickle.dumps(t)) == t
    assert eval(repr(t), {"heavytop": heavytop}) == t
    assert t == heavytop.Table("sliding", friction=0.3, friction_law="contensou", tip_material=(200e9, 0.29),
                               material="oak", rolling_resistance=1e-4, air=True)
    with pytest.raises(heavytop.InvalidInput, match="table.tip_material"):
        heavytop.Table("sliding", friction=0.3, friction_law="contensou", material="oak")
    with pytest.raises(heavytop.InvalidInput, match="table.air_density"):
        heavytop.Table("sliding", friction=0.3, air_density=1.2)


def test_the_losses_booked_are_the_energy_lost_and_the_spin_down_is_the_cli_s():
    config = heavytop.load(WOODEN)
    assert config.table.has_losses and config.table.air
    run = heavytop.simulate(config.body, **config.motion, table=config.table, t_end=0.5, samples=6)
    lost = run.energy[0] - run.energy
    booked = sum(run[c] for c in ("loss_sliding", "loss_drilling", "loss_rolling", "loss_air"))
    assert np.all(np.abs(booked[1:] - lost[1:]) <= 1e-6 * lost[1:])
    s = heavytop.stability(config.body, **config.motion, table=config.table, horizon=1.0)
    assert s.to_dict()["answer"]["table"]["spin_down"] == \
        cli_json("stability", "--config", WOODEN, "--horizon", "1")["answer"]["table"]["spin_down"]
    assert "Asleep on this table it spins about 51.31 s" in str(s)

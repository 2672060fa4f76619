"""read_map(): a sweep's map file (CSV or HDF5) read back, sliced and drawn; three-parameter maps."""
import numpy as np
import pytest

import heavytop
from conftest import BODIES, body_options, run_cli

PLATE = BODIES["asymmetric-plate"]
VARY = {"B/A": heavytop.grid_values(1.0, 2.2, 7), "C/A": heavytop.grid_values(1.2, 2.0, 5),
        "spin": heavytop.grid_values(0.0, 4.0, 6)}
CLI_VARY = ["--vary", "B/A=1:2.2:7", "--vary", "C/A=1.2:2:5", "--vary", "spin=0:4:6"]
NONLINEAR = ["--model", "nonlinear", "--theta0", "0.01", "--horizon", "20"]


@pytest.fixture(scope="module")
def map_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("maps")
    for fmt in ("csv", "hdf5"):
        run_cli("sweep", *body_options(PLATE), *CLI_VARY, *NONLINEAR, "--format", fmt, "--output",
                str(folder / f"map.{fmt}"))
    return folder


def assert_same_map(a, b):
    assert a.columns == b.columns and a.shape == b.shape
    for name in a.columns:
        assert np.array_equal(a[name], b[name]), name


@pytest.mark.parametrize("fmt", ["csv", "hdf5"])
def test_a_three_parameter_map_file_is_the_sweep_python_computes(map_files, fmt):
    read = heavytop.read_map(map_files / f"map.{fmt}")
    computed = heavytop.sweep(PLATE, VARY, theta0=0.01, nonlinear=True, horizon=20.0)
    assert read.shape == (7, 5, 6)
    assert_same_map(read, computed)
    # The verdicts vary over the map (a map that is all one colour would test little).
    for name in ("linearized", "nonlinear"):
        assert 0 < read[name].sum() < read[name].size, name


def test_the_slice_of_a_three_parameter_map_is_the_two_parameter_map_at_that_value(map_files):
    # An independent route: the map at C/A = 1.6 computed outright with C = 1.6 A.
    sliced = heavytop.read_map(map_files / "map.hdf5").slice("C/A", 1.61)  # nearest grid value: 1.6
    body = heavytop.Body(PLATE.A, PLATE.B, 1.6 * PLATE.A, mass=PLATE.mass, gravity=PLATE.gravity, length=PLATE.length)
    two = heavytop.sweep(body, {"B/A": VARY["B/A"], "spin": VARY["spin"]}, theta0=0.01, nonlinear=True, horizon=20.0)
    assert sliced.shape == (7, 6)
    assert_same_map(sliced, two)
    # Slicing along the first or last key keeps the others in order.
    assert heavytop.read_map(map_files / "map.csv").slice("B/A", 1.0).shape == (5, 6)
    assert list(heavytop.read_map(map_files / "map.csv").slice("spin", 4.0).parameters) == ["B/A", "C/A"]


def test_a_slice_draws_as_a_heat_map_of_its_verdicts(map_files):
    import matplotlib
    matplotlib.use("Agg")
    sliced = heavytop.read_map(map_files / "map.csv").slice("C/A", 2.0)
    ax = sliced.plot("nonlinear")
    drawn = np.asarray(ax.collections[0].get_array()).reshape(6, 7)  # spin up, B/A across
    assert np.array_equal(drawn, sliced.grid("nonlinear").T.astype(float))
    assert ax.get_xlabel() == "B/A (dimensionless)" and ax.get_ylabel() == "spin (rad/s)"  # units on every axis (issue 28)
    with pytest.raises(ValueError, match="needs two varied keys"):
        heavytop.read_map(map_files / "map.csv").plot("nonlinear")


def test_what_is_not_a_map_is_refused_naming_the_path_and_the_fault(map_files, tmp_path):
    text = (map_files / "map.csv").read_text()
    lines = text.splitlines()  # two rows swapped are off the grid (all reversed would be a grid, descending)
    cases = {
        "torn.csv": (text[:-3], "is torn"),
        "columns.csv": (text.replace("\n1,", "\n1,0,", 1), "columns, the header"),
        "order.csv": ("\n".join(lines[:1] + lines[2:3] + lines[1:2] + lines[3:]) + "\n", "not the grid's value"),
        "header.csv": ("x,y\n1,2\n", "not a sweep's CSV"),
        "cert.csv": (text.replace("linear-instability", "proof", 1), "is not a certificate"),
        "empty.csv": ("", "no header"),
    }
    for name, (content, message) in cases.items():
        (tmp_path / name).write_text(content)
        with pytest.raises(heavytop.InvalidInput, match=f"^path: .*{message}"):
            heavytop.read_map(tmp_path / name)
    (tmp_path / "fake.h5").write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(100))
    with pytest.raises(heavytop.InvalidInput, match="^path: .*not a heavytop map file"):
        heavytop.read_map(tmp_path / "fake.h5")
    with pytest.raises(heavytop.InvalidInput, match="^path: cannot read"):
        heavytop.read_map(tmp_path / "missing.csv")
    with pytest.raises(heavytop.InvalidInput, match="^slice: 'mass' is not a varied key"):
        heavytop.read_map(map_files / "map.csv").slice("mass", 1.0)

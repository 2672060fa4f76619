"""Hostile input in the Python adapter.

Round 3 (issue 30): the mesh files that crashed the command line (and aborted the interpreter:
a binary PLY hit an assertion inside Assimp) are read or refused with InvalidInput naming the
part and the file; a map that is a device is refused at once instead of read forever (4 GB in
8 s).

Round 4 (issue 46): a sweep whose grid has more points than an integer holds is refused as the
command line refuses it (its size wrapped around to 0: a map of no points)."""
import struct

import numpy as np
import pytest

import heavytop
from conftest import cli_error

VERTICES = [(0, 0, 0), (1, 0, 0), (1, 2, 0), (0, 2, 0), (0, 0, 3), (1, 0, 3), (1, 2, 3), (0, 2, 3)]
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
TRIANGLES = [t for a, b, c, d in QUADS for t in ((a, b, c), (a, c, d))]


def stl(triangles):
    out = b"\0" * 80 + struct.pack("<I", len(triangles))
    for t in triangles:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *VERTICES[i]) for i in t) + b"\0\0"
    return out


def ply(fmt, endian):
    head = ("ply\nformat %s 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 6\nproperty list uchar int vertex_indices\nend_header\n" % fmt).encode()
    return (head + b"".join(struct.pack(endian + "3f", *p) for p in VERTICES)
            + b"".join(struct.pack(endian + "B4i", 4, *q) for q in QUADS))


GOOD = stl(TRIANGLES)
MALFORMED = {
    "empty.stl": b"",
    "text.stl": b"this is some text, not a mesh at all, and it is long enough to be more than eighty-four bytes\n",
    "nofacets.stl": b"\0" * 80 + struct.pack("<I", 0),
    "count.stl": GOOD[:80] + struct.pack("<I", len(TRIANGLES) + 1) + GOOD[84:],
    "truncated.stl": GOOD[:-10],
    "not.ply": b"this is not a PLY file\n",
    "box-le-truncated.ply": ply("binary_little_endian", "<")[:-3],
}


@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_a_malformed_mesh_is_refused_naming_the_part_and_the_file(tmp_path, name):
    (tmp_path / name).write_bytes(MALFORMED[name])
    part = {"shape": "mesh", "file": name, "density": 1000.0}
    with pytest.raises(heavytop.InvalidInput, match=rf"^body\.part\[0\] \({name}\): .*'.*{name}'") as error:
        heavytop.body_from_parts([part], folder=str(tmp_path))
    assert "\n" not in str(error.value)
    (tmp_path / "mesh.toml").write_text(f'[[body.part]]\nshape = "mesh"\nfile = "{name}"\ndensity = 1000.0\n')
    with pytest.raises(heavytop.InvalidInput, match=rf"body\.part\[0\] \({name}\)"):
        heavytop.load(tmp_path / "mesh.toml")


@pytest.mark.parametrize("fmt,endian", [("binary_little_endian", "<"), ("binary_big_endian", ">")])
def test_a_binary_ply_reads_to_the_box_it_holds(tmp_path, fmt, endian):
    (tmp_path / "box.ply").write_bytes(ply(fmt, endian))
    body = heavytop.body_from_parts([{"shape": "mesh", "file": "box.ply", "density": 1000.0}], folder=str(tmp_path))
    # The box [0,1] x [0,2] x [0,3] m of 1000 kg/m^3: 6000 kg; about z through O, m (a^2 + b^2) / 3.
    assert body.mass == pytest.approx(6000.0, rel=1e-12)
    assert body.C == pytest.approx(6000.0 * (1 + 4) / 3, rel=1e-9)


def test_a_map_that_is_a_device_is_refused_before_it_is_read():
    with pytest.raises(heavytop.InvalidInput, match="^path: .*not a regular file"):
        heavytop.read_map("/dev/zero")


TOY = dict(A=4.35e-5, B=4.35e-5, C=1.2e-5, mass=0.06, length=0.025)


def test_a_spin_no_double_can_follow_is_refused_by_lifetime_naming_its_default_horizon():
    # Its default 1000 s ran for minutes towards max_steps.
    with pytest.raises(heavytop.InvalidInput, match=r"^horizon: the default 1e\+03 s is too long"):
        heavytop.lifetime(heavytop.Body(**TOY), spin=1.8e19)


def test_the_report_at_such_a_spin_leaves_the_diagrams_nonlinear_verdicts_out_and_says_so(tmp_path):
    # The stability diagram's nonlinear verdicts at 1.8e19 rad/s ran for hours.
    page = heavytop.report(heavytop.Body(**TOY), tmp_path / "fast", spin=1.8e19)
    assert "The nonlinear verdicts are left out: at spins up to 2.88e+19 rad/s" in open(page).read()


# ---- round 4 (issue 46) -------------------------------------------------------------------------

TOP = heavytop.example_toy_top()
LIMIT = 100_000_000  # the most grid points a sweep may have (include/heavytop/sweep.hpp: kMaxSweepPoints)


def test_a_grid_of_more_points_than_an_integer_holds_is_refused():
    # 2^22 x 2^22 x 2^20 = 2^64 points: their product in 64 bits is 0, and the sweep returned a
    # map of shape (4194304, 4194304, 1048576) with no points.
    vary = {"spin": np.linspace(100.0, 300.0, 2**22), "length": np.linspace(0.01, 0.03, 2**22),
            "mass": np.linspace(0.05, 0.07, 2**20)}
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.sweep(TOP, vary)
    assert error.value.key == "vary"
    points = float(2**22) * 2**22 * 2**20
    assert error.value.rule == f"the grid has {points:g} points, more than the {LIMIT} a sweep may have"


def test_a_grid_just_over_the_limit_is_refused_by_the_same_rule():
    vary = {"spin": np.linspace(100.0, 300.0, 10_001), "length": np.linspace(0.01, 0.03, LIMIT // 10_000)}
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.sweep(TOP, vary)
    points = 10_001 * (LIMIT // 10_000)
    assert str(error.value) == f"vary: the grid has {points:g} points, more than the {LIMIT} a sweep may have"


def test_the_command_lines_grid_too_large_for_an_integer_gets_its_message():
    counts = {"spin": (100.0, 300.0, 2**22), "length": (0.01, 0.03, 2**22), "mass": (0.05, 0.07, 2**20)}
    vary = {key: heavytop.grid_values(*grid) for key, grid in counts.items()}  # the CLI's very values
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.sweep(TOP, vary, spin=200.0)
    args = ["sweep", "--spin", "200"]
    for key, (start, stop, count) in counts.items():
        args += ["--vary", f"{key}={start!r}:{stop!r}:{count}"]
    assert str(error.value) == cli_error(*args)

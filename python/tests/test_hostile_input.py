"""Hostile input in the Python adapter.

Round 3 (issue 30): the mesh files that crashed the command line (and aborted the interpreter:
a binary PLY hit an assertion inside Assimp) are read or refused with InvalidInput naming the
part and the file; a map that is a device is refused at once instead of read forever (4 GB in
8 s).

Round 4 (issue 46): a sweep whose grid has more points than an integer holds is refused as the
command line refuses it (its size wrapped around to 0: a map of no points); every file the
adapter writes goes through a temporary name and a rename as --output does (a folder is refused
with InvalidInput, a write cut short by a file-size limit leaves the old file, a pipe is written
directly and stays a pipe)."""
import os
import stat
import struct
import subprocess
import sys
import tempfile
import threading

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


def needs_explorer_page():
    from heavytop import _api
    if not _api._explorer_page_file():
        pytest.skip("this build has no explorer page (Emscripten)")


def motion_view():
    view = heavytop.simulate(TOP, spin=200.0, theta0=0.05, t_end=0.2, samples=21).view()
    if not view.html.startswith("<!doctype"):
        pytest.skip("this build has no page script (npm)")
    return view


def explore():
    needs_explorer_page()
    return lambda path: heavytop.explore(TOP, path, spin=200.0)


def report_view():
    with tempfile.TemporaryDirectory(prefix="heavytop-test-report-") as folder:
        return heavytop.show(TOP, folder, spin=200.0, t_end=0.2)  # the page with its files inlined


# Every writer of the adapter by name: what makes it ready to write, giving a function of the
# path that writes there and returns the path. (report() writes its folder's files in C++,
# through the same temporary names and renames.)
WRITERS = {"explore": explore, "MotionView.save": lambda: motion_view().save,
           "ReportView.save": lambda: report_view().save}


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_folder_is_refused_naming_the_path(tmp_path, writer):
    (tmp_path / "inside").write_text("kept")
    with pytest.raises(heavytop.InvalidInput) as error:
        WRITERS[writer]()(tmp_path)
    assert str(error.value) == f"path: '{tmp_path}' is a folder"
    assert os.listdir(tmp_path) == ["inside"] and (tmp_path / "inside").read_text() == "kept"


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_pipe_is_written_directly_and_stays_a_pipe(tmp_path, writer):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received = []
    write = WRITERS[writer]()
    reader = threading.Thread(target=lambda: received.append(open(fifo, "rb").read()), daemon=True)
    reader.start()
    assert write(fifo) == str(fifo)
    reader.join(10.0)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and os.listdir(tmp_path) == ["pipe"]
    assert received and received[0].lower().startswith(b"<!doctype html>") and received[0].rstrip().endswith(b"</html>")


# In a process whose files may grow to `limit` bytes (RLIMIT_FSIZE; SIGXFSZ ignored, so a write
# past it fails with EFBIG instead of killing the process): the writer, then what it raised.
UNDER_A_LIMIT = """
import resource, signal, sys
sys.path[:0] = [sys.argv[1]]
import test_hostile_input as t
name, path, limit = sys.argv[2], sys.argv[3], int(sys.argv[4])
write = t.WRITERS[name]()
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (limit, resource.RLIM_INFINITY))
try:
    write(path)
    print("wrote")
except BaseException as e:
    print(type(e).__name__ + ": " + str(e))
"""


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_write_cut_short_by_a_file_size_limit_leaves_the_old_file(tmp_path, writer):
    page = tmp_path / "page.html"
    WRITERS[writer]()(page)
    size = page.stat().st_size
    limit = min(1 << 20, size // 2)  # 1 MB, or less for a page smaller than 2 MB
    assert size > limit
    old = b"the old page, kept whole\n"
    page.write_bytes(old)
    result = subprocess.run([sys.executable, "-c", UNDER_A_LIMIT, os.path.dirname(__file__), writer, str(page),
                             str(limit)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert page.read_bytes() == old  # was cut at the limit: a page missing its end
    assert os.listdir(tmp_path) == ["page.html"]  # no temporary file, no lock file left
    said = result.stdout.strip().splitlines()[-1]
    assert said.startswith(f"OSError: path: cannot write '{page}'") and "File too large" in said, said


def test_a_report_folder_that_is_a_file_is_refused_naming_the_folder(tmp_path):
    (tmp_path / "file").write_text("kept")
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.report(TOP, tmp_path / "file", spin=200.0, t_end=0.2)
    assert str(error.value) == f"folder: cannot create the folder '{tmp_path / 'file'}'"  # not --output
    assert (tmp_path / "file").read_text() == "kept"


def test_a_spin_in_rpm_is_the_spin_in_rad_s():
    # spin_rpm passed the key's check and was then ignored: every point judged at the base spin 0.
    rpms = np.array([100.0, 3000.0, 20000.0])
    in_rpm = heavytop.sweep(TOP, {"spin_rpm": rpms, "mass": [0.05, 0.06]})
    in_rad_s = heavytop.sweep(TOP, {"spin": [heavytop.rpm(x) for x in rpms], "mass": [0.05, 0.06]})
    assert in_rpm.columns == in_rad_s.columns and in_rpm.shape == in_rad_s.shape == (3, 2)
    for column in in_rad_s.columns:
        np.testing.assert_array_equal(in_rpm[column], in_rad_s[column])
    assert in_rad_s["linearized"].any() and not in_rad_s["linearized"].all()  # the spins decide
    with pytest.raises(heavytop.InvalidInput, match="^vary: 'spin' is varied twice$"):
        heavytop.sweep(TOP, {"spin": [1.0, 2.0], "spin_rpm": [100.0, 200.0]})

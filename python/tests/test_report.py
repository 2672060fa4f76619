"""heavytop.report() writes the folder `heavytop report --output` writes: the same files, the same
data (JSON, CSV) and the same page, for a free and a damped body, and from a configuration file."""
import os

import pytest

import heavytop
from conftest import body_options, motion_options, run_cli

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOP = heavytop.example_toy_top()


def files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, names in os.walk(folder) for f in names)


def assert_same_folder(mine, theirs):
    assert files(mine) == files(theirs)
    assert "report.html" in files(mine)
    compared = 0
    for name in files(mine):
        if name.endswith((".json", ".csv", ".html", ".js")):
            with open(os.path.join(mine, name), "rb") as a, open(os.path.join(theirs, name), "rb") as b:
                assert a.read() == b.read(), name
            compared += 1
    assert compared >= 3


@pytest.mark.parametrize("body,motion", [
    (TOP, dict(spin=200.0, theta0=0.05)),
    (heavytop.Body(TOP.A, TOP.B, TOP.C, TOP.mass, TOP.length, TOP.gravity, axial_damping=2e-7), dict(spin=200.0, theta0=0.05)),
])
def test_report_writes_the_cli_s_folder(tmp_path, body, motion):
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    # The title names where the body came from (the command line there); all else is the same bytes.
    page = heavytop.report(body, mine, **motion, t_end=2.0, title="A body given on the command line")
    assert page == os.path.join(str(mine), "report.html")
    damping = ["--transverse-damping", repr(body.transverse_damping), "--axial-damping", repr(body.axial_damping),
               "--friction", repr(body.friction)]
    run_cli("report", *body_options(body), *damping, *motion_options(**motion), "--t-end", "2", "--output", str(theirs))
    assert_same_folder(mine, theirs)
    if body.axial_damping:
        assert "lifetime.json" in files(mine)


def test_report_from_a_configuration_names_its_file(tmp_path):
    path = os.path.join(ROOT, "examples", "toy-top.toml")
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    heavytop.report(heavytop.load(path), mine, t_end=1.0)
    run_cli("report", "--config", path, "--t-end", "1", "--output", str(theirs))
    assert_same_folder(mine, theirs)
    assert "toy-top.toml" in (mine / "report.html").read_text()


def test_report_refuses_bad_input(tmp_path):
    with pytest.raises(heavytop.InvalidInput, match="^t_end: must be finite and > 0$"):
        heavytop.report(TOP, tmp_path / "r", spin=200.0, t_end=-1.0)
    with pytest.raises(heavytop.InvalidInput, match="^slice: needs map=FILE$"):
        heavytop.report(TOP, tmp_path / "r", spin=200.0, slice=("spin", [1.0]))
    with pytest.raises(heavytop.InvalidInput, match="^map: "):
        heavytop.report(TOP, tmp_path / "r", spin=200.0, map=tmp_path / "missing.csv")


def test_show_inlines_the_report_page_with_its_3d_view(tmp_path):
    view = heavytop.show(TOP, tmp_path / "r", spin=200.0, theta0=0.05, t_end=1.0)
    page = view.html
    assert "src='report-data.js'" not in page and "src='heavytop-report.js'" not in page
    assert "src='tilt.svg'" not in page and "src='data:image/svg+xml;base64," in page
    if os.path.exists(tmp_path / "r" / "heavytop-report.js"):  # the build had npm: the 3D view's bundle
        assert "window.HEAVYTOP_REPORT = " in page and "id='scene'" in page  # where three.js draws
        bundle = (tmp_path / "r" / "heavytop-report.js").read_text()
        assert bundle[:2000].replace("</script", "<\\/script") in page
        assert page.index("window.HEAVYTOP_REPORT") < page.index(bundle[:200])  # the data before the bundle
        assert page.rindex("</body>") > page.index(bundle[:200])                # the bundle after the page
    assert (tmp_path / "r" / "report.html").read_text().split("<h2")[1] in page  # the page's own text
    frame = view._repr_html_()
    assert frame.startswith("<iframe srcdoc=\"") and "height: 720px" in frame and "&lt;h2" in frame
    assert view.save(str(tmp_path / "one.html")) and (tmp_path / "one.html").read_text() == page


def test_report_titles(tmp_path):
    heavytop.report(TOP, tmp_path / "a", spin=200.0, t_end=0.5, title="My top")
    assert "<title>heavytop: My top: " in (tmp_path / "a" / "report.html").read_text()
    other = heavytop.Body(4.35e-5, 4.5e-5, 1.2e-5, 0.06, 0.025)
    assert "<title>heavytop: A body given in Python: " in heavytop.show(other, tmp_path / "b", spin=200.0, t_end=0.5).html


def test_show_leaves_no_temporary_folder_behind(tmp_path):
    # A Python (a notebook's kernel) that shows a report and exits: its temporary report folder
    # (a few MB) is there while it runs and gone after; one that fails leaves none at all.
    import subprocess
    import sys
    private = tmp_path / "tmp"
    private.mkdir()
    script = ("import os, heavytop\n"
              "view = heavytop.show(heavytop.example_toy_top(), spin=200.0, theta0=0.05, t_end=0.5)\n"
              "assert os.path.isfile(os.path.join(view.folder, 'report.html')), view.folder\n"
              "assert os.path.dirname(view.folder) == os.environ['TMPDIR'], view.folder\n"
              "try:\n"
              "    heavytop.show(heavytop.example_toy_top(), spin=200.0, t_end=-1.0)\n"
              "except heavytop.InvalidInput:\n"
              "    pass\n"
              "assert len([f for f in os.listdir(os.environ['TMPDIR']) if f.startswith('heavytop-report-')]) == 1\n"
              "print(view.folder)\n")
    run = subprocess.run([sys.executable, "-c", script], env=dict(os.environ, TMPDIR=str(private)),
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().startswith(str(private / "heavytop-report-"))
    assert sorted(p.name for p in private.glob("heavytop-report-*")) == []
    # A folder given is the caller's: kept.
    heavytop.show(TOP, tmp_path / "mine", spin=200.0, t_end=0.5)
    assert (tmp_path / "mine" / "report.html").is_file()

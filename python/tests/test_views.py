"""A trajectory shows its motion in 3D (the report's own three.js view, offline), and explore()
writes the explorer page or says, as the command line does, why it cannot."""
import json
import os
import re

import numpy as np
import pytest

import heavytop

TOP = heavytop.example_toy_top()


def view_data(page):
    """window.HEAVYTOP_REPORT of a MotionView's page, as a dict."""
    match = re.search(r"<script>window\.HEAVYTOP_REPORT = (.*?);\n</script>", page, re.S)
    assert match, page[:300]
    return json.loads(match.group(1))


def needs_page_script():
    script, missing = heavytop._core.page_script()
    if script is None:
        pytest.skip(f"this build has no page script: {missing}")
    return script


def test_a_trajectory_shows_the_report_s_3d_view(tmp_path):
    script = needs_page_script()
    motion = heavytop.simulate(TOP, "nonlinear", spin=200.0, theta0=0.05, t_end=0.5, samples=501)
    view = heavytop.show(motion)
    assert isinstance(view, heavytop.MotionView) and view.height == 720
    page = view.html
    # The report's own bundle, inlined whole: the same bytes `heavytop report` writes.
    report = tmp_path / "report"
    heavytop.report(TOP, report, spin=200.0, theta0=0.05, t_end=0.2)
    bundle = (report / "heavytop-report.js").read_bytes()
    assert bundle == script
    assert bundle.decode().replace("</script", "<\\/script") in page
    assert "<script type='text/plain' id='page-script'>" in page  # run once the frame has a width
    assert "http://" not in page.split("<script>")[0] and "src=" not in page  # nothing fetched
    for element in ("scene", "play", "speed", "scrub", "time", "inset-scale", "spin-note", "exaggerate"):
        assert f"id='{element}'" in page, element
    data = view_data(page)
    assert data["t"] == motion.t.tolist() and data["nonlinear"]["theta"] == motion.theta.tolist()
    # psi, the spin angle: psi' = w3 + theta' sin(phi) with w3 = axial_momentum / C, integrated
    # by the trapezoid rule; here with NumPy, an independent route.
    rate = motion.axial_momentum / TOP.C + motion.theta_rate * np.sin(motion.phi)
    psi = np.concatenate([[0.0], np.cumsum(0.5 * np.diff(motion.t) * (rate[1:] + rate[:-1]))])
    np.testing.assert_allclose(data["nonlinear"]["psi"], psi, rtol=1e-12, atol=1e-12)
    assert abs(psi[-1] - 200.0 * 0.5) < 1e-3 * 100.0  # the spin turns it 100 rad in 0.5 s
    # The drawn ellipsoid has the body's moments: C = m (a^2 + b^2) / 5.
    a, b, c = data["shape"]["semi_axes"]
    assert TOP.mass * (a * a + b * b) / 5 == pytest.approx(TOP.C, rel=1e-12)
    # The trajectory's own HTML holds the view (in an iframe) above its table.
    own = motion._repr_html_()
    assert own.index("<iframe srcdoc=") < own.index("<table>")
    assert view.save(str(tmp_path / "motion.html")) == str(tmp_path / "motion.html")


def test_a_linear_model_turns_at_its_constant_spin():
    needs_page_script()
    motion = heavytop.simulate(TOP, "first-order", spin=200.0, theta0=0.05, t_end=0.5, samples=101)
    psi = view_data(motion.view().html)["nonlinear"]["psi"]
    rate = 200.0 + motion.theta_rate * np.sin(motion.phi)
    expected = np.concatenate([[0.0], np.cumsum(0.5 * np.diff(motion.t) * (rate[1:] + rate[:-1]))])
    np.testing.assert_allclose(psi, expected, rtol=1e-12, atol=1e-12)


def test_show_of_a_trajectory_takes_only_height():
    motion = heavytop.simulate(TOP, "nonlinear", spin=200.0, theta0=0.05, t_end=0.1, samples=11)
    with pytest.raises(heavytop.InvalidInput, match="^show: a trajectory takes only height=$"):
        heavytop.show(motion, spin=3.0)


def test_explore_writes_nothing_for_bad_input(tmp_path):
    with pytest.raises(heavytop.InvalidInput, match=r"^motion\.spin: must be a finite number$"):
        heavytop.explore(TOP, tmp_path / "e.html", spin=float("nan"))
    assert not os.path.exists(tmp_path / "e.html")


def test_explore_without_the_page_says_how_to_build_it(tmp_path, monkeypatch):
    from heavytop import _api
    monkeypatch.setattr(_api, "_explorer_page_file", lambda: "")
    with pytest.raises(heavytop.InvalidInput) as error:
        heavytop.explore(TOP, tmp_path / "e.html", spin=200.0)
    assert str(error.value) == ("explore: this heavytop was built without the explorer page, which needs Emscripten: "
                                "run ./scripts/build.sh --web (or configure with -DHEAVYTOP_BUILD_WEB=ON and build "
                                "the target heavytop_web), then run this again")
    assert not os.path.exists(tmp_path / "e.html")

"""simulate(): NumPy arrays of the right shape and dtype, the C++ tests' reference values, and
the command line's CSV for the same input."""
import io
import threading
import time

import numpy as np
import pytest

import heavytop
from conftest import BODIES, body_options, motion_options, run_cli

COLUMNS = ["t", "theta", "phi", "theta_rate", "phi_rate", "tilt", "azimuth"]
NONLINEAR_EXTRAS = ["energy", "vertical_momentum", "axial_momentum", "energy_drift",
                    "vertical_momentum_drift", "axial_momentum_drift"]
REFERENCE = dict(spin=1.6, theta0=0.01, phi0=0.02)  # tests/test_linear_motion.cpp


@pytest.mark.parametrize("model", heavytop.MODELS)
def test_arrays_have_the_csv_columns_shape_and_dtype(model):
    body = BODIES["toy-top"]
    result = heavytop.simulate(body, model, **heavytop.example_motion(), t_end=0.5, samples=501)
    expected = COLUMNS + (NONLINEAR_EXTRAS if model == "nonlinear" else [])
    assert list(result) == expected
    for name, column in result.items():
        assert isinstance(column, np.ndarray), name
        assert column.dtype == np.float64 and column.shape == (501,), name
        assert column.flags.c_contiguous, name
    np.testing.assert_array_equal(result["t"], np.arange(501) * 0.5 / 500)
    assert result["theta"][0] == pytest.approx(0.05, abs=1e-15)


def test_first_order_reference_value_of_the_cpp_tests():
    # tests/test_linear_motion.cpp, PaperSection8: A=1, B=1.3, C=2, m g R = 1, w0 = 1.6,
    # theta0 = 0.01, phi0 = 0.02: the first-order model's theta(0.5) = 0.0118 to 5e-5.
    body = BODIES["reference"]
    assert body.mgR == 1.0
    for method in ("analytic", "numeric"):
        result = heavytop.simulate(body, "first-order", **REFERENCE, t_end=1.0, samples=3, method=method)
        assert result["t"][1] == 0.5
        assert abs(result["theta"][1] - 0.0118) <= 5e-5


def test_analytic_and_numeric_agree():
    body = BODIES["reference"]
    a = heavytop.simulate(body, "linearized", **REFERENCE, t_end=20.0, samples=2001)
    n = heavytop.simulate(body, "linearized", **REFERENCE, t_end=20.0, samples=2001, method="numeric")
    for name in COLUMNS:
        np.testing.assert_allclose(a[name], n[name], rtol=0, atol=1e-9)


def read_csv(text):
    header = text.splitlines()[0].split(",")
    data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


@pytest.mark.parametrize("model,body,motion", [
    ("first-order", "reference", REFERENCE),
    ("body-fixed", "reference", REFERENCE),
    ("linearized", "reference", REFERENCE),
    ("linearized", "asymmetric-plate", dict(spin=1.3, theta0=1e-4, phi_rate0=1e-3)),
    ("nonlinear", "reference", dict(REFERENCE, theta_rate0=0.005, phi_rate0=-0.01)),
    ("nonlinear", "toy-top", dict(spin=200.0, theta0=0.05)),
    ("lagrange-exact", "toy-top", dict(spin=200.0, theta0=0.05, phi_rate0=1.0)),
])
def test_equals_the_cli_csv(model, body, motion):
    body = BODIES[body]
    csv = run_cli("simulate", *body_options(body), *motion_options(**motion), "--model", model,
                  "--t-end", "3", "--samples", "301", "--format", "csv").stdout
    expected = read_csv(csv)
    result = heavytop.simulate(body, model, **motion, t_end=3.0, samples=301)
    assert list(result) == list(expected)
    for name in expected:
        np.testing.assert_allclose(result[name], expected[name], rtol=0, atol=1e-15, err_msg=name)
        # The CSV prints the shortest decimal that reads back: in fact they are equal.
        np.testing.assert_array_equal(result[name] + 0.0, expected[name], err_msg=name)


def test_numeric_method_and_tolerances_equal_the_cli():
    body = BODIES["reference"]
    csv = run_cli("simulate", *body_options(body), *motion_options(**REFERENCE), "--model", "first-order",
                  "--method", "numeric", "--t-end", "2", "--samples", "11").stdout
    result = heavytop.simulate(body, "first-order", **REFERENCE, t_end=2.0, samples=11, method="numeric")
    for name, column in read_csv(csv).items():
        np.testing.assert_array_equal(result[name] + 0.0, column, err_msg=name)
    csv = run_cli("simulate", *body_options(body), *motion_options(**REFERENCE), "--model", "nonlinear",
                  "--rtol", "1e-8", "--atol", "1e-10", "--t-end", "2", "--samples", "11").stdout
    result = heavytop.simulate(body, **REFERENCE, t_end=2.0, samples=11, rtol=1e-8, atol=1e-10)
    for name, column in read_csv(csv).items():
        np.testing.assert_array_equal(result[name] + 0.0, column, err_msg=name)


def test_the_gil_is_released_while_the_core_computes():
    body = BODIES["toy-top"]
    done = threading.Event()
    started = threading.Event()

    def work():
        started.set()
        # dopri5: a workload long enough to tell (the default, Taylor, does it in ~50 ms)
        heavytop.simulate(body, **heavytop.example_motion(), t_end=1000.0, samples=2001, integrator="dopri5")
        done.set()

    thread = threading.Thread(target=work)
    begin = time.perf_counter()
    thread.start()
    started.wait()
    spins = 0
    while not done.is_set():
        spins += 1  # runs only while the simulation does not hold the GIL
    thread.join()
    elapsed = time.perf_counter() - begin
    assert elapsed > 0.05, "the simulation was too quick to tell"
    assert spins > 10000, f"the main thread ran {spins} times in {elapsed:.2f} s: the GIL was held"

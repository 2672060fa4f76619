"""Long computations run with the GIL released and still stop on Ctrl-C (a Jupyter interrupt)."""
import os
import signal
import threading
import time

import pytest

import heavytop

TOP = heavytop.example_toy_top()
MOTION = heavytop.example_motion()


@pytest.mark.parametrize("name,call", [
    ("simulate", lambda: heavytop.simulate(TOP, **MOTION, t_end=1e5, samples=1001)),  # minutes
    ("compare", lambda: heavytop.compare(TOP, **MOTION, t_end=1e5, samples=1001)),
    ("sweep", lambda: heavytop.sweep(TOP, {"spin": heavytop.grid_values(100, 300, 4000)}, theta0=0.05,
                                     nonlinear=True, horizon=20.0)),
])
def test_ctrl_c_stops_a_long_computation(name, call):
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call()
    timer.join()
    assert time.perf_counter() - start < 5.0, name
    # The module works on afterwards.
    assert heavytop.stability(TOP, 200.0)["models"]["linearized"]["stable"] is True

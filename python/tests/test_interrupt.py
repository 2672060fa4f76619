"""Long computations run with the GIL released and still stop on Ctrl-C (a Jupyter interrupt)."""
import os
import signal
import threading
import time

import pytest

import heavytop

TOP = heavytop.example_toy_top()
MOTION = heavytop.example_motion()
# 5 % asymmetry: a symmetric top's sweep verdicts come from the closed form, in milliseconds,
# so a sweep that runs long enough to be interrupted has to integrate (about 20 s here).
ASYMMETRIC = heavytop.Body(TOP.A, 1.05 * TOP.A, TOP.C, TOP.mass, TOP.length, TOP.gravity)


@pytest.mark.parametrize("name,call", [
    ("simulate", lambda: heavytop.simulate(TOP, **MOTION, t_end=1e5, samples=1001)),  # minutes
    # Two samples: the core reports progress between samples too, not only after each one.
    ("simulate-two-samples", lambda: heavytop.simulate(TOP, **MOTION, t_end=1e5, samples=2)),
    ("simulate-splitting", lambda: heavytop.simulate(TOP, **MOTION, t_end=1e5, samples=2, integrator="splitting")),
    ("compare", lambda: heavytop.compare(TOP, **MOTION, t_end=1e5, samples=1001)),
    ("sweep", lambda: heavytop.sweep(ASYMMETRIC, {"spin": heavytop.grid_values(100, 300, 4000)}, theta0=0.05,
                                     nonlinear=True, horizon=200.0)),
])
def test_ctrl_c_stops_a_long_computation(name, call):
    sent = []

    def ctrl_c():
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.2, ctrl_c)
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call()
    stopped = time.perf_counter()
    timer.join()
    assert stopped - start < 5.0, name
    # Polled every 0.1 s; a sweep's workers also finish their block. Slack for a busy machine.
    print(f"\n{name}: stopped {stopped - sent[0]:.3f} s after Ctrl-C")
    assert stopped - sent[0] < 1.0, name
    # The module works on afterwards.
    assert heavytop.stability(TOP, 200.0)["models"]["linearized"]["stable"] is True

#!/usr/bin/env python3
"""A seeded random fuzzer of the Python module's argument conversion (issue 30; Atheris is not
available, so this is its own driver). Every public function of heavytop (and of its pybind11
layer heavytop._core, called directly, and the Body constructor) is called with arguments drawn
from a pool of hostile values (NaN, infinities, subnormals, 2^64, bools, None, empty and huge
strings, bytes, nested lists, NumPy arrays of every dtype and shape, objects whose __float__
raises, paths to /dev/zero and to missing files, ...), each argument either kept at a valid
value (so the call reaches deep) or replaced, sometimes dropped, sometimes an unknown keyword
added.

Rules, for every call: it returns, or raises ValueError (heavytop.InvalidInput is one) or
TypeError whose message is one non-empty line; or RuntimeError with one line when a valid
computation failed (the step limit, a model that does not apply; counted apart); or the
fuzzer's own value's exception (OwnError from a __float__ that raises), let through as float()
lets it through. Anything
else is a finding: another exception type, a multi-line message, a crash or an abort of the
interpreter (the child dies by a signal), a call that neither returns nor polls Ctrl-C for
WATCHDOG seconds (a hang), MemoryError.

    fuzz_python.py [--seconds S] [--seed N] [--case I]    (PYTHONPATH: the folder of heavytop/)

The parent runs the cases in a child interpreter and restarts it after each finding-free
crash-free batch; before each call the child writes the case to WORK/current, so that a crash
names the case: rerun it alone with --seed N --case I (each case draws from Random(N, I) only).
Exit status 0: no finding; 1: findings (printed, one line each, with their --case).
"""
import argparse
import json
import math
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
import warnings

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WATCHDOG = 60.0  # s without a new case: the child is stuck in a call that does not poll signals
CALL_LIMIT = 2.0  # s a valid call may run before SIGALRM interrupts it (a Slow, not a finding)


class Slow(BaseException):
    """Raised by SIGALRM in a call that runs past CALL_LIMIT (heavytop polls signals)."""


class OwnError(ArithmeticError):
    """Raised by the fuzzer's own hostile values: heavytop lets it through, as float() does."""


class BadFloat:
    def __float__(self):
        raise OwnError("__float__ refuses")

    def __index__(self):
        raise OwnError("__index__ refuses")

    def __repr__(self):
        return "BadFloat()"


class HugeIndex:
    def __index__(self):
        return 2 ** 70

    def __repr__(self):
        return "HugeIndex()"


class FloatLike:
    def __float__(self):
        return 3.0

    def __repr__(self):
        return "FloatLike()"


class BadPath:
    def __fspath__(self):
        return b"\xff\xfe/not/a/path"

    def __repr__(self):
        return "BadPath()"


class BadMapping(dict):
    def items(self):
        raise OwnError("items refuses")

    def __repr__(self):
        return "BadMapping()"


def hostile_pool(np, heavytop, scratch):
    """Values each argument may be replaced by: wrong types, edge numbers, edge containers."""
    floats = [0.0, -0.0, 1.0, -1.0, 0.5, 3.0, 200.0, 1e-310, 5e-324, -5e-324, 1e-300, 1e300, -1e300, 1e308,
              1.7976931348623157e308, math.inf, -math.inf, math.nan, 2.0 ** 53 + 1, 1e15, math.pi]
    ints = [0, 1, -1, 2, 3, 7, 2 ** 31, 2 ** 31 - 1, -(2 ** 31), 2 ** 32, 2 ** 53 + 1, 2 ** 63, 2 ** 63 - 1, -(2 ** 63) - 1,
            2 ** 64, 2 ** 64 - 1, 10 ** 100, -10 ** 100, 10 ** 9]
    strings = ["", " ", "nonlinear", "linearized", "first-order", "body-fixed", "lagrange-exact", "dopri5", "taylor",
               "splitting", "auto", "analytic", "numeric", "euler-moving", "phi-theta", "spin", "B/A", "mass", "A",
               "theta0", "1.0", "nan", "inf", "-1", "\x00", "a\nb", "\r", "é", "\udcff", "x" * 5000, "%s%n{}", "../",
               "/dev/zero", "/dev/null", "/proc/self/mem", "/nonexistent/file.csv", scratch, "down", "mesh",
               "cylinder", "sphere", "mm", "inch"]
    others = [None, True, False, b"", b"1.0", bytearray(b"x"), 1j, complex(math.nan, 1), (), [], {}, set(), object(),
              BadFloat(), HugeIndex(), FloatLike(), BadPath(), BadMapping(), range(3), range(10 ** 12),
              slice(1, 2), Ellipsis, NotImplemented, type, len, heavytop.example_toy_top(),
              heavytop.Body(1.0, 1.0, 1.0, mass=1.0, length=1.0, gravity=1.0, Ixy=0.1)]
    containers = [[0.0], [math.nan], [1.0, 2.0], [[1.0]], [None], ["a"], [0.0] * 100000, list(range(5)),
                  (1.0, 2.0, 3.0), {"spin": [1.0, 2.0]}, {"spin": []}, {"": [1.0]}, {"x": [1.0]}, {1: 2},
                  {"spin": [math.nan]}, {"spin": [1.0], "B/A": [1.0], "mass": [1.0], "length": [1.0]},
                  {"spin": "abc"}, {"spin": {"a": 1}}, ("spin", [1.0]), ("spin", "x"), ("mass", []),
                  [{"shape": "cylinder"}], [{}], [{"shape": "mesh", "file": "/dev/zero", "density": 1.0}],
                  [{"shape": "sphere", "radius": math.nan, "density": 1.0}], [{"shape": 1}], ["cylinder"]]
    arrays = [np.array([]), np.array([math.nan]), np.array([math.inf, 1.0]), np.zeros((2, 2)), np.zeros((0, 3)),
              np.array(["a", "b"]), np.array([1, 2, 3], dtype=np.int8), np.array([1, 2], dtype=np.uint64),
              np.array([True, False]), np.array([1 + 2j]), np.array([None, 1.0], dtype=object),
              np.arange(4.0)[::-1], np.arange(10.0)[::3], np.float32(1.5), np.float64(math.nan), np.int64(-1),
              np.uint64(2 ** 64 - 1), np.bool_(True), np.array(2.0), np.ones(3, dtype=">f8"),
              np.linspace(0, 1, 1_000_000), np.array([[0.0, 1.0], [2.0, 3.0]], order="F")]
    return floats, ints, strings, others + containers + arrays


class Target:
    def __init__(self, name, fn, valid, weight=1.0):
        self.name, self.fn, self.valid, self.weight = name, fn, valid, weight


def targets(heavytop, np, scratch):
    """Each function with valid arguments: (positional, keyword)."""
    core = heavytop._core
    top = heavytop.example_toy_top()
    sym = heavytop.Body(1.0, 1.0, 2.0, mass=1.0, length=1.0, gravity=1.0)
    damped = heavytop.Body(1.0, 1.0, 2.0, mass=1.0, length=1.0, gravity=1.0, transverse_damping=0.01)
    maps = os.path.join(ROOT, "fuzz", "corpus", "map")
    a_map = next(os.path.join(maps, f) for f in sorted(os.listdir(maps)) if f.endswith(".csv")) if os.path.isdir(maps) else "map.csv"
    config = os.path.join(ROOT, "examples", "toy-top.toml")
    t = np.linspace(0.0, 4.0, 9)
    decay = 200.0 * np.exp(-0.1 * t)
    parts = [{"shape": "cylinder", "radius": 0.02, "height": 0.01, "z0": 0.02, "density": 7800.0},
             {"shape": "cone", "radius": 0.005, "height": 0.02, "apex": "down", "density": 1000.0}]
    motion = dict(spin=200.0, theta0=0.05, phi0=0.0, theta_rate0=0.0, phi_rate0=0.0)
    out = [
        Target("Body", heavytop.Body, ((1.0, 1.3, 2.0), dict(mass=1.0, length=1.0, gravity=1.0, transverse_damping=0.0,
                                                              axial_damping=0.0, friction=0.0, driven=False, offset_x=0.0,
                                                              offset_y=0.0, Ixy=0.0, Ixz=0.0, Iyz=0.0)), 3),
        Target("stability", heavytop.stability, ((top, 200.0), dict(spin_rpm=None, theta0=0.0, phi0=0.0, theta_rate0=0.0,
                                                                     phi_rate0=0.0, horizon=100.0, max_tilt=1.0)), 3),
        Target("simulate", heavytop.simulate, ((top, "nonlinear"), dict(**motion, t_end=0.05, samples=11, method=None,
                                                                         integrator=None, rtol=None, atol=None, step=None,
                                                                         order=None, max_steps=None)), 3),
        Target("simulate(linearized)", heavytop.simulate, ((top, "linearized"), dict(**motion, t_end=0.05, samples=11,
                                                                                      method="analytic"))),
        Target("compare", heavytop.compare, ((top,), dict(**motion, t_end=0.05, samples=11, rtol=None, atol=None)), 2),
        Target("sweep", heavytop.sweep, ((top, {"spin": [0.0, 100.0, 200.0]}), dict(**motion, nonlinear=False, horizon=1.0,
                                                                                     max_tilt=0.5, rtol=None, atol=None,
                                                                                     integrator=None)), 3),
        Target("read_map", heavytop.read_map, ((a_map,), {}), 2),
        Target("grid_values", heavytop.grid_values, ((0.0, 1.0, 5), {})),
        Target("lifetime", heavytop.lifetime, ((damped,), dict(**motion, horizon=1.0, max_tilt=1.0, rtol=None, atol=None,
                                                                max_steps=None)), 2),
        Target("fit_decay", heavytop.fit_decay, ((t, decay), dict(body=None, spin0=None)), 2),
        Target("precession", heavytop.precession, ((top, 0.3, 200.0), dict(spin_rpm=None)), 2),
        Target("body_from_parts", heavytop.body_from_parts, ((parts,), dict(gravity=9.81, folder=".")), 2),
        Target("body_report", heavytop.body_report, ((parts,), dict(gravity=9.81, folder="."))),
        Target("load", heavytop.load, ((config,), {}), 2),
        Target("rpm", heavytop.rpm, ((1000.0,), {})),
        Target("example_toy_top", heavytop.example_toy_top, ((), {}), 0.2),
        Target("example_motion", heavytop.example_motion, ((), {}), 0.2),
        Target("report", heavytop.report, ((top, os.path.join(scratch, "report")), dict(spin=200.0, theta0=0.05, t_end=0.1)), 0.1),
        # The pybind11 layer itself, below _api.py's conversions.
        Target("_core.stability", core.stability, ((top, 200.0), dict(theta0=0.0)), 2),
        Target("_core.simulate", core.simulate, ((top, "nonlinear"), dict(**motion, t_end=0.05, samples=11)), 2),
        Target("_core.read_map", core.read_map, ((a_map,), {})),
        Target("_core.grid_values", core.grid_values, ((0.0, 1.0, 5), {})),
        Target("_core.rad_per_s_from_rpm", core.rad_per_s_from_rpm, ((1000.0,), {})),
        Target("_core.assemble_parts", core.assemble_parts, (('[[body.part]]\nshape = "sphere"\nradius = 0.01\n'
                                                              'z0 = 0.01\ndensity = 1000.0\n', 9.81, "."), {})),
        Target("_core.load_configuration", core.load_configuration, ((config,), {})),
    ]
    if heavytop.HAS_DERIVE:
        out.append(Target("derive_rotations", heavytop.derive_rotations, ((), dict(order=1)), 0.1))
    return out


def draw(rng, valid, pool):
    floats, ints, strings, others = pool
    r = rng.random()
    if r < 0.35:
        return valid
    if r < 0.55:
        return rng.choice(floats)
    if r < 0.65:
        return rng.choice(ints)
    if r < 0.78:
        return rng.choice(strings)
    if r < 0.82 and isinstance(valid, float):  # a nearby number
        return valid * rng.choice([-1.0, 1e-300, 1e300, 1.0 + 2 ** -52, 0.0, 1e10, -1e-10])
    return rng.choice(others)


def make_case(rng, target, pool):
    args, kwargs = target.valid
    args = [draw(rng, a, pool) for a in args]
    kwargs = {k: draw(rng, v, pool) for k, v in kwargs.items()}
    r = rng.random()
    if r < 0.1 and args:
        args.pop(rng.randrange(len(args)))  # a positional argument missing
    elif r < 0.2 and kwargs:
        kwargs.pop(rng.choice(sorted(kwargs)))  # a keyword left at its default
    elif r < 0.25:
        kwargs[rng.choice(["bogus", "Spin", "spin ", "t_end", "x" * 100])] = draw(rng, 1.0, pool)
    elif r < 0.3 and args:
        kwargs.update({"body": args[0]})  # given twice
    elif r < 0.33:
        args.append(draw(rng, 1.0, pool))  # one positional too many
    return args, kwargs


def short(value, limit=120):
    try:
        text = repr(value)
    except Exception as e:  # noqa: BLE001 - a value whose repr raises is still shown
        text = f"<repr raised {type(e).__name__}>"
    return text if len(text) <= limit else text[:limit] + f"...({len(text)} chars)"


def child(seed, first, count, work, one):
    import numpy as np
    import heavytop
    warnings.simplefilter("ignore")
    os.chdir(work)
    scratch = os.path.join(work, "scratch")
    os.makedirs(scratch, exist_ok=True)
    pool = hostile_pool(np, heavytop, scratch)
    table = targets(heavytop, np, scratch)
    weights = [t.weight for t in table]

    def alarm(signum, frame):
        raise Slow()

    signal.signal(signal.SIGALRM, alarm)
    counts = {"returned": 0, "ValueError": 0, "TypeError": 0, "RuntimeError": 0, "slow": 0, "own": 0}
    findings = []
    current = os.path.join(work, "current")
    for i in range(first, first + count):
        rng = random.Random(f"{seed}:{i}")
        target = rng.choices(table, weights)[0]
        args, kwargs = make_case(rng, target, pool)
        case = f"case {i}: {target.name}({', '.join(short(a) for a in args)}" + \
               "".join(f", {k}={short(v)}" for k, v in kwargs.items()) + ")"
        with open(current, "w") as f:
            f.write(case + "\n")
        if one:
            print(case, flush=True)
        signal.setitimer(signal.ITIMER_REAL, CALL_LIMIT)
        try:
            try:
                target.fn(*args, **kwargs)
                outcome = "returned"
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
        except Slow:
            outcome = "slow"
        except KeyboardInterrupt:
            outcome = "slow"
        except OwnError:
            outcome = "own"  # the value's own exception, let through
        except (ValueError, TypeError, RuntimeError) as e:
            message = str(e)
            kind = "RuntimeError" if isinstance(e, RuntimeError) else "TypeError" if isinstance(e, TypeError) else "ValueError"
            outcome = kind
            if not message.strip() or "\n" in message or "\r" in message:
                findings.append(f"{case}: {type(e).__name__} not one line: {message[:400]!r}")
            if one:
                print(f"  {type(e).__name__}: {message}")
        except BaseException as e:  # noqa: BLE001 - any other exception is a finding
            outcome = "other"
            findings.append(f"{case}: {type(e).__name__}: {str(e)[:300]!r}")
            if one:
                print(f"  {type(e).__name__}: {e}")
        counts[outcome] = counts.get(outcome, 0) + 1
    with open(os.path.join(work, "result.json"), "w") as f:
        json.dump({"counts": counts, "findings": findings}, f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--case", type=int, help="run this one case in this process and show its outcome")
    parser.add_argument("--batch", type=int, default=200, help="cases per child interpreter")
    parser.add_argument("--child", nargs=3, metavar=("FIRST", "COUNT", "WORK"), help=argparse.SUPPRESS)
    options = parser.parse_args()
    if options.child:
        child(options.seed, int(options.child[0]), int(options.child[1]), options.child[2], False)
        return 0
    work = tempfile.mkdtemp(prefix="fuzz_python_")
    if options.case is not None:
        child(options.seed, options.case, 1, work, True)
        result = json.load(open(os.path.join(work, "result.json")))
        print(result)
        return 1 if result["findings"] else 0
    start = time.monotonic()
    totals, findings, first, children = {}, [], 0, 0
    while time.monotonic() - start < options.seconds:
        result_file = os.path.join(work, "result.json")
        if os.path.exists(result_file):
            os.remove(result_file)
        process = subprocess.Popen([sys.executable, os.path.abspath(__file__), "--seed", str(options.seed), "--child",
                                    str(first), str(options.batch), work], stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE)
        children += 1
        last, seen = None, time.monotonic()
        while process.poll() is None:
            time.sleep(0.2)
            try:
                now = open(os.path.join(work, "current")).read()
            except OSError:
                now = None
            if now != last:
                last, seen = now, time.monotonic()
            elif time.monotonic() - seen > WATCHDOG:
                process.kill()
                process.wait()
                findings.append(f"hang (no return, no Ctrl-C poll in {WATCHDOG:.0f} s): {now.strip()}")
                break
        stderr = process.stderr.read().decode(errors="replace")
        if not os.path.exists(os.path.join(work, "current")):
            print(f"fuzz_python: the child interpreter did not start a case (exit {process.returncode}): {stderr[-2000:]}")
            return 2
        if process.returncode != 0 and not (findings and findings[-1].startswith("hang")):
            case = open(os.path.join(work, "current")).read().strip()
            signal_name = signal.Signals(-process.returncode).name if process.returncode < 0 else f"exit {process.returncode}"
            findings.append(f"the interpreter died ({signal_name}) in {case}; stderr: {stderr[-600:]!r}")
        if os.path.exists(result_file):
            result = json.load(open(result_file))
            for k, v in result["counts"].items():
                totals[k] = totals.get(k, 0) + v
            findings += result["findings"]
            first += options.batch
        else:  # died or hung: go on after the case that did it
            first = int(open(os.path.join(work, "current")).read().split()[1].rstrip(":")) + 1
    calls = sum(totals.values())
    elapsed = time.monotonic() - start
    print(f"fuzz_python: seed {options.seed}, {elapsed:.0f} s, {calls} calls ({calls / elapsed:.0f}/s) in {children} "
          f"interpreters; outcomes {json.dumps(totals, sort_keys=True)}; findings {len(findings)}")
    for f in findings[:50]:
        print("  FINDING " + f.replace("\n", "\\n"))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())

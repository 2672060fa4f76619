#!/usr/bin/env python3
"""Two builds of one Google Benchmark program, run alternately on the same machine, their
medians side by side (a refactoring that should cost nothing, measured as it runs):

    bench/compare_medians.py BEFORE_BINARY AFTER_BINARY [--rounds 3] [--filter REGEX]
                             [--repetitions 3] [--min-time 0.2]

Each round runs BEFORE then AFTER (then AFTER then BEFORE in the next round, so neither
always goes first); every repetition of every round counts toward a benchmark's median of real
time (or CPU time, --clock cpu). Prints one row a benchmark: the two medians, their ratio AFTER / BEFORE, and the spread
(the largest over the smallest repetition) of each, then the machine (CPU model, cores, load).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys


def run(binary, args):
    command = [binary, "--benchmark_format=json", f"--benchmark_repetitions={args.repetitions}",
               f"--benchmark_min_time={args.min_time}"]
    if args.filter:
        command.append(f"--benchmark_filter={args.filter}")
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") == "aggregate":
            continue
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        times.setdefault(b["run_name"], []).append(b[args.clock + "_time"] * unit)
    return times


def machine():
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the end"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--repetitions", type=int, default=3)
    p.add_argument("--min-time", type=float, default=0.2)
    p.add_argument("--filter", default="")
    p.add_argument("--clock", choices=("real", "cpu"), default="real",
                   help="the benchmark's real time (its own measure) or its CPU time (less disturbed "
                        "by other work on a shared machine)")
    args = p.parse_args()
    samples = {"before": {}, "after": {}}
    for r in range(args.rounds):
        order = ("before", "after") if r % 2 == 0 else ("after", "before")
        for which in order:
            for name, times in run(getattr(args, which), args).items():
                samples[which].setdefault(name, []).extend(times)
    names = [n for n in samples["before"] if n in samples["after"]]
    width = max(len(n) for n in names)
    print(f"{'benchmark':{width}}  {'before':>11}  {'after':>11}  after/before  spread before, after")
    ratios = []
    for n in names:
        b, a = statistics.median(samples["before"][n]), statistics.median(samples["after"][n])
        if not (b > 0.0 and a > 0.0):  # a benchmark that skipped itself (an error) has no time
            print(f"{n:{width}}  (no time: skipped)")
            continue
        ratios.append(a / b)
        sb = max(samples["before"][n]) / min(samples["before"][n])
        sa = max(samples["after"][n]) / min(samples["after"][n])
        print(f"{n:{width}}  {b * 1e3:9.4f}ms  {a * 1e3:9.4f}ms  {a / b:12.3f}  {sb:.2f}, {sa:.2f}")
    print(f"median of the ratios: {statistics.median(ratios):.3f} over {len(ratios)} benchmarks, "
          f"{args.rounds} rounds x {args.repetitions} repetitions each, {args.clock} time")
    print(f"machine: {machine()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

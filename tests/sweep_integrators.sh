#!/usr/bin/env bash
# sweep --integrator (issue 14): auto (the batched Taylor integrator) and dopri5 (one point at
# a time, the old path) give the same nonlinear verdicts, except at points whose largest tilt
# is within the sampling's resolution of --max-tilt; taylor is auto bit for bit; dop853 agrees
# too; the splitting, and dop853 on a damped body, are refused before any row is written; a
# damped body goes through the Taylor integrator one point at a time, as auto.
source "$(dirname "$0")/harness.sh"

# The asymmetric plate (examples/asymmetric-plate.toml) over B/A and spin: both verdicts on the map.
plate=(--A 0.010 --B 0.015 --C 0.020 --mass 1 --gravity 9.81 --length 1.0193679918450561e-3 --theta0 1e-4)
grid=(--vary B/A=1.1:2.9:7 --vary spin=0.5:4:9 --model nonlinear --horizon 20 --max-tilt 0.5)
for i in auto taylor dopri5 dop853; do
  "$H" sweep "${plate[@]}" "${grid[@]}" --integrator "$i" --output "$i.csv"
  check "sweep --integrator $i exit 0" test $? -eq 0
done
check "taylor is auto, byte for byte" cmp -s auto.csv taylor.csv
check "auto and dopri5 agree away from max_tilt" python3 - "$H" auto.csv dopri5.csv dop853.csv "${plate[@]}" <<'PY'
import csv, math, subprocess, sys
h, auto, dopri5, dop853, plate = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
rows = {n: list(csv.DictReader(open(n))) for n in (auto, dopri5, dop853)}
assert len(rows[auto]) == 63
stable = sum(r["nonlinear"] == "1" for r in rows[auto])
assert 5 < stable < 58, stable  # both verdicts on the map
for k, r in enumerate(rows[auto]):
    for other in (dopri5, dop853):
        o = rows[other][k]
        assert {c: r[c] for c in r if c != "nonlinear"} == {c: o[c] for c in o if c != "nonlinear"}
        if r["nonlinear"] == o["nonlinear"]:
            continue
        # A differing verdict must sit on the threshold: the largest tilt of a densely sampled
        # run (dopri5, 1e-12) within 1e-3 rad of max_tilt (the sampling's resolution).
        base_b = float(plate[plate.index("--A") + 1])
        out = subprocess.run([h, "simulate", *plate, "--B", str(float(r["B/A"]) * base_b), "--spin", r["spin"],
                              "--model", "nonlinear", "--integrator", "dopri5", "--t-end", "20",
                              "--samples", "20001", "--format", "csv"], capture_output=True, text=True, check=True)
        tilt = max(math.acos(math.cos(float(s["theta"])) * math.cos(float(s["phi"])))
                   for s in csv.DictReader(out.stdout.splitlines()))
        assert abs(tilt - 0.5) < 1e-3, (k, r, other, tilt)
PY

# Refusals, before the header: exit 2, the key named, no output file.
"$H" sweep "${plate[@]}" "${grid[@]}" --integrator splitting --output refused.csv 2>err.txt
check "splitting refused, exit 2" test $? -eq 2
check "splitting refused names --integrator" grep -q -- "--integrator" err.txt
check "no file for the refused splitting" test ! -e refused.csv
"$H" sweep "${plate[@]}" "${grid[@]}" --integrator dop853 --transverse-damping 1e-4 >out.txt 2>err.txt
check "dop853 on a damped body refused, exit 2" test $? -eq 2
check "dop853 on a damped body names --integrator" grep -q -- "--integrator: dop853 integrates the conservative body" err.txt
check "nothing written to stdout for it" test ! -s out.txt

# A damped body: taylor (one point at a time, not batched) is auto byte for byte, and its
# verdicts are dopri5's away from max_tilt (here: everywhere).
for i in auto taylor dopri5; do
  "$H" sweep "${plate[@]}" "${grid[@]}" --transverse-damping 1e-4 --axial-damping 1e-5 --integrator "$i" --output "damped-$i.csv"
  check "damped sweep --integrator $i exit 0" test $? -eq 0
done
check "damped: taylor is auto, byte for byte" cmp -s damped-auto.csv damped-taylor.csv
check "damped: taylor's verdicts are dopri5's" cmp -s damped-auto.csv damped-dopri5.csv
finish

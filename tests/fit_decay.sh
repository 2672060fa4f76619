#!/usr/bin/env bash
# heavytop fit-decay as a user drives it: the example's fit, the [damping] section pasted back
# into a configuration (accepted, same values), rpm against rad/s, and bad data files refused
# with exit 2 naming the line, writing nothing.
source "$(dirname "$0")/harness.sh"
example="${EXAMPLES:?set EXAMPLES to the examples folder}/spin-decay.csv"

cat > body.toml <<'TOML'
[body]
A = 4.35e-5
B = 4.35e-5
C = 1.2e-5
mass = 0.06
length = 0.025
[damping]
transverse = 1.5e-6
TOML

"$H" fit-decay --config body.toml --data "$example" > fit.txt
check "fit-decay text exit 0" test $? -eq 0
"$H" fit-decay --config body.toml --data "$example" --format json --output fit.json
check "fit-decay json exit 0" test $? -eq 0
check "json keys and the generating values within 3 uncertainties" python3 - fit.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for k in ("axial", "friction", "spin0"):
    assert set(d[k]) >= {"value", "uncertainty"}, d[k]
    assert d[k]["fitted"] and not d[k]["at_bound"], d[k]
assert d["points"] == 56 and d["converged"] is True, d
assert 0.5 < d["rms_residual"] < 1.5, d["rms_residual"]   # the stated noise: 1 rad/s
for k, truth in (("axial", 2e-7), ("friction", 1e-5), ("spin0", 200.0)):
    assert abs(d[k]["value"] - truth) < 3 * d[k]["uncertainty"], (k, d[k], truth)
PY
check "text: values with uncertainties, the assumption, the section" bash -c "
  grep -q '^  axial damping  d_a  = .* +- .* N m s$' fit.txt &&
  grep -q '^Assumed: the law C w. = -d_a w - tau0 sign(w) of a free spin (no motor) of a symmetric body (A = B), C from the body' fit.txt &&
  grep -q '^\[damping\]$' fit.txt && grep -q '^transverse = 1.5e-06$' fit.txt"

# Paste the section into the configuration in place of its own [damping]: accepted by every
# command's configuration reader, and read back as the fitted values exactly.
{ sed '/^\[damping\]/,$d' body.toml; sed -n '/^\[damping\]/,$p' fit.txt; } > pasted.toml
"$H" stability --config pasted.toml --format json > /dev/null
check "pasted configuration accepted" test $? -eq 0
check "pasted values are the fit's" python3 - pasted.toml fit.json <<'PY'
import json, sys, tomllib
c = tomllib.load(open(sys.argv[1], "rb"))["damping"]
d = json.load(open(sys.argv[2]))
assert c == {"transverse": 1.5e-6, "axial": d["axial"]["value"], "friction": d["friction"]["value"]}, (c, d)
PY

# The same data in rpm: the same fit (to rounding of the conversion).
python3 - "$example" > rpm.csv <<'PY'
import math, sys
for line in open(sys.argv[1]):
    if line.startswith("#"): continue
    if line.startswith("t,"): print("spin_rpm,t"); continue
    t, w = line.strip().split(",")
    print(f"{float(w) * 30 / math.pi!r},{t}")
PY
"$H" fit-decay --config body.toml --data rpm.csv --format json > rpm.json
check "rpm columns give the same fit" python3 - fit.json rpm.json <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
for k in ("axial", "friction", "spin0"):
    assert abs(a[k]["value"] - b[k]["value"]) <= 1e-9 * abs(a[k]["value"]), (k, a[k], b[k])
PY

# Bad data: exit 2, one line naming the line, no output file, an existing one unchanged.
bad() {  # NAME EXPECTED-MESSAGE CSV-CONTENT
  printf '%b' "$3" > bad.csv
  rm -f out.txt
  "$H" fit-decay --data bad.csv --output out.txt 2> err.txt
  local rc=$?
  check "$1: exit 2" test $rc -eq 2
  check "$1: message" grep -qx "heavytop: error: $2" err.txt
  check "$1: one line" test "$(wc -l < err.txt)" -eq 1
  check "$1: no output file" test ! -e out.txt
}
bad "not a number" "data: line 7: spin 'x' is not a number" "# c\nt,spin\n0,200\n1,190\n2,180\n3,170\n4,x\n"
bad "nan" "data: line 4: spin must be a finite number" "t,spin\n0,200\n1,190\n2,nan\n3,1\n"
bad "t decreasing" "data: line 5: t = 1.5 is before the previous line's 2 (t must not decrease)" "t,spin\n0,200\n1,190\n2,180\n1.5,170\n"
bad "negative spin" "data: line 3: the spin must be >= 0 (its magnitude)" "t,spin\n0,200\n1,-190\n2,180\n3,170\n"
bad "no header" "data: line 1: unknown column '0' (the header names t and spin (rad/s) or spin_rpm (rpm))" "0,200\n1,190\n"
bad "field count" "data: line 3: 3 fields, the header has 2" "t,spin\n0,200\n1,190,3\n"
bad "too few points" "data: 3 points; at least 4 are needed" "t,spin\n0,200\n1,190\n2,180\n"
bad "every spin 0" "data: every spin is 0: there is no decay to fit" "t,spin\n0,0\n1,0\n2,0\n3,0\n"

echo keep > out.txt
"$H" fit-decay --data missing.csv --output out.txt 2> err.txt
check "missing file: exit 2" test $? -eq 2
check "missing file: message" grep -qx "heavytop: error: --data: cannot read 'missing.csv': no such file" err.txt
check "existing output unchanged" test "$(cat out.txt)" = keep
"$H" fit-decay 2> err.txt
check "no --data: exit 2" test $? -eq 2
"$H" fit-decay --data "$example" --known-spin0 -1 2> err.txt
check "--known-spin0 -1: exit 2" test $? -eq 2
check "--known-spin0 message" grep -qx "heavytop: error: --known-spin0: must be a finite number > 0" err.txt
printf 't,spin\n0,200\n1,190\n2,180\n' > three.csv
"$H" fit-decay --data three.csv --known-spin0 200 --format json > known.json
check "three points suffice with a known spin0" python3 -c '
import json; d = json.load(open("known.json")); assert d["spin0"] == {"value": 200.0, "uncertainty": 0.0, "fitted": False, "at_bound": False}, d'
"$H" fit-decay --config body.toml --data "$example" --axial 1 2> err.txt
check "unknown option: exit 2" test $? -eq 2
finish

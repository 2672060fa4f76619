#!/usr/bin/env bash
# The command line as scripts use it (SPEC sections 1, 4, 5): exit codes, one-line errors
# naming the key, no file written on bad input, SPEC's JSON keys and CSV columns.
source "$(dirname "$0")/harness.sh"

cat > ok.toml <<'TOML'
[body]
A = 1.0
B = 1.0
C = 2.0
mass = 1.0
gravity = 1.0
length = 1.0
[motion]
spin = 3.0
TOML

# ---- stability --format json: SPEC keys, and C^2 w0^2 = 4 A m g R gives w0 = 1 --------------
"$H" stability --config ok.toml --format json > out.json
check "stability json exit 0" test $? -eq 0
check "stability json keys" python3 - out.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert set(d["body"]) == {"A", "B", "C", "mass", "gravity", "length"}
assert d["spin"] == 3.0
for m in ("first-order", "body-fixed", "linearized"):
    e = d["models"][m]
    for k in ("stable", "critical_spin", "stable_spin_intervals", "eigenvalues"):
        assert k in e, (m, k)
    assert len(e["eigenvalues"]) == 4 and all(len(p) == 2 for p in e["eigenvalues"])
    if e["stable"]:
        f = e["frequencies"]
        assert f == sorted(f) and len(set(f)) == len(f)
assert abs(d["models"]["first-order"]["critical_spin"] - 1.0) < 1e-12
assert d["models"]["first-order"]["stable_spin_intervals"] == [[1.0, None]]
assert d["models"]["body-fixed"]["critical_spin"] is not None
PY

# Options override the file; hanging body stable at every spin -> critical 0, interval [0, null].
"$H" stability --config ok.toml --length -1 --format json > hang.json
check "hanging body critical 0" python3 -c '
import json; d = json.load(open("hang.json"))
assert d["body"]["length"] == -1.0
assert d["models"]["first-order"]["critical_spin"] == 0.0
assert d["models"]["first-order"]["stable_spin_intervals"] == [[0.0, None]]'

# ---- SPEC 7: the Lyapunov verdict beside "models", and the wander ----------------------------
crit=(--A 1 --B 1 --C 2 --mass 1 --gravity 1 --length 1 --spin 1 --theta0 1e-3)
"$H" stability "${crit[@]}" --format json > lyap.json
check "lyapunov at the boundary of (9): critical-quartic, wander 2 asin(sqrt(sin(delta/2)))" python3 -c '
import json, math; d = json.load(open("lyap.json"))
assert list(d)[-2:] == ["lyapunov", "wander"], list(d)
l = d["lyapunov"]
assert list(l) == ["verdict", "certificate", "energy_index", "stable_spin_intervals", "superfast_spin", "normal_form"], l
assert l == {"verdict": "stable", "certificate": "critical-quartic", "energy_index": 0,
             "stable_spin_intervals": [[1.0, None]], "superfast_spin": 1.0, "normal_form": None}, l
assert d["models"]["first-order"]["stable"] is False   # the linear model grows (E2)
w = d["wander"]
assert w["method"] == "closed form" and w["horizon"] is None, w
assert abs(w["max_tilt"] - 2 * math.asin(math.sqrt(math.sin(5e-4)))) < 1e-12, w'
"$H" stability "${crit[@]}" > lyap.txt
check "lyapunov text: the proof, the boundary, the wander" bash -c '
grep -q "^  Lyapunov: stable (proof: " lyap.txt && grep -q "the linear models grow" lyap.txt &&
grep -q "^  Axis wander from the given state: largest tilt 0.0447251 rad (closed form)" lyap.txt'
rm -f lyap.txt
hang_asym=(--A 1 --B 1.2 --C 0.7 --mass 1 --gravity 1 --length -1 --theta0 1e-4)
"$H" stability "${hang_asym[@]}" --spin 2 --horizon 20 --format json > kam.json
check "index 2, linearly stable, A != B: stable by Arnold (kam), the normal form; [0, sqrt 2) and above sqrt(1/0.3) proven" python3 -c '
import json; d = json.load(open("kam.json")); l = d["lyapunov"]
assert d["models"]["linearized"]["stable"] is True
assert (l["verdict"], l["certificate"], l["energy_index"], l["superfast_spin"]) == ("stable", "kam", 2, None), l
assert l["stable_spin_intervals"][0] == [0.0, 2 ** 0.5] and abs(l["stable_spin_intervals"][1][0] - (1 / 0.3) ** 0.5) < 1e-12, l
assert l["stable_spin_intervals"][1][1] is None, l
n = l["normal_form"]; assert set(n) == {"frequencies", "c20", "c11", "c02", "D", "resonance", "a13"}, n
w1, w2 = n["frequencies"]; assert abs(n["D"] - (n["c20"] * w2 ** 2 + n["c11"] * w1 * w2 + n["c02"] * w1 ** 2)) < 1e-12 * abs(n["D"]), n
assert n["resonance"] is None and n["a13"] is None, n
w = d["wander"]; assert w["method"] == "integrated" and w["horizon"] == 20.0 and 1e-4 <= w["max_tilt"] < 1.2e-4, w'
rm -f kam.json
check "kam text: the proof holds for perturbations small enough, the distance to a resonance" bash -c "'$H' stability ${hang_asym[*]} --spin 2 --horizon 20 > kam.txt && grep -q 'Lyapunov: stable (proof (for perturbations small enough): Arnold' kam.txt && grep -q 'holds for perturbations small enough' kam.txt && grep -q 'from the nearest resonance that matters' kam.txt"
rm -f kam.txt
check "odd index" bash -c "'$H' stability ${hang_asym[*]} --spin 1.6 --horizon 5 --format json | python3 -c 'import json,sys; l = json.load(sys.stdin)[\"lyapunov\"]; assert (l[\"verdict\"], l[\"certificate\"], l[\"energy_index\"]) == (\"unstable\", \"odd-index\", 1), l'"

# No spin stabilises the body-fixed model of a sphere-like body: critical_spin null.
"$H" stability --config ok.toml --A 2 --B 2 --C 2 --format json > sphere.json
check "A=B=C body-fixed never stable" python3 -c '
import json; d = json.load(open("sphere.json"))
assert d["models"]["body-fixed"]["critical_spin"] is None
assert d["models"]["body-fixed"]["stable_spin_intervals"] == []'

# ---- bad input: exit 2, one line naming the key, no file created or changed -----------------
refused() {  # refused KEY ARGS... : exit 2, one stderr line containing KEY, --output untouched
  local key=$1; shift
  echo "previous content" > keep.txt
  "$H" "$@" --output new.out 2> err.txt > /dev/null; local code=$?
  "$H" "$@" --output keep.txt 2> /dev/null > /dev/null
  [ $code -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -qF -- "$key" err.txt &&
    [ ! -e new.out ] && [ "$(cat keep.txt)" = "previous content" ] &&
    [ -z "$(ls -A | grep -v -e '^ok.toml$' -e '^keep.txt$' -e '^err.txt$' -e '\.json$' -e '\.toml$' -e '\.csv$')" ] ||
    { echo "  $* -> exit $code: $(cat err.txt)"; return 1; }
}
for cmd in stability simulate; do
  check "$cmd A > 0" refused body.A $cmd --config ok.toml --A 0
  check "$cmd B > 0" refused body.B $cmd --config ok.toml --B -1
  check "$cmd C > 0" refused body.C $cmd --config ok.toml --C 0
  check "$cmd mass > 0" refused body.mass $cmd --config ok.toml --mass -1
  check "$cmd mass NaN" refused body.mass $cmd --config ok.toml --mass nan
  check "$cmd gravity >= 0" refused body.gravity $cmd --config ok.toml --gravity -9.81
  check "$cmd gravity finite" refused body.gravity $cmd --config ok.toml --gravity inf
  check "$cmd length finite" refused body.length $cmd --config ok.toml --length nan
  check "$cmd A + B >= C" refused body.C $cmd --config ok.toml --C 2.5
  check "$cmd B + C >= A" refused body.A $cmd --config ok.toml --A 3.5
  check "$cmd C + A >= B" refused body.B $cmd --config ok.toml --B 3.5
  check "$cmd spin finite" refused motion.spin $cmd --config ok.toml --spin nan
  check "$cmd missing config" refused -- --config $cmd --config missing.toml
  check "$cmd bad format" refused --format $cmd --config ok.toml --format xml
  check "$cmd unknown option" refused --frobnicate $cmd --config ok.toml --frobnicate 1
done

printf '[body]\nA = 1.0\nB = 1.0\nC = 2.0\nmass = -1.0\nlength = 1.0\n' > neg.toml
check "stability --horizon is checked" refused horizon stability --config ok.toml --horizon 0
check "negative mass in file" refused body.mass stability --config neg.toml
printf '[body]\nA = 1.0\nB = 1.0\nC = 2.0\nmass = 1.0\nlength = 1.0\ncolour = 3\n' > unknown_key.toml
check "unknown key" refused body.colour stability --config unknown_key.toml
printf '[body]\nA = 1.0\nB = 1.0\nC = 2.0\nmass = 1.0\nlength = 1.0\n[extras]\nx = 1\n' > unknown_section.toml
check "unknown section" refused extras stability --config unknown_section.toml
printf '[body]\nA = 1.0\nB = 1.0\nC = 2.0\nmass = 1.0\n' > missing_key.toml
check "missing length" refused body.length stability --config missing_key.toml
printf '[body]\nA = 1.0\nB = "one"\nC = 2.0\nmass = 1.0\nlength = 1.0\n' > string.toml
check "string value" refused body.B stability --config string.toml
printf '[body]\nA = 1.0\nB = = 1\n' > malformed.toml
check "malformed TOML" refused malformed.toml stability --config malformed.toml
check "samples >= 2" refused --samples simulate --config ok.toml --samples 1
check "t-end > 0" refused --t-end simulate --config ok.toml --t-end 0
check "unknown model" refused --model simulate --config ok.toml --model quadratic
check "rtol > 0" refused --rtol simulate --config ok.toml --rtol -1
check "step > 0" refused --step simulate --config ok.toml --integrator splitting --step 0
check "order 2 or 4" refused --order simulate --config ok.toml --integrator splitting --order 3
check "integrator for nonlinear only" refused --integrator simulate --config ok.toml --model first-order --integrator splitting
check "lagrange-exact needs A = B" refused body.B simulate --config ok.toml --model lagrange-exact --B 1.5

# gravity is optional and defaults to 9.81; integer values are numbers too.
printf '[body]\nA = 1\nB = 1\nC = 2\nmass = 1\nlength = 1\n' > nogravity.toml
"$H" stability --config nogravity.toml --format json > g.json
check "gravity defaults to 9.81" python3 -c '
import json; d = json.load(open("g.json")); assert d["body"]["gravity"] == 9.81
assert abs(d["models"]["first-order"]["critical_spin"] - 9.81 ** 0.5) < 1e-12'

# ---- simulate --format csv: header, N rows at t_i = i T / (N - 1) ---------------------------
for model in first-order body-fixed linearized nonlinear lagrange-exact; do
  "$H" simulate --config ok.toml --theta0 0.01 --model $model --t-end 2 --samples 5 --format csv --output $model.csv
  check "simulate $model exit 0" test $? -eq 0
  check "simulate $model csv" python3 - $model.csv <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
assert rows[0][:5] == ["t", "theta", "phi", "theta_rate", "phi_rate"], rows[0]
assert len(rows) == 6
for i, r in enumerate(rows[1:]):
    assert abs(float(r[0]) - i * 2 / 4) < 1e-15
assert abs(float(rows[1][1]) - 0.01) < 1e-15 and abs(float(rows[1][2])) < 1e-15
PY
done
# The splitting integrator and the exact solution agree on a symmetric top.
"$H" simulate --config ok.toml --theta0 0.3 --model nonlinear --integrator splitting --order 4 --step 1e-3 --t-end 5 --samples 6 > split.csv
"$H" simulate --config ok.toml --theta0 0.3 --model lagrange-exact --t-end 5 --samples 6 > exact.csv
check "splitting agrees with lagrange-exact" python3 -c '
import csv
a = list(csv.reader(open("split.csv"))); b = list(csv.reader(open("exact.csv")))
assert a[0][5:] == ["tilt", "azimuth", "energy", "vertical_momentum", "axial_momentum", "energy_drift", "vertical_momentum_drift", "axial_momentum_drift"]
assert max(abs(float(x) - float(y)) for ra, rb in zip(a[1:], b[1:]) for x, y in zip(ra[1:3], rb[1:3])) < 1e-9'
# Damping and friction (SPEC 6) and the lifetime (SPEC 8).
for cmd in stability simulate lifetime; do
  check "$cmd transverse damping >= 0" refused damping.transverse $cmd --config ok.toml --transverse-damping -1
  check "$cmd axial damping finite" refused damping.axial $cmd --config ok.toml --axial-damping nan
  check "$cmd friction >= 0" refused damping.friction $cmd --config ok.toml --friction -0.1
done
{ cat ok.toml; printf '[damping]\naxial = -2e-7\n'; } > neg_damping.toml
check "damping key in the file" refused damping.axial stability --config neg_damping.toml
{ cat ok.toml; printf 'driven = 1\n'; } > bad_driven.toml
check "driven must be a boolean" refused motion.driven stability --config bad_driven.toml
{ cat ok.toml; printf '[damping]\ndrag = 1\n'; } > unknown_damping.toml
check "unknown damping key" refused damping.drag stability --config unknown_damping.toml
check "splitting refuses damping" refused --integrator simulate --config ok.toml --model nonlinear --integrator splitting --axial-damping 0.1
check "lagrange-exact refuses damping" refused --model simulate --config ok.toml --model lagrange-exact --friction 0.1
check "the closed form refuses drag" refused --method simulate --config ok.toml --model first-order --method analytic --transverse-damping 0.1
check "lifetime max-tilt in (0, pi]" refused --max-tilt lifetime --config ok.toml --max-tilt 4
check "lifetime horizon > 0" refused --horizon lifetime --config ok.toml --horizon -1
"$H" stability --transverse-damping 1e-6 --format json > damped.json
check "damped stability: growth rates, KTC (no stable spin), the damping object" python3 - damped.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["damping"] == {"transverse": 1e-6, "axial": 0.0, "friction": 0.0, "driven": False}, d["damping"]
for name, m in d["models"].items():
    assert not m["stable"] and m["growth_rate"] > 0 and m["stable_spin_intervals"] == [] and m["critical_spin"] is None, (name, m)
    assert abs(m["growth_rate"] - max(e[0] for e in m["eigenvalues"])) <= 1e-15
PY
"$H" stability --format json > undamped.json
check "undamped stability: growth_rate 0 when stable, no damping object" python3 -c '
import json; d = json.load(open("undamped.json")); assert "damping" not in d
assert all(m["growth_rate"] == 0 for m in d["models"].values() if m["stable"])'
"$H" lifetime --axial-damping 2e-7 --theta0 0.01 --format json > life.json
"$H" lifetime --axial-damping 2e-7 --theta0 0.01 > life.txt
check "lifetime json: the toy top's time to critical by the law, the fall after it" python3 - life.json <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
C, A, mgR, w0 = 1.2e-5, 4.35e-5, 0.06 * 9.81 * 0.025, 200.0
wc = 2 * math.sqrt(A * mgR) / C
assert abs(d["spin_decay"]["critical_spin"] - wc) < 1e-9 * wc
t = C / 2e-7 * math.log(w0 / wc)
assert abs(d["spin_decay"]["time_to_critical"] - t) < 1e-12 * t
assert d["horizon"] == 10 * d["spin_decay"]["time_to_critical"]
f = d["fall"]
assert f["max_tilt"] == 1.0 and f["time"] > t and f["spin"] < wc
assert abs(f["spin"] - w0 * math.exp(-2e-7 * f["time"] / C)) < 1e-9 * w0
PY
check "lifetime text: one line for the critical spin, one for the fall" bash -c "grep -c 'reaches the critical spin 133.344 rad/s' life.txt | grep -qx 1 && grep -q 'The top falls (tilt past 1 rad) at t = ' life.txt"
"$H" simulate --model nonlinear --driven true --axial-damping 1e-7 --transverse-damping 1e-7 --t-end 2 --samples 3 > driven.csv
check "driven: the motor_torque column, the spin held" python3 -c '
import csv; r = list(csv.reader(open("driven.csv"))); h = r[0]
assert h[-4:] == ["dissipated_work", "vertical_momentum_loss", "axial_momentum_loss", "motor_torque"], h
assert all(abs(float(x[h.index("motor_torque")]) - 2e-5) < 1e-18 for x in r[1:])'
# --integrator taylor takes a [damping] section (issue 14): dopri5's columns, its numbers to 1e-9.
{ cat ok.toml; printf '[damping]\ntransverse = 0.01\naxial = 0.02\nfriction = 0.05\n'; } > damped.toml
"$H" simulate --config damped.toml --model nonlinear --integrator taylor --theta0 0.1 --t-end 2 --samples 5 > damped-taylor.csv
"$H" simulate --config damped.toml --model nonlinear --integrator dopri5 --theta0 0.1 --t-end 2 --samples 5 > damped-dopri5.csv
check "taylor with [damping]: dopri5's columns and values" python3 - damped-taylor.csv damped-dopri5.csv <<'PY'
import csv, sys
a, b = (list(csv.reader(open(n))) for n in sys.argv[1:])
assert a[0] == b[0] and a[0][-3:] == ["dissipated_work", "vertical_momentum_loss", "axial_momentum_loss"], a[0]
assert float(a[-1][a[0].index("dissipated_work")]) > 1e-3  # something was dissipated
for x, y in zip(a[1:], b[1:]):
    assert all(abs(float(u) - float(v)) < 1e-9 for u, v in zip(x, y)), (x, y)
PY
# A damped body's report says how long it stays up: the lifetime command's JSON, and its figure.
"$H" report --axial-damping 2e-7 --theta0 0.01 --output damped-report > /dev/null 2>&1
check "damped report: lifetime.json is the lifetime command's, with its figure" bash -c \
  "cmp -s damped-report/lifetime.json life.json && test -s damped-report/lifetime.png && grep -q 'How long does it stay up' damped-report/report.html"
rm -rf damped-report
check "no temporary files left" test -z "$(ls -A | grep tmp)"

finish

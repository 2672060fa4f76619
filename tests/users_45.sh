#!/usr/bin/env bash
# What a teacher and a toy maker could not do (issue 45): angles typed in degrees beside rad
# (--theta0-deg, --phi0-deg, --max-tilt-deg, precession --tilt-deg, [motion] theta0_deg), the
# same bytes as the rad they stand for; `body` gives the minimum spin in rpm; `stability --brief`
# gives the answer alone; [[body.part]] in millimetres on every shape, and a warning when a body
# is too heavy or too large for a top (mm typed as m).
examples=$(realpath "$(dirname "$0")/../examples")
source "$(dirname "$0")/harness.sh"
refused() {  # refused PATTERN CMD...: exit 2, one line matching PATTERN, nothing on stdout
  local pattern=$1; shift
  "$H" "$@" > out 2> err
  [ $? -eq 2 ] && [ "$(wc -l < err)" -eq 1 ] && grep -Eq -- "$pattern" err && [ ! -s out ]
}
same() {  # same "ARGS IN DEGREES" "ARGS IN RAD": both exit 0 and write the same bytes, stderr too
  # shellcheck disable=SC2086
  "$H" $1 > deg.out 2> deg.err && "$H" $2 > rad.out 2> rad.err && [ -s deg.out ] && cmp -s deg.out rad.out &&
    cmp -s deg.err rad.err
}
# 30 and 40 degrees in rad as Python's math.radians gives them (repr: the same double read back).
r30=0.5235987755982988
r40=0.6981317007977318
r5=0.08726646259971647
check "python agrees on the doubles" python3 -c "
import math
assert repr(math.radians(30)) == '$r30' and repr(math.radians(40)) == '$r40' and repr(math.radians(5)) == '$r5'"

# ---- 1. angles in degrees -------------------------------------------------------------------
check "simulate --theta0-deg 30 is --theta0 $r30, byte for byte" \
  same "simulate --model nonlinear --t-end 0.5 --samples 51 --theta0-deg 30" \
       "simulate --model nonlinear --t-end 0.5 --samples 51 --theta0 $r30"
check "... --phi0-deg too" \
  same "simulate --model linearized --t-end 0.5 --samples 11 --phi0-deg 5 --format json" \
       "simulate --model linearized --t-end 0.5 --samples 11 --phi0 $r5 --format json"
check "stability --theta0-deg 30 --max-tilt-deg 40" \
  same "stability --theta0-deg 30 --max-tilt-deg 40 --horizon 5 --format json" \
       "stability --theta0 $r30 --max-tilt $r40 --horizon 5 --format json"
check "compare --theta0-deg" \
  same "compare --theta0-deg 5 --t-end 1 --samples 101 --format json" "compare --theta0 $r5 --t-end 1 --samples 101 --format json"
check "lifetime --theta0-deg --max-tilt-deg" \
  same "lifetime --axial-damping 2e-7 --theta0-deg 5 --max-tilt-deg 40 --horizon 5 --format json" \
       "lifetime --axial-damping 2e-7 --theta0 $r5 --max-tilt $r40 --horizon 5 --format json"
check "sweep --theta0-deg --max-tilt-deg" \
  same "sweep --vary spin=100:300:3 --model nonlinear --horizon 2 --theta0-deg 5 --max-tilt-deg 40" \
       "sweep --vary spin=100:300:3 --model nonlinear --horizon 2 --theta0 $r5 --max-tilt $r40"
check "sweep refuses --max-tilt-deg without --model nonlinear" \
  refused "^heavytop: error: --max-tilt-deg: sets the nonlinear verdict" sweep --vary spin=0:1:3 --max-tilt-deg 40
check "precession --tilt-deg 30 is --tilt $r30" same "precession --tilt-deg 30" "precession --tilt $r30"
check "... in JSON too" same "precession --tilt-deg 30 --format json" "precession --tilt $r30 --format json"
for cmd in simulate stability compare sweep report lifetime precession explore; do
  check "$cmd --help lists --theta0-deg" bash -c "'$H' $cmd --help | grep -Eq -- '--theta0-deg[ ,]'"
done
for cmd in stability lifetime sweep explore; do
  check "$cmd --help lists --max-tilt-deg" bash -c "'$H' $cmd --help | grep -q -- '--max-tilt-deg NUM'"
done

# In the file: theta0_deg, phi0_deg beside theta0, phi0.
printf '[body]\nA = 1.2e-4\nB = 1.2e-4\nC = 4e-5\nmass = 0.1\nlength = 0.03\n[motion]\nspin = 300\ntheta0_deg = 30\nphi0_deg = 5\n' > deg.toml
printf '[body]\nA = 1.2e-4\nB = 1.2e-4\nC = 4e-5\nmass = 0.1\nlength = 0.03\n[motion]\nspin = 300\ntheta0 = %s\nphi0 = %s\n' $r30 $r5 > rad.toml
check "[motion] theta0_deg = 30, phi0_deg = 5 are theta0 = $r30, phi0 = $r5" \
  same "stability --config deg.toml --horizon 5 --format json" "stability --config rad.toml --horizon 5 --format json"
check "... simulate reads them too" \
  same "simulate --config deg.toml --model nonlinear --t-end 0.2 --samples 21" \
       "simulate --config rad.toml --model nonlinear --t-end 0.2 --samples 21"
check "--theta0-deg overrides the file's theta0" \
  same "stability --config rad.toml --theta0-deg 5 --horizon 5 --format json" \
       "stability --config rad.toml --theta0 $r5 --horizon 5 --format json"
check "--theta0 overrides the file's theta0_deg" \
  same "stability --config deg.toml --theta0 $r5 --horizon 5 --format json" \
       "stability --config rad.toml --theta0 $r5 --horizon 5 --format json"

# Both units of one angle: refused naming both, nothing written.
check "--theta0 with --theta0-deg: exit 2 naming both" \
  refused "^heavytop: error: --theta0-deg: give --theta0 or --theta0-deg, not both$" stability --theta0 0.1 --theta0-deg 5 --output never.json
check "... no file written" test ! -e never.json
check "--max-tilt with --max-tilt-deg: exit 2 naming both" \
  refused "--max-tilt-deg: give --max-tilt or --max-tilt-deg, not both" lifetime --max-tilt 1 --max-tilt-deg 40
check "--tilt with --tilt-deg: exit 2 naming both" refused "--tilt-deg: give --tilt or --tilt-deg, not both" precession --tilt 0.3 --tilt-deg 30
printf '[body]\nA = 1\nB = 1\nC = 1.5\nmass = 1\nlength = 0.1\n[motion]\ntheta0 = 0.1\ntheta0_deg = 5\n' > both.toml
check "theta0 and theta0_deg in one file: exit 2 naming both" \
  refused "^heavytop: error: motion.theta0_deg: give theta0 or theta0_deg, not both$" stability --config both.toml --output never.json
check "... no file written" test ! -e never.json
check "spin and spin_rpm in one file: the message as before" \
  bash -c "printf '[motion]\nspin = 1\nspin_rpm = 2\n' > rpm.toml; '$H' simulate --config rpm.toml 2>&1 | grep -qx 'heavytop: error: motion.spin_rpm: give spin or spin_rpm, not both'"

# precession without a tilt names both ways of giving one (it named --tilt alone to one who typed --tilt-deg).
check "precession without a tilt: exit 2 naming --tilt and --tilt-deg" refused "^heavytop: error: --tilt: is required.*--tilt-deg" precession
check "precession --tilt-deg 0: the rule, naming --tilt-deg and the degrees" \
  refused "^heavytop: error: --tilt-deg: must be a finite angle in \(0, pi\) rad.*\(here 0 degrees, 0 rad\)$" precession --tilt-deg 0
check "--max-tilt-deg 200: the rule, naming --max-tilt-deg" \
  refused "^heavytop: error: --max-tilt-deg: must be in \(0, pi\] \(here 200 degrees, 3.49066 rad\)$" stability --max-tilt-deg 200
check "--theta0-deg nan: refused naming it" refused "^heavytop: error: --theta0-deg: must be a finite number" simulate --theta0-deg nan
check "body refuses --theta0-deg (it takes the body only)" refused "^heavytop: error: --theta0-deg: .*does not use the motion" body --theta0-deg 5

# ---- 2. body: the minimum spin in rad/s and rpm ---------------------------------------------
"$H" body > body.txt
"$H" lifetime --format json > life.json
check "body prints the minimum spin in rad/s and rpm, lifetime's critical spin" python3 -c "
import json, math, re
text = open('body.txt').read()
m = re.search(r'Minimum spin to stand upright \(the critical spin of the linearized model, without damping\): ([0-9.e+-]+) rad/s \(([0-9.e+-]+) rpm\)', text)
assert m, text
w, rpm = float(m.group(1)), float(m.group(2))
wc = json.load(open('life.json'))['spin_decay']['critical_spin']
A, C, mgR = 4.35e-5, 1.2e-5, 0.06 * 9.81 * 0.025  # the toy top: w_c = 2 sqrt(A m g R) / C
assert abs(w - wc) <= 1e-5 * wc and abs(wc - 2 * math.sqrt(A * mgR) / C) <= 1e-9 * wc, (w, wc)
assert abs(rpm - wc * 30 / math.pi) <= 1e-5 * rpm, (rpm, wc * 30 / math.pi)
assert 1273 < rpm < 1274, rpm  # 133.344 rad/s"
check "a hanging body needs no spin" bash -c "'$H' body --A 1 --B 1 --C 0.5 --mass 1 --length -0.5 | grep -q 'Minimum spin to stand upright: none needed'"
check "a general body has no minimum spin (the models refuse it)" bash -c "
printf '[body]\nA = 1\nB = 1\nC = 1.5\nmass = 1\nlength = 0.1\nIxy = 0.01\n' > general.toml
'$H' body --config general.toml > general.txt && grep -q 'NOT a body of the models' general.txt && ! grep -q 'Minimum spin' general.txt"
check "body's JSON is unchanged (no new key)" bash -c "'$H' body --format json | python3 -c '
import json, sys; assert \"critical_spin\" not in json.load(sys.stdin)'"

# ---- 3. stability --brief: the answer only ---------------------------------------------------
"$H" stability --theta0-deg 3 > full.txt
"$H" stability --theta0-deg 3 --brief > brief.txt
check "stability --brief is the text's first paragraph, nothing more" python3 -c "
full, brief = open('full.txt').read(), open('brief.txt').read()
assert brief == full.split('\n\n')[0] + '\n', brief
assert 'The details' not in brief and brief.startswith('Stays up'), brief"
check "--brief on a table: the table's answer" bash -c "
'$H' stability --contact frictionless --tip-radius 0.001 --horizon 2 > tfull.txt &&
'$H' stability --contact frictionless --tip-radius 0.001 --horizon 2 --brief > tbrief.txt &&
python3 -c \"full, brief = open('tfull.txt').read(), open('tbrief.txt').read(); assert brief == full.split('\n\n')[0] + '\n' and len(brief) < len(full)\""
check "--brief --format json: exit 2 naming --brief, nothing written" \
  refused "^heavytop: error: --brief: .*--format text only" stability --brief --format json --output never.json
check "... no file written" test ! -e never.json

# ---- 4. parts in millimetres ------------------------------------------------------------------
parts() {  # parts UNIT SCALE: a top of every shape, its lengths in UNIT (SCALE per m)
  python3 - "$1" "$2" <<'EOF'
import sys
unit, k = sys.argv[1], float(sys.argv[2])
def part(shape, **keys):
    s = f'[[body.part]]\nshape = "{shape}"\n'
    if unit == "mm": s += 'units = "mm"\n'
    for key, v in keys.items():
        s += f'{key} = {v * k!r}\n' if key in ("radius", "inner_radius", "height", "z0") else f'{key} = {v!r}\n'
    return s
print(part("cone", radius=0.02, height=0.02, density=700.0)
      + part("cylinder", radius=0.025, height=0.006, z0=0.02, mass=0.03)
      + part("tube", radius=0.025, inner_radius=0.02, height=0.004, z0=0.026, density=7800.0)
      + part("sphere", radius=0.004, z0=0.03, density=1200.0)
      + part("cylinder", radius=0.002, height=0.02, z0=0.034, density=700.0) + '[motion]\nspin = 300\n')
EOF
}
parts m 1 > top-m.toml
parts mm 1000 > top-mm.toml
parts m 1000 > top-slip.toml  # the same numbers as top-mm.toml, read as metres
check "units = \"mm\" on every shape is accepted" bash -c "'$H' body --config top-mm.toml --format json > mm.json 2> mm.err"
check "... and says nothing on stderr" test ! -s mm.err
"$H" body --config top-m.toml --format json > m.json
check "a body of parts in mm has the moments of the same in m (1e-12 relative)" python3 -c "
import json
a, b = json.load(open('mm.json')), json.load(open('m.json'))
for k in ('A', 'B', 'C', 'mass', 'length'):
    assert abs(a[k] - b[k]) <= 1e-12 * abs(b[k]), (k, a[k], b[k])
for p, q in zip(a['parts'], b['parts']):
    assert abs(p['mass'] - q['mass']) <= 1e-12 * q['mass'] and abs(p['centre_of_mass'][2] - q['centre_of_mass'][2]) <= 1e-12 * abs(q['centre_of_mass'][2])"
check "... stability agrees to the same (its verdict and critical spins)" bash -c "
'$H' stability --config top-mm.toml --horizon 2 --format json > smm.json && '$H' stability --config top-m.toml --horizon 2 --format json > sm.json &&
python3 -c \"
import json
a, b = json.load(open('smm.json')), json.load(open('sm.json'))
assert a['answer']['verdict'] == b['answer']['verdict']
for x, y in zip(a['models'].values(), b['models'].values()):
    assert (x['critical_spin'] is None) == (y['critical_spin'] is None)
    assert x['critical_spin'] is None or abs(x['critical_spin'] - y['critical_spin']) <= 1e-9 * y['critical_spin']\""
check "a bad size in mm is named as the part's key" refused "^heavytop: error: body.part\[0\].radius \(cone\): " body --config <(sed '0,/radius = 20.0/s//radius = -20.0/' top-mm.toml)

# mm typed as m: the body works out at thousands of tonnes; one warning line, exit 0, output as ever.
"$H" body --config top-slip.toml > slip.txt 2> slip.err
check "mm typed as m: exit 0 and the body printed" grep -q '^Body: A = ' slip.txt
check "... one warning line on stderr naming the mass, the size and the likely slip" bash -c "
[ \$(wc -l < slip.err) -eq 1 ] && grep -Eq '^heavytop: warning: a mass of [0-9.e+]+ kg and a radius of gyration about O of [0-9.]+ m is implausible for a hand-held top: sizes typed in mm as m\? .*units = \"mm\".*going on$' slip.err"
check "... the mass is the slip's (1e9 times the top's)" python3 -c "
import re, json
said = float(re.search(r'a mass of ([0-9.e+]+) kg', open('slip.err').read()).group(1))
m = json.load(open('m.json'))['mass']
# The part given by its mass keeps it; the others scale by 1e9.
assert 1e6 < said < 1e9 * m, (said, m)"
check "... every command says it, once" bash -c "'$H' stability --config top-slip.toml --spin 1e6 --horizon 1 > /dev/null 2> s.err; [ \$(grep -c 'implausible for a hand-held top' s.err) -eq 1 ]"
check "a body given by its moments, 200 kg: the warning too" bash -c "
'$H' stability --A 20 --B 20 --C 30 --mass 200 --length 0.1 --spin 10 --horizon 1 2>&1 > /dev/null | grep -q 'a mass of 200 kg is implausible'"
check "a length of 15 m: the warning names the size" bash -c "
'$H' body --A 2000 --B 2000 --C 1 --mass 1 --length 15 2>&1 > /dev/null | grep -q 'a radius of gyration about O of 44.7214 m is implausible'"
check "no warning for the examples" bash -c "
for ex in '$examples'/*.toml; do '$H' simulate --config \"\$ex\" --t-end 0.001 --samples 2 > /dev/null 2> e.err || exit 1; ! grep -q implausible e.err || exit 1; done"
check "... nor for bad input: the refusal alone" refused "^heavytop: error: body.A" body --A -1 --B 2000 --C 1 --mass 1000 --length 15

# A damped top started exactly upright (issue 45): not "stays up" without a word, but when its
# spin passes the critical spin (the spin law's closed form: 60 ln(207.08 / 183.344) = 7.304 s).
check "stability: exactly upright, damped, says when it becomes unstable" bash -c "
'$H' stability --spin-rpm 1500 --axial-damping 2e-7 --friction 1e-5 --theta0 0 | head -1 | grep -q 'only because it starts exactly upright.*below the critical spin at t = 7.304 s'"
check "lifetime: the same caveat" bash -c "
'$H' lifetime --spin-rpm 1500 --axial-damping 2e-7 --friction 1e-5 --theta0 0 | grep -q '^But only because it starts exactly upright: from t = 7.304 s'"

finish

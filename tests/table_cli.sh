#!/usr/bin/env bash
# The top on a table from the command line (SPEC section 16), as a user drives it: the columns,
# the answer's verdicts for the examples, the leaving event, every refusal naming its key with
# exit 2 and no file written, and the pivot unchanged by a shape key.
examples=$(realpath "$(dirname "$0")/../examples")
source "$(dirname "$0")/harness.sh"

# simulate: SPEC's seven columns, then the table's.
"$H" simulate --config "$examples/tippe-top.toml" --t-end 1 --samples 3 > tippe.csv
check "table columns" [ "$(head -1 tippe.csv)" = "t,theta,phi,theta_rate,phi_rate,tilt,azimuth,x,y,height,normal_force,slip_speed,spin,energy,jellett,vertical_momentum" ]
check "three rows" [ "$(wc -l < tippe.csv)" = 4 ]
# Jellett's integral is the same in every row (to the digits printed: 1e-9 relative).
check "jellett kept" python3 -c "
import csv, sys
rows = list(csv.DictReader(open('tippe.csv')))
j = [float(r['jellett']) for r in rows]
sys.exit(0 if max(abs(x - j[0]) for x in j) < 1e-9 * abs(j[0]) else 1)"

# stability: the answer for each example.
verdict() { "$H" stability --config "$examples/$1" --format json | python3 -c "import json,sys; print(json.load(sys.stdin)['answer']['verdict'])"; }
check "tippe top turns over" [ "$(verdict tippe-top.toml)" = "turns over" ]
check "rising top stays up" [ "$(verdict rising-top.toml)" = "stays up" ]
check "rising top text" bash -c "'$H' stability --config '$examples/rising-top.toml' | head -1 | grep -q '^Rises to vertical in 6.93 s and sleeps.'"
check "slow rising top falls" bash -c "'$H' stability --config '$examples/rising-top.toml' --spin 100 --format json | grep -q '\"verdict\": \"falls\"'"
"$H" stability --config "$examples/tippe-top.toml" --format json > tippe.json
check "table block" python3 -c "
import json, sys
d = json.load(open('tippe.json'))
t = d['table']
ok = t['contact'] == 'sliding' and t['upright']['stable'] is False and t['inverted']['asymptotically'] is True
ok = ok and abs(t['inverted']['critical_spin'] - 79.73004452526) < 1e-6 and 5.0 < d['answer']['table']['turns_over_at'] < 5.3
sys.exit(0 if ok else 1)"

# Coulomb's law at a point: the tippe top sticks and rolls, and does not turn over.
check "coulomb tippe top" bash -c "'$H' stability --config '$examples/tippe-top.toml' --friction-law coulomb --horizon 10 | head -1 | grep -q '^Stays up for the horizon.'"

# Leaving the table: a top without spin swinging up towards vertical so fast that its centre of
# mass, slowing near the top of its swing, drops faster than gravity pulls it: it hops at
# t = 0.006146 s (test_table's quadrature); the last row is then.
"$H" simulate --A 4.35e-5 --B 4.35e-5 --C 1.2e-5 --mass 0.06 --length 0.025 --contact frictionless \
  --theta0 0.3 --theta-rate0 -20 --t-end 1 --samples 11 > leave.csv 2> leave.err
check "leaves: exit 0" [ $? -eq 0 ]
check "leaves: said on stderr" grep -q "^heavytop: the body leaves the table at t = 0.006145549" leave.err
check "leaves: last row at the event" bash -c "tail -1 leave.csv | grep -q '^0.006145549'"
check "leaves: N = 0 there" python3 -c "
import csv, sys
rows = list(csv.DictReader(open('leave.csv')))
sys.exit(0 if abs(float(rows[-1]['normal_force'])) < 1e-9 and len(rows) == 2 else 1)"
"$H" simulate --A 4.35e-5 --B 4.35e-5 --C 1.2e-5 --mass 0.06 --length 0.025 --contact frictionless \
  --theta0 0.15 --theta-rate0 -20 --t-end 1 --samples 11 > leave0.csv 2> leave0.err
check "N < 0 at once: one row" [ "$(wc -l < leave0.csv)" = 2 ]
check "N < 0 at once: said" grep -q "leaves the table at t = 0 s" leave0.err

# Refusals: exit 2, one line naming the key, no file.
refuse() {  # refuse KEY ARGS...
  local key=$1; shift
  rm -f out.csv
  "$H" "$@" --output out.csv > /dev/null 2> err.txt
  local rc=$?
  [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" = 1 ] && grep -q -- "$key" err.txt && [ ! -e out.csv ]
}
printf '[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n[table]\ncontact = "pivot"\nfriction = 0.3\n' > pivot.toml
check "friction with a pivot" refuse table.friction stability --config pivot.toml
printf '[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n[table]\ncontact = "skating"\n' > skate.toml
check "unknown contact" refuse table.contact stability --config skate.toml
check "negative tip radius" refuse body.tip_radius simulate --contact sliding --tip-radius -1e-3
check "slip speed 0" refuse table.slip_speed simulate --contact sliding --slip-speed 0
check "negative friction" refuse table.friction simulate --contact sliding --table-friction -1
check "friction without sliding" refuse table.friction simulate --contact rolling --table-friction 0.3
check "linear model on a table" refuse table.contact simulate --contact rolling --model first-order
check "taylor on a table" refuse --integrator simulate --contact rolling --integrator taylor
check "rosenbrock4 on a pivot" refuse --integrator simulate --integrator rosenbrock4
# stability --max-steps: a run that stops early says how far it got and decides nothing.
"$H" stability --config "$examples/tippe-top.toml" --max-steps 2000 > stopped.txt
check "a stopped run: exit 0, Not decided" grep -q "^Not decided\. .*could be computed only to t = " stopped.txt
# A small slip speed makes the viscous law stiff: auto takes the implicit Rosenbrock 4 there (at
# a tolerance where it is the faster), the two methods agree, and the JSON says which ran.
"$H" simulate --config "$examples/tippe-top.toml" --slip-speed 1e-6 --rtol 1e-9 --atol 1e-9 --t-end 0.2 --samples 3 --format json > stiff-auto.json
"$H" simulate --config "$examples/tippe-top.toml" --slip-speed 1e-6 --rtol 1e-9 --atol 1e-9 --t-end 0.2 --samples 3 --integrator dop853 --format json > stiff-dop853.json
check "auto is rosenbrock4 when stiff" grep -q '"integrator":"rosenbrock4"' stiff-auto.json
check "dop853 when asked" grep -q '"integrator":"dop853"' stiff-dop853.json
check "the two agree to 1e-7 rad" python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in ('stiff-auto.json', 'stiff-dop853.json'))
sys.exit(0 if max(abs(x - y) for x, y in zip(a['tilt'], b['tilt'])) < 1e-7 else 1)"
# The body's own losses (docs/table.md): Contensou's law over Hertz's patch, the air on the
# parts, rolling resistance. The energy the loss columns book is the energy the body lost.
"$H" simulate --config "$examples/wooden-top-on-table.toml" --rolling-resistance 1e-4 --t-end 1 --samples 11 > losses.csv
check "loss columns" [ "$(head -1 losses.csv | cut -d, -f17-)" = "loss_sliding,loss_drilling,loss_rolling,loss_air" ]
check "the losses booked are the energy lost" python3 -c "
import csv
rows = list(csv.DictReader(open('losses.csv')))
e0 = float(rows[0]['energy'])
for r in rows[1:]:
    lost = e0 - float(r['energy'])
    booked = sum(float(r[k]) for k in ('loss_sliding', 'loss_drilling', 'loss_rolling', 'loss_air'))
    assert lost > 0 and abs(booked - lost) < 1e-6 * lost, (lost, booked)
assert all(float(rows[-1][k]) > 0 for k in ('loss_drilling', 'loss_rolling', 'loss_air'))"
"$H" stability --config "$examples/wooden-top-on-table.toml" --horizon 2 --format json > wooden.json
check "the spin-down takes the kinetic energy between the spins" python3 -c "
import json, math
d = json.load(open('wooden.json'))
s, C = d['answer']['table']['spin_down'], d['body']['C']
w0, wc = 3000 * math.pi / 30, s['critical_spin']
assert abs(wc - d['table']['upright']['critical_spin']) < 1e-9 * wc
assert 40 < s['time_to_critical'] < 60 and s['losses']['air'] > s['losses']['drilling'] > 0, s
taken = s['losses']['drilling'] + s['losses']['air']
assert abs(taken - 0.5 * C * (w0 ** 2 - wc ** 2)) < 1e-9 * taken, (taken, 0.5 * C * (w0 ** 2 - wc ** 2))"
check "spin-down in words" bash -c "'$H' stability --config '$examples/wooden-top-on-table.toml' --horizon 2 | head -1 | grep -q 'Asleep on this table it spins about 51.31 s before its spin falls to the critical 160.2 rad/s (1530 rpm)'"
# The upright's critical spin with the losses is the viscous law's closed form (docs/table.md).
check "critical spin: the closed form, free of mu" python3 -c "
import json, math, subprocess
def run(mu):
    return json.loads(subprocess.run(['$H', 'stability', '--config', '$examples/wooden-top-on-table.toml', '--table-friction',
                                      mu, '--horizon', '0.01', '--format', 'json'], capture_output=True, text=True).stdout)
d = run('0.3')
b = d['body']
m, l, r, C, g = b['mass'], b['length'], b['tip_radius'], b['C'], b['gravity']
Ag, a = b['A'] - m * l * l, r + l
closed = math.sqrt(m * g * l * a * a / (r * (C * a - Ag * r)))
for w in (d['table']['upright']['critical_spin'], run('0.03')['table']['upright']['critical_spin']):
    assert abs(w - closed) < 1e-12 * closed, (w, closed)"
check "contensou needs materials" refuse table.tip_material simulate --config "$examples/tippe-top.toml" --friction-law contensou
check "unknown material" refuse table.material simulate --config "$examples/tippe-top.toml" --friction-law contensou --tip-material abs --table-material granite
check "contensou needs a round tip" refuse body.tip_radius simulate --contact sliding --friction-law contensou --tip-material steel --table-material oak
check "air on a pivot" refuse table.air simulate --air true
check "rolling resistance under coulomb" refuse table.rolling_resistance simulate --config "$examples/tippe-top.toml" --friction-law coulomb --rolling-resistance 1e-4
printf '[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\ntip_radius = 5e-4\n[table]\ncontact = "sliding"\nfriction = 0.3\nair_density = 1.2\n' > thin-air.toml
check "air density without air" refuse table.air_density simulate --config thin-air.toml
# lifetime on a table: SPEC 8's keys from the spin-down asleep, and the motion over the horizon.
"$H" lifetime --config "$examples/wooden-top-on-table.toml" --horizon 2 --format json > wooden-life.json
check "lifetime on a table" python3 -c "
import json
life, s = json.load(open('wooden-life.json')), json.load(open('wooden.json'))['answer']['table']['spin_down']
assert life['spin_decay']['time_to_critical'] == s['time_to_critical'] and life['table']['spin_down'] == s, (life, s)
assert life['fall']['time'] is None and life['horizon'] == 2 and life['table']['verdict'] == 'stays up for the horizon'"
check "lifetime on a table falls" bash -c "'$H' lifetime --config '$examples/rising-top.toml' --spin 100 | head -1 | grep -q '^Falls after'"
check "damping on a table" refuse damping.axial simulate --contact sliding --axial-damping 1e-6
check "unknown law" refuse table.friction_law simulate --contact sliding --friction-law dry
check "flat rim" refuse motion.theta0 simulate --contact rolling --rim-radius 0.01 --theta0 0

# A shape key on a pivot changes nothing but the body's JSON.
"$H" simulate --t-end 0.1 --samples 3 > pivot.csv
"$H" simulate --t-end 0.1 --samples 3 --tip-radius 0.002 > pivot_tip.csv
check "pivot with a tip radius: same motion" cmp -s pivot.csv pivot_tip.csv

# A body of parts on a table falls where another part touches the table (SPEC 16), not at
# --max-tilt: a cone tip (height h) under a disc of radius R2 on a tip of radius r touches at
# atan2(h, R2) + asin(r / hypot(h, R2)), the disc's lower rim on the table.
cat > parts.toml <<'TOML'
[body]
tip_radius = 0.002
[[body.part]]
shape = "cone"
radius = 0.01
height = 0.03
z0 = 0.0
density = 700.0
[[body.part]]
shape = "cylinder"
radius = 0.035
height = 0.008
z0 = 0.03
density = 700.0
[motion]
spin = 30.0
theta0 = 0.1
[table]
contact = "sliding"
friction = 0.3
TOML
"$H" stability --config parts.toml --max-tilt 1.2 --format json > parts.json
check "a body of parts falls where its disc touches the table, not at --max-tilt" python3 -c "
import json, math
a = json.load(open('parts.json'))['answer']
touch = math.atan2(0.03, 0.035) + math.asin(0.002 / math.hypot(0.03, 0.035))
assert a['verdict'] == 'falls' and abs(a['table']['final_tilt'] - touch) < 1e-9 and abs(a['max_tilt'] - touch) < 1e-9, (a, touch)
assert 'where another of its parts touches the table' in a['reason'], a['reason']"
finish

#!/usr/bin/env bash
# Real bodies from the command line (SPEC sections 9, 10, 11): spins in rpm give the same JSON
# and CSV as in rad/s; a body from its parts and from meshes (STL binary and ASCII, OBJ, PLY,
# m and mm) gives the exact mass properties through every command; bad parts and the general
# body are refused naming the key (exit 2, nothing written); `precession` starts a steady
# precession that the nonlinear body keeps.
examples="$(cd "$(dirname "$0")/../examples" && pwd)"
source "$(dirname "$0")/harness.sh"

run() {
  local expected=$1; shift
  "$H" "$@" > out 2> err
  local rc=$?
  [ "$rc" -eq "$expected" ] || { echo "  exit $rc, expected $expected: $* :: $(head -c 300 err)"; return 1; }
}
says() { grep -q -- "$1" err || { echo "  stderr lacks '$1': $(cat err)"; return 1; }; }
one_line() { [ "$(wc -l < err)" -eq 1 ] || { echo "  not one line: $(cat err)"; return 1; }; }
py() { python3 -c "$1"; }

# ---- SPEC 9: rpm ----------------------------------------------------------------------------
# The rad/s value of 3000 rpm as heavytop computes it, printed to the last bit by its JSON.
w=$("$H" stability --spin-rpm 3000 --format json | py "import json,sys; print(repr(json.load(sys.stdin)['spin']))")
check "3000 rpm is 100 pi rad/s" py "import math; assert abs($w - 100*math.pi) < 1e-12, $w"
"$H" stability --spin-rpm 3000 --format json > rpm.json
"$H" stability --spin "$w" --format json > rad.json
check "stability: --spin-rpm and --spin give identical JSON" cmp rpm.json rad.json
for model in first-order linearized nonlinear; do
  "$H" simulate --model $model --spin-rpm 3000 --t-end 0.2 --samples 51 --format json > rpm.json
  "$H" simulate --model $model --spin "$w" --t-end 0.2 --samples 51 --format json > rad.json
  check "simulate $model: rpm and rad/s give identical JSON" cmp rpm.json rad.json
done
cat > rpm.toml <<'EOF'
[body]
A = 4.35e-5
B = 4.35e-5
C = 1.2e-5
mass = 0.06
length = 0.025
[motion]
spin_rpm = 3000
theta0 = 0.05
EOF
sed 's/^spin_rpm = 3000/spin = '"$w"'/' rpm.toml > rad.toml
"$H" stability --config rpm.toml --format json > a.json
"$H" stability --config rad.toml --format json > b.json
check "spin_rpm in [motion] is the same as spin" cmp a.json b.json
"$H" sweep --vary spin_rpm=0:3000:7 --output a.csv
"$H" sweep --vary spin=0:"$w":7 --output b.csv
check "sweep --vary spin_rpm: the CSV of --vary spin in rad/s" cmp a.csv b.csv
check "... its column is spin, in rad/s" bash -c "head -1 a.csv | grep -q '^spin,' && tail -1 a.csv | grep -q '^314.159265358979'"
check "--spin-rpm overrides the file's spin" bash -c "'$H' stability --config rad.toml --spin-rpm 60 --format json | grep -q '\"spin\": 6.28318530717958'"
check "--spin overrides the file's spin_rpm" bash -c "'$H' stability --config rpm.toml --spin 7 --format json | grep -q '\"spin\": 7'"
check "the text gives spins in rpm too" bash -c "'$H' stability --spin-rpm 3000 | grep -q 'critical spins in rpm: first-order 1273.34'"
printf '[motion]\nspin = 1\nspin_rpm = 2\n' > both.toml
check "spin and spin_rpm in one file: exit 2" run 2 stability --config both.toml
check "... naming motion.spin_rpm" says "motion.spin_rpm: give spin or spin_rpm, not both"
check "--spin and --spin-rpm: exit 2" run 2 stability --spin 1 --spin-rpm 2 --output never.json
check "... naming --spin-rpm, writing nothing" bash -c "grep -q -- '--spin-rpm' err && test ! -e never.json"

# ---- SPEC 10: parts ---------------------------------------------------------------------------
cat > top.toml <<'EOF'
[body]
gravity = 9.81
[[body.part]]
shape = "cone"
radius = 0.02
height = 0.02
density = 700.0
[[body.part]]
shape = "cylinder"
radius = 0.02
height = 0.005
z0 = 0.02
density = 700.0
[[body.part]]
shape = "tube"
radius = 0.003
inner_radius = 0.001
height = 0.03
z0 = 0.025
mass = 0.002
[[body.part]]
shape = "sphere"
radius = 0.004
z0 = 0.055
mass = 0.003
[[body.part]]
shape = "cone"
apex = "up"
radius = 0.01
height = 0.004
z0 = -0.004
density = 7800
[motion]
spin_rpm = 2500
EOF
check "body from parts" run 0 body --config top.toml --format json
cp out body.json
# The closed forms of docs/mass-properties.md, evaluated here in Python: (V, centroid above
# the lowest point, variance along z, mean r^2) per shape, then the parallel-axis theorem.
check "body: A, B, C, mass, length are the parts' closed forms (1e-12)" py "
import json, math
pi = math.pi
def part(V, u, var, r2, z0, rho=None, m=None):
    m = rho * V if m is None else m
    zc = z0 + u
    return m, m * zc, m * (r2 / 2 + var + zc * zc), m * r2
ps = [part(pi*.02**2*.02/3, .75*.02, 3*.02**2/80, .3*.02**2, 0, rho=700),
      part(pi*.02**2*.005, .0025, .005**2/12, .02**2/2, .02, rho=700),
      part(pi*(.003**2-.001**2)*.03, .015, .03**2/12, (.003**2+.001**2)/2, .025, m=.002),
      part(4*pi*.004**3/3, .004, .004**2/5, 2*.004**2/5, .055, m=.003),
      part(pi*.01**2*.004/3, .004/4, 3*.004**2/80, .3*.01**2, -.004, rho=7800)]
m = sum(p[0] for p in ps); R = sum(p[1] for p in ps) / m
A = sum(p[2] for p in ps); C = sum(p[3] for p in ps)
b = json.load(open('body.json'))
for k, v in (('mass', m), ('length', R), ('A', A), ('B', A), ('C', C)):
    assert abs(b[k] - v) <= 1e-12 * abs(v), (k, b[k], v)
assert b['products'] == {'xy': 0, 'xz': 0, 'yz': 0} and b['offset'] == {'x': 0, 'y': 0} and not b['general']
assert len(b['parts']) == 5 and b['parts'][4]['name'] == 'body.part[4] (cone)'
"
check "every command uses the body the parts make" py "
import json, subprocess
b = json.load(open('body.json'))
s = json.loads(subprocess.run(['$H', 'stability', '--config', 'top.toml', '--format', 'json'], capture_output=True, check=True).stdout)
assert all(s['body'][k] == b[k] for k in ('A', 'B', 'C', 'mass', 'length')), s['body']
import math; assert abs(s['spin'] - 2500 * math.pi / 30) < 1e-12
"
check "simulate and precession take it too" bash -c "'$H' simulate --config top.toml --model nonlinear --t-end 0.01 --samples 3 > /dev/null && '$H' precession --config top.toml --tilt 0.2 > /dev/null"
check "body text shows the [body] it makes" bash -c "'$H' body --config top.toml | grep -q '^  C = '"

# Bad parts: exit 2, one line naming the key, nothing written.
bad_part() {  # NAME KEY LINES...
  local name=$1 key=$2; shift 2
  printf '%s\n' '[[body.part]]' "$@" > bad.toml
  check "$name: exit 2" run 2 stability --config bad.toml --output never.json
  check "$name: names $key" says "$key"
  check "$name: one line, nothing written" bash -c "[ \$(wc -l < err) -eq 1 ] && test ! -e never.json"
}
bad_part "density and mass" "body.part\[0\].mass (cylinder): give density or mass, not both" \
  'shape = "cylinder"' 'radius = 0.01' 'height = 0.01' 'density = 700' 'mass = 0.1'
bad_part "neither density nor mass" "body.part\[0\].density (cylinder)" 'shape = "cylinder"' 'radius = 0.01' 'height = 0.01'
bad_part "negative radius" "body.part\[0\].radius (cone): must be a finite number > 0" \
  'shape = "cone"' 'radius = -0.01' 'height = 0.01' 'density = 700'
bad_part "unknown shape" "body.part\[0\].shape: unknown shape 'pyramid'" 'shape = "pyramid"' 'radius = 0.01'
bad_part "missing shape" "body.part\[0\].shape: is required" 'radius = 0.01'
bad_part "apex on a cylinder" "body.part\[0\].apex" 'shape = "cylinder"' 'radius = 0.01' 'height = 0.01' 'density = 1' 'apex = "up"'
bad_part "a bad apex" "body.part\[0\].apex" 'shape = "cone"' 'radius = 0.01' 'height = 0.01' 'density = 1' 'apex = "sideways"'
bad_part "inner radius >= radius" "body.part\[0\].inner_radius (tube)" \
  'shape = "tube"' 'radius = 0.01' 'inner_radius = 0.01' 'height = 0.01' 'density = 1'
bad_part "an unknown key" "body.part\[0\].colour" 'shape = "sphere"' 'radius = 0.01' 'density = 1' 'colour = "red"'
bad_part "a missing mesh" "body.part\[0\] (nowhere.stl): cannot read" 'shape = "mesh"' 'file = "nowhere.stl"' 'density = 1'
bad_part "a mesh without file" "body.part\[0\].file" 'shape = "mesh"' 'density = 1'
bad_part "bad units" "body.part\[0\].units" 'shape = "mesh"' 'file = "x.stl"' 'units = "inch"' 'density = 1'
printf '[body]\nA = 1\n[[body.part]]\nshape = "sphere"\nradius = 0.01\ndensity = 1\n' > bad.toml
check "parts and A in one [body]: exit 2" run 2 stability --config bad.toml
check "... naming body.A" says "body.A: cannot be given with \[\[body.part\]\]"
check "--A over a body of parts: exit 2" run 2 stability --config top.toml --A 1
check "... naming --A" says "^heavytop: error: --A: the body is made of parts"

# ---- meshes -------------------------------------------------------------------------------------
# A box [0.5, 1.5] x [-0.25, 0.75] x [0, 2] (units of the file; exact in float32), written as
# binary and ASCII STL, OBJ and PLY; and an open copy. The exact integrals are products of
# one-dimensional ones.
py "
import struct
lo, hi = (0.5, -0.25, 0.0), (1.5, 0.75, 2.0)
v = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
tris = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
def stl_binary(name, tris):
    with open(name, 'wb') as f:
        f.write(b' ' * 80 + struct.pack('<I', len(tris)))
        for t in tris:
            f.write(struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *v[i]) for i in t) + b'\0\0')
stl_binary('box.stl', tris)
stl_binary('open.stl', tris[:-1])
with open('box-ascii.stl', 'w') as f:
    f.write('solid box\n')
    for t in tris:
        f.write(' facet normal 0 0 0\n  outer loop\n' + ''.join('   vertex %r %r %r\n' % v[i] for i in t) + '  endloop\n endfacet\n')
    f.write('endsolid box\n')
with open('box.obj', 'w') as f:
    f.write(''.join('v %r %r %r\n' % p for p in v) + ''.join('f %d %d %d\n' % tuple(i + 1 for i in t) for t in tris))
with open('box.ply', 'w') as f:
    f.write('ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n'
            'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % len(tris))
    f.write(''.join('%r %r %r\n' % p for p in v) + ''.join('3 %d %d %d\n' % t for t in tris))
"
mesh_body() {  # FILE UNITS: writes mesh.toml for a mesh part of density 1000
  printf '[[body.part]]\nshape = "mesh"\nfile = "%s"\nunits = "%s"\ndensity = 1000.0\n' "$1" "$2" > mesh.toml
}
box_check() {  # SCALE: body.json is the box at SCALE m per unit, density 1000
  py "
import json
s = $1
lo, hi = [0.5*s, -0.25*s, 0.0], [1.5*s, 0.75*s, 2.0*s]
I = lambda d, p: (hi[d]**(p+1) - lo[d]**(p+1)) / (p+1)
mom = lambda a, b, c: 1000 * I(0, a) * I(1, b) * I(2, c)
m = mom(0,0,0); xx, yy, zz = mom(2,0,0), mom(0,2,0), mom(0,0,2)
e = {'mass': m, 'A': yy+zz, 'B': xx+zz, 'C': xx+yy, 'length': mom(0,0,1)/m}
b = json.load(open('body.json'))
for k, v in e.items():
    assert abs(b[k] - v) <= 1e-12 * abs(v), (k, b[k], v)
tr = e['A'] + e['B'] + e['C']
for k, v in (('xy', mom(1,1,0)), ('xz', mom(1,0,1)), ('yz', mom(0,1,1))):
    assert abs(b['products'][k] - v) <= 1e-12 * tr, (k, b['products'][k], v)
assert abs(b['offset']['x'] - mom(1,0,0)/m) <= 1e-12 * s and abs(b['offset']['y'] - mom(0,1,0)/m) <= 1e-12 * s
assert b['general'] and b['principal_axis_tilt'] > 0
"
}
for f in box.stl box-ascii.stl box.obj box.ply; do
  mesh_body $f m
  check "mesh $f: body" run 0 body --config mesh.toml --format json
  cp out body.json
  check "mesh $f: the box's exact mass properties, products and offset (1e-12)" box_check 1
done
mesh_body box.stl mm
"$H" body --config mesh.toml --format json > body.json
check "units = mm scales by 1e-3" box_check 1e-3
mkdir -p elsewhere && (cd elsewhere && "$H" body --config ../mesh.toml --format json > ../body.json)
check "a relative mesh path is relative to the configuration's folder" box_check 1e-3
mesh_body box.stl m
check "a general body: stability refuses it" run 2 stability --config mesh.toml --output never.json
check "... naming the part, the offset and the products" says "body.part\[0\] (box.stl): its centre of mass is .* m off the z axis.*products of inertia.*integrated by .simulate --model nonlinear. only"
check "... one line, nothing written" bash -c "[ \$(wc -l < err) -eq 1 ] && test ! -e never.json"
check "a general body: simulate --model linearized refuses it, naming the part" run 2 simulate --model linearized --config mesh.toml
check "... saying which model takes it" says "body.part\[0\] (box.stl): .*integrated by .simulate --model nonlinear. only"
check "a general body: nonlinear integrates it (SPEC 11)" run 0 simulate --model nonlinear --config mesh.toml --t-end 0.05 --samples 11 --format json
check "... by the Taylor integrator (order 22 at 1e-12: 22 evaluations a step), its products in the JSON body, energy conserved" py "import json; d = json.load(open('out')); b = d['body']; s = d['summary']; assert b['Ixy'] != 0 and b['offset_x'] != 0, b; assert s['max_relative_energy_drift'] < 1e-10, s; assert s['rhs_evaluations'] == 22 * s['steps'] and s['rejected_steps'] == 0, s"
cp out taylor.json
check "a general body: --integrator dopri5 integrates it too" run 0 simulate --model nonlinear --integrator dopri5 --config mesh.toml --t-end 0.05 --samples 11 --format json
check "... the same motion as the Taylor integrator's (1e-9 rad)" py "import json; a = json.load(open('out')); b = json.load(open('taylor.json')); assert a['summary']['rhs_evaluations'] != b['summary']['rhs_evaluations']; assert max(abs(x - y) for k in ('theta', 'phi') for x, y in zip(a[k], b[k])) < 1e-9"
check "a general body: --integrator dop853 refuses it" run 2 simulate --model nonlinear --integrator dop853 --config mesh.toml
check "... naming --integrator" says "--integrator: dop853 integrates the ordinary body only"
mesh_body open.stl m
check "an open mesh: exit 2" run 2 body --config mesh.toml
check "... naming the part and the count of open edges" says "body.part\[0\] (open.stl): .*3 open edges"
check "... in one line" one_line
check "the example mesh top: a symmetric body every command accepts" bash -c "
  '$H' body --config '$examples/mesh-top.toml' --format json | grep -q '\"general\": false' &&
  '$H' stability --config '$examples/mesh-top.toml' > /dev/null"

# ---- SPEC 11's keys: reported by body, integrated by nonlinear, refused by every other model ----
printf '[body]\nA = 1\nB = 1\nC = 1.5\nmass = 1\nlength = 0.1\nIxy = 0.01\noffset_x = 0.001\n' > general.toml
check "body reports SPEC 11's keys" run 0 body --config general.toml --format json
check "... as products and offset" py "import json; b = json.load(open('out')); assert b['products']['xy'] == 0.01 and b['offset']['x'] == 0.001 and b['general']"
check "stability refuses Ixy" run 2 stability --config general.toml
check "... naming body.Ixy and the model that takes it" says "body.Ixy: is 0.01: .*integrated by .simulate --model nonlinear. only"
check "simulate --model first-order refuses it" run 2 simulate --model first-order --config general.toml
check "... naming body.offset_x" says "body.offset_x: is nonzero: .*not by simulate --model first-order"
check "simulate --model nonlinear integrates SPEC 11's keys" run 0 simulate --model nonlinear --config general.toml --t-end 0.5 --samples 6
check "... a CSV with the nonlinear columns" bash -c "head -1 out | grep -q '^t,theta,phi,theta_rate,phi_rate,tilt,azimuth,energy,vertical_momentum'"
printf '[body]\nA = 1\nB = 1\nC = 1.5\nmass = 1\nlength = 0.1\nIxy = 1.2\n' > impossible.toml
check "a tensor that is not positive definite: exit 2" run 2 simulate --model nonlinear --config impossible.toml
check "... naming body.Ixy" says "body.Ixy: the inertia tensor .* must be positive definite"

# ---- precession -------------------------------------------------------------------------------
check "precession --tilt" run 0 precession --tilt 0.4 --spin 200 --format json
cp out prec.json
for which in slow fast; do
  # The state it gives, into the nonlinear body for 100 periods: the tilt stays constant.
  args=$(py "
import json; p = json.load(open('prec.json'))['steady_precession']['$which']
s = p['state']; print(' '.join('--%s %r' % (k, s[k]) for k in ('spin', 'theta0', 'phi0', 'theta_rate0', 'phi_rate0')), 100 * p['period'])")
  t_end=${args##* }; args=${args% *}
  "$H" simulate --model nonlinear $args --t-end "$t_end" --samples 2001 --rtol 1e-13 --atol 1e-13 > prec.csv
  check "$which steady precession: the nonlinear body keeps the tilt to 1e-10 over 100 periods" py "
import csv, math
rows = list(csv.DictReader(open('prec.csv')))
dev = max(abs(math.acos(min(1, math.cos(float(r['theta'])) * math.cos(float(r['phi'])))) - 0.4) for r in rows)
assert len(rows) == 2001 and dev < 1e-10, dev
"
done
check "precession text shows rates in rad/s and rpm" bash -c "'$H' precession --tilt 0.4 --spin-rpm 2000 | grep -q 'slow: W = .* rad/s (.* rpm)'"
check "below the minimum spin: none" bash -c "'$H' precession --tilt 0.4 --spin 10 --format json | grep -q '\"slow\": null'"
check "an asymmetric body: permanent rotations only" bash -c "
  '$H' precession --A 1 --B 1.5 --C 2.2 --mass 1 --gravity 1 --length 0.3 --tilt 0.8 --format json |
  python3 -c 'import json,sys; d = json.load(sys.stdin); assert d[\"steady_precession\"] is None and len(d[\"permanent_rotations\"]) == 2'"
check "--tilt 0: exit 2" run 2 precession --tilt 0 --output never.json
check "... naming --tilt, nothing written" bash -c "grep -q -- '--tilt: must be' err && test ! -e never.json"
check "--tilt is required" run 2 precession

finish

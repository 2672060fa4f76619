#!/usr/bin/env bash
# The report page in a real browser (browser_report.cjs: headless chromium, puppeteer-core from
# report/web's npm packages): the built-in example's report as `heavytop` writes it, and an
# asymmetric body whose approximate models diverge, bodies of parts and meshes (the view draws
# them as they are), a falling and a horizontal body. Screenshots are kept in $ARTEFACTS.
# Skips (exit 77) when this build has no interactive page (npm was not reachable at build time).
source "$(dirname "$0")/harness.sh"
: "${CHROMIUM:?}" "${NODE:?}" "${NODE_MODULES:?}" "${ARTEFACTS:?}"
mkdir -p "$ARTEFACTS"
rm -f "$ARTEFACTS"/*.png

"$H" > example.log
check "the built-in example's report" test $? -eq 0 -a -e heavytop-report/report.html
if [ ! -e heavytop-report/heavytop-report.js ]; then
  echo "SKIP: this heavytop was built without the interactive page:"
  grep -o "No interactive view[^<]*" heavytop-report/report.html
  exit 77
fi
"$H" report --A 1 --B 1.5 --C 2 --mass 1 --gravity 1 --length 1 --spin 1.3 --theta0 0.01 --output asymmetric > /dev/null
check "an asymmetric body's report" test $? -eq 0

# The 3D view draws the real body (SPEC section 10's parts): the mesh example (binary STL); a top
# of every solid shape; the same top's mesh as OBJ with solid parts on it; a bob hanging below O
# on a rod, the mesh mirrored as ASCII PLY (so oriented inwards). And bodies that fall or lie
# horizontal, which the camera must keep in view.
examples=$(realpath "$(dirname "$0")/../examples")
"$H" report --config "$examples/mesh-top.toml" --output mesh-top > /dev/null
check "the mesh example's report" test $? -eq 0
cat > parts-top.toml <<'EOF2'
# A top of parts: a point, a disc in a brass rim, a dome and a knob.
[[body.part]]
shape = "cone"
radius = 0.02
height = 0.015
apex = "down"
density = 700.0
[[body.part]]
shape = "cylinder"
radius = 0.02
height = 0.008
z0 = 0.015
density = 700.0
[[body.part]]
shape = "tube"
radius = 0.03
inner_radius = 0.02
height = 0.008
z0 = 0.015
density = 8500.0
[[body.part]]
shape = "cone"
radius = 0.02
height = 0.01
z0 = 0.023
apex = "up"
density = 700.0
[[body.part]]
shape = "sphere"
radius = 0.004
z0 = 0.031
density = 700.0
[motion]
spin_rpm = 3000.0
theta0 = 0.05
EOF2
"$H" report --config parts-top.toml --output parts-top > /dev/null
check "a body of parts' report" test $? -eq 0
python3 - "$examples/meshes/spinning-top.stl" <<'EOF2'
import struct, sys
data = open(sys.argv[1], 'rb').read()
index, verts, tris = {}, [], []
for t in range(struct.unpack_from('<I', data, 80)[0]):
    f = struct.unpack_from('<12f', data, 84 + 50 * t)
    tri = []
    for k in range(3):
        v = f[3 + 3 * k: 6 + 3 * k]
        if v not in index: index[v] = len(verts); verts.append(v)
        tri.append(index[v])
    tris.append(tri)
with open('top.obj', 'w') as out:  # the top, mm
    out.writelines(['v %.6f %.6f %.6f\n' % v for v in verts] + ['f %d %d %d\n' % (a + 1, b + 1, c + 1) for a, b, c in tris])
with open('bob.ply', 'w') as out:  # mirrored below O, point up, 60 mm down: oriented inwards
    out.write('ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
              'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % (len(verts), len(tris)))
    out.writelines(['%.6f %.6f %.6f\n' % (x, y, -z - 60.0) for x, y, z in verts] + ['3 %d %d %d\n' % tuple(t) for t in tris])
EOF2
cat > mixed.toml <<'EOF2'
# The spinning top's mesh (as OBJ) with a brass rim and a knob: a mesh and solid parts.
[[body.part]]
shape = "mesh"
file = "top.obj"
units = "mm"
density = 700.0
[[body.part]]
shape = "tube"
radius = 0.0265
inner_radius = 0.0245
height = 0.004
z0 = 0.021
density = 8500.0
[[body.part]]
shape = "sphere"
radius = 0.005
z0 = 0.0445
density = 700.0
[motion]
spin_rpm = 3000.0
theta0 = 0.05
EOF2
cat > hanging.toml <<'EOF2'
# A bob hanging on a rod below the pivot: the top's mesh mirrored (PLY, oriented inwards).
[[body.part]]
shape = "cylinder"
radius = 0.002
height = 0.06
z0 = -0.06
density = 2700.0
[[body.part]]
shape = "mesh"
file = "bob.ply"
units = "mm"
density = 700.0
[motion]
spin = 30.0
theta0 = 0.1
EOF2
"$H" report --config mixed.toml --output mixed > /dev/null && "$H" report --config hanging.toml --output hanging > /dev/null
check "a mesh (OBJ) with parts, a hanging body with a PLY mesh: their reports" test $? -eq 0
"$H" report --config "$examples/horizontal-gyroscope.toml" --output horizontal > /dev/null
check "the horizontal gyroscope's report" test $? -eq 0
"$H" report --spin 100 --output falling > /dev/null && "$H" stability --spin 100 --format json > falling.json
check "a falling body's report" test $? -eq 0

NODE_PATH="$NODE_MODULES" "$NODE" "$(dirname "$0")/browser_report.cjs" "$CHROMIUM" "$ARTEFACTS" \
  example="$PWD/heavytop-report" asymmetric="$PWD/asymmetric" mesh-top="$PWD/mesh-top" parts-top="$PWD/parts-top" \
  mixed="$PWD/mixed" hanging="$PWD/hanging" horizontal="$PWD/horizontal" falling="$PWD/falling"
check "in the browser" test $? -eq 0
# The answer first (SPEC 14): the example (proven stable), a top too slow (falls), a damped one.
"$H" stability --format json > example.json
"$H" report --axial-damping 2e-6 --output damped > /dev/null && "$H" stability --axial-damping 2e-6 --format json > damped.json &&
  "$H" lifetime --axial-damping 2e-6 --format json > damped-lifetime.json
check "a damped body's report" test $? -eq 0
NODE_PATH="$NODE_MODULES" "$NODE" "$(dirname "$0")/browser_answer.cjs" "$CHROMIUM" \
  example="$PWD/heavytop-report,example.json" falling="$PWD/falling,falling.json" \
  damped="$PWD/damped,damped.json,damped-lifetime.json"
check "the answer first, in the browser" test $? -eq 0
echo "screenshots: $ARTEFACTS"
finish

#!/usr/bin/env bash
# Hostile input, round 3 (issue 30): meshes, damped verdicts, lifetime, precession, fit-decay,
# maps and resumes, empty values, and the first round's leftovers. Each check is a case the
# review found wrong, and more of its own.
source "$(dirname "$0")/harness.sh"

messages="$work/messages"
: > "$messages"
run() {
  local expected=$1; shift
  "$H" "$@" > out 2> err
  local rc=$?
  cat err >> "$messages"
  [ "$rc" -eq "$expected" ] || { echo "  exit $rc, expected $expected: $* :: $(head -c 300 err)"; return 1; }
}
one_line() { [ "$(wc -l < err)" -eq 1 ] || { echo "  not one line: $(cat err)"; return 1; }; }
says() { grep -q -- "$1" err || { echo "  stderr lacks '$1': $(cat err)"; return 1; }; }
json() { python3 -c "import json,sys; d=json.load(open('out')); $1"; }

# ---- 1. Mesh files: every one reads or is refused (exit 2, the part and the file named) --------
python3 - <<'PY'
import struct
def box():
    v = [(0,0,0),(1,0,0),(1,2,0),(0,2,0),(0,0,3),(1,0,3),(1,2,3),(0,2,3)]
    q = [(0,3,2,1),(4,5,6,7),(0,1,5,4),(1,2,6,5),(2,3,7,6),(3,0,4,7)]
    return v, q
v, q = box()
tris = [t for a,b,c,d in q for t in ((a,b,c),(a,c,d))]
def stl(tris):
    out = b'\0'*80 + struct.pack('<I', len(tris))
    for t in tris:
        out += struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *v[i]) for i in t) + b'\0\0'
    return out
good = stl(tris)
open('empty.stl','wb').write(b'')
open('text.stl','w').write('this is some text, not a mesh at all, and it is long enough to be more than eighty-four bytes\n')
open('short.stl','w').write('hello\n')
open('nofacets.stl','wb').write(b'\0'*80 + struct.pack('<I', 0))
open('count.stl','wb').write(good[:80] + struct.pack('<I', len(tris) + 1) + good[84:])
open('truncated.stl','wb').write(good[:-10])
open('not.ply','w').write('this is not a PLY file\n')
def ply(fmt, endian):
    h = ('ply\nformat %s 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n'
         'element face 6\nproperty list uchar int vertex_indices\nend_header\n' % fmt).encode()
    body = b''.join(struct.pack(endian + '3f', *p) for p in v)
    body += b''.join(struct.pack(endian + 'B4i', 4, *f) for f in q)
    return h + body
open('box-le.ply','wb').write(ply('binary_little_endian', '<'))
open('box-be.ply','wb').write(ply('binary_big_endian', '>'))
open('box-le-truncated.ply','wb').write(ply('binary_little_endian', '<')[:-3])
with open('box.ply','w') as f:
    f.write('ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n'
            'element face 6\nproperty list uchar int vertex_indices\nend_header\n')
    for p in v: f.write('%g %g %g\n' % p)
    for a in q: f.write('4 %d %d %d %d\n' % a)
PY
mesh_body() {  # FILE: writes mesh.toml for a mesh part of density 1000, A box of 1 x 2 x 3 m in the file
  printf '[[body.part]]\nshape = "mesh"\nfile = "%s"\ndensity = 1000.0\n' "$1" > mesh.toml
}
for f in empty.stl text.stl short.stl nofacets.stl count.stl truncated.stl not.ply box-le-truncated.ply; do
  mesh_body $f
  check "mesh $f: refused, exit 2 (was a segfault)" run 2 body --config mesh.toml
  check "... naming the part and the file" says "body.part\[0\] ($f): .*'.*$f'"
  check "... in one line" one_line
  check "mesh $f: stability refuses it the same way" run 2 stability --config mesh.toml
done
mesh_body count.stl; run 2 body --config mesh.toml
check "a binary STL whose count does not match its size says so" says "a binary STL of 13 triangles has 684 bytes, not 734"
mesh_body nofacets.stl; run 2 body --config mesh.toml
check "an STL with no facets holds no triangles" says "holds no triangles"
for f in box-le.ply box-be.ply box.ply; do
  mesh_body $f
  check "mesh $f reads (a binary PLY was an assertion in Assimp)" run 0 body --config mesh.toml --format json
  check "... the box's mass, 6000 kg, and C = m (1 + 4) / 3 + ..." json '
m = d["mass"]; assert abs(m - 6000) < 1e-9, m
C = 6000 * (1 + 4) / 3  # about z through O: (a^2 + b^2) / 3 for the box [0,1]x[0,2]
assert abs(d["C"] - C) < 1e-9 * C, d["C"]'
done

finish

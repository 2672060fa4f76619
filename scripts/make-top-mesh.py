#!/usr/bin/env python3
"""Generates examples/meshes/spinning-top.stl: a turned wooden spinning top (a surface of
revolution: a steel-like point, a conical body, a rounded rim, a crown and a stem), as a binary
STL in millimetres, its tip at the origin, its axis +z. A generated mesh, not a scan or a CAD
export.

The mesh is exactly symmetric under the square's eight symmetries (x -> -x, y -> -y, x <-> y),
coordinate for coordinate in float32: every circle's points are made in the first octant, then
mirrored and swapped (exact operations). So its products of inertia and the centre of mass's
offset vanish to rounding and A = B, as for the ideal top, although STL stores float32.

    python3 scripts/make-top-mesh.py [OUTPUT] [SEGMENTS_PER_OCTANT]
"""
import math
import struct
import sys

# (r, z) in mm, from the tip up to the top of the stem (r = 0 at both ends).
PROFILE = [
    (0.0, 0.0), (0.6, 0.25), (1.2, 0.8), (2.0, 2.0), (4.0, 4.2), (8.0, 7.6), (12.0, 10.6), (16.0, 13.4),
    (19.5, 16.0), (22.0, 18.2), (23.6, 20.0), (24.5, 21.8), (24.8, 23.0), (24.5, 24.2), (23.6, 25.2),
    (21.5, 26.2), (17.0, 27.2), (11.0, 28.0), (6.0, 28.6), (4.0, 29.2), (3.6, 30.0), (3.5, 44.0),
    (3.2, 45.2), (2.4, 46.0), (1.2, 46.4), (0.0, 46.5),
]


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def circle(m):
    """Unit-circle points in order, 8 m of them, exactly D4-symmetric in float32."""
    octant = [(f32(math.cos(k * math.pi / (4 * m))), f32(math.sin(k * math.pi / (4 * m)))) for k in range(m)]
    c45 = f32(math.sqrt(0.5))
    octant_end = octant + [(c45, c45)]
    quadrant = octant + [(s, c) for (c, s) in reversed(octant_end[1:])]  # 0..90 degrees, 2 m points
    points = []
    for turn in range(4):
        for (x, y) in quadrant:
            for _ in range(turn):
                x, y = -y, x  # a quarter turn, exact
            points.append((x, y))
    return points


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "examples/meshes/spinning-top.stl"
    m = int(sys.argv[2]) if len(sys.argv) > 2 else 16
    ring = circle(m)
    n = len(ring)
    rings = []
    for (r, z) in PROFILE:
        rf, zf = f32(r), f32(z)
        rings.append(None if r == 0.0 else [(f32(rf * x), f32(rf * y), zf) for (x, y) in ring])
    triangles = []
    for i in range(len(PROFILE) - 1):
        lo, hi = rings[i], rings[i + 1]
        zlo, zhi = f32(PROFILE[i][1]), f32(PROFILE[i + 1][1])
        for k in range(n):
            j = (k + 1) % n
            if lo is None:  # the tip: a fan from the pole
                triangles.append(((0.0, 0.0, zlo), hi[j], hi[k]))
            elif hi is None:  # the top of the stem
                triangles.append((lo[k], lo[j], (0.0, 0.0, zhi)))
            else:  # outward: counter-clockwise seen from outside
                triangles.append((lo[k], lo[j], hi[j]))
                triangles.append((lo[k], hi[j], hi[k]))
    with open(out, "wb") as f:
        f.write(b"heavytop generated spinning top (mm), scripts/make-top-mesh.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            a, b, c = t
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            nrm = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in nrm)) or 1.0
            f.write(struct.pack("<3f", *[x / length for x in nrm]))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")
    print(f"{out}: {len(triangles)} triangles, {n} segments around")



if __name__ == "__main__":
    main()

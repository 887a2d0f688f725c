#!/usr/bin/env python3
"""Writes fine_table.obj (a table tessellated as furniture models are: 2 cm quads, split into
triangles) and fine_table_points.txt (points on it and on the floor round and under it), for
fine_table.json. Run from this directory: python3 fine_table.py"""
import math, random

STEP = 0.02  # the model's own face size
verts, faces = [], []

def quad_grid(origin, u, v, nu, nv):
    """A rectangle origin + s*u + t*v (s, t in [0, 1]) as nu x nv quads, wound counter-clockwise
    seen from the side u x v points to."""
    base = len(verts)
    for j in range(nv + 1):
        for i in range(nu + 1):
            s, t = i / nu, j / nv
            verts.append(tuple(origin[k] + s * u[k] + t * v[k] for k in range(3)))
    for j in range(nv):
        for i in range(nu):
            a = base + j * (nu + 1) + i
            b, c, d = a + 1, a + nu + 2, a + nu + 1
            faces.append((a, b, c))
            faces.append((a, c, d))

def box(lo, hi, skip_bottom=False):
    """An axis-aligned box's faces, facing out, each a grid of STEP quads."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    n = lambda d: max(1, round(d / STEP))
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    quad_grid((x0, y1, z0), (0, 0, dz), (dx, 0, 0), n(dz), n(dx))   # top, +y
    if not skip_bottom:
        quad_grid((x0, y0, z0), (dx, 0, 0), (0, 0, dz), n(dx), n(dz))  # bottom, -y
    quad_grid((x0, y0, z1), (dx, 0, 0), (0, dy, 0), n(dx), n(dy))   # +z
    quad_grid((x1, y0, z0), (-dx, 0, 0), (0, dy, 0), n(dx), n(dy))  # -z
    quad_grid((x1, y0, z0), (0, dy, 0), (0, 0, dz), n(dy), n(dz))   # +x
    quad_grid((x0, y0, z0), (0, 0, dz), (0, dy, 0), n(dz), n(dy))   # -x

TOP_Y0, TOP_Y1 = 0.71, 0.75
X0, X1, Z0, Z1 = -0.6, 0.6, -0.4, 0.4
box((X0, TOP_Y0, Z0), (X1, TOP_Y1, Z1))
LEG = 0.05
for (x, z) in [(X0 + 0.04, Z0 + 0.04), (X1 - 0.04 - LEG, Z0 + 0.04), (X0 + 0.04, Z1 - 0.04 - LEG), (X1 - 0.04 - LEG, Z1 - 0.04 - LEG)]:
    box((x, 0.0, z), (x + LEG, TOP_Y0, z + LEG), skip_bottom=True)

with open("fine_table.obj", "w") as f:
    f.write("# A table tessellated in 2 cm quads (fine_table.py)\n")
    for v in verts:
        f.write("v %.6f %.6f %.6f\n" % v)
    for a, b, c in faces:
        f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))

rng = random.Random(1)
points = []
def add(p, n, tag):
    points.append("%.4f %.4f %.4f %g %g %g %s" % (p + n + (tag,)))
for _ in range(40):  # the table top
    add((rng.uniform(X0 + 0.01, X1 - 0.01), TOP_Y1, rng.uniform(Z0 + 0.01, Z1 - 0.01)), (0, 1, 0), "top")
for _ in range(40):  # the floor under it, in its shadow: indirect light alone
    add((rng.uniform(X0 + 0.12, X1 - 0.12), 0.0, rng.uniform(Z0 + 0.12, Z1 - 0.12)), (0, 1, 0), "under")
for _ in range(20):  # the table's edges, facing out
    t = rng.uniform(X0 + 0.05, X1 - 0.05)
    add((t, rng.uniform(TOP_Y0 + 0.005, TOP_Y1 - 0.005), Z1), (0, 0, 1), "edge")
for _ in range(40):  # the floor round it, 5-50 cm from its outline
    while True:
        x, z = rng.uniform(X0 - 0.5, X1 + 0.5), rng.uniform(Z0 - 0.5, Z1 + 0.5)
        if not (X0 - 0.05 < x < X1 + 0.05 and Z0 - 0.05 < z < Z1 + 0.05):
            break
    add((x, 0.0, z), (0, 1, 0), "round")
with open("fine_table_points.txt", "w") as f:
    f.write("\n".join(points) + "\n")
print(len(verts), "vertices,", len(faces), "triangles,", len(points), "points")

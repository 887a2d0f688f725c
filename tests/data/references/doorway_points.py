#!/usr/bin/env python3
# The points of tests/data/references/doorway_points.txt: python3 tests/data/references/doorway_points.py > tests/data/references/doorway_points.txt
# (stdlib only, seed 11; the reference itself is tests/data/references/doorway_reference.csv, from
# radiosity reference scenes/doorway.json --points tests/data/references/doorway_points.txt -o tests/data/references/doorway_reference.csv).
import random, math

random.seed(11)
M = 2.0  # every point at least this far (mm) from any edge, corner or the doorway hole

print("# Points in room B of scenes/doorway.json (z 4100..8100, lit only through the doorway), seed 11,")
print("# each 'x y z nx ny nz tag' with the normal facing room B. 200 points stratified by area over")
print("# room B's surfaces (counts in proportion to area, largest remainder; on each surface one point per")
print("# cell of a jittered grid): floor, ceiling, left wall x=0, right wall x=4000, back wall z=8100 and")
print("# partition_back z=4100 without the doorway (x 1600..2500, y 0..2100); tags roomB_*. Then 40 points")
print("# in the doorway (tags doorway_*): 11 on each jamb (x=1600 normal +x, x=2500 normal -x; z 4000..4100,")
print("# y 0..2100), 6 on the lintel's underside (y=2100 normal -y) and 12 on room B's floor within 300 mm of")
print("# the partition beside and behind the doorway (z 4100..4400, x 1300..2800). All at least 2 mm from")
print("# every edge, corner and the doorway hole. Made by tests/data/references/doorway_points.py.")


def grid(n, w, h):
    """rows x cols for about n cells of a w x h rectangle, cells about square, rows*cols >= n."""
    cols = max(1, round(math.sqrt(n * w / h)))
    rows = max(1, math.ceil(n / cols))
    while rows * cols < n:
        cols += 1
    return rows, cols


def stratified(n, u0, u1, v0, v1, inside=lambda u, v: True):
    """n points (u, v) in [u0,u1] x [v0,v1], one in each of n cells of a jittered grid chosen at
    random among the cells that hold any allowed point; a point not allowed is drawn again in its cell."""
    rows, cols = grid(n, u1 - u0, v1 - v0)
    du, dv = (u1 - u0) / cols, (v1 - v0) / rows
    cells = []
    for r in range(rows):
        for c in range(cols):
            a, b = u0 + c * du, v0 + r * dv
            # a cell is usable when some of it is allowed (its corners and centre tested)
            probes = [(a, b), (a + du, b), (a, b + dv), (a + du, b + dv), (a + du / 2, b + dv / 2)]
            if any(inside(*p) for p in probes):
                cells.append((a, b))
    if len(cells) < n:  # not expected: the grid is large enough for the areas here
        raise SystemExit("too few cells")
    pts = []
    for a, b in sorted(random.sample(cells, n)):
        for _ in range(10000):
            u, v = a + random.random() * du, b + random.random() * dv
            if inside(u, v):
                break
        else:
            raise SystemExit("no allowed point in a cell")
        pts.append((u, v))
    return pts


def out_of_doorway(x, y):
    return not (1600 - M < x < 2500 + M and y < 2100 + M)


# Room B's surfaces: (tag, area, point maker for n points)
X0, X1, Y0, Y1, Z0, Z1 = 0.0, 4000.0, 0.0, 2500.0, 4100.0, 8100.0
surfaces = [
    ("roomB_floor", (X1 - X0) * (Z1 - Z0),
     lambda n: [(x, 0.0, z, 0, 1, 0) for x, z in stratified(n, X0 + M, X1 - M, Z0 + M, Z1 - M)]),
    ("roomB_ceiling", (X1 - X0) * (Z1 - Z0),
     lambda n: [(x, Y1, z, 0, -1, 0) for x, z in stratified(n, X0 + M, X1 - M, Z0 + M, Z1 - M)]),
    ("roomB_left_wall", (Y1 - Y0) * (Z1 - Z0),
     lambda n: [(X0, y, z, 1, 0, 0) for z, y in stratified(n, Z0 + M, Z1 - M, Y0 + M, Y1 - M)]),
    ("roomB_right_wall", (Y1 - Y0) * (Z1 - Z0),
     lambda n: [(X1, y, z, -1, 0, 0) for z, y in stratified(n, Z0 + M, Z1 - M, Y0 + M, Y1 - M)]),
    ("roomB_back_wall", (X1 - X0) * (Y1 - Y0),
     lambda n: [(x, y, Z1, 0, 0, -1) for x, y in stratified(n, X0 + M, X1 - M, Y0 + M, Y1 - M)]),
    ("roomB_partition_back", (X1 - X0) * (Y1 - Y0) - 900.0 * 2100.0,
     lambda n: [(x, y, Z0, 0, 0, 1)
                for x, y in stratified(n, X0 + M, X1 - M, Y0 + M, Y1 - M, out_of_doorway)]),
]

N = 200
total = sum(a for _, a, _ in surfaces)
quota = [N * a / total for _, a, _ in surfaces]
counts = [int(q) for q in quota]
for i in sorted(range(len(quota)), key=lambda i: counts[i] - quota[i])[: N - sum(counts)]:
    counts[i] += 1


def emit(p, tag):
    x, y, z, nx, ny, nz = p
    print(f"{x:.4f} {y:.4f} {z:.4f} {nx} {ny} {nz} {tag}")


for (tag, _, make), n in zip(surfaces, counts):
    for p in make(n):
        emit(p, tag)

# The doorway: its reveals (the wall's thickness z 4000..4100) and room B's floor just behind it.
for x, y, z, nx, ny, nz in [(1600.0, y, z, 1, 0, 0) for z, y in stratified(11, 4000 + M, 4100 - M, 0 + M, 2100 - M)]:
    emit((x, y, z, nx, ny, nz), "doorway_jamb_left")
for x, y, z, nx, ny, nz in [(2500.0, y, z, -1, 0, 0) for z, y in stratified(11, 4000 + M, 4100 - M, 0 + M, 2100 - M)]:
    emit((x, y, z, nx, ny, nz), "doorway_jamb_right")
for x, z in stratified(6, 1600 + M, 2500 - M, 4000 + M, 4100 - M):
    emit((x, 2100.0, z, 0, -1, 0), "doorway_lintel")
for x, z in stratified(12, 1300.0, 2800.0, 4100 + M, 4400.0):
    emit((x, 0.0, z, 0, 1, 0), "doorway_floor")

#!/usr/bin/env python3
"""Cost against size from tests/bench/scale.sh's CSV files: a log-log SVG of the time of the
meshing stages, the direct light and refinement, the shooting and the final gather against the
triangle count, each with the exponent fitted from 100k triangles up (least squares on the
logs), and a Markdown table of the same on stdout.

    tests/bench/scale_plot.py OUT.svg RESULTS.csv [MORE.csv ...]
"""
import csv
import math
import sys

GROUPS = [
    ("meshing (load to assembly)", "#1f77b4"),
    ("direct light and refinement", "#ff7f0e"),
    ("shooting", "#2ca02c"),
    ("final gather", "#d62728"),
]


def group_of(stage):
    if stage in ("direct light and refinement", "shooting", "final gather"):
        return stage
    if stage == "baking":
        return None
    return "meshing (load to assembly)"


def read(paths):
    """{triangles: {"group": seconds, ..., "peak": MiB, "elements": n}}"""
    rows = {}
    for path in paths:
        with open(path) as f:
            for r in csv.DictReader(f):
                n = int(r["triangles"])
                row = rows.setdefault(n, {"peak": 0.0, "elements": int(r["elements"])})
                g = group_of(r["stage"])
                if g:
                    row[g] = row.get(g, 0.0) + float(r["seconds"])
                row["peak"] = max(row["peak"], float(r["peak_mib"]))
    return rows


def exponent(points):
    """Least-squares slope of log(seconds) against log(triangles), from 100k up."""
    pts = [(math.log(n), math.log(t)) for n, t in points if n >= 100000 and t > 0]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx > 0 else None


def svg(rows, out):
    sizes = sorted(rows)
    W, H, L, R, T, B = 720, 460, 80, 250, 40, 60
    xs = [math.log10(n) for n in sizes]
    ts = [rows[n][g] for n in sizes for g, _ in GROUPS if rows[n].get(g, 0) > 0]
    x0, x1 = math.floor(min(xs) * 2) / 2, math.ceil(max(xs) * 2) / 2
    y0, y1 = math.floor(math.log10(min(ts))), math.ceil(math.log10(max(ts)))
    px = lambda x: L + (x - x0) / (x1 - x0) * (W - L - R)
    py = lambda y: H - B - (y - y0) / (y1 - y0) * (H - T - B)
    s = [f"<svg xmlns='http://www.w3.org/2000/svg' width='{W}' height='{H}' font-family='sans-serif' font-size='12'>",
         "<rect width='100%' height='100%' fill='white'/>",
         f"<text x='{(L + W - R) / 2}' y='22' text-anchor='middle' font-size='15'>Seconds per stage against triangles (Modern Hall split; 2 cores)</text>"]
    for e in range(int(y0), int(y1) + 1):
        s.append(f"<line x1='{L}' y1='{py(e)}' x2='{W - R}' y2='{py(e)}' stroke='#ddd'/>")
        s.append(f"<text x='{L - 6}' y='{py(e) + 4}' text-anchor='end'>1e{e}</text>")
    for n in sizes:
        x = px(math.log10(n))
        s.append(f"<line x1='{x}' y1='{T}' x2='{x}' y2='{H - B}' stroke='#eee'/>")
        s.append(f"<text x='{x}' y='{H - B + 16}' text-anchor='middle'>{n // 1000}k</text>")
    s.append(f"<text x='{(L + W - R) / 2}' y='{H - 16}' text-anchor='middle'>triangles in the scene's mesh files (log)</text>")
    for i, (g, colour) in enumerate(GROUPS):
        pts = [(n, rows[n][g]) for n in sizes if rows[n].get(g, 0) > 0]
        if not pts:
            continue
        path = " ".join(f"{px(math.log10(n)):.1f},{py(math.log10(t)):.1f}" for n, t in pts)
        s.append(f"<polyline points='{path}' fill='none' stroke='{colour}' stroke-width='2'/>")
        for n, t in pts:
            s.append(f"<circle cx='{px(math.log10(n)):.1f}' cy='{py(math.log10(t)):.1f}' r='3' fill='{colour}'/>")
        k = exponent(pts)
        label = g + (f": N^{k:.2f}" if k is not None else "")
        s.append(f"<rect x='{W - R + 12}' y='{T + 20 * i}' width='12' height='4' fill='{colour}'/>")
        s.append(f"<text x='{W - R + 30}' y='{T + 20 * i + 6}'>{label}</text>")
    s.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(s) + "\n")


def table(rows):
    sizes = sorted(rows)
    head = "| triangles | elements | " + " | ".join(g for g, _ in GROUPS) + " | peak MiB |"
    print(head)
    print("|" + "---|" * (len(GROUPS) + 3))
    for n in sizes:
        r = rows[n]
        cells = [f"{r[g]:.1f} s" if g in r else "—" for g, _ in GROUPS]
        print(f"| {n:,} | {r['elements']:,} | " + " | ".join(cells) + f" | {r['peak']:.0f} |")
    fits = []
    for g, _ in GROUPS:
        k = exponent([(n, rows[n][g]) for n in sizes if rows[n].get(g, 0) > 0])
        if k is not None:
            fits.append(f"{g} N^{k:.2f}")
    print("\nfitted from 100k up: " + ", ".join(fits))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = read(sys.argv[2:])
    svg(rows, sys.argv[1])
    table(rows)

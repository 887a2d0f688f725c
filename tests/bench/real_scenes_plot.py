#!/usr/bin/env python3
"""Time against elements over real scenes, from tests/bench/real_scenes.sh's CSV: a log-log SVG
with one point per scene and quality (labelled with the true error), and a Markdown table of
the runs on stdout.

    tests/bench/real_scenes_plot.py OUT.svg real_scenes.csv [MORE.csv ...]
"""
import csv
import math
import sys

COLOURS = {"draft": "#ff7f0e", "default": "#1f77b4", "final": "#2ca02c"}


def read(paths):
    """The runs that finished: dicts of the CSV's columns."""
    runs = []
    for path in paths:
        with open(path) as f:
            runs += [r for r in csv.DictReader(f) if r["seconds"]]
    return runs


def svg(runs, out):
    W, H, L, R, T, B = 760, 480, 80, 160, 40, 60
    xs = [math.log10(int(r["elements"])) for r in runs]
    ys = [math.log10(float(r["seconds"])) for r in runs]
    x0, x1 = math.floor(min(xs)), math.ceil(max(xs))
    y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
    if x1 == x0:
        x1 += 1
    if y1 == y0:
        y1 += 1
    px = lambda x: L + (x - x0) / (x1 - x0) * (W - L - R)
    py = lambda y: H - B - (y - y0) / (y1 - y0) * (H - T - B)
    s = [f"<svg xmlns='http://www.w3.org/2000/svg' width='{W}' height='{H}' font-family='sans-serif' font-size='12'>",
         "<rect width='100%' height='100%' fill='white'/>",
         f"<text x='{(L + W - R) / 2}' y='22' text-anchor='middle' font-size='15'>Solve time against elements, real scenes (2 cores; label: true RMS error)</text>"]
    for e in range(y0, y1 + 1):
        s.append(f"<line x1='{L}' y1='{py(e)}' x2='{W - R}' y2='{py(e)}' stroke='#ddd'/>")
        s.append(f"<text x='{L - 6}' y='{py(e) + 4}' text-anchor='end'>{10.0 ** e:g} s</text>")
    for e in range(x0, x1 + 1):
        s.append(f"<line x1='{px(e)}' y1='{T}' x2='{px(e)}' y2='{H - B}' stroke='#eee'/>")
        s.append(f"<text x='{px(e)}' y='{H - B + 16}' text-anchor='middle'>{10 ** e:,}</text>")
    s.append(f"<text x='{(L + W - R) / 2}' y='{H - 16}' text-anchor='middle'>elements after refinement (log)</text>")
    for r, x, y in zip(runs, xs, ys):
        colour = COLOURS.get(r["quality"], "#555")
        error = f" {r['rms_percent']} %" if r["rms_percent"] else ""
        s.append(f"<circle cx='{px(x):.1f}' cy='{py(y):.1f}' r='4' fill='{colour}'/>")
        s.append(f"<text x='{px(x) + 7:.1f}' y='{py(y) + 4:.1f}'>{r['scene']}{error}</text>")
    for i, (quality, colour) in enumerate(COLOURS.items()):
        s.append(f"<circle cx='{W - R + 40}' cy='{T + 20 * i}' r='4' fill='{colour}'/>")
        s.append(f"<text x='{W - R + 50}' y='{T + 20 * i + 4}'>{quality}</text>")
    s.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(s) + "\n")


def table(runs):
    print("| scene | quality | elements | gathering vertices | seconds | peak MiB | true RMS | worst point |")
    print("|---|---|---|---|---|---|---|---|")
    for r in runs:
        rms = f"{r['rms_percent']} %" if r["rms_percent"] else "—"
        worst = f"{r['worst_percent']} %" if r["worst_percent"] else "—"
        print(f"| {r['scene']} | {r['quality']} | {int(r['elements']):,} | {int(r['gather_points']):,} | "
              f"{float(r['seconds']):.1f} | {r['peak_mib']} | {rms} | {worst} |")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    runs = read(sys.argv[2:])
    if not runs:
        sys.exit("no finished runs in " + ", ".join(sys.argv[2:]))
    svg(runs, sys.argv[1])
    table(runs)

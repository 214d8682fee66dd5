#!/usr/bin/env python3
"""Plot FMPP clocks per frame against pass size (blocks) as an SVG, from the JSON
reports of `fmpp-render --oracle` (docs/perf-history.md, "Culling against the oracle").

    tools/plot_pass_size.py OUT.svg report_1024.json report_2048.json ...

Each report gives one point per line: measured clocks, the any-hit oracle's and the
nearest-hit oracle's clocks for the same passes. No plotting library: plain SVG.
"""
import json
import math
import sys


def main(argv):
    if len(argv) < 3:
        sys.exit("usage: plot_pass_size.py OUT.svg REPORT.json...")
    points = []
    for path in argv[2:]:
        try:
            with open(path) as f:
                r = json.load(f)
            points.append((r["fmpp"]["blocks"], r["cycles"], r["oracle"]["any_hit_cycles"],
                           r["oracle"]["nearest_hit_cycles"]))
        except (OSError, ValueError, KeyError) as e:
            sys.exit(f"plot_pass_size.py: {path}: not a report of fmpp-render --oracle ({e})")
    points.sort()
    w, h, left, right, top, bottom = 560, 320, 70, 170, 20, 50
    xs = [math.log2(p[0]) for p in points]
    ymax = max(max(p[1:]) for p in points) * 1.1
    x0, x1 = min(xs), max(xs)
    if x1 == x0:
        x1 = x0 + 1

    def px(x):
        return left + (x - x0) / (x1 - x0) * (w - left - right)

    def py(y):
        return top + (1 - y / ymax) * (h - top - bottom)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<line x1="{left}" y1="{py(0)}" x2="{w - right}" y2="{py(0)}" stroke="black"/>',
           f'<line x1="{left}" y1="{top}" x2="{left}" y2="{py(0)}" stroke="black"/>']
    step = 10 ** math.floor(math.log10(ymax / 4))
    tick = step * max(1, round(ymax / 4 / step))
    y = 0.0
    while y <= ymax:
        out.append(f'<text x="{left - 6}" y="{py(y) + 4}" text-anchor="end">{y / 1e6:g} M</text>')
        out.append(f'<line x1="{left}" y1="{py(y)}" x2="{w - right}" y2="{py(y)}" stroke="#ddd"/>')
        y += tick
    for x, p in zip(xs, points):
        out.append(f'<text x="{px(x)}" y="{py(0) + 18}" text-anchor="middle">{p[0]}</text>')
    out.append(f'<text x="{(left + w - right) / 2}" y="{h - 10}" text-anchor="middle">blocks (rays per pass)</text>')
    series = [(1, "measured", "#c0392b"), (2, "any-hit oracle", "#2471a3"), (3, "nearest-hit oracle", "#229954")]
    for i, (col, name, colour) in enumerate(series):
        pts = " ".join(f"{px(x):.1f},{py(p[col]):.1f}" for x, p in zip(xs, points))
        out.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for x, p in zip(xs, points):
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(p[col]):.1f}" r="3" fill="{colour}"/>')
        out.append(f'<text x="{w - right + 10}" y="{top + 20 * i + 10}" fill="{colour}">{name}</text>')
    out.append(f'<text x="{left + 4}" y="{top + 10}">FMPP clocks per frame</text>')
    out.append("</svg>")
    with open(argv[1], "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv)

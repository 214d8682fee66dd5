#!/usr/bin/python3
"""Steps per broadcast of every intersection form at every multiplier width n.

    tools/form_steps.py --intersect build/fmpp-intersect [--csv OUT.csv] [--work DIR]

Runs `fmpp-intersect --report` (golden model) on one fixed scene for each form and n and
prints (or writes) form, n, steps per broadcast and broadcasts as CSV. The scene: 300
triangles of random size and orientation 3 to 5 units in front of the origin and 1,024
rays from the origin into them, drawn with a fixed seed, so the counts are the same on
every machine (tools/docs.py's generator `steps` and the ctest docs_check use them).
The figures of an earlier build are kept as CSV in docs/data/ (the table shows them
beside today's).
"""
import argparse
import csv
import io
import json
import os
import random
import subprocess
import sys
import tempfile

NS = [8, 12, 16, 20, 24, 28, 32]
# (name, fmpp-intersect options)
# Every row is the whole program (--no-gates: a gate skips a broadcast's tail where no
# block may be inside, intersection.md, which would make the figure the scene's).
FORMS = [
    ("paper, ray-parallel, constant multiply", ["--no-gates"]),
    ("paper, ray-parallel, generic multiply", ["--mul", "generic", "--no-gates"]),
    ("paper, object-parallel, constant multiply", ["--mapping", "object", "--no-gates"]),
    ("watertight", ["--watertight", "--no-gates"]),
    ("arbitrary origin", ["--origins", "general", "--no-gates"]),
    # The same on 32-word blocks, the frames' machine, where the form keeps its pair words
    # (intersection.md); the build before them ran the same program on either.
    ("arbitrary origin, 32-word blocks", ["--origins", "general", "--words", "32", "--no-gates"]),
]


def write_scene(folder):
    """The fixed scene's triangle and ray files in folder; returns their paths."""
    rng = random.Random(20261127)
    tris, rays = os.path.join(folder, "steps_tris.txt"), os.path.join(folder, "steps_rays.txt")
    with open(tris, "w") as f:
        for _ in range(300):
            c = [rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(3, 5)]
            size = rng.uniform(0.05, 0.3)
            pts = [[c[k] + rng.uniform(-size, size) for k in range(3)] for _ in range(3)]
            f.write(" ".join("%.9g" % v for p in pts for v in p) + "\n")
    with open(rays, "w") as f:
        for _ in range(1024):
            f.write("0 0 0 %.9g %.9g 1\n" % (rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)))
    return tris, rays


def measure(intersect, folder):
    """{(form, n): (steps per broadcast, broadcasts)} from fmpp-intersect on the fixed scene."""
    os.makedirs(folder, exist_ok=True)
    tris, rays = write_scene(folder)
    out = {}
    for name, opts in FORMS:
        for n in NS:
            cmd = [intersect, "--triangles", tris, "--rays", rays, "--bits", str(n), "--blocks", "1024",
                   "--out", os.devnull, "--report", "-"] + opts
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit("form_steps.py: %s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stderr))
            rep = json.loads(r.stdout)
            out[(name, n)] = (float(rep["steps_per_broadcast"]), int(rep["broadcasts"]))
    return out


def to_csv(figures):
    s = io.StringIO()
    w = csv.writer(s, lineterminator="\n")
    w.writerow(["form", "n", "steps_per_broadcast", "broadcasts"])
    for (name, n), (steps, count) in figures.items():
        w.writerow([name, n, "%.1f" % steps, count])
    return s.getvalue()


def read_csv(path):
    """{(form, n): (steps, broadcasts)} of a CSV this tool wrote (lines starting # are provenance)."""
    with open(path, encoding="utf-8") as f:
        rows = csv.DictReader(l for l in f if not l.startswith("#"))
        return {(r["form"], int(r["n"])): (float(r["steps_per_broadcast"]), int(r["broadcasts"])) for r in rows}


def cell(fig):
    steps, count = fig
    return "-" if count == 0 else "%.1f" % steps


def table(now, before, before_label):
    """Markdown: per form and n, the steps per broadcast before and now."""
    lines = ["| form | " + " | ".join("n = %d" % n for n in NS) + " |",
             "| --- | " + " | ".join("---:" for _ in NS) + " |"]
    for name, _ in FORMS:
        cells = []
        for n in NS:
            b, a = before.get((name, n)), now[(name, n)]
            if b is None or b[1] == 0 or a[1] == 0:
                cells.append(cell(a))
            else:
                cells.append("%s -> %s (%.2fx)" % (cell(b), cell(a), a[0] / b[0]))
        lines.append("| %s | %s |" % (name, " | ".join(cells)))
    lines += ["", "Each cell: %s -> this build (the ratio); '-': every triangle went to the host at that n "
              "(no broadcast to count)." % before_label]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--intersect", required=True, help="the fmpp-intersect to measure")
    ap.add_argument("--csv", help="write the CSV here (default: standard output)")
    ap.add_argument("--work", help="folder for the scene files (default: a temporary one)")
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="form-steps-")
    text = to_csv(measure(a.intersect, work))
    if a.csv:
        with open(a.csv, "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()

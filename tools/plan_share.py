#!/usr/bin/env python3
"""The precision plan's share of a first render, per shipped scene (docs/perf.md).

Runs `fmpp-render --replan --plan-cache ""` (a first render: the plan made, not read from
a cache) on the golden model at 128 x 128, `--runs` times per scene, the scenes
interleaved so that a slow spell of the machine falls on all of them, and prints per
scene the medians (and ranges) of:

  plan       the report's plan.seconds
  render     the report's wall_seconds: the plan and the frame, from the scene loaded to
             the picture made
  whole run  the command's own wall time (the program's start, loading the scene and
             writing the picture included), as `time` gives it
  and the plan's share of each.

Outputs go to a temporary directory; nothing is written into the repository.
Usage: tools/plan_share.py [--build build] [--runs 5] [--scenes a,b,...] [--size 128]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHIPPED = ["cornell", "spheres_1k", "spheres_10k", "one_triangle", "armadillo", "scans", "armadillo_soft"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build directory (fmpp-render in it)")
    ap.add_argument("--runs", type=int, default=5, help="runs per scene (>= 1)")
    ap.add_argument("--scenes", default=",".join(SHIPPED), help="comma-separated scene names of scenes/")
    ap.add_argument("--size", type=int, default=128, help="the picture's width and height")
    a = ap.parse_args()
    if a.runs < 1:
        ap.error("--runs must be at least 1")
    render = os.path.join(os.path.abspath(a.build), "fmpp-render")
    if not os.access(render, os.X_OK):
        ap.error(f"{render}: not built (cmake --build {a.build} --target fmpp-render)")
    scenes = [s for s in a.scenes.split(",") if s]
    for s in scenes:
        if not os.path.isfile(os.path.join(ROOT, "scenes", s + ".json")):
            ap.error(f"no scene scenes/{s}.json")
    got = {s: [] for s in scenes}
    with tempfile.TemporaryDirectory(prefix="plan-share-") as tmp:
        for run in range(a.runs):
            for s in scenes:
                report = os.path.join(tmp, s + ".json")
                cmd = [render, "--scene", os.path.join(ROOT, "scenes", s + ".json"), "--backend", "cmodel",
                       "--width", str(a.size), "--height", str(a.size), "--replan", "--plan-cache", "", "--quiet",
                       "--report", report, "--out", os.path.join(tmp, s + ".png")]
                t0 = time.monotonic()
                r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                whole = time.monotonic() - t0
                if r.returncode != 0:
                    sys.exit(f"plan_share: {s}: fmpp-render failed ({r.returncode}): {r.stderr.strip()}")
                with open(report) as f:
                    rep = json.load(f)
                got[s].append((rep["plan"]["seconds"], rep["wall_seconds"], whole, rep["plan"]["bits"]))
            print(f"run {run + 1} of {a.runs} done", file=sys.stderr)

    def ms(v):
        return f"{1e3 * v:.1f} ms" if v < 1 else f"{v:.2f} s"

    def med(xs, fmt):
        return f"{fmt(statistics.median(xs))} ({fmt(min(xs))} to {fmt(max(xs))})"

    pct = lambda v: f"{100 * v:.0f} %"
    print(f"| scene | n | plan | render | whole run | plan's share of the render | of the whole run |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for s in scenes:
        plan = [g[0] for g in got[s]]
        rend = [g[1] for g in got[s]]
        whole = [g[2] for g in got[s]]
        share = [g[0] / g[1] for g in got[s]]
        share_whole = [g[0] / g[2] for g in got[s]]
        bits = sorted({g[3] for g in got[s]})
        print(f"| {s} | {', '.join(map(str, bits))} | {med(plan, ms)} | {med(rend, ms)} | {med(whole, ms)} | "
              f"{med(share, pct)} | {med(share_whole, pct)} |")


if __name__ == "__main__":
    main()

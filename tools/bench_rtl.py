#!/usr/bin/env python3
"""make bench-rtl: the Verilated FMPP against the golden model on the same frames.

    tools/bench_rtl.py [--build build] [--rounds 3] [--json FILE] [--before OTHER_BUILD]

For each frame (the README's render command, `make render`'s, and one gallery frame at the
README's gallery settings), runs fmpp-render with --backend rtl and with --backend cmodel
one after the other, --rounds times (interleaved, so that a machine's slow minute falls on
both), and reports the median wall time of each, their ratio, the FMPP clocks and the
simulated clocks per second of the RTL. The pictures of every pair must be byte-identical
(the RTL and the golden model are bit-exact): a difference is an error. Where the
precision plan chooses the machine (the README's command), the golden model may get a
machine the RTL is not built in (fewer words per block), so the clocks are each backend's.
Prints a Markdown table (and writes the figures as JSON with --json). --before runs a second
build's RTL (another RTL's fmpp-render) in the same rounds: a change's cost in simulation
speed, measured interleaved on the same machine.
"""
import argparse
import filecmp
import json
import os
import resource
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import docblock  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CPU = {}  # picture path -> the render's CPU seconds (user + system): less moved by a loaded machine than wall time

# (name, fmpp-render arguments): the README's main job, then a gallery frame.
FRAMES = (
    ("README render (make render)", []),
    ("gallery: spheres_1k 256 x 256", ["--scene", "scenes/spheres_1k.json", "--bits", "24", "--blocks", "4096",
                                       "--words", "32", "--width", "256", "--height", "256", "--oracle"]),
)


def render(build, args, backend, out_dir, tag):
    png = os.path.join(out_dir, "%s_%s.png" % (tag, backend))
    report = os.path.join(out_dir, "%s_%s.json" % (tag, backend))
    cmd = [os.path.join(build, "fmpp-render")] + args + ["--backend", backend, "--out", png, "--report", report,
                                                          "--quiet"]
    t0, c0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.monotonic() - t0
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU[png] = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    if r.returncode != 0:
        sys.exit("bench_rtl: %s failed (exit %d): %s" % (" ".join(cmd), r.returncode, r.stderr.strip()))
    with open(report, encoding="utf-8") as f:
        rep = json.load(f)
    return wall, rep["cycles"], png


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory (fmpp-render)")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds per frame (median taken)")
    ap.add_argument("--frames", type=int, default=len(FRAMES), help="the first N frames only")
    ap.add_argument("--json", help="write the figures here")
    ap.add_argument("--before", help="a second build directory (another RTL's fmpp-render): its RTL backend runs in "
                                     "the same interleaved rounds, and the table gives both ratios")
    a = ap.parse_args()
    if a.rounds < 1 or not 1 <= a.frames <= len(FRAMES):
        sys.exit("bench_rtl: --rounds must be >= 1 and --frames in [1, %d]" % len(FRAMES))
    out_dir = os.path.join(a.build, "bench-rtl")
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for k, (name, args) in enumerate(FRAMES[:a.frames]):
        runs = (("before", "rtl"),) if a.before else ()
        runs += (("rtl", "rtl"), ("cmodel", "cmodel"))
        times = {tag: [] for tag, _ in runs}
        cpu = {}
        clocks = {}
        for rnd in range(a.rounds):
            pngs = {}
            for tag, be in runs:
                build = os.path.abspath(a.before) if tag == "before" else a.build
                wall, cyc, pngs[tag] = render(build, args, be, out_dir, "f%d_r%d_%s" % (k, rnd, tag))
                times[tag].append(wall)
                cpu.setdefault(tag, []).append(CPU[pngs[tag]])
                if clocks.setdefault(tag, cyc) != cyc:
                    sys.exit("bench_rtl: %s on %s: %d clocks on one run, %d on another" % (name, tag, clocks[tag], cyc))
            for tag, _ in runs[:-1]:
                if not filecmp.cmp(pngs[tag], pngs["cmodel"], shallow=False):
                    sys.exit("bench_rtl: %s: the RTL's picture (%s) differs from the golden model's (%s, %s)"
                             % (name, tag, pngs[tag], pngs["cmodel"]))
            print("%s, round %d: %s" % (name, rnd + 1, ", ".join("%s %.2f s" % (t, times[t][-1]) for t, _ in runs)),
                  flush=True)
        rtl, cm = statistics.median(times["rtl"]), statistics.median(times["cmodel"])
        rows.append(dict(frame=name, args=args, rtl_s=round(rtl, 2), cmodel_s=round(cm, 2), ratio=round(rtl / cm, 2),
                         rtl_clocks=clocks["rtl"], cmodel_clocks=clocks["cmodel"],
                         rtl_clocks_per_s=round(clocks["rtl"] / rtl), rounds=a.rounds))
        rows[-1]["cpu_s"] = {t: round(statistics.median(v), 2) for t, v in cpu.items()}
        if a.before:
            bt = statistics.median(times["before"])
            rows[-1].update(before_s=round(bt, 2), before_ratio=round(bt / cm, 2), before_clocks=clocks["before"])
    stamp = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    print("\n%s, %s, %d cores, %d interleaved rounds, medians; pictures byte-identical\n"
          % (stamp, docblock.cpu_model(), os.cpu_count() or 0, a.rounds))
    before = " | rtl of --before | before / cmodel" if a.before else ""
    print("| frame | FMPP clocks (rtl, cmodel) | rtl | cmodel | rtl / cmodel | RTL clocks/s%s |" % before)
    print("| --- | ---: | ---: | ---: | ---: | ---:%s |" % (" | ---: | ---:" if a.before else ""))
    for r in rows:
        same = r["rtl_clocks"] == r["cmodel_clocks"]
        cyc = format(r["rtl_clocks"], ",") + ("" if same else ", " + format(r["cmodel_clocks"], ","))
        extra = " | %.2f s | %.2f" % (r["before_s"], r["before_ratio"]) if a.before else ""
        print("| %s | %s | %.2f s | %.2f s | **%.2f** | %s%s |" % (r["frame"], cyc, r["rtl_s"], r["cmodel_s"], r["ratio"],
                                                                  format(r["rtl_clocks_per_s"], ","), extra))
    print("\nCPU time (user + system) of the same renders, medians:\n")
    tags = list(rows[0]["cpu_s"]) if rows else []
    print("| frame | " + " | ".join(tags) + " | " + " | ".join("%s / cmodel" % t for t in tags if t != "cmodel") + " |")
    print("| --- |" + " ---: |" * (2 * len(tags) - 1))
    for r in rows:
        c = r["cpu_s"]
        print("| %s | %s | %s |" % (r["frame"], " | ".join("%.2f s" % c[t] for t in tags),
                                    " | ".join("%.2f" % (c[t] / c["cmodel"]) for t in tags if t != "cmodel")))
    if a.json:
        with open(a.json, "w", encoding="utf-8") as f:
            json.dump(dict(date=stamp, cpu=docblock.cpu_model(), cores=os.cpu_count(), frames=rows), f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())

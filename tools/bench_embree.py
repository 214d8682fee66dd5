#!/usr/bin/env python3
"""make bench-embree: the gallery's frames traced by Embree on one CPU thread beside the
FMPP's rays per second from its clocks; rewrites the block `embree` of docs/perf.md.

    tools/bench_embree.py [--build build] [--repeat 5] [--tables-only]

For each frame of tools/gallery.py's BENCH_FRAMES: the FMPP's report (BUILD/gallery/, made by
`make gallery` or here if missing) gives the frame's rays and clocks; fmpp-embree-bench
renders the same frame with Embree (rays per second of the rtcIntersect1 calls, and of
one rtcIntersect1M stream per batch, in the fastest of --repeat renders or more; BVH
build apart) and checks a sample of every batch's hits
against the exact reference.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import docblock  # noqa: E402
import gallery  # noqa: E402

ROOT = gallery.ROOT
PAPER_MHZ = 50.0  # the paper's clock
# The measured clocks: make fpga's largest HX8K machine and make asic's largest size in
# 0.18 um cells (gallery.py reads both from the committed results: the 4,096-block chip's clock).
FPGA_MHZ = gallery.fpga_mhz()
ASIC_MHZ, ASIC_SIZE = gallery.asic_clock()
# make asic's clock projected to the CPU's process node (tools/node_scale.py): labelled so.
PROJ_MHZ, PROJ_LABEL = gallery.projected_clock(ASIC_MHZ)
KINDS = ("primary", "shadow", "secondary")


def bench_path(build, scene, side, stream=False):
    return os.path.join(build, "bench-embree", "%s_%d%s.json" % (scene, side, "_stream" if stream else ""))


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def fmpp_rays(rep, kind=None):
    r = rep["rays"]
    if kind is None:
        return sum(r.values())
    return r["reflection"] + r["refraction"] if kind == "secondary" else r[kind]


def si(x):
    for unit, f in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if x >= f:
            return "%.3g %s" % (x / f, unit)
    return "%.3g" % x


def tables(build, repeat, min_seconds):
    main = ["| scene, frame | rays: Embree render (FMPP render) | Embree, 1 thread, per ray | Embree, stream "
            "| BVH build | FMPP clocks | FMPP at 50 MHz | at %.1f MHz (iCE40, measured) "
            "| at %.1f MHz (%s) | faster Embree / FMPP at %.1f MHz "
            "| at %.0f MHz (%s) | faster Embree / FMPP there |" % (
                FPGA_MHZ, ASIC_MHZ, ASIC_SIZE, ASIC_MHZ, PROJ_MHZ, PROJ_LABEL),
            "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    kinds = ["| scene, frame | batch kind | rays | Embree rays/s, per ray | stream | FMPP clocks per ray "
             "| FMPP rays/s at 50 MHz |", "| --- | --- | ---: | ---: | ---: | ---: | ---: |"]
    check = ["| scene, frame | rays checked (of all) | same hit | hit at the ray's end vs miss | tie (shared edge) "
             "| hit vs miss | other triangle | largest relative t error |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    cpu_hz = docblock.cpu_mhz() * 1e6
    clocks = ["| scene, frame | FMPP rays per 1000 clocks | Embree rays per 1000 CPU clocks, per ray (stream) "
              "| FMPP broadcasts (any-hit oracle) | FMPP clocks / any-hit oracle | load + readback share of the clocks "
              "| box tests: host, FMPP (their share of the clocks) | host ray-triangle tests |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    meta = None
    for scene, side in gallery.BENCH_FRAMES:
        f = gallery.load(build, scene, side)
        e = load(bench_path(build, scene, side))
        es = load(bench_path(build, scene, side, True))
        meta = e
        name = "%s %d x %d" % (scene, side, side)
        n, cyc = fmpp_rays(f), f["cycles"]
        fmpp = lambda mhz: n / (cyc / (mhz * 1e6))  # noqa: E731
        embree = max(e["rays_per_second"], es["rays_per_second"])
        main.append("| %s | %s (%s) | %s rays/s | %s rays/s | %.1f ms | %s | %s rays/s | %s | %s | %.1f | %s | %.2f |" % (
            name, docblock.fmt_int(e["rays_total"]), docblock.fmt_int(n), si(e["rays_per_second"]),
            si(es["rays_per_second"]), 1e3 * e["build_seconds"], docblock.fmt_int(cyc), si(fmpp(PAPER_MHZ)),
            si(fmpp(FPGA_MHZ)), si(fmpp(ASIC_MHZ)), embree / fmpp(ASIC_MHZ), si(fmpp(PROJ_MHZ)),
            embree / fmpp(PROJ_MHZ)))
        per_cpu_clock = lambda x: "%.2f" % (1e3 * x / cpu_hz) if cpu_hz else "?"  # noqa: E731
        clocks.append("| %s | %.2f | %s (%s) | %s (%s) | %.2f | %.1f %% | %s, %s (%.1f %%) | %s |" % (
            name, 1e3 * n / cyc, per_cpu_clock(e["rays_per_second"]), per_cpu_clock(es["rays_per_second"]),
            docblock.fmt_int(f["broadcasts"]), docblock.fmt_int(f["oracle"]["any_hit_broadcasts"]),
            f["oracle"]["cycles_over_any_hit"], 100.0 * (f["load_cycles"] + f["readback_cycles"]) / cyc,
            docblock.fmt_int(f["box_tests"]), docblock.fmt_int(f.get("fmpp_box_tests", 0)),
            100.0 * f.get("box_cycles", 0) / cyc, docblock.fmt_int(f["host_tests"])))
        for k in KINDS:
            nk, ck = fmpp_rays(f, k), f["by_kind"][k]["cycles"]
            if nk == 0:
                continue
            kinds.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                name, k, docblock.fmt_int(nk), si(e["by_kind"][k]["rays_per_second"]),
                si(es["by_kind"][k]["rays_per_second"]), docblock.fmt_int(ck / nk),
                si(nk / (ck / (PAPER_MHZ * 1e6)))))
        c = e["check"]["all"]
        check.append("| %s | %s (%s) | %s | %s | %s | %s | %s | %.1e |" % (
            name, docblock.fmt_int(c["checked"]), docblock.fmt_int(e["rays_total"]), docblock.fmt_int(c["same"]),
            docblock.fmt_int(c["at_end"]), docblock.fmt_int(c["tie"]), docblock.fmt_int(c["near_miss"]),
            docblock.fmt_int(c["other"]), c["max_t_error"]))
    head = ("%s; Embree %s, %d thread, per ray: %s, stream: "
            "rtcIntersect1M, one coherent stream per batch; the fastest of at least %d renders (more until the calls took %g s). FMPP: the golden model's clocks (n = 24, 4096 x 32 blocks, culled), rays per second = the frame's rays / "
            "(clocks / clock rate). Regenerate with `make bench-embree` (after `make gallery`)." % (
                docblock.provenance(os.path.join(build, "bench-embree")), meta["embree"]["version"], meta["embree"]["threads"], meta["embree"]["call"], repeat, min_seconds))
    per_clock = ("Per clock (the CPU's clock as the kernel reports it, %.0f MHz: nominal, a VM does not show the "
                 "boost clock), and where the FMPP's clocks go (the host's work beside them):" % (cpu_hz / 1e6))
    return "\n".join([head, ""] + main + ["", "By batch kind:", ""] + kinds + ["", per_clock, ""] + clocks +
                     ["", "Embree's hits against the exact reference on the same renders' rays (every ray where a "
                      "batch costs the reference at most 2e8 ray-triangle tests, else an even sample):", ""] + check)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build", help="build directory holding fmpp-render and fmpp-embree-bench")
    ap.add_argument("--out-dir", help="where the block goes (default: BUILD/docs; installed by make docs-update)")
    ap.add_argument("--repeat", type=int, default=5, help="timed Embree renders per frame, at least (the fastest counts)")
    ap.add_argument("--min-seconds", type=float, default=1.0, help="render again until the calls took this long")
    ap.add_argument("--check-tests", type=float, default=2e8, help="reference tests allowed per batch for the check")
    ap.add_argument("--tables-only", action="store_true", help="no runs: rewrite the block from the reports")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    if a.repeat < 1:
        sys.exit("--repeat %d: must be at least 1" % a.repeat)
    os.makedirs(os.path.join(build, "bench-embree"), exist_ok=True)
    if not a.tables_only:
        docblock.save_provenance(os.path.join(build, "bench-embree"), ROOT)
        for scene, side in gallery.BENCH_FRAMES:
            if not os.path.exists(gallery.report_path(build, scene, side)):
                gallery.render(build, scene, side)
            cmd = [os.path.join(build, "fmpp-embree-bench"), "--scene", os.path.join(ROOT, "scenes", scene + ".json"),
                   "--width", str(side), "--height", str(side), "--repeat", str(a.repeat), "--min-seconds",
                   "%g" % a.min_seconds]
            docblock.run(cmd + ["--check-tests", "%g" % a.check_tests, "--json", bench_path(build, scene, side)])
            docblock.run(cmd + ["--stream", "--check-tests", "0", "--json", bench_path(build, scene, side, True)])
    text = tables(build, a.repeat, a.min_seconds)
    with open(os.path.join(build, "bench-embree", "table.md"), "w", encoding="utf-8") as f:
        f.write(text + "\n")
    docblock.save_block(os.path.abspath(a.out_dir or os.path.join(build, "docs")), "docs/perf.md", "embree", text)
    print("make docs-update installs it into docs/perf.md")


if __name__ == "__main__":
    main()

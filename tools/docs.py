#!/usr/bin/python3
"""The generated documentation: regenerate it, install it, check it.

    tools/docs.py build  [--build build] [--only NAME ...]   # make docs
    tools/docs.py update [--build build]                     # make docs-update
    tools/docs.py check  [--build build]                     # the ctest docs_check
    tools/docs.py list                                       # the generators

`build` runs every generator (GENERATORS below) into BUILD/docs/, a copy of the docs/
layout: whole generated files in generated/, pictures and plots in img/, plot data in
data/, and the generated blocks of hand-written files in blocks/ (tools/docblock.py).
Nothing there is committed; `update` copies the files over the committed ones and
installs the blocks into README.md and docs/*.md - the one command that writes them.

`check` regenerates, at small sizes, what does not depend on the machine's speed (clock
and instruction counts, steps per broadcast, ray counts, the lockstep report) and
fails naming every committed figure that differs; timings are never compared (they
carry the machine and the date they were measured on instead).
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import chip_figures  # noqa: E402
import docblock  # noqa: E402
import form_steps  # noqa: E402
import gallery  # noqa: E402

from docs_common import PY, ROOT, out_dir, run, tool  # noqa: E402,F401
from docs_plan import PLAN_CHECK, gen_plan, plan_render, plan_row, share_sentence  # noqa: E402,F401


# ------------------------------------------------------------------ generators

def synth_baselines(data):
    """--baseline-dir/--baseline-label pairs of fmpp-report area, from docs/data/synth/baselines.txt."""
    args = []
    with open(os.path.join(data, "synth", "baselines.txt"), encoding="utf-8") as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                folder, label = line.rstrip("\n").split("|", 1)
                args += ["--baseline-dir", os.path.join(data, "synth", folder), "--baseline-label", label]
    return args


def area_md(build, out):
    """fmpp-report area over the committed synthesis and FPGA results, then the standard-cell
    section tools/asic_report.py makes from docs/asic/ (make asic's committed results)."""
    data = os.path.join(ROOT, "docs", "data")
    base = out + ".base"
    run([tool(build, "fmpp-report"), "area", "--synth-dir", os.path.join(data, "synth"),
         "--fpga-csv", os.path.join(data, "fpga", "summary.csv")] + synth_baselines(data) + ["--out", base])
    run([sys.executable, os.path.join(ROOT, "tools", "asic_report.py"), "doc", "--area-md", base,
         "--dir", os.path.join(ROOT, "docs", "asic"), "--out", out])
    os.remove(base)


def gen_area(build):
    """docs/generated/area.md: the FPGA and gate counts, and the standard cells."""
    os.makedirs(os.path.join(out_dir(build), "generated"), exist_ok=True)
    area_md(build, os.path.join(out_dir(build), "generated", "area.md"))


def paper_clocks():
    """--clock arguments of fmpp-report paper: make asic's measured clock and its projection to the CPU's node."""
    asic, size = gallery.asic_clock()
    proj, label = gallery.projected_clock(asic)
    return ["--clock", "%.1f:%s" % (asic, size), "--clock", "%.1f:%s" % (proj, label)]


def gen_paper(build):
    """docs/generated/paper-reproduction.md, docs/img/fig{5,6,7}*.png, docs/data/paper_data.json."""
    run([tool(build, "fmpp-report"), "paper", "--out", os.path.join(out_dir(build), "generated", "paper-reproduction.md"),
         "--img-dir", os.path.join(out_dir(build), "img"), "--data-dir", os.path.join(out_dir(build), "data")] +
        paper_clocks())


def gen_precision(build):
    """docs/generated/precision.md, docs/img/precision_*.png, docs/data/precision_data.json (about 6 min)."""
    run([tool(build, "fmpp-report"), "precision", "--out", os.path.join(out_dir(build), "generated", "precision.md"),
         "--img-dir", os.path.join(out_dir(build), "img"), "--data-dir", os.path.join(out_dir(build), "data")])


def gen_gallery(build):
    """README.md's gallery, docs/raytracer.md's gallery-oracle table, docs/img/gallery/ (make gallery)."""
    run([PY, os.path.join(ROOT, "tools", "gallery.py"), "--build", build, "--out-dir", out_dir(build)])


def gen_embree(build):
    """docs/perf.md's embree block (make bench-embree; after the gallery)."""
    run([PY, os.path.join(ROOT, "tools", "bench_embree.py"), "--build", build, "--out-dir", out_dir(build)])


# The precision plan's choices on the scenes of docs/raytracer.md's table: golden model,
# 128 x 128, the plan free (no --bits, --blocks, --words), compared with the reference.


def gen_render(build):
    """docs/img/cornell_rtl.png: make render's picture (the Verilated RTL, else the golden model's same picture)."""
    listing = subprocess.run([tool(build, "fmpp-sim"), "--list"], capture_output=True, text=True).stdout
    backend = []
    if "large" not in listing.split():
        # The plan then picks among the built configurations only; the golden model, bit for
        # bit the RTL, renders the picture make render makes with every configuration built.
        print("docs/img/cornell_rtl.png from the golden model: the RTL configuration 'large' is not built here",
              file=sys.stderr)
        backend = ["--backend", "cmodel"]
    os.makedirs(os.path.join(out_dir(build), "img"), exist_ok=True)
    run([tool(build, "fmpp-render"), "--quiet", "--out", os.path.join(out_dir(build), "img", "cornell_rtl.png"),
         "--report", os.path.join(build, "docs-render.json")] + backend)


# The lockstep walk-through of docs/debugging.md (make wave-inject's run).
INJECT = {"config": "odd", "at": 2000}


def inject_report(build, folder):
    os.makedirs(folder, exist_ok=True)
    cmd = [tool(build, "fmpp-sim"), "--config", INJECT["config"], "--seed", "1", "--ops", str(INJECT["at"] + 1000),
           "--mode", "check", "--inject-at", str(INJECT["at"]), "--trace", os.path.join(folder, "inject.fst")]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 1 or "LOCKSTEP MISMATCH" not in r.stdout + r.stderr:
        sys.exit("fmpp-sim --inject-at: expected a lockstep mismatch (exit 1), got %d:\n%s" % (r.returncode, r.stdout + r.stderr))
    return (r.stdout + r.stderr).replace(folder, "build/wave")


def inject_facts(text):
    def find(pattern):
        m = re.search(pattern, text)
        if not m:
            sys.exit("the lockstep report has no '%s':\n%s" % (pattern, text))
        return m.groups()
    blk, word, rtl, model = find(r"inject: block (\d+) word (\d+): RTL <- (0x[0-9a-f]+), model <- (0x[0-9a-f]+)")
    entry, ecycle, seen = find(r"after queue entry #(\d+) \(.* executed at cycle (\d+)\) at cycle (\d+)")
    t = find(r"at t = (\d+) \(cycle")[0]
    return {"block": blk, "word": word, "rtl": rtl, "model": model, "entry": entry, "cycle": ecycle, "seen": seen,
            "t": int(t)}


def inject_block(text):
    f = inject_facts(text)
    # The run's wall time is the one figure of the report that depends on the machine.
    lines = [re.sub(r" seconds=[0-9.]+", "", l) for l in text.splitlines()
             if l.strip() and not l.startswith("open it yourself")]
    first, last = f["t"] - 150, f["t"]
    return "\n".join([
        "```", *lines, "```", "",
        "- **Which entry**: queue entry #%s, a window write of block %s word %s with %s *as the model received it*." % (
            f["entry"], f["block"], f["word"], f["model"]),
        "- **When**: it executed at clock edge %s, i.e. at t = 10 x %s - 5 = %d in the FST (the last line says so "
        "when tracing). %s The check compares the state right after each entry, and the trace ends with the "
        "mismatch." % (f["cycle"], f["cycle"], f["t"],
                       "The run stopped at that same cycle." if f["seen"] == f["cycle"] else
                       "The run noticed at cycle %s, when a later access drained the queue." % f["seen"]),
        "- **What differs**: after that entry the RTL's block %s word %s is %s, the model's %s. Nothing else differs "
        "(the report lists up to 16 differences)." % (f["block"], f["word"], f["rtl"], f["model"]),
        "- **Reproduce**: the same seed gives the same accesses, so a long run can be repeated with `--trace-start` / "
        "`--trace-end` around the reported cycle to keep the FST small.", "",
        "In GTKWave (`gtkwave build/wave/inject.fst tb/fmpp.gtkw`) type %d into *From:* and %d into *To:* (each "
        "followed by Enter) and click in the wave area at %d to place the marker: the names column then shows each "
        "signal's value at the marker. `make wave-inject` takes the picture below the same way: 15 clocks up to "
        "the edge; the trace ends with the mismatch, so the marker sits at the right edge of the picture, where "
        "the word takes the RTL's value." % (first, last, f["t"])])


def gen_inject(build):
    """docs/debugging.md's walk-through figures and docs/img/lockstep-mismatch.png (make wave-inject)."""
    folder = os.path.join(build, "wave")
    text = inject_report(build, folder)
    docblock.save_block(out_dir(build), "docs/debugging.md", "inject", inject_block(text))
    if shutil.which("xvfb-run") and shutil.which("gtkwave"):
        run([os.path.join(ROOT, "tools", "wave_inject.sh"), tool(build, "fmpp-sim"), INJECT["config"], str(INJECT["at"]),
             folder], stdout=subprocess.DEVNULL)
        os.makedirs(os.path.join(out_dir(build), "img"), exist_ok=True)
        shutil.copyfile(os.path.join(folder, "inject.png"), os.path.join(out_dir(build), "img", "lockstep-mismatch.png"))
    else:
        print("skipped docs/img/lockstep-mismatch.png: xvfb-run and gtkwave are needed (make deps)", file=sys.stderr)


# docs/perf.md's table of steps per broadcast per form and n, beside an earlier build's.
STEPS_BEFORE = ("steps_before_shr.csv", "the build before the shifted operand (commit 4709c66)")


def steps_block(build, folder):
    now = form_steps.measure(tool(build, "fmpp-intersect"), folder)
    return form_steps.table(now, form_steps.read_csv(os.path.join(ROOT, "docs", "data", STEPS_BEFORE[0])),
                            STEPS_BEFORE[1])


def gen_steps(build):
    """docs/perf.md's steps per broadcast of every form at every n (fmpp-intersect, golden model)."""
    docblock.save_block(out_dir(build), "docs/perf.md", "form-steps", steps_block(build, os.path.join(build, "form-steps")))


def gen_chip(build):
    """docs/architecture.md's and docs/perf.md's chip-figures, docs/verification.md's fpga-figures (tools/chip_figures.py)."""
    for target, name, which in chip_figures.TARGETS:
        docblock.save_block(out_dir(build), target, name, chip_figures.BLOCKS[which]())


GENERATORS = {"chip": gen_chip, "area": gen_area, "inject": gen_inject, "plan": gen_plan, "render": gen_render, "paper": gen_paper,
              "precision": gen_precision, "gallery": gen_gallery, "embree": gen_embree, "steps": gen_steps}


# ------------------------------------------------------------------ update

def target_of(rel):
    """The committed path of a file under BUILD/docs (README.md sits at the top)."""
    return "README.md" if rel == "README.md" else os.path.join("docs", rel)


def update(build):
    out = out_dir(build)
    copied = 0
    for sub in ("generated", "img", "data"):
        for d, _, files in os.walk(os.path.join(out, sub)):
            for f in files:
                src = os.path.join(d, f)
                dst = os.path.join(ROOT, target_of(os.path.relpath(src, out)))
                os.makedirs(os.path.dirname(dst), exist_ok=True)
                shutil.copyfile(src, dst)
                copied += 1
    blocks = docblock.saved_blocks(out)
    for target, name, text in blocks:
        docblock.replace_block(os.path.join(ROOT, target), name, text)
    print("installed %d files and %d blocks from %s" % (copied, len(blocks), out))


# ------------------------------------------------------------------ check

def sections(md):
    """{heading: text} of a Markdown file's '## ' sections."""
    parts = re.split(r"^## ", md, flags=re.M)
    return {p.split("\n", 1)[0]: p for p in parts[1:]}


# The sections of paper-reproduction.md made of counts alone (Table 1, the steps per
# broadcast, the models built on them); the others hold the CPU's measured rate.
PAPER_SECTIONS = ["Table 1: instructions per basic operation", "Steps per broadcast",
                  "Table 2: ideal FMPP against the sequential machine", "Fig. 7: limited capacity, 1024 x 1024 pixels"]


PRECISION_CHECK = "one_triangle"  # the scene of precision.md whose section docs_check measures again


class Checker:
    def __init__(self):
        self.errors = []

    def same(self, what, committed, fresh):
        if committed is None:
            self.errors.append("%s: missing from the committed docs" % what)
        elif committed.strip() != fresh.strip():
            self.errors.append("%s differs from a fresh run:\n--- committed\n%s\n--- now\n%s" % (what, committed.strip(),
                                                                                             fresh.strip()))


def committed(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def table_rows(text, first_cells):
    """Rows of the Markdown tables in text, by their first cell(s) (a tuple of first_cells cells)."""
    rows = {}
    for line in (text or "").splitlines():
        if line.startswith("| ") and not line.startswith("| ---"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            rows[tuple(cells[:first_cells])] = cells
    return rows


def check(build):
    c = Checker()
    tmp = tempfile.mkdtemp(prefix="docs-check-", dir=build)
    try:
        # docs/generated/area.md: the whole file (made from committed data only).
        area = os.path.join(tmp, "area.md")
        area_md(build, area)
        c.same("docs/generated/area.md", committed("docs/generated/area.md"), open(area, encoding="utf-8").read())

        # The blocks of today's clock, area and energy figures (made from the committed results).
        for target, name, which in chip_figures.TARGETS:
            c.same("%s, block %s" % (target, name), docblock.read_block(os.path.join(ROOT, target), name),
                   chip_figures.BLOCKS[which]())

        # docs/debugging.md: the lockstep report and the figures read from it.
        if INJECT["config"] in subprocess.run([tool(build, "fmpp-sim"), "--list"], capture_output=True,
                                              text=True).stdout.split():
            c.same("docs/debugging.md, block inject",
                   docblock.read_block(os.path.join(ROOT, "docs/debugging.md"), "inject"),
                   inject_block(inject_report(build, os.path.join(tmp, "wave"))))
        else:
            print("skipped docs/debugging.md: the RTL configuration '%s' is not built here" % INJECT["config"])

        # docs/raytracer.md's plan table and the README's share: the cheap scenes' rows.
        have = table_rows(docblock.read_block(os.path.join(ROOT, "docs/raytracer.md"), "plan"), 1)
        for scene in PLAN_CHECK:
            r = plan_render(build, scene, os.path.relpath(os.path.join(tmp, "plan"), build))
            row = table_rows(plan_row(scene, r), 1)[(scene,)]
            c.same("docs/raytracer.md, plan table, row %s" % scene, " | ".join(have.get((scene,), [])) or None,
                   " | ".join(row))
            if scene == "cornell":
                c.same("README.md, block redone", docblock.read_block(os.path.join(ROOT, "README.md"), "redone"),
                       share_sentence(r))

        # The gallery's tables: the cheap frames' rows, every column but the wall time.
        folder = os.path.relpath(os.path.join(tmp, "gallery"), build)
        for scene, side in (("one_triangle", 128), ("one_triangle", 256), ("cornell", 128)):
            gallery.render(build, scene, side, folder)
            fresh = table_rows("\n".join(gallery.figures_table(build, [(scene, side)], folder)), 3)
            key = (scene, docblock.fmt_int(gallery.load(build, scene, side, folder)["triangles"]), "%d x %d" % (side, side))
            want = fresh[key][:gallery.WALL_COLUMN]
            blocks = [("docs/raytracer.md", "gallery-oracle")] + ([("README.md", "gallery")] if side == 256 else [])
            for target, name in blocks:
                got = table_rows(docblock.read_block(os.path.join(ROOT, target), name), 3).get(key)
                c.same("%s, block %s, row %s" % (target, name, " ".join(key)),
                       " | ".join(got[:gallery.WALL_COLUMN]) if got else None, " | ".join(want))

        # docs/perf.md: the steps per broadcast of every form and n.
        c.same("docs/perf.md, block form-steps", docblock.read_block(os.path.join(ROOT, "docs/perf.md"), "form-steps"),
               steps_block(build, os.path.join(tmp, "form-steps")))

        # docs/generated/paper-reproduction.md: the sections made of counts.
        paper = os.path.join(tmp, "paper.md")
        run([tool(build, "fmpp-report"), "paper", "--counts-only", "--no-plots", "--out", paper, "--img-dir",
             os.path.join(tmp, "paper-img"), "--data-dir", os.path.join(tmp, "paper-data")])
        have, now = sections(committed("docs/generated/paper-reproduction.md")), sections(open(paper, encoding="utf-8").read())
        for name in PAPER_SECTIONS:
            c.same("docs/generated/paper-reproduction.md, section '%s'" % name, have.get(name), now.get(name, ""))

        # docs/generated/precision.md: the section of its cheapest scene (every column a count).
        prec = os.path.join(tmp, "precision.md")
        run([tool(build, "fmpp-report"), "precision", "--only-scene", PRECISION_CHECK, "--no-plots", "--out", prec,
             "--img-dir", os.path.join(tmp, "precision-img"), "--data-dir", os.path.join(tmp, "precision-data")])
        have, now = sections(committed("docs/generated/precision.md")), sections(open(prec, encoding="utf-8").read())
        name = next((h for h in now if h.startswith(PRECISION_CHECK + " (")), None)
        c.same("docs/generated/precision.md, section '%s'" % name, have.get(name), now.get(name, ""))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if c.errors:
        print("\n\n".join(c.errors), file=sys.stderr)
        sys.exit("docs_check: %d generated figure(s) of the committed docs differ from this build's; `make docs` "
                 "regenerates them and `make docs-update` installs them" % len(c.errors))
    print("docs_check: the committed deterministic figures match this build")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("command", choices=["build", "update", "check", "list"])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory (default: ROOT/build)")
    ap.add_argument("--only", action="append", choices=sorted(GENERATORS), help="run only this generator (repeatable)")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    if a.command == "list":
        for name, f in GENERATORS.items():
            print("%-10s %s" % (name, f.__doc__))
    elif a.command == "build":
        for name, f in GENERATORS.items():
            if not a.only or name in a.only:
                print("== %s: %s" % (name, f.__doc__), file=sys.stderr, flush=True)
                f(build)
        print("regenerated into %s; `make docs-update` installs it" % out_dir(build))
    elif a.command == "update":
        update(build)
    else:
        check(build)


if __name__ == "__main__":
    main()

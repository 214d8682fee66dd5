#!/usr/bin/env python3
"""Every measured clock, area and energy figure against the RTL it describes.

    figures_check.py [--root DIR]     fails when a result file the docs quote was measured
                                      on other RTL than DIR's rtl/ (the ctest figures_fresh)
    figures_check.py --list           the result files, their role and who quotes them
    figures_check.py --self-test      a copy of the tree with one line of rtl/ changed, a file
                                      added to rtl/ or the map edited must fail (the ctest
                                      figures_check_self_test)

The figures of README.md and docs/ (clock in MHz, cells, area, energy) are made by
tools/docs.py and fmpp-report from result files that the flows write: tools/asic.sh
(docs/asic/), tools/fpga.sh (docs/data/fpga/), tools/synth.sh (docs/data/synth/). Each of
those files records the RTL it was measured on as a comment line `# rtl-sha256 <hex>`
(tools/rtl_hash.py defines the hash; energy_frame.json has it under "rtl_sha256"). Every
result file is listed in SOURCES below with its role:

  current  quoted as today's design: its hash must equal tools/rtl_hash.py's of today's rtl/,
           or the check fails naming the file, the figures that quote it and both hashes;
  history  measured on an older RTL on purpose (a before/after comparison), quoted only with
           the commit of its RTL (docs/perf-history.md, or a baseline label of
           docs/generated/area.md): not compared, but the label must be there.

A result file under docs/asic/ or docs/data/ that SOURCES does not list fails the check too,
so that a new one cannot be quoted unchecked; so do a file of rtl/ that the hash does not
cover and a map (rtl/fmpp_map.json) that generates another package than rtl/fmpp_pkg.sv.
Editing one line of rtl/ therefore makes this
check fail until the flows are run again and their results copied into docs/ (the
commands: docs/verification.md, "Figures and the RTL they were measured on").
"""
import argparse
import glob
import json
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rtl_hash  # noqa: E402

ROOT = rtl_hash.ROOT

# Quoted by: what a stale file would make wrong.
_CLOCK = ("README.md (gallery table: the iCE40 and 0.18 um clock columns and the 10 nm projection), "
          "docs/raytracer.md (gallery-oracle block), docs/perf.md (Embree table and block chip-figures), "
          "docs/generated/paper-reproduction.md, docs/generated/area.md")
SOURCES = [
    # (path relative to the root, role, quoted by / RTL label)
    ("docs/asic/summary.csv", "current", "standard-cell Fmax, cells, area, power of the sizes: docs/generated/area.md, "
     "docs/architecture.md and docs/perf.md (block chip-figures)"),
    ("docs/asic/cells.csv", "current", "cell counts by type: docs/generated/area.md"),
    ("docs/asic/library.csv", "current", "the library's cell areas (read with the above): docs/generated/area.md"),
    ("docs/asic/energy.csv", "current", "energy per instruction class: docs/generated/area.md, docs/perf.md (block chip-figures)"),
    ("docs/asic/energy_frame.json", "current", "the traced frame of the energy figures: docs/generated/area.md"),
    ("docs/asic/pnr.csv", "current", "the placed and routed sizes: docs/generated/area.md"),
    ("docs/asic/chip*.csv", "current", "the 4,096-block chip's clock with its networks' wires (tools/asic_chip.py) "
     "and its energy (tools/asic_chip_energy.py; docs/perf.md, block energy-per-ray): " + _CLOCK),
    ("docs/data/fpga/summary.csv", "current", "iCE40 Fmax, logic cells: " + _CLOCK),
    ("docs/data/fpga/critical_*.txt", "current", "the iCE40 critical paths: docs/generated/area.md"),
    ("docs/data/synth/*.csv", "current", "make synth's generic cells per size and type: docs/generated/area.md"),
    ("docs/asic/history_b1f3c2c/*", "history",
     "1 x 8 placed and routed, energy of 8 x 32 and 16 x 32, RTL of commit b1f3c2c: docs/perf-history.md"),
    ("docs/asic/single_cycle/*.csv", "history", "the single-cycle design, RTL of commit 2dae345: docs/perf-history.md"),
    ("docs/data/fpga/history_a1b3b0b/*", "history",
     "the iCE40 runs of 1 x 8, 2 x 8 and the UP5K not repeated on today's RTL, RTL of commit a1b3b0b: docs/perf-history.md"),
    ("docs/data/synth/before_shr/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit 4709c66"),
    ("docs/data/synth/before_cmp/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit b28488d"),
    ("docs/data/synth/before_divstep/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit 1f73d13"),
]
# Every run of the flows writes these (the others only with the options that make them:
# energy, place and route).
REQUIRED = ("docs/asic/summary.csv", "docs/asic/cells.csv", "docs/asic/library.csv", "docs/data/fpga/summary.csv",
            "docs/data/synth/*.csv")
# Where result files live: every file found here must be in SOURCES.
RESULT_GLOBS = ("docs/asic/**/*.csv", "docs/asic/**/*.json", "docs/data/fpga/**/*", "docs/data/synth/**/*.csv")


# Hand-typed figures: outside the generated blocks (<!-- NAME:begin --> ... <!-- NAME:end -->)
# of README.md and docs/ (generated/ is generated whole; perf-history.md is the record of
# older RTL, each figure labelled with its RTL), a number with a unit of clock, time, area,
# energy or power is an error, unless it is one of these, which describe no measurement of
# the RTL: (file, regular expression, why).
FIGURE = re.compile(r"(?<![\w.])\d[\d,.]*\s*(?:MHz|GHz|mm\^2|um\^2|pJ|nJ|uJ|mW|ns"
                    r"|(?:[a-z-]+ ){0,2}(?:cells|transistors|LUTs|flip-flops))\b")
PROSE_ALLOWED = (
    ("*", r"50 MHz", "the paper's clock"),
    ("*", r"0\.18 um (?:standard )?cells", "the library's name"),
    ("docs/paper.md", r".*", "the paper's own figures"),
    ("docs/perf.md", r"18 transistors", "the paper's CAM cell"),
    ("docs/perf.md", r"2\.6 GHz", "the CPU's nominal clock"),
    ("docs/perf.md", r"19 ns per access|8 to 19 ns", "the SystemC platform's cost per access (software)"),
    ("docs/verification.md", r"60 MHz", "the iCE40 clock asked for (a goal, not a measurement)"),
    ("docs/architecture.md", r"0\.1 ns", "the iCE40's carry logic per bit (the device's data sheet)"),
    ("docs/asic/notes.md", r"10 ns|1\.0 ns|100 MHz", "the flow's constraints: the clock period, input and output delays, the power's clock"),
    ("docs/asic/notes.md", r"\d+ um\^2", "the library's cell areas"),
)
PROSE_SKIP = ("docs/perf-history.md", "docs/generated/")


def hand_typed(root):
    """[(file, line, figure)] of the figures typed outside generated blocks."""
    import fnmatch
    found = []
    docs = ["README.md"] + sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "docs", "**", "*.md"),
                                                                                recursive=True))
    for rel in docs:
        if rel.startswith(PROSE_SKIP) or not os.path.isfile(os.path.join(root, rel)):
            continue
        allowed = [re.compile(rx) for f, rx, _ in PROSE_ALLOWED if fnmatch.fnmatch(rel, f)]
        block = None
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                m = re.match(r"<!-- ([\w-]+):(begin|end)", line)
                if m:
                    block = m.group(1) if m.group(2) == "begin" else None
                    continue
                if block:
                    continue
                spans = [m.span() for a in allowed for m in a.finditer(line)]
                for fig in FIGURE.finditer(line):
                    if not any(a <= fig.start() and fig.end() <= b for a, b in spans):
                        found.append((rel, n, fig.group(0)))
    return found


# Clocks quoted with their source: each must be the value today's result file gives (as
# tools/gallery.py reads it), at the precision it is printed with.
QUOTED_CLOCKS = (
    (re.compile(r"([\d.]+) MHz \((?:iCE40, measured|measured, iCE40)"), "fpga"),
    (re.compile(r"([\d.]+) MHz \(0\.18 um cells"), "asic"),
    (re.compile(r"([\d.]+) MHz \(projected to 10 nm"), "projected"),
    (re.compile(r"measured clock of this design is ([\d.]+) MHz"), "fpga"),
)


def quoted_clocks(root):
    """[(file, line, quoted, today's, which)] of the quoted clocks that are not today's result files'."""
    import gallery
    import node_scale
    try:
        now = {"fpga": gallery.fpga_mhz(os.path.join(root, "docs", "data", "fpga", "summary.csv")),
               "asic": gallery.asic_clock(os.path.join(root, "docs", "asic"))[0]}
    except (OSError, SystemExit, KeyError, ValueError) as e:
        return [("docs/asic/chip.csv, summary.csv or docs/data/fpga/summary.csv", 0, "?", str(e), "clock")]
    now["projected"] = node_scale.project_mhz(now["asic"])
    bad = []
    docs = ["README.md"] + sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "docs", "**", "*.md"),
                                                                                recursive=True))
    for rel in docs:
        if rel.startswith("docs/perf-history.md") or not os.path.isfile(os.path.join(root, rel)):
            continue
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                for rx, which in QUOTED_CLOCKS:
                    for m in rx.finditer(line):
                        q = m.group(1).rstrip(".")
                        digits = len(q.split(".")[1]) if "." in q else 0
                        if abs(float(q) - now[which]) > 0.5 * 10 ** -digits + 1e-9:
                            bad.append((rel, n, q, now[which], which))
    return bad


def recorded_hash(path):
    """The RTL hash a result file records, or None."""
    if path.endswith(".json"):
        with open(path, encoding="utf-8") as f:
            return json.load(f).get("rtl_sha256") or None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith(rtl_hash.PREFIX):  # noqa: SIM102
                return line[len(rtl_hash.PREFIX):].split()[0]
            if not line.startswith("#") and line.strip() and not line.startswith("Critical path"):
                break  # the comment lines are at the top
    return None


def expand(root, pattern):
    return sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, pattern), recursive=True)
                  if os.path.isfile(p))


MAP = "rtl/fmpp_map.json"


def rtl_outside_hash(root):
    """Errors for what of rtl/ the hash would miss: a file it does not cover (rtl/ holds the
    hardware alone; the map is read through the package generated from it), and a map
    whose generated package is not rtl/fmpp_pkg.sv."""
    errors = []
    covered = set(rtl_hash.covered(root)) | {MAP}
    for d, dirs, files in os.walk(os.path.join(root, "rtl")):
        dirs.sort()
        for name in sorted(files):
            rel = os.path.relpath(os.path.join(d, name), root).replace(os.sep, "/")
            if rel not in covered:
                errors.append(f"{rel}: a file of rtl/ that the RTL hash does not cover (list it in rtl/fmpp.f, or "
                              "keep it outside rtl/ if no hardware flow reads it)")
    from mapgen.model import MapError, load
    from mapgen.sv import gen_sv
    pkg = os.path.join(root, "rtl", "fmpp_pkg.sv")
    try:
        with open(pkg, encoding="utf-8") as f:
            same = f.read() == gen_sv(load(root))
    except (MapError, OSError, ValueError, KeyError, TypeError, IndexError) as e:
        return errors + [f"{MAP}: cannot be read into a package ({e})"]
    if not same:
        errors.append(f"{MAP}: generates another package than rtl/fmpp_pkg.sv: run tools/gen_map.py (the RTL hash "
                      "then changes) and measure the figures again")
    return errors


def check(root):
    """(errors, notes) for the tree at root."""
    root = os.path.abspath(root)
    today = rtl_hash.rtl_hash(root)
    errors, notes, listed = rtl_outside_hash(root), [], set()
    for pattern, role, quoted in SOURCES:
        files = expand(root, pattern)
        if not files and pattern in REQUIRED:
            errors.append(f"{pattern}: listed in tools/figures_check.py SOURCES but not found")
        for rel in files:
            listed.add(rel)
            if role == "history":
                if "RTL of commit" not in quoted:
                    errors.append(f"{rel}: a history result without the commit of its RTL in its label")
                notes.append(f"{rel}: history ({quoted})")
                continue
            got = recorded_hash(os.path.join(root, rel))
            if got is None:
                errors.append(f"{rel}: records no RTL hash ('{rtl_hash.PREFIX}<hex>'); quoted by {quoted}; "
                              f"today's rtl/ is {today}")
            elif got != today:
                errors.append(f"{rel}: measured on RTL {got}, today's rtl/ is {today}; stale figures: {quoted}")
    for pattern in RESULT_GLOBS:
        for rel in expand(root, pattern):
            if rel not in listed:
                errors.append(f"{rel}: a result file that tools/figures_check.py SOURCES does not list")
    for rel, n, q, now, which in quoted_clocks(root):
        errors.append(f"{rel}:{n}: quotes {q} MHz as the {which} clock; today's result file gives {now:.2f} MHz "
                      "(make docs regenerates it)")
    for rel, n, fig in hand_typed(root):
        errors.append(f"{rel}:{n}: '{fig}' typed by hand outside a generated block (make it a block of tools/docs.py, "
                      "or move it to docs/perf-history.md with the RTL it was measured on)")
    return errors, notes, today


def report(root):
    errors, notes, today = check(root)
    for e in errors:
        print("figures_check: STALE: " + e, file=sys.stderr)
    if errors:
        print(f"figures_check: {len(errors)} figure(s) or result file(s) do not describe today's rtl/ ({today}); run "
              "the flows again (docs/verification.md, 'Figures and the RTL they were measured on')", file=sys.stderr)
        return 1
    print(f"figures_check: every current result file was measured on today's rtl/ ({today}); "
          f"{len(notes)} history file(s) labelled with their RTL")
    return 0


def self_test():
    """On a copy of rtl/ and the result files: restamped with the copy's hash it passes; with
    one line of rtl/fmpp_tile.sv changed it fails, naming every current file and both hashes; a
    file added to rtl/, a map edited without its package, a result file unlisted or without a
    hash and a figure typed by hand fail it too."""
    bad = []
    with tempfile.TemporaryDirectory() as d:
        shutil.copytree(os.path.join(ROOT, "rtl"), os.path.join(d, "rtl"))
        for pattern in RESULT_GLOBS:
            for rel in expand(ROOT, pattern):
                os.makedirs(os.path.dirname(os.path.join(d, rel)), exist_ok=True)
                shutil.copy(os.path.join(ROOT, rel), os.path.join(d, rel))
        h0 = rtl_hash.rtl_hash(d)
        current = []
        for pattern, role, _ in SOURCES:
            if role != "current":
                continue
            for rel in expand(d, pattern):
                current.append(rel)
                p = os.path.join(d, rel)
                if p.endswith(".json"):
                    with open(p, encoding="utf-8") as f:
                        j = json.load(f)
                    j["rtl_sha256"] = h0
                    with open(p, "w", encoding="utf-8") as f:
                        json.dump(j, f)
                    continue
                with open(p, encoding="utf-8") as f:
                    lines = [ln for ln in f if not ln.startswith(rtl_hash.PREFIX)]
                with open(p, "w", encoding="utf-8") as f:
                    f.write(rtl_hash.PREFIX + h0 + "\n" + "".join(lines))
        errors, _, today = check(d)
        if errors or today != h0:
            bad.append("the restamped copy should pass: " + "; ".join(errors))
        # One line of the RTL changed (a comment: the hash covers every byte).
        tile = os.path.join(d, "rtl", "fmpp_tile.sv")
        with open(tile, encoding="utf-8") as f:
            text = f.read().split("\n")
        text[0] += " (edited)"
        with open(tile, "w", encoding="utf-8") as f:
            f.write("\n".join(text))
        errors, _, h1 = check(d)
        if h1 == h0:
            bad.append("the hash did not change with a line of rtl/fmpp_tile.sv")
        for rel in current:
            if not any(e.startswith(rel + ":") and h0 in e and h1 in e for e in errors):
                bad.append(f"{rel}: not reported stale with both hashes after the edit")
        # A file of rtl/ outside the hash, and a map edited without regenerating its package.
        open(os.path.join(d, "rtl", "build.cmake"), "w").close()
        with open(os.path.join(d, MAP), encoding="utf-8") as f:
            m = json.load(f)
        m["params"]["QueueDepth"]["value"] += 1
        with open(os.path.join(d, MAP), "w", encoding="utf-8") as f:
            json.dump(m, f)
        errors, _, _ = check(d)
        if not any(e.startswith("rtl/build.cmake:") and "does not cover" in e for e in errors):
            bad.append("a file of rtl/ outside the hash is not reported")
        if not any(e.startswith(MAP + ":") and "another package" in e for e in errors):
            bad.append("a map edited without regenerating rtl/fmpp_pkg.sv is not reported")
        # A result file nobody lists, and one without a hash.
        open(os.path.join(d, "docs", "data", "fpga", "extra.csv"), "w").close()
        with open(os.path.join(d, "docs", "data", "synth", "summary.csv"), encoding="utf-8") as f:
            lines = [ln for ln in f if not ln.startswith(rtl_hash.PREFIX)]
        with open(os.path.join(d, "docs", "data", "synth", "summary.csv"), "w", encoding="utf-8") as f:
            f.write("".join(lines))
        # A clock typed by hand into prose, and a generated clock that is not today's.
        with open(os.path.join(d, "docs", "prose.md"), "w", encoding="utf-8") as f:
            f.write("The chip runs at 123.4 MHz.\n<!-- x:begin -->\nat 1.0 MHz (iCE40, measured)\n<!-- x:end -->\n")
        errors, _, _ = check(d)
        if not any(e.startswith("docs/prose.md:1:") and "typed by hand" in e for e in errors):
            bad.append("a clock typed by hand into prose is not reported")
        if not any(e.startswith("docs/prose.md:3:") and "quotes 1.0 MHz" in e for e in errors):
            bad.append("a quoted iCE40 clock that is not the result file's is not reported")
        if not any(e.startswith("docs/data/fpga/extra.csv:") and "does not list" in e for e in errors):
            bad.append("an unlisted result file is not reported")
        if not any(e.startswith("docs/data/synth/summary.csv:") and "records no RTL hash" in e for e in errors):
            bad.append("a result file without a hash is not reported")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=ROOT)
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        bad = self_test()
        for b in bad:
            print("figures_check self-test: FAIL: " + b, file=sys.stderr)
        print("figures_check self-test: " + ("FAILED" if bad else "passed (one edited line of rtl/ fails the check)"))
        return 1 if bad else 0
    if a.list:
        for pattern, role, quoted in SOURCES:
            print(f"{pattern}\t{role}\t{quoted}")
        return 0
    return report(a.root)


if __name__ == "__main__":
    sys.exit(main())

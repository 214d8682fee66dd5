#!/usr/bin/env python3
"""Every measured clock, area and energy figure against the RTL it describes.

    figures_check.py [--root DIR]     fails when a result file the docs quote was measured
                                      on other RTL than DIR's rtl/ (the ctest figures_fresh)
    figures_check.py --list           the result files, their role and who quotes them
    figures_check.py --self-test      a copy of the tree with one line of rtl/ changed must
                                      fail (the ctest figures_check_self_test)

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
so that a new one cannot be quoted unchecked. Editing one line of rtl/ therefore makes this
check fail until the flows are run again and their results copied into docs/ (the
commands: docs/verification.md, "Figures and the RTL they were measured on").
"""
import argparse
import glob
import json
import os
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
    ("docs/asic/summary.csv", "current", "standard-cell Fmax, cells, area, power: " + _CLOCK),
    ("docs/asic/cells.csv", "current", "cell counts by type: docs/generated/area.md"),
    ("docs/asic/library.csv", "current", "the library's cell areas (read with the above): docs/generated/area.md"),
    ("docs/asic/energy.csv", "current", "energy per instruction class: docs/generated/area.md, docs/perf.md (block chip-figures)"),
    ("docs/asic/energy_frame.json", "current", "the traced frame of the energy figures: docs/generated/area.md"),
    ("docs/data/fpga/summary.csv", "current", "iCE40 Fmax, logic cells: " + _CLOCK),
    ("docs/data/fpga/critical_*.txt", "current", "the iCE40 critical paths: docs/generated/area.md"),
    ("docs/data/synth/*.csv", "current", "make synth's generic cells per size and type: docs/generated/area.md"),
    ("docs/asic/pnr.csv", "history", "1 x 8 placed and routed, RTL of commit b1f3c2c: docs/perf-history.md"),
    ("docs/asic/single_cycle/*.csv", "history", "the single-cycle design, RTL of commit 2dae345: docs/perf-history.md"),
    ("docs/data/synth/before_shr/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit 4709c66"),
    ("docs/data/synth/before_cmp/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit b28488d"),
    ("docs/data/synth/before_divstep/*.csv", "history", "baseline of docs/generated/area.md, RTL of commit 1f73d13"),
]
# Where result files live: every file found here must be in SOURCES.
RESULT_GLOBS = ("docs/asic/**/*.csv", "docs/asic/**/*.json", "docs/data/fpga/**/*", "docs/data/synth/**/*.csv")


def recorded_hash(path):
    """The RTL hash a result file records, or None."""
    if path.endswith(".json"):
        with open(path, encoding="utf-8") as f:
            return json.load(f).get("rtl_sha256") or None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith(rtl_hash.PREFIX):
                return line[len(rtl_hash.PREFIX):].split()[0]
            if not line.startswith("#") and line.strip() and not line.startswith("Critical path"):
                break  # the comment lines are at the top
    return None


def expand(root, pattern):
    return sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, pattern), recursive=True)
                  if os.path.isfile(p))


def check(root):
    """(errors, notes) for the tree at root."""
    root = os.path.abspath(root)
    today = rtl_hash.rtl_hash(root)
    errors, notes, listed = [], [], set()
    for pattern, role, quoted in SOURCES:
        files = expand(root, pattern)
        if not files:
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
    return errors, notes, today


def report(root):
    errors, notes, today = check(root)
    for e in errors:
        print("figures_check: STALE: " + e, file=sys.stderr)
    if errors:
        print(f"figures_check: {len(errors)} result file(s) do not describe today's rtl/ ({today}); run the flows "
              "again (docs/verification.md, 'Figures and the RTL they were measured on')", file=sys.stderr)
        return 1
    print(f"figures_check: every current result file was measured on today's rtl/ ({today}); "
          f"{len(notes)} history file(s) labelled with their RTL")
    return 0


def self_test():
    """On a copy of rtl/ and the result files: restamped with the copy's hash it passes; with
    one line of rtl/fmpp_tile.sv changed it fails, naming every current file and both hashes."""
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
        # A result file nobody lists, and one without a hash.
        open(os.path.join(d, "docs", "data", "fpga", "extra.csv"), "w").close()
        with open(os.path.join(d, "docs", "data", "synth", "summary.csv"), encoding="utf-8") as f:
            lines = [ln for ln in f if not ln.startswith(rtl_hash.PREFIX)]
        with open(os.path.join(d, "docs", "data", "synth", "summary.csv"), "w", encoding="utf-8") as f:
            f.write("".join(lines))
        errors, _, _ = check(d)
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

#!/usr/bin/env python3
"""The committed frame tables at today's measured clocks, without rendering again.

    reclock.py [--out-dir build/docs]    saves the blocks for tools/docs.py update

The README's gallery table, docs/raytracer.md's gallery-oracle table, docs/perf.md's
Embree table and docs/generated/paper-reproduction.md's comparison with the CPU give each frame's time at the clocks `make fpga` and `make asic` measured
(and the projection of the latter to 10 nm). The frames' clock counts do not depend on
those clocks, so when the flows are run again on new RTL the columns are recomputed here
from each row's FMPP clocks (and, in the Embree table, its rays and Embree's rates as
printed) with the formulas of tools/gallery.py and tools/bench_embree.py; every other
column and the measurement's provenance line stay as they were, and a sentence names the
clocks' source. `make gallery` and `make bench-embree` remake the tables whole.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import docblock  # noqa: E402
import gallery  # noqa: E402

ROOT = gallery.ROOT
NOTE = ("Columns at the measured clocks recomputed from the FMPP clocks by `tools/reclock.py` for the result "
        "files of RTL %s (docs/data/fpga/summary.csv, docs/asic/chip.csv).")


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def row(cs):
    return "| " + " | ".join(cs) + " |"


def num(text):
    return int(text.replace(",", ""))


def si_value(text):
    m = re.fullmatch(r"([\d.]+) ?([kMG]?)(?: rays/s)?", text)
    if not m:
        raise ValueError("not a rate: %r" % text)
    return float(m.group(1)) * {"": 1, "k": 1e3, "M": 1e6, "G": 1e9}[m.group(2)]


def clocks():
    fpga, (asic, size) = gallery.fpga_mhz(), gallery.asic_clock()
    proj, label = gallery.projected_clock(asic)
    return fpga, asic, size, proj, label


def rtl_short():
    return gallery.rtl_of(os.path.join(gallery.ASIC_DIR, "summary.csv"))


def with_note(lines):
    note = NOTE % rtl_short()
    lines = [ln for ln in lines if not ln.startswith("Columns at the measured clocks recomputed")]
    # the note goes right after the table's provenance line (the last line starting "Measured")
    for i in range(len(lines) - 1, -1, -1):
        if lines[i].startswith("Measured ") or " Measured " in lines[i]:
            return lines[:i + 1] + [note] + lines[i + 1:]
    return lines + ["", note]


def gallery_table(text):
    fpga, asic, size, proj, label = clocks()
    out = []
    for line in text.split("\n"):
        cs = cells(line) if line.startswith("|") else None
        if cs and cs[0] == "scene" and len(cs) == 13:
            cs[9] = "at %.1f MHz (iCE40, measured)" % fpga
            cs[10] = "at %.1f MHz (%s)" % (asic, size)
            cs[11] = "at %.0f MHz (%s)" % (proj, label)
            line = row(cs)
        elif cs and len(cs) == 13 and cs[0] not in ("---",) and re.fullmatch(r"[\d,]+", cs[4]):
            cyc = num(cs[4])
            cs[9] = "%.1f ms" % (1e3 * cyc / (fpga * 1e6))
            cs[10] = "%.1f ms" % (1e3 * cyc / (asic * 1e6))
            cs[11] = "%.2f ms" % (1e3 * cyc / (proj * 1e6))
            line = row(cs)
        out.append(line)
    return "\n".join(with_note(out))


def embree_row(cs):
    """(FMPP rays, FMPP clocks, Embree's faster rate) of a data row of docs/perf.md's Embree
    table (its cells), or None for any other row."""
    if len(cs) != 12 or not re.fullmatch(r"[\d,]+", cs[5]):
        return None
    return num(re.search(r"\(([\d,]+)\)", cs[1]).group(1)), num(cs[5]), max(si_value(cs[2]), si_value(cs[3]))


def embree_table(text):
    import bench_embree
    fpga, asic, size, proj, label = clocks()
    out = []
    for line in text.split("\n"):
        cs = cells(line) if line.startswith("|") else None
        if cs and len(cs) == 12 and cs[0] == "scene, frame":
            cs[7] = "at %.1f MHz (iCE40, measured)" % fpga
            cs[8] = "at %.1f MHz (%s)" % (asic, size)
            cs[9] = "faster Embree / FMPP at %.1f MHz" % asic
            cs[10] = "at %.0f MHz (%s)" % (proj, label)
            line = row(cs)
        elif cs and embree_row(cs):
            n, cyc, embree = embree_row(cs)
            fmpp = lambda mhz: n / (cyc / (mhz * 1e6))  # noqa: E731
            cs[7] = bench_embree.si(fmpp(fpga))
            cs[8] = bench_embree.si(fmpp(asic))
            cs[9] = "%.1f" % (embree / fmpp(asic))
            cs[10] = bench_embree.si(fmpp(proj))
            cs[11] = "%.2f" % (embree / fmpp(proj))
            line = row(cs)
        out.append(line)
    return "\n".join(with_note(out))


def paper_file(text):
    """docs/generated/paper-reproduction.md's clock columns and sentences at today's clocks: tests/s scale with
    the clock; the CPU's rate (measured with the rest of the file) and every count stay."""
    fpga, asic, size, proj, label = clocks()
    rtl = rtl_short()
    cpu = float(re.search(r"\*\*([\d.e+]+) ray-triangle tests per second\*\*", text).group(1))
    out = []
    for line in text.split("\n"):
        cs = cells(line) if line.startswith("|") else None
        if cs and len(cs) == 7 and cs[0] == "blocks":
            cs[3] = "tests/s at %.1f MHz (%s)" % (asic, size)
            cs[5] = "tests/s at %.1f MHz (%s)" % (proj, label)
            line = row(cs)
        elif cs and len(cs) == 7 and cs[0].endswith("^2"):
            base = float(cs[1])
            cs[3], cs[4] = "%.3g" % (base * asic / 50), "%.1f" % (base * asic / 50 / cpu)
            cs[5], cs[6] = "%.3g" % (base * proj / 50), "%.1f" % (base * proj / 50 / cpu)
            line = row(cs)
        elif cs and len(cs) == 5 and cs[0] == "blocks":
            cs[3] = "tests/s at %.1f MHz (measured, iCE40)" % fpga
            line = row(cs)
        elif cs and len(cs) == 5 and cs[0].endswith("^2"):
            base = float(cs[1])
            cs[3], cs[4] = "%.3g" % (base * fpga / 50), "%.1f" % (base * fpga / 50 / cpu)
            line = row(cs)
        line = re.sub(r"The one measured clock of this design is [\d.]+ MHz",
                      "The one measured clock of this design is %.1f MHz" % fpga, line)
        line = re.sub(r"with the FMPP at the measured [\d.]+ MHz and the sequential machine at 50 MHz each would be "
                      r"[\d.]+ times as large\. The times of Fig\. 7 are multiplied by [\d.]+ at the measured clock",
                      "with the FMPP at the measured %.1f MHz and the sequential machine at 50 MHz each would be %.2f "
                      "times as large. The times of Fig. 7 are multiplied by %.2f at the measured clock"
                      % (fpga, fpga / 50, 50 / fpga), line)
        out.append(line)
    text = "\n".join(out)
    note = ("(The clock columns and sentences of this section and the next recomputed for the result files of RTL %s by "
            "`tools/reclock.py`, from the rates at 50 MHz and the CPU's rate above.)" % rtl)
    text = re.sub(r"\n\(The clock columns and sentences of this section[^\n]*\)\n\n", "\n", text)
    return text.replace("\n## The paper's 50 MHz beside a measured clock", "\n" + note + "\n\n## The paper's 50 MHz beside a measured clock", 1)


BLOCKS = (("README.md", "gallery", gallery_table), ("docs/raytracer.md", "gallery-oracle", gallery_table),
          ("docs/perf.md", "embree", embree_table))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "build", "docs"))
    a = ap.parse_args()
    for target, name, fn in BLOCKS:
        text = docblock.read_block(os.path.join(ROOT, target), name)
        if text is None:
            sys.exit("reclock: %s has no block %s" % (target, name))
        docblock.save_block(a.out_dir, target, name, fn(text))
    paper = os.path.join(ROOT, "docs", "generated", "paper-reproduction.md")
    out = os.path.join(a.out_dir, "generated", "paper-reproduction.md")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(paper, encoding="utf-8") as f:
        text = paper_file(f.read())
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)
    print("wrote %s (docs/generated/paper-reproduction.md at today's clocks)" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main())

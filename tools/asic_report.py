#!/usr/bin/env python3
"""Reads the results of tools/asic.sh (yosys cell counts, OpenSTA reports) and reports them.

  line      one size's row on the terminal, from <dir>/<name>.{stat,sta.log,...}
  pnr-line  one routed size's unplaced against routed timing
  spef      qrouter's RC file (qflow's <top>.rc) as SPEF for OpenSTA's read_parasitics
  collect   summary.csv (one row per size), cells.csv (cell counts), pnr.csv (routed sizes)
  fit       the area cost model (fixed, per word, per block, per stored bit) from summary.csv
            and the storage comparison, as Markdown
  check     reads committed CSVs (docs/asic) and checks that they parse and the fit holds

Areas are the cells' LEF footprints in um^2 (the Liberty file agrees for every cell but
LATCH, which it gives an area of 0); transistors are the MOSFETs of each cell's SPICE
subcircuit in the library's .sp file.
"""
import argparse
import sys

from asic_collect import cmd_collect, cmd_line, cmd_pnr_line
from asic_common import ReportError
from asic_fit import cmd_check, cmd_doc, cmd_fit
from asic_spef import cmd_placed_spef, cmd_rc_spef


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("line")
    p.add_argument("--dir", required=True)
    p.add_argument("--lef", default="/usr/share/qflow/tech/osu018/osu018_stdcells.lef")
    p.add_argument("--name", required=True)
    p.add_argument("--period", type=float, required=True)
    p.add_argument("--secs", default="")
    p.set_defaults(func=cmd_line)
    p = sub.add_parser("pnr-line")
    p.add_argument("--dir", required=True)
    p.add_argument("--name", required=True)
    p.add_argument("--period", type=float, required=True)
    p.set_defaults(func=cmd_pnr_line)
    p = sub.add_parser("collect")
    p.add_argument("--dir", required=True)
    p.add_argument("--top", required=True)
    p.add_argument("--lef", required=True)
    p.add_argument("--spice", required=True)
    p.add_argument("--period", type=float, required=True)
    p.add_argument("--sizes", nargs="+", required=True)
    p.add_argument("--pnr", nargs="*", default=[])
    p.add_argument("--energy", nargs="*", default=[])
    p.add_argument("--lib", default="", help="Liberty file (its areas go beside the LEF's in library.csv)")
    p.add_argument("--readme", default="", help="README.md: the gallery's FMPP clocks, kept for the energy per frame")
    p.set_defaults(func=cmd_collect)
    p = sub.add_parser("fit")
    p.add_argument("--dir", required=True)
    p.add_argument("--period", type=float, default=10.0)
    p.add_argument("--activity-note", default="0.1")
    p.add_argument("--out", default="")
    p.set_defaults(func=cmd_fit)
    p = sub.add_parser("doc")
    p.add_argument("--area-md", required=True, help="fmpp-report area's output")
    p.add_argument("--dir", required=True, help="docs/asic: the CSVs and notes.md")
    p.add_argument("--period", type=float, default=10.0)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--out")
    g.add_argument("--check")
    p.set_defaults(func=cmd_doc)
    p = sub.add_parser("placed-spef")
    p.add_argument("--def", dest="deff", required=True)
    p.add_argument("--lef", required=True)
    p.add_argument("--verilog", required=True, help="the netlist OpenSTA reads (its port names)")
    p.add_argument("--top", required=True)
    p.add_argument("--hlayer", default="metal3")
    p.add_argument("--vlayer", default="metal2")
    p.add_argument("--out", required=True)
    p.set_defaults(func=cmd_placed_spef)
    p = sub.add_parser("rc-spef")
    p.add_argument("--rc", required=True)
    p.add_argument("--verilog", required=True)
    p.add_argument("--top", required=True)
    p.add_argument("--out", required=True)
    p.set_defaults(func=cmd_rc_spef)
    p = sub.add_parser("check")
    p.add_argument("--dir", required=True)
    p.set_defaults(func=cmd_check)
    a = ap.parse_args()
    try:
        a.func(a)
    except ReportError as e:
        print("asic_report.py: " + str(e), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
